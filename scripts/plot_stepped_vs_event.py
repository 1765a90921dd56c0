#!/usr/bin/python3
"""Stepped against event-driven dynamics from the same initial state, at decreasing dt.

Usage: plot_stepped_vs_event.py [--pedesis build/pedesis] [--work runs/stepped_vs_event]
                                [--out docs/images/stepped_vs_event.png] [--quick]

Runs the real binary (nothing is re-implemented here) and draws the three panels of
docs/images/stepped_vs_event.png, printing the numbers behind them as Markdown tables
for docs/stepped_vs_event.md:

A. Statistics (N = 1000 disks, packing fraction 0.2, walled box, equal speeds at the
   start, t = 400): for each seed one event run and one stepped run per dt. Wall pressure
   averaged over t > 20 (stepped / event - 1, mean and standard error over the seeds),
   and the final speeds: two-sample Kolmogorov-Smirnov distance between the stepped and
   the event run, and each against the Rayleigh distribution at the run's temperature.
B. Departure from the exact trajectory (N = 10000, same density, t <= 4): frames
   every 0.25 from both engines; the first frame in which some particle of the stepped
   run is more than 1e-4 from the event run's marks the first collision the stepped
   engine got wrong. (Rounding alone, amplified by the chaos of the gas, separates the
   two runs by at most ~3e-7 by t = 4; a missed collision changes a velocity by about
   g x / 6, i.e. moves a particle by ~1e-3 within a frame at the smallest dt.) Its rate (maximum likelihood over the seeds, censored at t = 4)
   against dt, and the prediction with no free parameter: the fraction x^2 / 24 of
   missed grazing collisions (x = g dt / sigma) averaged over the collisions, T dt^2 / 4
   in 2D for m = sigma = 1, times the event run's collision rate.

Uses Debian's python3-numpy and python3-matplotlib (hence /usr/bin/python3).
"""
import argparse
import json
import math
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ETA = 0.2
RADIUS = 0.5


def config(dynamics, seed, n, t_end, dt=None, frames=0.0, start="equal_speed"):
    length = math.sqrt(n * math.pi * RADIUS**2 / ETA)
    engine = f'[stepped]\ndt = {dt!r}\nmax_move = 1.0\n' if dynamics == "stepped" else ""
    return (
        f'dimension = 2\ndynamics = "{dynamics}"\nseed = {seed}\n'
        f'[box]\nlength = {length!r}\nboundary = "wall"\n'
        f'[[species]]\nname = "A"\ncount = {n}\nradius = {RADIUS}\nmass = 1.0\n'
        f'[initial]\npositions = "random"\nvelocities = "{start}"\nspeed = {math.sqrt(2.0)!r}\n'
        f"{engine}[run]\ntime = {t_end!r}\n"
        f'[output]\nlog_interval = 1.0\nsnapshot_interval = {frames!r}\nformats = ["xyz"]\n'
        f"progress = false\n"
    )


