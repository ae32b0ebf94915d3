"""Gyro bias estimation beside the peers, as a scenario mix on synthetic streams whose truth is known:
quatprop's ``BiasEstimator`` (through the Python package, bit for bit the Rust core), Fusion's
``FusionBias`` (imufusion, its pip package: the C code) and VQF's rest and motion bias estimation (vqf, its
pip package), each as its users call it.

    python python/benchmarks/bias.py [--out docs] [--seeds 32] [--quick]

Writes ``docs/bias.md`` (the tables, the mix's score) and ``docs/bias.png`` (the knob's curve against the
peers' points, and one seed of each scenario). The sensor model (every stream): float32 rates at 200 Hz,
white noise σ = 0.1 °/s per sample and axis (0.0071 °/s/√Hz), a bias of (0.6, −0.4, 0.25) °/s that walks
with 3·10⁻⁴ °/s/√s; an accelerometer reading gravity in the body axes (reference z up) plus 0.02 m/s²
noise and, in motion, the linear acceleration of a hand (bumps of up to 0.5 m/s²). Motions are smooth:
every change of rate ramps (a raised cosine). The scenarios:

- start: at rest from power-on, 60 s: how long until |b̂ − b| stays below 0.05 °/s;
- step: at rest, the bias steps by (+0.3, 0, −0.2) °/s at 60.37 s: how long until it is followed;
- turns: 30 s at rest, then a turn about a horizontal (x) or the vertical (z) axis at 0.5, 1 or 2 °/s for
  20 or 60 s (1 s ramps): the share of the turn's angle taken for bias;
- short motions: 30 s at rest, then every 4–12 s a motion of 0.4–2 s (peaks of 5–40 °/s about a random
  axis, with the hand's linear acceleration), no bias change: the largest wrong bias |b̂ − b| after 5 s;
- warm-up: 10 min, the bias moving by 0.005 °/s per °C as the sensor warms from 25 to 45 °C (τ = 3 min),
  20 s at rest and 40 s of motion in turn: rms |b̂ − b|;
- long rest: 600 s at rest, the bias walking and drifting (±0.02 °/s, period 400 s): rms |b̂ − b| after
  the first 60 s;
- change in motion (the knob's other side, not in the mix: no estimator can see it before the next rest):
  30 s at rest, 20 s of motion in which the bias steps by 0.2 °/s, then 120 s at rest: how long after the
  motion until it is followed.

Each metric is compared with the better of the two peers (ratio ≤ 1: at least as good); the mix's score is
the geometric mean of the ratios.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Dict, List, Optional, Tuple

import numpy as np

import quatprop

FS = 200.0
DT = 1.0 / FS
DEG = np.pi / 180.0
G = 9.81
B0_DPS = np.array([0.6, -0.4, 0.25])
NOISE_DPS = 0.1
WALK_DPS = 3e-4  # °/s/√s
ACC_NOISE = 0.02
EVERY = 20  # samples between two reads of an estimate (0.1 s)
GATE = 3.0 * DEG
FOLLOWED = 0.05  # °/s


def progress(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


# --- streams -------------------------------------------------------------------------------------------

@dataclass
class Stream:
    """A synthetic stream: f32 rates (rad/s), the true bias and rates (rad/s), accelerations (m/s²)."""

    gyr: np.ndarray
    bias: np.ndarray
    rate: np.ndarray
    acc: np.ndarray


def bump(t: np.ndarray, start: float, ramp: float, hold: float) -> np.ndarray:
    """0 before ``start``, a raised-cosine ramp of ``ramp`` s to 1, ``hold`` s at 1, the ramp back to 0."""
    x = t - start
    up = np.clip(x / ramp, 0.0, 1.0)
    down = np.clip((x - ramp - hold) / ramp, 0.0, 1.0)
    return 0.5 * (1.0 - np.cos(np.pi * up)) * 0.5 * (1.0 + np.cos(np.pi * down))


def attitude_of(rate: np.ndarray) -> np.ndarray:
    """The true attitude (body to reference, [w, x, y, z]) of the true rates, from the identity (f64)."""
    return quatprop.integrate(rate, dt=DT, precision="f64")


def gravity_in_body(q: np.ndarray) -> np.ndarray:
    """R(q)ᵀ (0, 0, G): the specific force at rest in body axes."""
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    # The third row of R(q) (reference z in body axes).
    return G * np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=1)


def make(seconds: float, seed: int, rate: Optional[np.ndarray] = None,
         bias_extra: Optional[Callable[[np.ndarray], np.ndarray]] = None,
         linear: Optional[np.ndarray] = None) -> Stream:
    n = int(round(seconds * FS))
    t = (np.arange(n) + 1) * DT
    rng = np.random.default_rng(seed)
    walk = np.cumsum(WALK_DPS * DEG * math.sqrt(DT) * rng.standard_normal((n, 3)), axis=0)
    b = B0_DPS * DEG + walk
    if bias_extra is not None:
        b = b + bias_extra(t)
    w = np.zeros((n, 3)) if rate is None else rate
    gyr = (w + b + NOISE_DPS * DEG * rng.standard_normal((n, 3))).astype(np.float32)
    f = gravity_in_body(attitude_of(w)) if rate is not None else np.tile([0.0, 0.0, G], (n, 1))
    if linear is not None:
        f = f + linear
    acc = f + ACC_NOISE * rng.standard_normal((n, 3))
    return Stream(gyr, b, w, acc)


def times(n: int) -> np.ndarray:
    return (np.arange(n) + 1) * DT


def turn_rate(seconds: float, axis: int, dps: float, start: float, hold: float) -> np.ndarray:
    t = times(int(round(seconds * FS)))
    w = np.zeros((len(t), 3))
    w[:, axis] = dps * DEG * bump(t, start, 1.0, hold)
    return w


def short_motions(seconds: float, seed: int) -> Tuple[np.ndarray, np.ndarray]:
    """Rates and linear accelerations of hand-held short motions after 30 s at rest."""
    rng = np.random.default_rng(10_000 + seed)
    t = times(int(round(seconds * FS)))
    w = np.zeros((len(t), 3))
    lin = np.zeros((len(t), 3))
    at = 30.0
    while at < seconds - 15.0:
        length = rng.uniform(0.4, 2.0)
        ramp = length / 2.0
        axis = rng.standard_normal(3)
        axis /= np.linalg.norm(axis)
        peak = rng.uniform(5.0, 40.0) * DEG
        shape = bump(t, at, ramp, 0.0)
        w += peak * shape[:, None] * axis
        push = rng.standard_normal(3)
        lin += 0.5 * push / np.linalg.norm(push) * np.sin(np.pi * np.clip((t - at) / length, 0, 1))[:, None]
        at += length + rng.uniform(4.0, 12.0)
    return w, lin


def short_motions_args(seconds: float, seed: int):
    w, lin = short_motions(seconds, seed)
    return w, None, lin


def warmup(seconds: float) -> Tuple[np.ndarray, Callable[[np.ndarray], np.ndarray]]:
    t = times(int(round(seconds * FS)))
    temperature = lambda tt: 25.0 + 20.0 * (1.0 - np.exp(-tt / 180.0))
    slope = np.array([0.005, -0.005, 0.005]) * DEG
    extra = lambda tt: slope * (temperature(tt) - 25.0)[:, None]
    moving = np.zeros(len(t))
    for k in range(int(seconds // 60)):
        moving += bump(t, 60.0 * k + 20.0, 1.0, 38.0)
    w = np.stack([0.35 * np.sin(0.9 * t), 0.3 * np.sin(1.3 * t + 1.0), 0.5 * np.sin(0.37 * t) + 0.3], axis=1)
    return w * moving[:, None], extra


# --- the estimators: each returns the estimate (rad/s) every EVERY samples, shape (n // EVERY, 3) -------

def quatprop_run(s: Stream, acc: bool = True, **options) -> np.ndarray:
    est = quatprop.BiasEstimator(window=1.0, gate=GATE, **options)
    st = quatprop.Stream(dt=DT, bias=est, precision="f32")
    out = np.empty((len(s.gyr) // EVERY, 3))
    for k in range(len(out)):
        sl = slice(k * EVERY, (k + 1) * EVERY)
        st.update(s.gyr[sl], acc=s.acc[sl] if acc else None)
        out[k] = st.bias
    return out


def fusion_run(s: Stream) -> np.ndarray:
    import imufusion

    settings = imufusion.BiasSettings()
    settings.sample_rate = FS  # stationary threshold 3 °/s, period 3 s: its defaults
    f = imufusion.Bias()
    f.set_settings(settings)
    dps = s.gyr.astype(np.float64) / DEG
    out = np.empty((len(s.gyr) // EVERY, 3))
    for k in range(len(out)):
        for g in dps[k * EVERY:(k + 1) * EVERY]:
            f.update(g)
        out[k] = np.asarray(f.get_offset()) * DEG
    return out


def vqf_run(s: Stream) -> np.ndarray:
    from vqf import VQF

    v = VQF(DT)
    r = v.updateBatch(np.ascontiguousarray(s.gyr, dtype=np.float64), np.ascontiguousarray(s.acc))
    return r["bias"][EVERY - 1::EVERY]


QUATPROP = "quatprop BiasEstimator (1 s, 3 °/s gate, accelerometer)"
FUSION = "Fusion FusionBias (imufusion defaults, gyro)"
VQF_NAME = "VQF rest + motion bias (vqf defaults, gyro + acc)"


def estimators(drift: Optional[float] = None) -> Dict[str, Callable[[Stream], np.ndarray]]:
    opts = {} if drift is None else {"drift": drift}
    return {
        QUATPROP: lambda s: quatprop_run(s, **opts),
        "quatprop BiasEstimator, gyro only": lambda s: quatprop_run(s, acc=False, **opts),
        "quatprop BiasEstimator + motion bias": lambda s: quatprop_run(s, motion=True, **opts),
        FUSION: fusion_run,
        VQF_NAME: vqf_run,
    }


# --- metrics --------------------------------------------------------------------------------------------

def grid(n: int) -> np.ndarray:
    return (np.arange(n // EVERY) + 1) * EVERY * DT


def truth_on_grid(s: Stream) -> np.ndarray:
    return s.bias[EVERY - 1::EVERY][: len(s.gyr) // EVERY]


def followed_after(t, err, start, tol=FOLLOWED * DEG) -> float:
    """Seconds after ``start`` from which ``err < tol`` to the end (the run's length after start if never)."""
    after = t > start
    bad = np.flatnonzero(after & (err >= tol))
    first = np.flatnonzero(after)[0]
    k = first if len(bad) == 0 else bad[-1] + 1
    return float(t[k] - start) if k < len(t) else float(t[-1] - start)


@dataclass
class Scenario:
    name: str
    unit: str
    seeds: int
    build: Callable[[int], Stream]
    score: Callable[[Stream, np.ndarray], float]
    pool: str = "mean"  # how the seeds' values are pooled: mean, max or rms


def scenarios(seeds: int) -> List[Scenario]:
    out = [
        Scenario("start at rest: followed within (s)", "s", seeds, lambda k: make(60.0, 100 + k),
                 lambda s, e: followed_after(grid(len(s.gyr)), np.linalg.norm(e - truth_on_grid(s), axis=1), 0.0)),
        Scenario("step at rest: followed within (s)", "s", seeds,
                 lambda k: make(120.0, 200 + k, bias_extra=lambda t: np.where((t >= 60.37)[:, None],
                                                                               np.array([0.3, 0.0, -0.2]) * DEG, 0.0)),
                 lambda s, e: followed_after(grid(len(s.gyr)), np.linalg.norm(e - truth_on_grid(s), axis=1), 60.37)),
    ]
    for axis, axis_name in ((0, "horizontal"), (2, "vertical")):
        for dps in (0.5, 1.0, 2.0):
            for hold in (20.0, 60.0):
                total = 30.0 + hold + 2.0 + 10.0

                def build(k, axis=axis, dps=dps, hold=hold, total=total):
                    return make(total, 300 + k, rate=turn_rate(total, axis, dps, 30.0, hold))

                def absorbed(s, e, axis=axis, dps=dps, hold=hold):
                    t = grid(len(s.gyr))
                    during = (t > 30.0) & (t <= 30.0 + 2.0 + hold)
                    lost = np.sum((e - truth_on_grid(s))[during, axis]) * EVERY * DT
                    return 100.0 * lost / ((hold + 1.0) * dps * DEG)

                out.append(Scenario(f"turn {axis_name} {dps:g} °/s for {hold:.0f} s: taken for bias (%)", "%",
                                    max(4, seeds // 8), build, absorbed))
    out += [
        Scenario("short motions: largest wrong bias (°/s)", "°/s", seeds,
                 lambda k: make(180.0, 500 + k, *short_motions_args(180.0, k)),
                 lambda s, e: float(np.max(np.linalg.norm(e - truth_on_grid(s), axis=1)[grid(len(s.gyr)) > 25.0]) / DEG),
                 pool="max"),
        Scenario("warm-up: rms |b̂ − b| (°/s)", "°/s", max(4, seeds // 8),
                 lambda k: make(600.0, 600 + k, rate=warmup(600.0)[0], bias_extra=warmup(600.0)[1]),
                 lambda s, e: float(np.sqrt(np.mean(np.sum((e - truth_on_grid(s)) ** 2, axis=1))) / DEG), pool="rms"),
        Scenario("long rest: rms |b̂ − b| (°/s)", "°/s", max(4, seeds // 8),
                 lambda k: make(600.0, 700 + k, bias_extra=lambda t: 0.02 * DEG * np.stack(
                     [np.sin(2 * np.pi * t / 400.0), np.cos(2 * np.pi * t / 400.0), np.sin(2 * np.pi * t / 400.0 + 1.0)], axis=1)),
                 lambda s, e: float(np.sqrt(np.mean(np.sum((e - truth_on_grid(s))[grid(len(s.gyr)) > 60.0] ** 2, axis=1))) / DEG),
                 pool="rms"),
    ]
    return out


def change_in_motion(seeds: int) -> Scenario:
    def build(k):
        total = 170.0
        t = times(int(round(total * FS)))
        axis = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
        w = 20.0 * DEG * np.sin(0.8 * t)[:, None] * bump(t, 30.0, 1.0, 18.0)[:, None] * axis
        return make(total, 800 + k, rate=w,
                    bias_extra=lambda tt: np.where((tt >= 40.0)[:, None], np.array([0.2, 0.0, 0.0]) * DEG, 0.0))

    return Scenario("change in motion: followed within (s after the motion)", "s", seeds, build,
                    lambda s, e: followed_after(grid(len(s.gyr)), np.linalg.norm(e - truth_on_grid(s), axis=1), 50.0))


def pool(values: List[float], how: str) -> float:
    v = np.asarray(values, dtype=float)
    if how == "max":
        return float(np.max(v))
    if how == "rms":
        return float(np.sqrt(np.mean(v ** 2)))
    return float(np.mean(v))


def run_scenario(sc: Scenario, runs: Dict[str, Callable[[Stream], np.ndarray]], cache: Dict) -> Dict[str, float]:
    vals: Dict[str, List[float]] = {name: [] for name in runs}
    for k in range(sc.seeds):
        s = sc.build(k)
        for name, run in runs.items():
            key = (sc.name, name, k)
            if key not in cache:
                cache[key] = sc.score(s, run(s))
            vals[name].append(cache[key])
    return {name: pool(v, sc.pool) for name, v in vals.items()}


# --- the report -----------------------------------------------------------------------------------------

def ratio(ours: float, peers: List[float]) -> float:
    better = min(peers)
    if better <= 0.0:
        return 1.0 if ours <= 0.0 else float("inf")
    return max(ours, 0.0) / better


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", default="docs", help="folder for bias.md and bias.png (default docs)")
    ap.add_argument("--seeds", type=int, default=32, help="seeds of the short scenarios (default 32)")
    ap.add_argument("--quick", action="store_true", help="4 seeds, no knob sweep: a check, not the record")
    args = ap.parse_args(argv)
    t0 = time.time()
    seeds = 4 if args.quick else args.seeds
    runs = estimators()
    cache: Dict = {}
    results: List[Tuple[Scenario, Dict[str, float]]] = []
    for sc in scenarios(seeds):
        results.append((sc, run_scenario(sc, runs, cache)))
        progress(f"  {sc.name}: " + ", ".join(f"{v:.3g}" for v in results[-1][1].values())
                 + f"  ({time.time() - t0:.0f} s)")
    motion_sc = change_in_motion(max(4, seeds // 4))
    motion_res = run_scenario(motion_sc, runs, cache)
    progress(f"  {motion_sc.name}: " + ", ".join(f"{v:.3g}" for v in motion_res.values()))

    # The knob: drift swept, each point's (change in motion, turn taken for bias) beside the peers'.
    drifts = [] if args.quick else [1e-5, 2e-5, 5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3]
    turn_sc = next(sc for sc, _ in results if sc.name.startswith("turn vertical 1 °/s for 20"))
    curve = []
    for d in drifts:
        one = {QUATPROP: estimators(d)[QUATPROP]}
        c = {}
        m = run_scenario(motion_sc, one, c)[QUATPROP]
        tr = run_scenario(turn_sc, one, c)[QUATPROP]
        curve.append((d, m, tr))
        progress(f"  drift {d:g}: change in motion {m:.1f} s, turn {tr:.1f} %")

    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    turn_res = next(r for sc, r in results if sc is turn_sc)
    plot(out / "bias.png", curve, motion_res, turn_res)
    md = report(args, seeds, results, motion_sc, motion_res, turn_res, curve, time.time() - t0)
    (out / "bias.md").write_text(md)
    progress(f"wrote {out / 'bias.md'} and {out / 'bias.png'} in {time.time() - t0:.0f} s")
    return 0


def cell(v: float) -> str:
    if isinstance(v, float) and (math.isnan(v) or math.isinf(v)):
        return "—"
    if abs(v) >= 100:
        return f"{v:.0f}"
    if abs(v) >= 10:
        return f"{v:.1f}"
    if abs(v) >= 0.1:
        return f"{v:.2f}"
    return f"{v:.3f}"


def report(args, seeds, results, motion_sc, motion_res, turn_res, curve, seconds) -> str:
    names = list(results[0][1].keys())
    ours = [n for n in names if n.startswith("quatprop")]
    header = "| scenario | seeds | " + " | ".join(names) + " | default / better peer |"
    lines = [header, "|---|---:|" + "---:|" * (len(names) + 1)]
    ratios = []
    worse = []
    for sc, r in results:
        q = ratio(r[QUATPROP], [r[FUSION], r[VQF_NAME]])
        ratios.append(q)
        if q > 1.0:
            worse.append(sc.name)
        lines.append(f"| {sc.name} | {sc.seeds} | " + " | ".join(cell(r[n]) for n in names) + f" | {cell(q)} |")
    score = float(np.exp(np.mean(np.log(np.maximum(ratios, 1e-6)))))
    peer_scores = {}
    for peer, other in ((FUSION, VQF_NAME), (VQF_NAME, FUSION)):
        rs = [ratio(r[peer], [r[FUSION], r[VQF_NAME]]) for _, r in results]
        peer_scores[peer] = float(np.exp(np.mean(np.log(np.maximum(rs, 1e-6)))))
    verdict = ("never worse than the better peer" if not worse
               else "worse than the better peer on: " + "; ".join(worse))
    curve_rows = "\n".join(f"| {d:g} ({d / DEG:.2g} °/s/√s) | {cell(m)} | {cell(t)} |" for d, m, t in curve)
    return f"""_Written by `python python/benchmarks/bias.py{' --quick' if args.quick else f' --seeds {args.seeds}'}` ({seconds:.0f} s); do not edit by hand, re-run it._

# Gyro bias estimation beside Fusion and VQF: a scenario mix

{versions_line()}

Synthetic streams whose truth is known (sensor model, motions and metrics: the docstring of
`python/benchmarks/bias.py`): float32 rates at 200 Hz, white noise 0.1 °/s per sample, a bias of
(0.6, −0.4, 0.25) °/s walking with 3·10⁻⁴ °/s/√s, an accelerometer with 0.02 m/s² noise and the hand's
linear accelerations. Each peer runs as its users call it: `imufusion.Bias` (Fusion's `FusionBias`, its C
code, fed °/s, defaults: 3 °/s for 3 s), `vqf.VQF(1/200).updateBatch(gyr, acc)["bias"]` (VQF's rest and
motion bias estimation, defaults). quatprop: `BiasEstimator(window=1.0, gate=3 °/s)` with its defaults
(`drift` and `rest_drift` 2e-5 rad/s/√s) through `quatprop.Stream(dt=1/200, precision="f32")`, given the
accelerations (`acc=`), also gyro only and with the motion bias. Estimates are read every 0.1 s.

![bias estimation: the knob and one seed of each scenario](bias.png)

## The mix

Lower is better in every row. The last column compares quatprop's default (the first column) with the
better of the two peers on that row (≤ 1: at least as good). Seeds: noise and motion seeds pooled (mean;
the short motions' largest error: the worst seed; rms errors: rms over the seeds).

{chr(10).join(lines)}

**Score of the mix** (geometric mean of the ratios to the better peer, lower is better): quatprop
{score:.3f}; FusionBias {peer_scores[FUSION]:.3f}, VQF {peer_scores[VQF_NAME]:.3f}. The default is
{verdict}.

## The knob: following a change against keeping a slow turn

`drift` (rad/s/√s) is how fast the bias may change. A bias that changed in motion is followed once the
estimate's uncertainty, grown by `drift²` per second, admits it; a slow turn is kept until the same
uncertainty would admit it. The change in motion ({motion_sc.seeds} seeds): 0.2 °/s during 20 s of motion,
then rest; its column is the time after the motion until |b̂ − b| stays below 0.05 °/s. The turn: about
the vertical at 1 °/s for 20 s. No bias estimator sees a change in motion before the next rest: the
peers' points are their time constants.

| drift (rad/s/√s) | change in motion: followed within (s) | vertical turn 1 °/s, 20 s: taken for bias (%) |
|---|---:|---:|
{curve_rows if curve else '| (not run with --quick) | | |'}
| **peers** | | |
| **quatprop default** | {cell(motion_res[QUATPROP])} | {cell(turn_res[QUATPROP])} |
| FusionBias | {cell(motion_res[FUSION])} | {cell(turn_res[FUSION])} |
| VQF | {cell(motion_res[VQF_NAME])} | {cell(turn_res[VQF_NAME])} |
"""


def versions_line() -> str:
    import importlib.metadata as md

    def v(p):
        try:
            return md.version(p)
        except md.PackageNotFoundError:
            return "?"

    return (f"quatprop {quatprop.__version__}, imufusion {v('imufusion')}, vqf {v('vqf')}, "
            f"numpy {np.__version__}.")


def plot(path: Path, curve, motion_res, turn_res) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    if curve:
        ax.plot([c[1] for c in curve], [c[2] for c in curve], "o-", label="quatprop, drift swept")
        for d, m, t in curve:
            ax.annotate(f"{d:g}", (m, t), fontsize=7, xytext=(3, 3), textcoords="offset points")
    for name, marker in ((FUSION, "s"), (VQF_NAME, "^")):
        ax.plot(motion_res[name], turn_res[name], marker, ms=9, label=name)
    ax.plot(motion_res[QUATPROP], turn_res[QUATPROP], "*", ms=14, label="quatprop default")
    ax.set(xlabel="change in motion: followed within (s)", ylabel="vertical turn 1 °/s, 20 s: taken for bias (%)",
           title="following a change against keeping a slow turn")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    raise SystemExit(main())
