"""In-run gyro calibration: what `CalibrationEstimator` learns of a gyro's gain (scale factor and axis
misalignment) on synthetic sensors, and what that does to gyro-only dead reckoning on BROAD, held out.

    python python/benchmarks/calibration.py PATH/TO/broad [--out docs] [--quick]

1. Synthetic sensors with a known gain (scale errors uniform in ±1 %, cross-axis terms in ±0.5°), a bias,
   white noise and linear acceleration, turned through K turns of 90–180° about axes drawn within a cone
   of half-angle α about the vertical, with or without rests between the turns: the error of the learned
   gain against the number of turns, their spread and the noise, and whether the estimator's own σ covers
   it.
2. BROAD, gyro-only as a user runs it (f32, no timing shift): `BiasEstimator(motion=CalibrationEstimator(
   sensitivity_sigma, misalignment_sigma, motion_noise))` learning from the start of each trial, its three
   settings chosen by leave-one-trial-out cross-validation on the 60 s error (crossval.py), beside vqf's
   strapdown with its bias estimation, quatprop without the gain and the offline 3 × 3 gain fitted to
   each trial's truth (an oracle: what a perfect calibration would give); and the drift envelope of the
   held-out issue (heldout.py) over the calibrated runs.

Writes OUT/calibration.md and OUT/calibration.png.

Data: D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation
Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0)
"""

from __future__ import annotations

import argparse
import itertools
import sys
import time
from pathlib import Path
from typing import Dict, List, Tuple

import numpy as np

import quatprop

import broad_metric as bm
import crossval
import heldout

COMMAND = "python python/benchmarks/calibration.py PATH/TO/broad --out docs"
FS = 100.0
G = 9.81
SEEDS = 16
# BROAD grid: prior sigmas of scale and cross-axis terms, measurement noise (rad/√s).
SENSITIVITY_SIGMAS = (0.001, 0.003, 0.01)
MISALIGNMENT_SIGMAS = (0.001, 0.003)
MOTION_NOISES = tuple(np.radians([0.1, 0.1 * np.sqrt(3.0), 0.3]))
# Synthetic noise levels: gyro white noise (°/√s), accelerometer white noise (m/s²/√Hz), linear
# acceleration rms (m/s², low-passed at 1 Hz).
NOISE_LEVELS = {
    "low": (0.005, 0.001, 0.0),
    "mid": (0.015, 0.003, 0.3),
    "high": (0.05, 0.01, 1.0),
}


