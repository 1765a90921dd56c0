"""The contact distance of each pair of species, from a run's config.toml: how close two
particles must be to count as touching in `pedesis analyze clusters`.

- harmonic: its range a (the particles overlap, so push each other, closer than a);
- wca: its cutoff 2^(1/6) sigma (closer than that they repel);
- lj: 1.5 sigma (Stillinger's criterion: the first shell of neighbours, past the minimum
  of the potential at 2^(1/6) sigma and before g(r)'s first minimum), or the cutoff
  if that is shorter;
- several pair forces: the largest of their distances, pair by pair;
- hard particles (event, stepped), or soft ones with no pair force: 1.1 (r_i + r_j),
  since hard particles never come closer than r_i + r_j and their dense phase lies
  within a tenth of that of touching.

Parameters are resolved per pair as the engine resolves them (plugin_registry.cpp,
pair_parameter): a [[force.pairs]] entry, else the force's own value, mixed
geometrically (lengths: arithmetically with mixing = "arithmetic") where it is given
per species; sigma and a default to r_i + r_j, lj's cutoff to 2.5.
"""
import math

import numpy as np

HARD_MARGIN = 1.1  # hard contact (r_i + r_j) times this
LJ_SHELL = 1.5  # Stillinger's first-shell distance, in sigma

_RULES = {
    "harmonic": ("a", 1.0, "harmonic's range a"),
    "wca": ("sigma", 2.0 ** (1.0 / 6.0), "wca's cutoff 2^(1/6) sigma"),
    "lj": ("sigma", LJ_SHELL, "lj's first shell 1.5 sigma"),
}


def contact_distances(config, names, radii):
    """(distances, reason): an (S, S) array of contact distances for species ``names``
    of ``radii``, and what they came from (for the printed line)."""
    radii = np.asarray(radii, dtype=float)
    hard = HARD_MARGIN * (radii[:, None] + radii[None, :])
    if str(config.get("dynamics", "event")) in ("event", "stepped"):
        return hard, "hard particles: 1.1 (r_i + r_j)"
    forces = [f for f in config.get("force", []) if f.get("name") in _RULES]
    if not forces:
        return hard, "no pair force: 1.1 (r_i + r_j)"
    out = np.zeros_like(hard)
    for force in forces:
        key, factor, _ = _RULES[force["name"]]
        for a in range(len(names)):
            for b in range(len(names)):
                length = _pair_value(force, key, names, a, b, radii[a] + radii[b])
                distance = factor * length
                if force["name"] == "lj":
                    distance = min(distance, _pair_value(force, "cutoff", names, a, b, 2.5) * length)
                out[a, b] = max(out[a, b], distance)
    reasons = sorted({_RULES[f["name"]][2] for f in forces})
    reason = reasons[0] if len(reasons) == 1 else "the largest of " + ", ".join(reasons)
    return out, reason


def _pair_value(force, key, names, a, b, fallback):
    """One parameter of the pair (names[a], names[b]), as the engine resolves it."""
    for entry in force.get("pairs", []):
        pair = list(entry.get("species", []))
        if sorted(pair) == sorted([names[a], names[b]]) and key in entry:
            return float(entry[key])
    value = force.get(key)
    if value is None:
        return float(fallback)
    if not isinstance(value, dict):
        return float(value)
    va, vb = float(value[names[a]]), float(value[names[b]])
    if key in ("a", "sigma") and force.get("mixing", "geometric") == "arithmetic":
        return 0.5 * (va + vb)
    return math.sqrt(va * vb)


def describe(distances, names, reason):
    """The printed line: one distance, or one per pair of species."""
    if len(names) == 1 or np.allclose(distances, distances.flat[0]):
        values = f"contact distance {distances.flat[0]:.4g}"
    else:
        values = "contact distances " + ", ".join(
            f"{names[a]}-{names[b]} {distances[a, b]:.4g}"
            for a in range(len(names)) for b in range(a, len(names)))
    return f"clusters: {values} ({reason}; --contact overrides)"
