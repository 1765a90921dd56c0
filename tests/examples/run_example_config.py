"""Runs one example config of examples/ shortened, as `pedesis run` would from the
README's instructions, and fails if the run does not end with exit 0 and a log.

    /usr/bin/python3 tests/examples/run_example_config.py PEDESIS_BIN examples/abp_trap.toml OUT

The run is cut short with --set so that every example runs in seconds: a stepped run
([run] steps) to at most 200 steps, a run to a time or to a number of collisions per
particle to a tenth of it (at most 2 time units, 1 collision). An example that continues
another (a `--restart` in its `Run:` comment line) is run after that one, both shortened.
"""
import pathlib
import re
import subprocess
import sys
import tomllib


def shortened(config, more=0):
    """--set arguments that shorten the run; ``more`` steps beyond the usual 200 for a run
    that continues a shortened one."""
    run = config.get("run", {})
    sets = []
    if "steps" in run:
        sets.append(f"run.steps={min(int(run['steps']), 200) + more}")
    if "time" in run:
        sets.append(f"run.time={min(float(run['time']) / 10, 2.0)}")
    if "collisions_per_particle" in run:
        sets.append(f"run.collisions_per_particle={min(float(run['collisions_per_particle']) / 10, 1.0)}")
    if not sets:
        raise SystemExit(f"no [run] steps, time or collisions_per_particle to shorten: {run}")
    return [arg for s in sets for arg in ("--set", s)]


def run(binary, path, out, restart=None):
    config = tomllib.loads(path.read_text())
    args = [binary, "run", str(path), "--out", str(out), "--set", "output.progress=false"]
    args += shortened(config, 100 if restart else 0)
    if restart:
        args += ["--restart", str(restart)]
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0 or not (out / "log.csv").is_file():
        raise SystemExit(f"{' '.join(args)}: exit {r.returncode}\n{r.stdout}{r.stderr}")
    print(f"{path.name}: ran ({' '.join(args[5:])})")


def main(binary, example, out):
    path = pathlib.Path(example).resolve()
    out = pathlib.Path(out)
    # its own command line with "--restart runs/ka/checkpoint.bin" names the run it
    # continues, and the example whose command writes runs/ka starts it
    restart = re.search(rf"pedesis run examples/{re.escape(path.name)} .*--restart "
                        r"runs/(\w+)/checkpoint\.bin", path.read_text())
    if restart:
        writes = re.compile(rf"pedesis run examples/(\S+\.toml) --out runs/{restart.group(1)}\b")
        first = next((m for f in sorted(path.parent.glob("*.toml"))
                      if (m := writes.search(f.read_text()))), None)
        if not first:
            raise SystemExit(f"{path.name} continues runs/{restart.group(1)}, but names no "
                             "command that writes it")
        run(binary, path.parent / first.group(1), out / "first")
        run(binary, path, out / "continued", out / "first" / "checkpoint.bin")
    else:
        run(binary, path, out)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    main(*sys.argv[1:])
