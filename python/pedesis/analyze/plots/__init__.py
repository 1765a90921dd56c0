"""The figures of `pedesis analyze KIND RUN_DIR` (docs/analyze.md): speed, thermo, msd and
order, each a module with main() that reads the run directory and saves one figure.
Run them with ``python3 -m pedesis.analyze KIND RUN_DIR [--out FILE]``."""
