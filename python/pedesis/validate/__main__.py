"""python3 -m pedesis.validate [--quick] [--out DIR] [--only CASE,...] [--jobs N] [--list]:
the physics suite of `pedesis validate` (docs/validation.md). Exit status 0 when every case
passes, 1 when one fails, 2 for bad arguments."""
import argparse
import os
import platform
import signal
import sys
import time
from concurrent.futures import ThreadPoolExecutor, as_completed

from . import CASES
from .checks import CaseError, CaseResult
from .report import console_table, write_report
from .runner import Context, find_binary


def parse(argv):
    p = argparse.ArgumentParser(prog="pedesis validate",
                                description="Run pedesis's physics validation suite.")
    p.add_argument("--quick", action="store_true",
                   help="short runs: under 2 minutes on 2 cores (the full suite: under 30)")
    p.add_argument("--out", help="report directory (default runs/validate or "
                                 "runs/validate_quick)")
    p.add_argument("--only", help="comma-separated case names (see --list)")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                   help="cases run side by side, one core each (default: every core)")
    p.add_argument("--list", action="store_true", help="list the cases and exit")
    return p.parse_args(argv)


def chosen_cases(args):
    cases = [(name, fn) for name, fn, quick in CASES if quick or not args.quick]
    if args.only:
        wanted = [w.strip() for w in args.only.split(",") if w.strip()]
        known = {name for name, _, _ in CASES}
        unknown = [w for w in wanted if w not in known]
        if unknown:
            raise ValueError(f"--only: no case named {', '.join(unknown)} (cases: "
                             f"{', '.join(sorted(known))})")
        cases = [(name, fn) for name, fn, _ in CASES if name in wanted]
    return cases


def run_case(name, fn, ctx):
    """A case's result; a case that fails to measure becomes a failed result."""
    start = time.monotonic()
    try:
        result = fn(ctx)
    except (CaseError, ValueError, OSError, KeyError) as e:
        result = CaseResult(name, name, "-", error=f"{type(e).__name__}: {e}")
    result.seconds = time.monotonic() - start
    return result


def _interrupt(number, frame):
    raise KeyboardInterrupt


def first_sentence(doc):
    """A case's docstring up to its first ". " or ": " outside parentheses (a cut inside
    one left "([[force]] tail = true" hanging)."""
    text = " ".join(doc.split())
    depth = 0
    for k, ch in enumerate(text):
        depth += {"(": 1, ")": -1}.get(ch, 0)
        if depth == 0 and ch in ".:" and text[k + 1:k + 2] in (" ", ""):
            return text[:k]
    return text


def main(argv):
    args = parse(argv)
    try:
        cases = chosen_cases(args)
        if args.jobs < 1:
            raise ValueError(f"--jobs must be at least 1, not {args.jobs}")
    except ValueError as e:
        sys.stderr.write(f"pedesis: error: {e}\n")
        return 2
    if args.list:
        for name, fn, quick in CASES:
            summary = first_sentence(fn.__doc__)
            print(f"{name:18s} {summary}{'' if quick else ' (full suite only)'}")
        return 0
    mode = "quick" if args.quick else "full"
    out = args.out or os.path.join("runs", "validate_quick" if args.quick else "validate")
    try:
        ctx = Context(find_binary(), os.path.join(out, "runs"), args.quick)
    except CaseError as e:
        sys.stderr.write(f"pedesis: error: {e}\n")
        return 2
    print(f"pedesis validate: {len(cases)} cases ({mode}), {args.jobs} at a time, into {out}",
          flush=True)
    start = time.monotonic()
    results = {}
    # SIGTERM and SIGHUP end the suite like Ctrl-C: the runs under way are stopped, so
    # that none goes on after the suite has ended
    for number in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(number, _interrupt)
    pool = ThreadPoolExecutor(max_workers=args.jobs)
    try:
        futures = {pool.submit(run_case, name, fn, ctx): name for name, fn in cases}
        for done, future in enumerate(as_completed(futures), start=1):
            r = future.result()
            results[r.name] = r
            print(f"[{done}/{len(cases)}] {r.name}: {'pass' if r.passed else 'FAIL'} "
                  f"({r.seconds:.0f} s)", flush=True)
    except KeyboardInterrupt:
        ctx.stop()
        pool.shutdown(wait=True, cancel_futures=True)
        sys.stderr.write("pedesis validate: interrupted; no report written\n")
        return 130
    pool.shutdown()
    ordered = [results[name] for name, _ in cases]
    seconds = time.monotonic() - start
    print()
    print(console_table(ordered))
    machine = f"{platform.machine()}, {os.cpu_count()} cores, {platform.system()}"
    report = write_report(ordered, out, mode, seconds, machine)
    failed = [r.name for r in ordered if not r.passed]
    print(f"\n{len(ordered) - len(failed)} of {len(ordered)} cases passed in {seconds:.0f} s; "
          f"report: {report}")
    if failed:
        print(f"failed: {', '.join(failed)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