def run(pedesis, work, name, text):
    out = work / name
    cfg = work / f"{name}.toml"
    cfg.write_text(text)
    r = subprocess.run([pedesis, "run", str(cfg), "--out", str(out)], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{name}: pedesis exited with {r.returncode}:\n{r.stdout}{r.stderr}")
    return out


def xyz_frames(path):
    """(times, positions, velocities) of every frame, rows in particle id order."""
    lines = path.read_text().splitlines()
    times, pos, vel = [], [], []
    k = 0
    while k < len(lines):
        n = int(lines[k])
        comment = lines[k + 1]
        times.append(float(comment.split("Time=")[1].split()[0]))
        rows = np.array([ln.split()[1:7] for ln in lines[k + 2:k + 2 + n]], dtype=float)
        pos.append(rows[:, 0:2])
        vel.append(rows[:, 3:5])
        k += 2 + n
    return np.array(times), pos, vel


def log_table(run_dir):
    return np.genfromtxt(run_dir / "log.csv", delimiter=",", names=True)


def ks_two_sample(a, b):
    a, b = np.sort(a), np.sort(b)
    x = np.concatenate([a, b])
    return np.max(np.abs(np.searchsorted(a, x, side="right") / a.size -
                         np.searchsorted(b, x, side="right") / b.size))


def ks_rayleigh(speeds, temperature):
    v = np.sort(speeds)
    cdf = 1.0 - np.exp(-0.5 * v * v / temperature)
    k = np.arange(1, v.size + 1)
    return max(np.max(k / v.size - cdf), np.max(cdf - (k - 1) / v.size))


def statistics(pedesis, work, seeds, dts, n=1000, t_end=400.0, t_eq=20.0):
    rows = {dt: {"dp": [], "ks_event": [], "ks_theory": [], "late": []} for dt in dts}
    event_ks = []
    for seed in seeds:
        ev = run(pedesis, work, f"A_event_{seed}", config("event", seed, n, t_end))
        log = log_table(ev)
        keep = log["time"] > t_eq
        p_event = np.mean(log["pressure"][keep])
        _, _, v_ev = xyz_frames(ev / "trajectory.xyz")
        s_ev = np.linalg.norm(v_ev[-1], axis=1)
        T = float(np.mean(s_ev**2) / 2.0)
        event_ks.append(ks_rayleigh(s_ev, T))
        for dt in dts:
            st = run(pedesis, work, f"A_stepped_{seed}_{dt}", config("stepped", seed, n, t_end, dt))
            log = log_table(st)
            rows[dt]["dp"].append(np.mean(log["pressure"][log["time"] > t_eq]) / p_event - 1.0)
            _, _, v_st = xyz_frames(st / "trajectory.xyz")
            s_st = np.linalg.norm(v_st[-1], axis=1)
            rows[dt]["ks_event"].append(ks_two_sample(s_st, s_ev))
            rows[dt]["ks_theory"].append(ks_rayleigh(s_st, T))
            rows[dt]["late"].append(json.loads((st / "summary.json").read_text())["late_fraction"])
            shutil.rmtree(st)
        shutil.rmtree(ev)
    return rows, float(np.mean(event_ks)), n


def departures(pedesis, work, seeds, dts, n=10000, t_end=4.0, frame=0.25, threshold=1e-4):
    """For each dt, the frame interval (a, b] in which each seed's stepped run first left
    the event run, or None when it never did before t_end."""
    out = {dt: [] for dt in dts}
    collision_rates = []
    for seed in seeds:
        ev = run(pedesis, work, f"B_event_{seed}", config("event", seed, n, t_end, frames=frame,
                                                         start="maxwell_boltzmann"))
        times, r_ev, _ = xyz_frames(ev / "trajectory.xyz")
        summary = json.loads((ev / "summary.json").read_text())
        collision_rates.append(summary["pair_collisions"] / summary["time"])
        for dt in dts:
            st = run(pedesis, work, f"B_stepped_{seed}_{dt}",
                     config("stepped", seed, n, t_end, dt, frames=frame, start="maxwell_boltzmann"))
            t_st, r_st, _ = xyz_frames(st / "trajectory.xyz")
            assert np.allclose(t_st, times), "frames at different times"
            diff = np.array([np.max(np.linalg.norm(a - b, axis=1)) for a, b in zip(r_st, r_ev)])
            gone = np.nonzero(diff > threshold)[0]
            out[dt].append((times[gone[0] - 1], times[gone[0]]) if gone.size else None)
            shutil.rmtree(st)
        shutil.rmtree(ev)
    return out, float(np.mean(collision_rates)), t_end


def departure_rate(intervals, t_end):
    """Maximum-likelihood rate of a Poisson process whose first event is known only to
    within a frame interval (a, b], or not to have happened by t_end; with the range
    where the log-likelihood is within 1/2 of its maximum (about one standard error)."""
    grid = np.geomspace(1e-3, 1e2, 4000)
    logl = np.zeros_like(grid)
    for iv in intervals:
        if iv is None:
            logl -= grid * t_end
        else:
            a, b = iv
            logl += np.log(np.maximum(np.exp(-grid * a) - np.exp(-grid * b), 1e-300))
    k = int(np.argmax(logl))
    inside = grid[logl >= logl[k] - 0.5]
    return grid[k], inside.min(), inside.max()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--pedesis", default="build/pedesis")
    ap.add_argument("--work", default="runs/stepped_vs_event")
    ap.add_argument("--out", default="docs/images/stepped_vs_event.png")
    ap.add_argument("--quick", action="store_true", help="fewer seeds (a smoke test)")
    ap.add_argument("--replot", action="store_true",
                    help="redraw from WORK/results.json of an earlier run, running nothing")
    args = ap.parse_args()
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    dts = [1 / 16, 1 / 32, 1 / 64, 1 / 128, 1 / 256]
    seeds_a = [1, 2] if args.quick else list(range(1, 9))
    seeds_b = [1, 2] if args.quick else list(range(1, 33))

    saved = work / "results.json"
    if args.replot:
        res = json.loads(saved.read_text())
    else:
        stats, event_ks, n_a = statistics(args.pedesis, work, seeds_a, dts)
        dep, rate, t_end_b = departures(args.pedesis, work, seeds_b, dts[:4])
        res = {"stats": {repr(dt): stats[dt] for dt in dts}, "event_ks": event_ks, "n_a": n_a,
               "seeds_a": len(seeds_a), "seeds_b": len(seeds_b), "rate": rate,
               "t_end_b": t_end_b, "dep": {repr(dt): dep[dt] for dt in dts[:4]}}
        saved.write_text(json.dumps(res))
    stats = {dt: res["stats"][repr(dt)] for dt in dts}
    dep = {dt: [None if iv is None else tuple(iv) for iv in res["dep"][repr(dt)]] for dt in dts[:4]}
    event_ks, n_a, rate = res["event_ks"], res["n_a"], res["rate"]
    seeds_a, seeds_b = range(res["seeds_a"]), range(res["seeds_b"])
    fits = {dt: departure_rate(dep[dt], res["t_end_b"]) for dt in dts[:4]}

    print(f"A. statistics: N = {n_a}, eta = {ETA}, {len(seeds_a)} seeds; "
          f"event final speeds vs Rayleigh: KS {event_ks:.4f}")
    print("| dt | wall pressure, stepped / event - 1 | "
          "KS stepped vs event | KS stepped vs Rayleigh | late collisions |")
    print("|---|---|---|---|---|")
    for dt in dts:
        r = stats[dt]
        dp = np.array(r["dp"])
        se = dp.std(ddof=1) / math.sqrt(dp.size)
        print(f"| {dt:g} | {100 * dp.mean():+.2f}% ± {100 * se:.2f}% | "
              f"{np.mean(r['ks_event']):.4f} | {np.mean(r['ks_theory']):.4f} | "
              f"{np.mean(r['late']):.1e} |")
    print(f"\nB. departures: N = 10000, {len(seeds_b)} seeds, event collision rate {rate:.0f} "
          "pair collisions per unit time")
    print("| dt | departed / seeds | rate measured (68% range) | rate predicted "
          "(collision rate x T dt^2 / 4) | measured / predicted |")
    print("|---|---|---|---|---|")
    for dt in dts[:4]:
        r, lo, hi = fits[dt]
        departed = sum(iv is not None for iv in dep[dt])
        predicted = rate * dt * dt / 4.0
        print(f"| {dt:g} | {departed} / {len(seeds_b)} | {r:.3g} ({lo:.3g}–{hi:.3g}) | "
              f"{predicted:.3g} | {r / predicted:.2f} |")
    xs = np.log(dts[:4])
    ys = np.log([fits[dt][0] for dt in dts[:4]])
    ws = 1.0 / np.array([0.5 * (math.log(fits[dt][2]) - math.log(fits[dt][1])) for dt in dts[:4]])
    coef, cov = np.polyfit(xs, ys, 1, w=ws, cov="unscaled")
    order, order_se = coef[0], math.sqrt(cov[0, 0])
    chi2 = float(np.sum(((ys - np.log([rate * dt * dt / 4.0 for dt in dts[:4]])) * ws) ** 2))
    print(f"\nfitted order of the departure rate (weighted by the 68% ranges): "
          f"{order:.2f} ± {order_se:.2f}; the prediction, no free parameter: chi^2 = {chi2:.1f} "
          f"for {len(xs)} points")

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.4), dpi=110)
    x = np.array(dts)
    dp = np.array([np.mean(stats[dt]["dp"]) for dt in dts]) * 100
    se = np.array([np.std(stats[dt]["dp"], ddof=1) / math.sqrt(len(seeds_a)) for dt in dts]) * 100
    ax[0].errorbar(x, dp, yerr=se, fmt="o-", capsize=3, label="stepped / event - 1")
    ax[0].axhline(0.0, color="k", lw=0.8)
    ax[0].set_xscale("log")
    ax[0].set_xlabel("dt (at 1/16 the fastest disks move up to one radius per step)")
    ax[0].set_ylabel("wall pressure error (%)")
    ax[0].set_title(f"A. wall pressure, N = {n_a}, η = {ETA}, t = 20–400")
    ax[0].legend()
    crit = 1.949 * math.sqrt(2.0 / n_a)
    ax[1].plot(x, [np.mean(stats[dt]["ks_event"]) for dt in dts], "o-", label="stepped vs event")
    ax[1].plot(x, [np.mean(stats[dt]["ks_theory"]) for dt in dts], "s-", label="stepped vs Rayleigh")
    ax[1].axhline(event_ks, color="C2", ls=":", label="event vs Rayleigh")
    ax[1].axhline(crit, color="k", ls="--", label="critical, two-sample, α = 0.001")
    ax[1].axhline(1.949 / math.sqrt(n_a), color="k", ls=":", label="critical, one-sample, α = 0.001")
    ax[1].set_xscale("log")
    ax[1].set_xlabel("dt")
    ax[1].set_ylabel("Kolmogorov–Smirnov distance")
    ax[1].set_title("A. final speed distribution")
    ax[1].legend(fontsize=8, loc="center right", bbox_to_anchor=(1.0, 0.46))
    xb = np.array(dts[:4])
    meas = np.array([fits[dt][0] for dt in dts[:4]])
    lo = meas - np.array([fits[dt][1] for dt in dts[:4]])
    hi = np.array([fits[dt][2] for dt in dts[:4]]) - meas
    ax[2].errorbar(xb, meas, yerr=[lo, hi], fmt="o", capsize=3,
                   label=f"measured (first departure): order {order:.2f}")
    fine = np.geomspace(xb.min(), xb.max(), 50)
    ax[2].plot(fine, rate * fine**2 / 4.0, "k-", label="missed grazing collisions: rate · T dt²/4")
    ax[2].set_xscale("log")
    ax[2].set_yscale("log")
    ax[2].set_xlabel("dt")
    ax[2].set_ylabel("departures per unit time")
    ax[2].set_title("B. leaving the exact trajectory, N = 10000")
    ax[2].legend(fontsize=8)
    for a in ax:
        a.set_xticks(dts if a is not ax[2] else dts[:4])
        a.set_xticklabels([f"1/{round(1 / d)}" for d in (dts if a is not ax[2] else dts[:4])])
        a.minorticks_off()
    fig.tight_layout()
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
