"""A dilute elastic hard-disk gas under gravity in the event engine ([event] gravity,
issue 53): its density profile is barometric, n(y) ~ exp(-m g y / T) with T its own
kinetic temperature, and the floor carries its weight."""
import numpy as np

from ...analyze import read_frames
from ..checks import CaseResult, Check
from ..stats import block_mean
from .active_models import _log_after

WIDTH, HEIGHT, COUNT, G = 8000.0, 16.0, 200, 1.0


def _config(time, snapshot_interval):
    return f"""dimension = 2
dynamics = "event"
seed = 11

[box]
lengths = [{WIDTH}, {HEIGHT}]
boundary = ["periodic", "wall"]

[[species]]
name = "A"
count = {COUNT}
radius = 0.5
positions = "random"
region = {{ lo = [{-WIDTH / 2}, {-HEIGHT / 2}], hi = [{WIDTH / 2}, {-HEIGHT / 2 + 2.0}] }}
velocities = "maxwell_boltzmann"
temperature = 1.0

[event]
gravity = [0.0, {-G}]

[run]
time = {time}

[output]
log_interval = 10.0
snapshot_interval = {snapshot_interval}
formats = ["gsd"]
progress = false
"""


def _slope(heights, low, high, bin_width=0.25):
    """The weighted least-squares slope of ln(counts) against height over [low, high]."""
    edges = np.arange(low, high + bin_width / 2, bin_width)
    counts, _ = np.histogram(heights, bins=edges)
    keep = counts >= 10
    centres = 0.5 * (edges[1:] + edges[:-1])
    return float(np.polyfit(centres[keep], np.log(counts[keep]), 1, w=np.sqrt(counts[keep]))[0])


def barometric_gas(ctx):
    """200 hard disks (diameter 1, mass 1) in 8000 x 16, walls along y, g = 1, started in
    the lowest 2 at T = 1: after settling, the slope of ln n(y) from 1 to 6 scale heights
    against -m g / T, and the floor's force per length against the weight per length."""
    settle, sample = 4000.0, ctx.pick(16000.0, 40000.0)
    run = ctx.run("barometric_gas", "gas", _config(settle + sample, 2.0))
    traj = read_frames(str(run))
    frames = traj.positions[np.asarray(traj.times) >= settle]
    heights = frames[:, :, 1] + HEIGHT / 2 - 0.5  # above the centres' lowest height
    T, T_err = block_mean(_log_after(ctx, run, "temperature", settle + 10.0))
    slopes = [_slope(block.ravel(), T, 6.0 * T) for block in np.array_split(heights, 10)]
    ratio = -np.mean(slopes) * T / G
    ratio_err = np.std(slopes, ddof=1) / np.sqrt(len(slopes)) * T / G
    checks = [Check.near(
        "slope of ln n(y) over -m g / T", float(ratio), float(ratio_err), 1.0, 0.03,
        "barometric law n ~ exp(-m g y / T) (the canonical distribution in a uniform field)",
        f"{len(frames)} frames 2 apart after t = {settle:g}, fitted from 1 to 6 scale heights "
        f"with T = {T:.4f} +- {T_err:.1g} the log's; the excluded volume at the floor's "
        "area fraction ~0.02 lowers the ratio by ~1.5 %; 3 %")]
    # pressure_yy is the mean of the floor's and the ceiling's force per length; the
    # ceiling, 20 scale heights up, gets nothing
    pyy, pyy_err = block_mean(_log_after(ctx, run, "pressure_yy", settle + 10.0))
    weight = COUNT * G / WIDTH
    checks.append(Check.near(
        "floor force per length over the weight per length", 2.0 * pyy / weight,
        2.0 * pyy_err / weight, 1.0, 0.01,
        "momentum balance: the floor carries the weight (exact in the mean)",
        "log rows every 10 after settling; the total momentum's change over the run is "
        "~1e-5 of the weight's impulse; 1 %"))

    def plot(ax):
        h = heights.ravel()
        counts, edges = np.histogram(h, bins=np.arange(0.0, 8.0 * T, 0.25))
        centres = 0.5 * (edges[1:] + edges[:-1])
        ax.semilogy(centres, counts / counts[0], "o", ms=3, label="event engine")
        ax.semilogy(centres, np.exp(-G * (centres - centres[0]) / T), "k-",
                    label="exp(-m g y / T)")
        ax.set(xlabel="height above the floor's contact plane", ylabel="n(y) / n(0)",
               title="hard disks under gravity")
        ax.legend()

    ran = (f"2D, N = {COUNT} hard disks in {WIDTH:g} x {HEIGHT:g} (walls along y), g = {G:g}, "
           f"elastic; settled for t = {settle:g}, sampled for t = {sample:g}")
    return CaseResult("barometric_gas", "Barometric profile of hard disks under gravity", ran,
                      checks, plot)
