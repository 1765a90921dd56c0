"""python3 -m pedesis.analyze KIND RUN_DIR [--out FILE]: the figures of `pedesis analyze`
(speed, thermo, msd, order, structure, bond_order, clusters; docs/analyze.md). Bad input: one line on stderr, exit 2."""
import importlib
import sys

KINDS = ("speed", "thermo", "msd", "order", "structure", "bond_order", "clusters")


def main(argv):
    if not argv or argv[0] not in KINDS:
        sys.stderr.write(f"usage: python3 -m pedesis.analyze {{{','.join(KINDS)}}} RUN_DIR "
                         "[--out FILE]\n")
        return 2
    kind = argv[0]
    try:
        plot = importlib.import_module(f"pedesis.analyze.plots.{kind}")
        from .plots.run_dir import main_guard
    except ImportError as e:
        if e.name not in ("numpy", "matplotlib", "scipy"):
            raise
        sys.stderr.write(f"pedesis: error: the plots need Debian's python3-numpy, python3-scipy "
                         f"and python3-matplotlib ({e}); apt-get install python3-matplotlib "
                         "python3-scipy\n")
        return 2
    # the figure's command line reads sys.argv, as when pedesis analyze ran a script
    sys.argv = [f"pedesis analyze {kind}", *argv[1:]]
    return main_guard(plot.main)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
