"""The figures of `pedesis analyze KIND RUN_DIR` (docs/analyze.md): speed, thermo, msd,
order, structure, bond_order, clusters and transport, each a module with main() that
reads the run directory and saves one figure (transport_files.py, run_dir.py and
figure.py are what they share). Run them with
``python3 -m pedesis.analyze KIND RUN_DIR [--out FILE]``."""
