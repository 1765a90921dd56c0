"""The compiled engines as the package shows them: the classes of _pedesis, one Plugin
subclass per catalogue entry, Dump. pedesis/__init__.py imports everything here."""
import inspect as _inspect

from . import _pedesis
from ._pedesis import Evolver, Gas, InputError, Plugin, RunError, System
from .simulation import Callback, GSDWriter, Periodic, Simulation, XYZWriter

__all__ = [
    "System", "Evolver", "Dump", "Gas", "Plugin", "InputError", "RunError",
    "HarmonicForce", "WcaForce", "LjForce", "SelfPropulsion", "PolarAlign", "BrownianIntegrator",
    "BrownianRotIntegrator", "LangevinIntegrator", "NVEIntegrator",
    "Simulation", "Periodic", "GSDWriter", "XYZWriter", "Callback",
]

def _plugin_class(entry):
    """One Plugin subclass per catalogue entry, so that the C++ catalogue (the same one
    `pedesis run` reads configs with) stays the single list of terms and parameters."""
    cls_name = entry["python_class"]
    keys = [p["key"] for p in entry["params"]]
    options = [f["key"] for f in entry["flags"]]
    if entry["pair_potential"]:
        options += ["pairs", "mixing"]

    def __init__(self, system, *args, **kwargs):
        if len(args) > len(keys):
            raise InputError(f"{cls_name}: takes at most {len(keys)} parameters "
                             f"({', '.join(keys) or 'none'}), got {len(args)}")
        params = dict(zip(keys, args))
        for k, v in kwargs.items():
            if k in params:
                raise InputError(f"{cls_name}: {k} given twice")
            params[k] = v
        params = {k: v for k, v in params.items() if v is not None}  # None: the default
        Plugin.__init__(self, entry["kind"], entry["name"], params, cls_name)
        if not isinstance(system, System):
            raise InputError(f"{cls_name}: the first argument must be the pedesis.System")
        self.check_species(system)
        self._params = params

    def __repr__(self):
        args = ", ".join(f"{k}={v!r}" for k, v in self._params.items())
        return f"pedesis.{cls_name}({args})"

    lines = [f"{entry['kind'].capitalize()} '{entry['name']}' of the soft/active engine.", "",
             f"    {entry['formula']}", "", "Parameters:",
             "    system: the pedesis.System it acts on"]
    for p in entry["params"]:
        need = "required" if p["required"] else "optional"
        per = "; a number, or a dict {species: number}" if p["per_species"] else ""
        lines.append(f"    {p['key']}: {p['meaning']} ({need}{per})")
    for f in entry["flags"]:
        lines.append(f"    {f['key']}: {f['meaning']} (optional; True or False)")
    if entry["pair_potential"]:
        lines += ["    pairs: values for pairs of species, {(\"A\", \"B\"): {parameter: number}}",
                  "    mixing: \"geometric\" (default) or \"arithmetic\", for pairs not given"]
    lines += ["", f"Config equivalent: [[{entry['kind']}]] name = \"{entry['name']}\"."]
    params = [_inspect.Parameter("self", _inspect.Parameter.POSITIONAL_ONLY),
              _inspect.Parameter("system", _inspect.Parameter.POSITIONAL_OR_KEYWORD)]
    for p in entry["params"]:
        default = _inspect.Parameter.empty if p["required"] else None
        params.append(_inspect.Parameter(p["key"], _inspect.Parameter.POSITIONAL_OR_KEYWORD,
                                         default=default))
    for key in options:
        params.append(_inspect.Parameter(key, _inspect.Parameter.KEYWORD_ONLY, default=None))
    __init__.__signature__ = _inspect.Signature(params)
    __init__.__doc__ = "\n".join(lines)
    return type(cls_name, (Plugin,), {"__init__": __init__, "__repr__": __repr__,
                                      "__doc__": "\n".join(lines), "__module__": "pedesis"})


for _entry in _pedesis._catalogue:
    globals()[_entry["python_class"]] = _plugin_class(_entry)
    if _entry["python_class"] not in __all__:  # every catalogue entry is pedesis.<Class>
        __all__.append(_entry["python_class"])


class Dump:  # (pedesis.Dump)
    """Snapshots of a System, as the tutorial's Dump: dump_vtp for ParaView, dump_json
    for the tutorial's JSON (System.read_init reads it back). Files are written to a
    temporary name and renamed, so a file that exists is complete."""

    def __init__(self, system):
        if not isinstance(system, System):
            raise InputError("Dump: the argument must be a pedesis.System")
        self.system = system

    def dump_vtp(self, path):
        """Writes a VTP PolyData file: positions, directors, velocities, forces, ids, types."""
        self.system.write_vtp(path)

    def dump_json(self, path):
        """Writes the state in the ABP tutorial's JSON layout."""
        self.system.write_json(path)

