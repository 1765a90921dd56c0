"""examples/slurm/pedesis_job.sh carries a run to its end as a chain of Slurm jobs. The
test plays Slurm by hand: a fake `sbatch` on PATH only records what it was asked to
submit; each job is the script copied where slurmd keeps it, run by bash in the submit
directory; the time limit's warning is a USR1 to the job's shell at a random instant
(--signal=B:USR1), scancel a TERM to every process of the job. Each submitted job is run
in turn until one finishes the run, which must then be the uninterrupted run's, byte for
byte, but for the timings of summary.json."""
import json
import os
import pathlib
import random
import shutil
import signal
import subprocess
import time

REPO = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = REPO / "examples" / "slurm" / "pedesis_job.sh"

# tests/support/kill_and_resume.hpp's event config, made longer (about 2.5 s here): a
# run of two species writing GSD, XYZ and VTP outputs, with checkpoints of its own.
CONFIG = """dimension = 2
seed = 3
[box]
length = 50.0
[[species]]
name = "A"
count = 800
radius = 0.5
[[species]]
name = "B"
count = 100
radius = 0.8
mass = 3.0
[run]
time = 1200.0
[output]
log_interval = 2.0
snapshot_interval = 20.0
checkpoint_interval = 30.0
formats = ["gsd", "xyz", "vtp"]
progress = false
"""

FAKE_SBATCH = """#!/bin/sh
printf '%s\\t' "$@" >> "$SBATCH_CALLS"
echo >> "$SBATCH_CALLS"
echo "Submitted batch job $$"
"""

TIMINGS = ("wall_seconds", "stepping_seconds", "particle_steps_per_second",
           "collisions_per_second", "cpu_seconds")

# The jobs in turn, and what Slurm sends each: the time limit's warning (USR1) to the batch
# shell alone, scancel's TERM to every process of the job, or nothing: the job that
# finishes the run, then one submitted by mistake, which must find the run finished.
JOBS = ["USR1", "USR1", "TERM", None, None]


def files_of(directory):
    return {p.relative_to(directory).as_posix(): p.read_bytes()
            for p in sorted(directory.rglob("*")) if p.is_file()}


def without_timings(summary):
    j = json.loads(summary)
    for key in TIMINGS:
        j.pop(key, None)
    return j


def test_the_slurm_job_resubmits_itself_until_the_run_is_done(tmp_path, pedesis_bin):
    seed = int(os.environ.get("PEDESIS_KILL_SEED", random.randrange(1 << 30)))
    rng = random.Random(seed)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive")
    (tmp_path / "run.toml").write_text(CONFIG)
    t0 = time.monotonic()
    ref = subprocess.run([pedesis_bin, "run", "run.toml", "--out", "ref"], cwd=tmp_path,
                         env=env, capture_output=True, text=True)
    run_seconds = time.monotonic() - t0
    assert ref.returncode == 0, ref.stderr

    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "sbatch").write_text(FAKE_SBATCH)
    (bin_dir / "sbatch").chmod(0o755)
    calls = tmp_path / "sbatch_calls.txt"
    env.update(PATH=f"{bin_dir}{os.pathsep}{env['PATH']}", SBATCH_CALLS=str(calls),
               CONFIG="run.toml", OUT="run", PEDESIS=pedesis_bin,
               PEDESIS_JOB_SCRIPT=str(SCRIPT))
    spool = tmp_path / "spool"
    spool.mkdir()

    submitted = SCRIPT  # the first job, submitted by hand
    history = []  # (signal, exit code, seconds from the signal to the job's end)
    for job, sig in enumerate(JOBS):
        # slurmd runs a copy of the submitted script: $0 is not the user's file
        copy = spool / f"job{job}" / "slurm_script"
        copy.parent.mkdir()
        shutil.copy(submitted, copy)
        calls.write_text("")
        output = tmp_path / f"pedesis-{job}.out"
        with open(output, "w") as out:
            p = subprocess.Popen(["bash", str(copy)], cwd=tmp_path, env=env, stdout=out,
                                 stderr=subprocess.STDOUT, start_new_session=True)
        try:
            latency = None
            if sig:
                time.sleep(rng.uniform(0.1, 0.22) * run_seconds)
                assert p.poll() is None, (
                    f"seed {seed}: job {job} ended before its {sig}: {output.read_text()}")
                sent = time.monotonic()
                if sig == "USR1":
                    p.send_signal(signal.SIGUSR1)
                else:
                    os.killpg(p.pid, signal.SIGTERM)
                code = p.wait(timeout=10)
                latency = time.monotonic() - sent
            else:
                code = p.wait(timeout=60)
        finally:
            # nothing of a job outlives it, even when the test fails
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            p.wait()
        text = output.read_text()
        requests = [line.rstrip("\t").split("\t") for line in calls.read_text().splitlines()]
        history.append((sig, code, latency))
        context = f"seed {seed}, job {job} ({sig}), exit {code}, sbatch {requests}:\n{text}"
        assert latency is None or latency < 5.0, context

        if sig == "USR1":
            # checkpointed at the time limit: the job submits the same script again
            assert code == 0 and requests == [[str(SCRIPT)]], context
            assert "submitted the next job" in text, context
            submitted = pathlib.Path(requests[0][0])
        elif sig == "TERM":
            # cancelled: no new job; the user submits one by hand to continue
            assert code == 75 and requests == [], context
            assert f"to continue: sbatch {SCRIPT}" in text, context
        else:
            # unsignalled: the first ends the run, the second finds it finished
            assert code == 0 and requests == [], context
            assert "run: the run is done" in text, context
            if job == len(JOBS) - 1:
                assert "holds a finished run" in text, context
            else:
                assert "holds a finished run" not in text, context

    want, got = files_of(tmp_path / "ref"), files_of(tmp_path / "run")
    assert sorted(got) == sorted(want), f"seed {seed}"
    for name in want:
        if name == "summary.json":
            assert without_timings(got[name]) == without_timings(want[name]), f"seed {seed}"
        else:
            assert got[name] == want[name], f"seed {seed}: {name} differs"
    print(f"seed {seed}, run {run_seconds:.2f} s, jobs (signal, exit, seconds to end): "
          f"{history}")