def progress(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


# ---------------------------------------------------------------------------------------------------------
# 1. Synthetic sensors


def rot(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotation matrices (…, 3, 3) about the unit `axis` (3,) by `angle` (…,) (Rodrigues)."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    a = np.asarray(angle)[..., None, None]
    return np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * (k @ k)


def random_gain(rng: np.random.Generator) -> np.ndarray:
    """The true correction `I − G`: scale errors uniform in ±1 %, cross-axis terms in ±0.5° (rad)."""
    g = rng.uniform(-np.radians(0.5), np.radians(0.5), (3, 3))
    g[np.diag_indices(3)] = rng.uniform(-0.01, 0.01, 3)
    return np.eye(3) - g


def scenario(rng: np.random.Generator, turns: int, cone: float, rests: bool, noise: str):
    """Gyro readings (N, 3) (rad/s) and accelerometer (N, 3) (m/s²) of a sensor with a random gain and
    bias, and the true correction `I − G`. A 5 s rest, then `turns` turns of 90–180° (2 s each, a raised
    cosine rate) about axes drawn within `cone` (rad) of the vertical, each followed by a 4 s rest when
    `rests`."""
    dt = 1.0 / FS
    m = random_gain(rng)
    bias = rng.normal(0.0, np.radians(0.5), 3)
    gyro_n, acc_n, lin = NOISE_LEVELS[noise]
    # A random initial attitude.
    v = rng.normal(size=3)
    r_now = rot(v / np.linalg.norm(v), rng.uniform(0, np.pi))
    rates, accs = [], []

    def rest(seconds):
        n = int(round(seconds * FS))
        rates.append(np.zeros((n, 3)))
        accs.append(np.repeat((r_now.T @ np.array([0, 0, G]))[None], n, axis=0))

    rest(5.0)
    span = 2.0
    n = int(round(span * FS))
    t = np.arange(n + 1) * dt
    for _ in range(turns):
        cos_t = rng.uniform(np.cos(cone), 1.0)
        phi = rng.uniform(0, 2 * np.pi)
        s = np.sqrt(1 - cos_t ** 2)
        u = np.array([s * np.cos(phi), s * np.sin(phi), cos_t]) * rng.choice([-1.0, 1.0])
        a = rng.uniform(np.pi / 2, np.pi)
        theta = a / span * (t - span / (2 * np.pi) * np.sin(2 * np.pi * t / span))
        body_axis = r_now.T @ u
        rates.append((np.diff(theta) / dt)[:, None] * body_axis[None])  # the mean rate over each step
        r_t = rot(u, theta[1:]) @ r_now  # the attitude at each step's end
        accs.append(np.einsum("nji,j->ni", r_t, np.array([0, 0, G])))
        r_now = r_t[-1]
        if rests:
            rest(4.0)
    w = np.concatenate(rates)
    acc = np.concatenate(accs)
    readings = w @ np.linalg.inv(m).T + bias + rng.normal(0, np.radians(gyro_n) / np.sqrt(dt), w.shape)
    acc = acc + rng.normal(0, acc_n / np.sqrt(dt), acc.shape)
    if lin > 0:
        # Linear acceleration: white noise low-passed at 1 Hz, scaled to `lin` rms, in motion only.
        from scipy.signal import butter, lfilter

        b, a = butter(2, 1.0, fs=FS)
        x = lfilter(b, a, rng.normal(size=acc.shape), axis=0)
        moving = np.linalg.norm(w, axis=1) > 0
        acc = acc + lin * x / x.std() * moving[:, None]
    return readings, acc, m


def learn(readings: np.ndarray, acc: np.ndarray, motion_noise=None):
    """The gain learned over the whole run and its σ (3 × 3 each), f32 as a firmware runs it."""
    est = quatprop.BiasEstimator(window=1.0, gate=np.radians(3.0), motion=quatprop.CalibrationEstimator(
        0.01, np.radians(0.5), motion_noise))
    s = quatprop.Stream(dt=1.0 / FS, scheme="expmap", input="history", precision="f32", bias=est)
    s.update(readings, acc=acc)
    c = s.learned_calibration
    return c["gain"], c["gain_std_dev"]


def recovery(rng_seed: int, turns: int, cone: float, rests: bool, noise: str) -> Dict[str, float]:
    """Over SEEDS sensors: the rms error of the scale terms (%) and of the cross-axis terms (°), before
    and after, and the share of the terms within 3σ."""
    scale, cross, scale0, cross0, inside = [], [], [], [], []
    off = ~np.eye(3, dtype=bool)
    for k in range(SEEDS):
        rng = np.random.default_rng([rng_seed, k])
        readings, acc, m = scenario(rng, turns, cone, rests, noise)
        gain, sd = learn(readings, acc)
        err = gain - m
        scale.append(np.diag(err))
        cross.append(err[off])
        scale0.append(np.diag(np.eye(3) - m))
        cross0.append((np.eye(3) - m)[off])
        inside.append(np.abs(err) <= 3 * sd)
    rms = lambda x: float(np.sqrt(np.mean(np.square(x))))  # noqa: E731
    return {"scale": 100 * rms(scale), "cross": np.degrees(rms(cross)), "scale0": 100 * rms(scale0),
            "cross0": np.degrees(rms(cross0)), "inside": float(np.mean(inside))}


def synthetic(quick: bool):
    counts = (2, 4, 8, 16) if quick else (2, 4, 8, 16, 32, 64)
    cones = {"within 20° of the vertical": np.radians(20.0), "within 60° of the vertical": np.radians(60.0),
             "any direction": np.pi}
    by_count = {}
    for rests in (True, False):
        for name, cone in cones.items():
            for k in counts:
                by_count[(rests, name, k)] = recovery(1, k, cone, rests, "mid")
                progress(f"  synthetic: {'rests' if rests else 'no rests'}, cone {name}, {k} turns")
    by_noise = {}
    for level in NOISE_LEVELS:
        by_noise[level] = recovery(2, 16, np.pi, True, level)
        progress(f"  synthetic: noise {level}")
    return counts, cones, by_count, by_noise


# ---------------------------------------------------------------------------------------------------------
# 2. BROAD


def calibrated_stream(t: bm.Trial, setting) -> quatprop.Stream:
    sens, mis, noise = setting
    est = quatprop.BiasEstimator(window=1.0, gate=heldout.GATE,
                                 motion=quatprop.CalibrationEstimator(sens, mis, noise))
    return quatprop.Stream(dt=t.dt, scheme="expmap", input="history", precision="f32", bias=est)


def calibrated_run(t: bm.Trial, setting) -> np.ndarray:
    return np.asarray(calibrated_stream(t, setting).update(t.gyr, acc=t.acc), dtype=np.float64)


def oracle_run(t: bm.Trial) -> Tuple[np.ndarray, np.ndarray]:
    """The 3 × 3 gain fitted to the trial's own truth (least squares on the 10 s errors from every start
    point), applied from the start before the rest estimator: what a perfect calibration would give. In
    f64: the f32 run's rounding makes the finite-difference Jacobian of the fit too noisy to move."""
    from scipy.optimize import least_squares

    starts = bm.start_points(t.movement, t.fs)

    def run(p):
        m = np.eye(3) + p.reshape(3, 3) * 1e-2
        est = quatprop.BiasEstimator(window=1.0, gate=heldout.GATE)
        return np.asarray(quatprop.integrate(t.gyr @ m.T, dt=t.dt, scheme="expmap", input="history",
                                             precision="f64", bias=est, acc=t.acc), dtype=np.float64)

    def resid(p):
        e = bm.errors(run(p), t.quat, t.fs, starts, (10.0,), movement=t.movement)[0]
        return np.nan_to_num(e[np.isfinite(e)])

    sol = least_squares(resid, np.zeros(9), diff_step=0.05, max_nfev=60)
    return run(sol.x), np.eye(3) + sol.x.reshape(3, 3) * 1e-2


def envelope(trials, settings):
    """The held-out issue's drift envelope over the runs with `settings[name]`: pairs per trial."""
    white = {t.name: quatprop.allan(t.gyr[: t.first_movement], dt=t.dt, min_tau=16 * t.dt)["white"]["value"]
             for t in trials}
    pairs = {}
    for t in trials:
        if settings[t.name] is None:
            q, starts, var = heldout.envelope_run(t, heldout.DRIFTS[0], 0.0, False)
        else:
            q, starts, var = heldout.stream_at_start_points(t, calibrated_stream(t, settings[t.name]))
        pairs[t.name] = heldout.envelope_pairs(t, q, starts, var, white[t.name])
    names = [t.name for t in trials]
    env = crossval.leave_one_out_by(
        heldout.ENVELOPE_GRID, names,
        lambda sg, training: heldout.envelope_objective([p for n in training for p in pairs[n]], sg),
        lambda sg, n: heldout.envelope_objective(pairs[n], sg))
    return pairs, env


def broad(trials, quick: bool):
    names = [t.name for t in trials]
    h = heldout.HORIZONS.index(heldout.SCORE_HORIZON)
    grid = list(itertools.product(SENSITIVITY_SIGMAS, MISALIGNMENT_SIGMAS, MOTION_NOISES))
    if quick:
        grid = grid[:4]
    scores = {}
    t0 = time.time()
    for k, s in enumerate(grid):
        scores[s] = {t.name: float(heldout.per_trial(t, calibrated_run(t, s))[h]) for t in trials}
        progress(f"  BROAD [{k + 1}/{len(grid)}] {setting_text(s)} ({time.time() - t0:.0f} s)")
    cv = crossval.leave_one_out(scores, names)
    peers = {
        "vqf": {t.name: float(heldout.per_trial(t, heldout.vqf_run(t))[h]) for t in trials},
        "rest": {t.name: float(heldout.per_trial(t, heldout.quatprop_run(t, heldout.DRIFTS[0], 0.0, False))[h])
                 for t in trials},
        "motion": {t.name: float(heldout.per_trial(t, heldout.quatprop_run(t, heldout.DRIFTS[0], 0.0, True))[h])
                   for t in trials},
    }
    progress(f"  BROAD peers ({time.time() - t0:.0f} s)")
    oracle, oracle_gain = {}, {}
    if not quick:
        for t in trials:
            q, m = oracle_run(t)
            oracle[t.name] = float(heldout.per_trial(t, q)[h])
            oracle_gain[t.name] = m
        progress(f"  BROAD oracle ({time.time() - t0:.0f} s)")
    learned = {}
    for c in cv.choices:
        t = next(x for x in trials if x.name == c.trial)
        s = calibrated_stream(t, c.setting)
        s.update(t.gyr, acc=t.acc)
        learned[c.trial] = s.learned_calibration
    chosen = {c.trial: c.setting for c in cv.choices}
    pairs_cal, env_cal = envelope(trials, chosen)
    pairs_off, env_off = envelope(trials, {n: None for n in names})
    progress(f"  BROAD envelope ({time.time() - t0:.0f} s)")
    return cv, peers, oracle, oracle_gain, learned, (pairs_cal, env_cal), (pairs_off, env_off)


def setting_text(s) -> str:
    sens, mis, noise = s
    return f"σ_s {sens:g}, σ_m {mis:g}, noise {np.degrees(noise):.3g} °/√s"


# ---------------------------------------------------------------------------------------------------------
# Report


def plot(path: Path, counts, cones, by_count, cv, peers, oracle) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.6))
    for (name, color) in zip(cones, ("C0", "C1", "C2")):
        for rests, style in ((True, "-o"), (False, "--s")):
            a1.loglog(counts, [by_count[(rests, name, k)]["scale"] for k in counts], style, color=color, ms=4,
                      label=f"{name}, {'rests' if rests else 'no rests'}")
    a1.axhline(by_count[(True, "any direction", counts[0])]["scale0"], color="k", lw=0.8, ls=":",
               label="before (the true scale errors)")
    a1.set_xticks(counts, [str(k) for k in counts])
    a1.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
    a1.set(xlabel="turns", ylabel="rms scale-factor error (%)",
           title="synthetic: the learned scale factors (16 sensors each)")
    a1.legend(fontsize=7)
    names = [c.trial for c in cv.choices]
    x = np.arange(len(names))
    held = [c.held_out for c in cv.choices]
    a2.bar(x - 0.3, [peers["vqf"][n] for n in names], 0.2, label="vqf strapdown + its bias estimation")
    a2.bar(x - 0.1, [peers["rest"][n] for n in names], 0.2, label="quatprop, bias at rest only")
    a2.bar(x + 0.1, held, 0.2, label="quatprop + CalibrationEstimator (held out)")
    if oracle:
        a2.bar(x + 0.3, [oracle[n] for n in names], 0.2, label="offline gain fitted to the truth (oracle)")
    a2.set_xticks(x, [n[:2] for n in names])
    a2.set(xlabel="BROAD trial", ylabel="gyro-only error at 60 s (°)", title="BROAD, no timing shift")
    a2.legend(fontsize=7)
    fig.text(0.5, 0.005, "Data: " + bm.ATTRIBUTION, ha="center", va="bottom", fontsize=6)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def report(seconds, quick, trials, synth, broad_result) -> str:
    counts, cones, by_count, by_noise = synth
    cv, peers, oracle, oracle_gain, learned, (pairs_cal, env_cal), (pairs_off, env_off) = broad_result
    names = [t.name for t in trials]

    srows = ["| spread of the turn axes | rests | " + " | ".join(f"{k} turns" for k in counts) + " |",
             "|---|---|" + "---:|" * len(counts)]
    for name in cones:
        for rests in (True, False):
            cells = [f"{by_count[(rests, name, k)]['scale']:.3f} % / {by_count[(rests, name, k)]['cross']:.3f}°"
                     f" ({100 * by_count[(rests, name, k)]['inside']:.0f} %)" for k in counts]
            srows.append(f"| {name} | {'yes' if rests else 'no'} | " + " | ".join(cells) + " |")
    before = by_count[(True, "any direction", counts[0])]
    nrows = ["| noise | gyro white (°/√s) | accelerometer white (m/s²/√Hz) | linear acceleration (m/s² rms) | "
             "scale error (rms) | cross-axis error (rms) | terms within 3σ |", "|---|---:|---:|---:|---:|---:|---:|"]
    for level, r in by_noise.items():
        gn, an, lin = NOISE_LEVELS[level]
        nrows.append(f"| {level} | {gn:g} | {an:g} | {lin:g} | {r['scale']:.3f} % | {r['cross']:.3f}° | "
                     f"{100 * r['inside']:.0f} % |")

    vqf_mean = float(np.mean([peers["vqf"][n] for n in names]))
    rest_mean = float(np.mean([peers["rest"][n] for n in names]))
    motion_mean = float(np.mean([peers["motion"][n] for n in names]))
    brows = ["| trial | setting chosen without it | held out | in-sample | vqf strapdown + its bias | "
             "quatprop, rest bias | quatprop, + motion bias | oracle gain | held out / vqf |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for c in cv.choices:
        o = f"{oracle[c.trial]:.2f}" if oracle else "—"
        brows.append(f"| {c.trial} | {setting_text(c.setting)} | {c.held_out:.2f} | {c.in_sample:.2f} | "
                     f"{peers['vqf'][c.trial]:.2f} | {peers['rest'][c.trial]:.2f} | {peers['motion'][c.trial]:.2f} | "
                     f"{o} | {c.held_out / peers['vqf'][c.trial]:.2f} |")
    omean = f"**{np.mean(list(oracle.values())):.2f}**" if oracle else "—"
    brows.append(f"| **mean over trials** | | **{cv.held_out_mean:.2f}** | **{cv.in_sample_mean:.2f}** | "
                 f"**{vqf_mean:.2f}** | **{rest_mean:.2f}** | **{motion_mean:.2f}** | {omean} | "
                 f"**{cv.held_out_mean / vqf_mean:.3f}** |")
    grows = ["| trial | learned scale (diagonal of `I − G`) | largest learned cross-axis term | its σ (largest) | "
             "oracle's scale (diagonal) | oracle's largest cross-axis term |", "|---|---|---:|---:|---|---:|"]
    off = ~np.eye(3, dtype=bool)
    for n in names:
        g = learned[n]["gain"]
        sd = learned[n]["gain_std_dev"]
        og = oracle_gain.get(n)
        ocells = ("—", "—") if og is None else (
            ", ".join(f"{x:.4f}" for x in np.diag(og)), f"{np.degrees(np.abs(og[off]).max()):.2f}°")
        grows.append(f"| {n} | {', '.join(f'{x:.4f}' for x in np.diag(g))} | {np.degrees(np.abs(g[off]).max()):.2f}° | "
                     f"{np.degrees(sd[off].max()):.2f}° | {ocells[0]} | {ocells[1]} |")
    erows_cal, _ = heldout.envelope_table(pairs_cal, env_cal)
    erows_off, _ = heldout.envelope_table(pairs_off, env_off)
    chosen = ", ".join(f"{setting_text(s)} ({n} of {len(names)})" for s, n in cv.settings_chosen().items())
    verdict = "meets" if cv.held_out_mean <= 0.8 * vqf_mean else "does not meet"
    # The configuration for real data: the setting most folds chose, the default noise left implicit.
    rec_s, rec_m, rec_n = max(cv.settings_chosen().items(), key=lambda kv: kv[1])[0]
    rec_noise = "" if np.isclose(rec_n, MOTION_NOISES[1]) else f", motion_noise=np.radians({np.degrees(rec_n):.3g})"
    recommended_text = f"CalibrationEstimator({rec_s:g}, {rec_m:g}{rec_noise})"
    noise_note = (f" (the estimator's default motion noise, {np.degrees(rec_n):.3g} °/√s, is the one the folds chose)"
                  if not rec_noise else "")
    verdict_vqf = "below" if cv.held_out_mean < vqf_mean else "not below"
    at_or_below = sum(c.held_out <= peers["vqf"][c.trial] for c in cv.choices)
    return f"""<!-- Written by python/benchmarks/calibration.py: do not edit by hand. Regenerate with `{COMMAND}`. -->

# In-run gyro calibration: the gain learned from the accelerometer

*Written by `python/benchmarks/calibration.py` ({seconds:.0f} s{', --quick: a reduced grid' if quick else ''}).
quatprop {quatprop.__version__}.*

`frontend::CalibrationEstimator` learns the gyro's gain `I − G` (three scale factors, six cross-axis
terms) and its residual bias while the body moves, from the accelerometer: a wrong gain tilts the attitude
in proportion to how the body turns, and the accelerometer, low-passed, shows the tilt (the construction
VQF uses for the bias, `frontend::MotionBias`; the principle of Tedaldi, Pretto and Menegatti's calibration
without external equipment, ICRA 2014). What it has not seen stays at its prior and its σ says so:
a turn about the vertical never shows that axis's own scale, and a term needs turns about its axis at
attitudes where they tilt. In Python: `BiasEstimator(window, gate, motion=CalibrationEstimator(
sensitivity_sigma, misalignment_sigma))`, then `Stream.learned_calibration`.

![left: the learned scale factors' error against the number of turns; right: BROAD gyro-only error at 60 s](calibration.png)

## 1. Synthetic sensors: recovery against the number and spread of turns, and the noise

Each cell: the rms error of the three scale factors (%) / of the six cross-axis terms (°) over
{SEEDS} sensors, after a 5 s rest and the turns (each 90–180° in 2 s about an axis drawn within the cone
of the vertical; with rests: 4 s still after each), and in brackets the share of the nine terms within
the estimator's own 3σ. The sensors: scale errors uniform in ±1 %, cross-axis terms in ±0.5° (rms
before: {before['scale0']:.3f} % and {before['cross0']:.3f}°), a bias of 0.5 °/s rms, the "mid" noise below;
100 Hz, f32, the priors 1 % and 0.5°, the default measurement noise.

{chr(10).join(srows)}

Against the noise (16 turns about any axis, with rests):

{chr(10).join(nrows)}

## 2. BROAD: gyro-only, held out, no timing shift

quatprop: `Stream(dt, scheme="expmap", input="history", precision="f32", bias=BiasEstimator(window=1.0,
gate=3 °/s, motion=CalibrationEstimator(σ_s, σ_m, noise)))`, learning from the first sample of each trial;
no `group_delay`. The grid: σ_s in {{{", ".join(f"{x:g}" for x in SENSITIVITY_SIGMAS)}}}, σ_m in
{{{", ".join(f"{x:g}" for x in MISALIGNMENT_SIGMAS)}}} rad, noise in
{{{", ".join(f"{np.degrees(x):.3g}" for x in MOTION_NOISES)}}} °/√s; each trial is scored with the setting
whose mean 60 s error over the other {len(trials) - 1} trials is lowest (held out), beside the one lowest
over all (in-sample: {setting_text(cv.in_sample_setting)}). The error at 60 s (°), the mean over each
trial's start points, the truth unshifted (the metric of docs/broad.md and docs/heldout.md). vqf:
`VQF(1/fs).updateBatchFullState(gyr, acc)["gyrQuat"]` (its strapdown with its rest and motion bias
estimation). Oracle: a 3 × 3 gain fitted to the trial's own truth (least squares over the 10 s errors),
applied from the start — not causal, not held out: what a perfect calibration would give.

{chr(10).join(brows)}

The target of issue 37 is a held-out mean at most 0.8 × vqf's: held out / vqf = **{cv.held_out_mean / vqf_mean:.3f}**
({verdict} it). Settings the folds chose: {chosen}. Held out against in-sample: {cv.held_out_mean - cv.in_sample_mean:+.3f}°.

**The configuration for real data** (gyro and accelerometer, no magnetometer; the setting most folds
chose): `Stream(dt, scheme="expmap", input="history", precision="f32",
bias=BiasEstimator(window=1.0, gate=np.radians(3.0), motion={recommended_text}))`, fed `update(gyr,
acc=acc)`{noise_note}. Sample timing: each sample's
own interval, no `group_delay` (the gyro and the accelerometer read at the same instant, as the IMU stamps
them); the truth is not shifted. Held out, its mean 60 s error is {verdict_vqf} vqf's strapdown with its
bias estimation ({cv.held_out_mean:.2f}° against {vqf_mean:.2f}°), at or below it on {at_or_below} of
{len(names)} trials.

What it learned on each trial, beside the oracle's gain (the held-out setting; σ from the filter):

{chr(10).join(grows)}

The learned gains do not match the oracle's term by term, and neither is the sensor's gain alone: the
oracle fits nine numbers to one trial's truth over 10 s spans (it also absorbs timing and the truth's own
errors), and on a real recording the estimator's gain also takes up what its model lacks — a bias that
moves in motion, linear acceleration left after the low-pass, the gyro's timing against the
accelerometer. Read the learned gain as the correction that keeps the accelerometer's inclination
consistent with the gyro, which is what cuts the drift; on synthetic sensors (section 1), where the model
is complete, it is the sensor's gain.

## 3. The drift envelope over the calibrated runs

The envelope of docs/heldout.md (white noise, the rest estimate's error carried through the rotation, a
gain error σ_g, a bias wander σ_w, the truth's timing σ_τ and its own error σ_0 chosen by
leave-one-trial-out, the 3σ level first), computed over the calibrated runs (each trial with its held-out setting) and, beside it, over the
runs without the gain (the rest bias only). In the calibrated runs σ_g stands for the gain error left
after calibration.

Calibrated ((σ_g, σ_w, σ_τ, σ_0) chosen in-sample: {env_cal.in_sample_setting}):

{chr(10).join(erows_cal)}

Without the gain (in-sample: {env_off.in_sample_setting}):

{chr(10).join(erows_off)}

Data: {bm.ATTRIBUTION}
"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("data", help="folder of BROAD .hdf5 trials")
    ap.add_argument("--out", default="docs")
    ap.add_argument("--quick", action="store_true", help="a reduced grid (a smoke run, not the figures)")
    args = ap.parse_args(argv)
    t0 = time.time()
    trials = [bm.read_trial(p) for p in sorted(Path(args.data).glob("*.hdf5"))]
    progress(f"{len(trials)} trials")
    synth = synthetic(args.quick)
    progress(f"synthetic done ({time.time() - t0:.0f} s)")
    result = broad(trials, args.quick)
    progress(f"BROAD done ({time.time() - t0:.0f} s)")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    plot(out / "calibration.png", synth[0], synth[1], synth[2], result[0], result[1], result[2])
    (out / "calibration.md").write_text(report(time.time() - t0, args.quick, trials, synth, result))
    progress(f"wrote {out / 'calibration.md'} ({time.time() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
