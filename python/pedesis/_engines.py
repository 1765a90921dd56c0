"""The compiled engines as the package shows them: the classes of _pedesis, one Plugin
subclass per catalogue entry, Dump. pedesis/__init__.py imports everything here."""
import functools as _functools
import inspect as _inspect
import warnings as _warnings

from . import _pedesis
from ._pedesis import Evolver, Gas, InputError, Plugin, RunError, System
from .simulation import Callback, GSDWriter, Periodic, Simulation, XYZWriter
from . import recording as _recording
from .recording import Recording

__all__ = [
    "System", "Evolver", "Dump", "Gas", "Plugin", "InputError", "RunError",
    "HarmonicForce", "WcaForce", "LjForce", "SelfPropulsion", "PolarAlign", "BrownianIntegrator",
    "BrownianRotIntegrator", "LangevinIntegrator", "NVEIntegrator", "BussiIntegrator",
    "NoseHooverIntegrator", "Wall",
    "Gravity", "HarmonicTrap", "ActiveOU",
    "ActiveTorque", "RunAndTumble", "NematicAlign", "VelocityAlign",
    "Simulation", "Periodic", "GSDWriter", "XYZWriter", "Callback", "StopName", "Recording",
]

def _plugin_class(entry):
    """One Plugin subclass per catalogue entry, so that the C++ catalogue (the same one
    `pedesis run` reads configs with) stays the single list of terms and parameters."""
    cls_name = entry["python_class"]
    keys = [p["key"] for p in entry["params"]]
    options = [f["key"] for f in entry["flags"]] + [c["key"] for c in entry["choices"]]
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

    # The parameters read back as attributes (None: the default), and an assignment
    # raises: an Evolver builds its own term from them when the term is added, so a
    # changed attribute would change nothing (bi.T = 1.0 used to pass silently).
    def __getattr__(self, name):
        if name in keys or name in options:
            return self.__dict__.get("_params", {}).get(name)
        raise AttributeError(f"{cls_name} has no attribute {name!r}")

    def __setattr__(self, name, value):
        if name.startswith("_"):
            Plugin.__setattr__(self, name, value)
            return
        if name in keys or name in options:
            raise AttributeError(
                f"{cls_name}.{name}: a term's parameters are fixed when it is made (an "
                f"Evolver holds its own copy of each term added); make a new "
                f"{cls_name}(system, ..., {name}={value!r}) for a new Evolver, or, in a "
                f"pedesis.Simulation, change a running parameter with sim.set(...)")
        raise AttributeError(f"{cls_name} has no parameter {name!r} (it has: "
                             f"{', '.join(keys + options) or 'none'})")

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
                                      "__getattr__": __getattr__, "__setattr__": __setattr__,
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



# The names Gas.run returned before it took those of `pedesis run` (summary.json's
# stopped_by), with the name each became (issue 28).
_RENAMED_STOPS = {"no_events": "no more events", "energy": "energy_fraction"}


class StopName(str):
    """The stop condition a run met, by the name `pedesis run` writes as summary.json's
    "stopped_by": "time", "collisions_per_particle", "steps", "energy_fraction",
    "no more events", "grown". A plain str, except that it also equals the names
    Gas.run returned before, "no_events" and "energy", with a DeprecationWarning, so
    that scripts comparing against them keep working until they change."""

    __slots__ = ()

    def __eq__(self, other):
        same = str.__eq__(self, other)
        if same is NotImplemented or same:
            return same
        if isinstance(other, str) and _RENAMED_STOPS.get(str(other)) == str(self):
            _warnings.warn(f"Gas.run: the stop name {str(other)!r} is deprecated; it is "
                           f"{str(self)!r} now, as in summary.json's stopped_by",
                           DeprecationWarning, stacklevel=2)
            return True
        return False

    def __ne__(self, other):
        same = self.__eq__(other)
        return same if same is NotImplemented else not same

    # a dict or set keyed by the new names finds it; the old names only compare equal
    __hash__ = str.__hash__


def _named_stops(run):
    @_functools.wraps(run)
    def wrapped(self, *args, **kwargs):
        return StopName(run(self, *args, **kwargs))
    return wrapped


Gas.run = _recording.recording_gas_run(_named_stops(Gas.run))

# Frames recorded as the run goes, and the inline view (pedesis/recording.py)
Gas.record = _recording.gas_record
Gas._repr_html_ = _recording.gas_repr_html
System._repr_html_ = _recording.system_repr_html
Evolver.record = _recording.evolver_record
Evolver.run = _recording.recording_evolver_run(Evolver.run)
Evolver.evolve = _recording.recording_evolve(Evolver.evolve)
