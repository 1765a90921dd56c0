"""Reading a run's transport measurement (docs/formats.md): transport.csv, the
correlation functions and running coefficients, and summary.json's "transport" object.
Every fault raises InputError naming the file."""
import math

import numpy as np

from .run_dir import InputError, read_csv_rows

COEFFICIENTS = ("diffusion", "shear_viscosity", "bulk_viscosity", "thermal_conductivity")
QUANTITIES = COEFFICIENTS + ("velocity_autocorrelation",)
HEADER = ("quantity", "lag", "correlation", "running_coefficient")
NO_TRANSPORT = "the run measured no transport coefficients: add a [transport] table to its config"


def read_curves(path):
    """transport.csv as {quantity: (lag, correlation, running_coefficient) arrays}, only
    the quantities it has. Refuses another header, an unknown quantity, text that is not
    a number and a quantity's lags out of ascending order."""
    if not path.is_file():
        raise InputError(f"{path}: missing; {NO_TRANSPORT}, and run again")
    rows = read_csv_rows(path)
    if not rows or tuple(h.strip() for h in rows[0]) != HEADER:
        found = ",".join(rows[0]) if rows and rows[0] else "nothing"
        raise InputError(f"{path}: the header must be {','.join(HEADER)}, not {found}")
    columns = {}
    for line, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        if len(row) != len(HEADER):
            raise InputError(f"{path}: line {line} has {len(row)} fields, the header has 4")
        name = row[0].strip()
        if name not in QUANTITIES:
            raise InputError(f"{path}: line {line}: unknown quantity '{name}' (known: "
                             f"{', '.join(QUANTITIES)})")
        numbers = [_number(x, path, line) for x in row[1:]]
        rows_of = columns.setdefault(name, [])
        if rows_of and not numbers[0] > rows_of[-1][0]:
            raise InputError(f"{path}: line {line}: the lags of {name} are not in ascending "
                             "order")
        rows_of.append(numbers)
    return {name: tuple(np.array(values, dtype=float).T) for name, values in columns.items()}


def read_summary(run):
    """summary.json's "transport" object, checked: each coefficient's entry (absent ones
    left out) as {"value", "error", "why"}, and "fit_window" (from, to), "blocks",
    "interval", "enskog" {name: value}, "diffusion_infinite" where it has them."""
    path = run.path / "summary.json"
    if not path.is_file():
        raise InputError(f"{path}: missing (the run did not finish, or was killed)")
    transport = run.summary().get("transport")
    if transport is None:
        raise InputError(f"{path}: no \"transport\" object; {NO_TRANSPORT}, and run again")
    if not isinstance(transport, dict):
        raise InputError(f"{path}: \"transport\" must be an object")
    where = f"{path}: transport"
    out = {"coefficients": {}, "enskog": {}}
    for name in ("diffusion", "diffusion_infinite") + COEFFICIENTS[1:]:
        if name in transport:
            out["coefficients"][name] = _coefficient(transport[name], f"{where}.{name}")
    window = transport.get("fit_window")
    if window is not None:
        if not isinstance(window, dict):
            raise InputError(f"{where}.fit_window must be an object {{\"from\", \"to\"}}")
        low = _finite(window.get("from"), f"{where}.fit_window.from")
        high = _finite(window.get("to"), f"{where}.fit_window.to")
        if not 0 <= low < high:
            raise InputError(f"{where}.fit_window: from {low:g} to {high:g} is not a window "
                             "(0 <= from < to)")
        out["fit_window"] = (low, high)
    for key in ("blocks", "interval"):
        if transport.get(key) is not None:
            out[key] = _finite(transport[key], f"{where}.{key}")
    enskog = transport.get("enskog")
    if enskog is not None:
        if not isinstance(enskog, dict):
            raise InputError(f"{where}.enskog must be an object")
        for name in COEFFICIENTS:
            if enskog.get(name) is not None:
                out["enskog"][name] = _finite(enskog[name], f"{where}.enskog.{name}")
    return out


def _coefficient(entry, where):
    if not isinstance(entry, dict) or "value" not in entry:
        raise InputError(f"{where} must be an object with \"value\"")
    value = entry["value"]
    if value is None:
        why = entry.get("why")
        return {"value": None, "error": None,
                "why": str(why) if why else "not measured; summary.json gives no reason"}
    error = entry.get("error")
    return {"value": _finite(value, f"{where}.value"),
            "error": None if error is None else _finite(error, f"{where}.error"), "why": None}


def _finite(x, where):
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x):
        raise InputError(f"{where}: {x!r} is not a number")
    return float(x)


def _number(text, path, line):
    try:
        return float(text)
    except ValueError:
        raise InputError(f"{path}: line {line}: '{text.strip()}' is not a number") from None
