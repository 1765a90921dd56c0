"""python3 -m pedesis.analyze KIND RUN_DIR [--out FILE]: the figures of `pedesis analyze`
(speed, thermo, msd, order, structure, bond_order, clusters, transport; docs/analyze.md).
Bad input: one line on stderr, exit 2."""
import importlib
import os
import sys

KINDS = ("speed", "thermo", "msd", "order", "structure", "bond_order", "clusters", "transport")


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
    sys.stdout = _ReaderMayLeave(sys.stdout)
    code = main_guard(plot.main)
    sys.stdout.flush()  # (a buffered stdout's last lines go now, not in the shutdown)
    return code


class _ReaderMayLeave:
    """stdout for `pedesis analyze clusters RUN | head -3`: once the reader has closed the
    pipe, the remaining lines go to /dev/null and the figure is still drawn and saved,
    exit 0, as a Unix filter ends quietly, instead of a BrokenPipeError traceback."""

    def __init__(self, stream):
        self._stream = stream

    def write(self, text):
        try:
            return self._stream.write(text)
        except BrokenPipeError:
            self._to_devnull()
            return len(text)

    def flush(self):
        try:
            self._stream.flush()
        except BrokenPipeError:
            self._to_devnull()

    def _to_devnull(self):
        # the stream keeps its descriptor (and Python flushes it once more at exit), so
        # that descriptor now leads to /dev/null
        null = os.open(os.devnull, os.O_WRONLY)
        os.dup2(null, self._stream.fileno())
        os.close(null)

    def __getattr__(self, name):
        return getattr(self._stream, name)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
