"""pedesis: particle dynamics of gases and active matter, scripted from Python.

The soft/active engine reads like the ABP tutorial (seed 001)::

    import pedesis
    s = pedesis.System(rcut=3.0, pad=0.5)
    s.read_init("init.json")
    e = pedesis.Evolver(s)
    e.add_force(pedesis.HarmonicForce(s, 10.0, 2.0))
    e.add_force(pedesis.SelfPropulsion(s, 1.0))
    e.add_torque(pedesis.PolarAlign(s, 1.0, 2.0))
    e.add_integrator(pedesis.BrownianIntegrator(s, T=0.0, gamma=1.0))
    e.add_integrator(pedesis.BrownianRotIntegrator(s, T=0.1, gamma=1.0))
    d = pedesis.Dump(s)
    e.run(1000, 0.01, every=10, callback=lambda step: d.dump_vtp(f"test_{step:05d}.vtp"))

and the hard-particle gases (event-driven or time-stepped) are pedesis.Gas.
Everything runs in C++; numpy arrays view its memory. See docs/python.md. In a
notebook, pedesis.show(run_dir) (or a Simulation or pedesis.open_run(run_dir) ending a
cell) draws a run inline, and pedesis.movie(run_dir) plays it (pedesis/show.py).
"""
try:
    from ._version import __version__  # the build's (CMake or setup.py): `pedesis --version`'s
except ImportError:  # the source tree's python/, unbuilt: no version to tell
    __version__ = "unknown"
from .show import open_run, show, movie  # noqa: F401  (pure Python: the CLI draws)
from .box import Box  # noqa: F401  (pure Python: pedesis.analyze takes it too)
try:
    from . import _pedesis  # noqa: F401
except ImportError as _error:
    # a build without the compiled module (the sanitizer build has none): the pure-Python
    # parts (pedesis.analyze and its plots) still work; the engines say what is missing
    _missing = _error

    def __getattr__(name):
        raise ImportError(f"pedesis.{name} needs pedesis' compiled module, which this "
                          f"build lacks ({_missing})")
else:
    from ._engines import *  # noqa: F401,F403
    from ._engines import __all__ as _engine_names
    from . import builder  # noqa: F401  (needs the names above)

    __all__ = [*_engine_names, "builder", "open_run", "show", "movie", "Box"]
