"""Gyro-only orientation error of quatprop and its peers on real IMU recordings (BROAD).

    python python/benchmarks/broad.py PATH/TO/broad [--out docs] [--trials 02,05,...]

runs every method on every BROAD trial (HDF5 files) in the folder and writes OUT/broad.md and OUT/broad.png.
The peers are the installed packages, run as their users run them: imufusion (Fusion's Python package),
vqf, ahrs and SciPy (pip install imufusion vqf ahrs scipy h5py matplotlib, and quatprop from ./python).
The data and the metric are in broad_metric.py (conventions there: [w, x, y, z], Hamilton, body → ENU,
rad/s, seconds, errors in degrees).

Data: D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation
Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0)
"""

import argparse
import datetime
import os
import platform
import sys
import time
import warnings
from dataclasses import dataclass
from importlib.metadata import version as package_version
from pathlib import Path
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import ahrs
import imufusion
import matplotlib
import numpy as np
import vqf
from scipy.spatial.transform import Rotation

import quatprop

import broad_metric as bm

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the non-interactive backend)
from matplotlib import ticker  # noqa: E402

COMMAND = "python python/benchmarks/broad.py PATH/TO/broad --out docs"
#: Horizons (s) of the tables; the plot also uses the others.
TABLE_HORIZONS = (10.0, 30.0, 60.0)
HORIZONS = (2.0, 5.0, 10.0, 20.0, 30.0, 45.0, 60.0)
START_EVERY = 5.0  # s between start points
#: Shifts of the truth searched for the timing alignment, in half samples: −3 … +3 samples.
SHIFTS = tuple(range(-6, 7))
#: The horizon (s) whose pooled oracle-bias error chooses each method's best shift.
SHIFT_FIT_HORIZON = 10.0
BIAS_COLUMNS = ("none", "own", "oracle")
COLUMN_TITLES = {
    "none": "(a) no bias removal",
    "own": "(b) own bias estimator",
    "oracle": "(c) oracle bias",
}
COST_REPEATS = 3  # the cost is the best of this many whole-trial runs, on the first trial
STANDARD_GRAVITY = 9.80665  # m/s² per g (imufusion takes g)
GATE = np.radians(3.0)  # rad/s: quatprop's BiasEstimator gate, 3 °/s on every axis


@dataclass(frozen=True)
class Method:
    """A method under test. run(gyr rad/s (N, 3), acc m/s² (N, 3), fs Hz, estimate_bias) → (N, 4) float64
    attitudes [w, x, y, z] after each sample, from identity; estimate_bias=True runs the method's own bias
    estimator (only asked of a method whose own_bias is not None)."""

    name: str
    run: Callable[[np.ndarray, np.ndarray, float, bool], np.ndarray]
    how: str  # the call(s) that run it
    timing: str  # how the method places a sample in time
    own_bias: Optional[str]  # its own bias estimator, as run in column (b); None: it has none


# ---- quatprop: one line per configuration -------------------------------------------------------------

QUATPROP_TIMING = {
    "history": "ω_k is the rate at t_k; step [t_{k−1}, t_k] integrates the cubic through ω_{k−3}…ω_k "
    "(the first sample only starts)",
    "linear": "ω_k is the rate at t_k; step [t_{k−1}, t_k] integrates the line from ω_{k−1} to ω_k "
    "(the first sample only starts)",
    "hold": "zero-order hold: ω_k held over [t_{k−1}, t_k] (the first sample steps)",
}


def quatprop_method(
    name: str,
    bias_estimator: Optional[dict] = None,
    timing: Optional[str] = None,
    use_acc: bool = False,
    **integrate_kwargs,
) -> Method:
    """A quatprop configuration: `integrate_kwargs` go to quatprop.integrate (scheme, input, precision, …);
    column (b) adds bias=quatprop.BiasEstimator(window=1.0 (s), gate=3 °/s), any of whose
    arguments `bias_estimator` overrides or adds; use_acc=True also passes the accelerometer (m/s²) as
    integrate(acc=…), for the options that read it. `timing` describes how the configuration places a
    sample in time; it is needed unless the configuration's only timing option is an input model of
    QUATPROP_TIMING."""
    estimator = {"gate": GATE, **(bias_estimator or {})}
    if timing is None:
        if {"sample", "group_delay"} & integrate_kwargs.keys():
            raise ValueError(f"quatprop {name}: describe its timing (timing=…)")
        timing = QUATPROP_TIMING[integrate_kwargs.get("input", "history")]

    def run(gyr: np.ndarray, acc: np.ndarray, fs: float, estimate_bias: bool) -> np.ndarray:
        bias = quatprop.BiasEstimator(**{"window": 1.0, **estimator}) if estimate_bias else None
        with_acc = {"acc": acc} if use_acc and estimate_bias else {}  # acc feeds the estimator only
        q = quatprop.integrate(gyr, dt=1.0 / fs, bias=bias, **with_acc, **integrate_kwargs)
        return np.asarray(q, dtype=np.float64)

    arguments = ", ".join(f"{k}={v!r}" for k, v in integrate_kwargs.items())
    estimator_text = {
        "window": "1.0 (s)",
        **estimator,
        "gate": f"{np.degrees(estimator['gate']):.3g} °/s",
    }
    return Method(
        name=f"quatprop {name}",
        run=run,
        how=f"quatprop.integrate(gyr, dt=1/fs, {arguments}{', acc=acc' if use_acc else ''}, "
        "bias=None or the estimator)",
        timing=timing,
        own_bias="BiasEstimator(" + ", ".join(f"{k}={v}" for k, v in estimator_text.items()) + ")",
    )


QUATPROP_METHODS = [
    quatprop_method("expmap+history f64", scheme="expmap", input="history", precision="f64"),
    quatprop_method("expmap+history f32", scheme="expmap", input="history", precision="f32"),
    quatprop_method("expmap+hold f64", scheme="expmap", input="hold", precision="f64"),
    quatprop_method("rk4+linear f64", scheme="rk4", input="linear", precision="f64"),
    # What a sample means (SampleTiming): BROAD's gyro lags the optical reference by about one sample.
    quatprop_method(
        "expmap+history f32, group delay 3.5 ms",
        timing="ω_k is the rate at t_k − 3.5 ms (one sample); History integrates to there and each attitude "
        "is carried forward by 3.5 ms at ω_k",
        scheme="expmap", input="history", precision="f32", group_delay=3.5e-3,
    ),
    quatprop_method(
        "expmap+interval means (two-sample coning) f64",
        timing="ω_k is the mean rate over [t_{k−1}, t_k]: the increment ω_k·dt, with the two-sample coning "
        "correction",
        scheme="expmap", input="delta_angles", coning="two_sample", sample="interval_mean", precision="f64",
    ),
    quatprop_method(
        "expmap+interval means f64, group delay 1.75 ms",
        timing="ω_k is the mean rate over [t_{k−1}, t_k] − 1.75 ms (half a sample): the increment ω_k·dt, "
        "each attitude carried forward by 1.75 ms",
        scheme="expmap", input="delta_angles", coning="two_sample", sample="interval_mean", precision="f64",
        group_delay=1.75e-3,
    ),
    # The accelerometer tells rest from motion and informs the bias in motion (never the attitude).
    quatprop_method(
        "expmap+history f32, accelerometer rest gate",
        bias_estimator={"accel_gate": 0.5}, use_acc=True,
        scheme="expmap", input="history", precision="f32",
    ),
    quatprop_method(
        "expmap+history f32, motion bias",
        bias_estimator={"motion": True}, use_acc=True,
        scheme="expmap", input="history", precision="f32",
    ),
    quatprop_method(
        "expmap+history f64, motion bias, group delay 3.5 ms",
        timing="ω_k is the rate at t_k − 3.5 ms (one sample); History integrates to there and each attitude "
        "is carried forward by 3.5 ms at ω_k",
        bias_estimator={"motion": True}, use_acc=True,
        scheme="expmap", input="history", precision="f64", group_delay=3.5e-3,
    ),
]


# ---- the peers ----------------------------------------------------------------------------------------


def imufusion_ahrs(fs: float) -> "imufusion.Ahrs":
    """imufusion's Ahrs made gyro-only: gain 0, and skip_startup() (its 3 s startup ramps the gain down from
    10 and zeroes the heading, using the accelerometer). What is left is Fusion's integrator:
    q ← normalise(q + q ⊗ (0, ½ ω dt)) in float32."""
    fusion = imufusion.Ahrs()
    fusion.set_settings(imufusion.AhrsSettings(sample_rate=fs, gain=0.0))
    fusion.skip_startup()
    return fusion


def check_imufusion_gyro_only(fs: float) -> None:
    """Fail loudly if the gain-0 Ahrs is not gyro-only: two accelerometer streams, the same attitudes."""
    rng = np.random.default_rng(0)
    gyr_dps = rng.normal(0.0, 100.0, (500, 3))
    attitudes = []
    for acc_g in (np.tile([0.0, 0.0, 1.0], (500, 1)), rng.normal(0.0, 1.0, (500, 3))):
        fusion = imufusion_ahrs(fs)
        q = []
        for g, a in zip(gyr_dps, acc_g):
            fusion.update_no_magnetometer(g, a)
            q.append(fusion.get_quaternion())
        attitudes.append(np.array(q))
    if not np.array_equal(attitudes[0], attitudes[1]):
        raise RuntimeError("imufusion's Ahrs with gain 0 uses the accelerometer: it is not gyro-only")


def run_imufusion(gyr: np.ndarray, acc: np.ndarray, fs: float, estimate_bias: bool) -> np.ndarray:
    """imufusion: Bias (column b) and a gain-0 Ahrs, sample by sample, in °/s and g as Fusion takes them."""
    fusion = imufusion_ahrs(fs)
    bias = None
    if estimate_bias:
        bias = imufusion.Bias()
        bias.set_settings(imufusion.BiasSettings(sample_rate=fs))  # 3 °/s threshold, 3 s period: defaults
    gyr_dps = np.degrees(gyr)
    acc_g = acc / STANDARD_GRAVITY
    out = np.empty((len(gyr), 4))
    for k in range(len(gyr)):
        g = bias.update(gyr_dps[k]) if bias is not None else gyr_dps[k]
        fusion.update_no_magnetometer(g, acc_g[k])
        out[k] = fusion.get_quaternion()
    return out


def run_vqf(gyr: np.ndarray, acc: np.ndarray, fs: float, estimate_bias: bool) -> np.ndarray:
    """vqf: VQF's gyro-only strapdown quaternion quat3D (state gyrQuat; updateBatch returns only quat6D),
    with its rest and motion bias estimation (both use the accelerometer) on in column (b), off otherwise."""
    filt = vqf.VQF(1.0 / fs, motionBiasEstEnabled=estimate_bias, restBiasEstEnabled=estimate_bias)
    state = filt.updateBatchFullState(np.ascontiguousarray(gyr), np.ascontiguousarray(acc))
    return state["gyrQuat"]


def run_ahrs(gyr: np.ndarray, acc: np.ndarray, fs: float, estimate_bias: bool) -> np.ndarray:
    """ahrs: filters.AngularRate, its default closed-form step (a Python loop over the samples)."""
    return np.asarray(ahrs.filters.AngularRate(gyr=gyr, frequency=fs).Q, dtype=np.float64)


def run_scipy(gyr: np.ndarray, acc: np.ndarray, fs: float, estimate_bias: bool) -> np.ndarray:
    """SciPy: R_k = R_{k−1} · Rotation.from_rotvec(ω_k dt), composed sample by sample."""
    steps = Rotation.from_rotvec(gyr / fs).as_quat()  # scalar last: SciPy's order
    attitude = Rotation.identity()
    out = np.empty((len(gyr), 4))
    for k in range(len(gyr)):
        attitude = attitude * Rotation.from_quat(steps[k])
        out[k] = attitude.as_quat(scalar_first=True)
    return out


PEER_METHODS = [
    Method(
        "imufusion Ahrs gain 0",
        run_imufusion,
        "per sample: Bias.update(ω_k in °/s) (column b), then Ahrs.update_no_magnetometer(ω, a in g) and "
        "get_quaternion(); Ahrs with AhrsSettings(sample_rate=fs, gain=0) and skip_startup(): gyro-only, "
        "Fusion's own integrator",
        "zero-order hold: update(ω_k) steps by ω_k·dt, first order (q + ½ q⊗(0, ω) dt, normalised), "
        "float32: ω_k over [t_{k−1}, t_k]",
        "Bias(BiasSettings(sample_rate=fs)): stationary_threshold 3 °/s, stationary_period 3 s (its defaults); "
        "its corrected °/s go into the same gain-0 Ahrs",
    ),
    Method(
        "vqf quat3D",
        run_vqf,
        "VQF(1/fs, motionBiasEstEnabled=b, restBiasEstEnabled=b).updateBatchFullState(gyr, acc)['gyrQuat'] "
        "= quat3D after each sample (updateBatch returns quat6D only); b = column (b)",
        "zero-order hold: updateGyr(ω_k) applies exp(ω_k·Ts), exact for a constant rate: "
        "ω_k over [t_{k−1}, t_k]",
        "VQF's rest and motion bias estimation, default parameters (both use the accelerometer: rest "
        "detection, and the inclination during motion)",
    ),
    Method(
        "ahrs AngularRate",
        run_ahrs,
        "ahrs.filters.AngularRate(gyr=gyr, frequency=fs).Q (default method 'closed'; a Python loop)",
        "zero-order hold: Q[t] = exp(½Ω(ω_t)·dt)·Q[t−1], closed form; ω_0 is not used: "
        "ω_k over [t_{k−1}, t_k]",
        None,
    ),
    Method(
        "SciPy Rotation",
        run_scipy,
        "R_k = R_{k−1} * Rotation.from_quat(Rotation.from_rotvec(gyr/fs).as_quat()[k]), a Python loop",
        "zero-order hold: R_k = R_{k−1}·from_rotvec(ω_k·dt): ω_k over [t_{k−1}, t_k]",
        None,
    ),
]

METHODS = QUATPROP_METHODS + PEER_METHODS


# ---- running ------------------------------------------------------------------------------------------


def timed_run(method: Method, gyr, acc, fs, estimate_bias, repeats: int) -> Tuple[np.ndarray, float]:
    """The attitudes of the first run and the best wall time (s) of `repeats` runs."""
    best, q = np.inf, None
    for _ in range(repeats):
        start = time.perf_counter()
        result = method.run(gyr, acc, fs, estimate_bias)
        best = min(best, time.perf_counter() - start)
        q = result if q is None else q
    return q, best


def progress(text: str) -> None:
    sys.stderr.write("\r\033[K" + text)
    sys.stderr.flush()


@dataclass
class Results:
    """errors[(method, column, trial)]: (len(SHIFTS), len(HORIZONS), starts) degrees; cost[(method, column)]:
    ns per sample on the cost trial; starts[trial]: the start samples."""

    trials: List[bm.Trial]
    errors: Dict[Tuple[str, str, str], np.ndarray]
    cost: Dict[Tuple[str, str], float]
    starts: Dict[str, np.ndarray]
    seconds: float  # wall time of the whole run
    load: float  # the machine's 1-minute load average at its end


def run_all(trials: List[bm.Trial]) -> Results:
    errors, cost, starts = {}, {}, {}
    began = time.perf_counter()
    runs = [(m, c) for m in METHODS for c in BIAS_COLUMNS if c != "own" or m.own_bias is not None]
    for i, trial in enumerate(trials):
        starts[trial.name] = bm.start_points(trial.movement, trial.fs, START_EVERY)
        truths = [bm.shift_truth(trial.quat, shift) for shift in SHIFTS]
        oracle_gyr = trial.gyr - trial.rest_bias()
        for method, column in runs:
            progress(f"[{i + 1}/{len(trials)}] {trial.name}: {method.name} {COLUMN_TITLES[column]}")
            gyr = oracle_gyr if column == "oracle" else trial.gyr
            repeats = COST_REPEATS if i == 0 and column != "oracle" else 1
            q, seconds = timed_run(method, gyr, trial.acc, trial.fs, column == "own", repeats)
            if i == 0 and column != "oracle":
                cost[(method.name, column)] = seconds / len(gyr) * 1e9
            errors[(method.name, column, trial.name)] = np.stack(
                [
                    bm.errors(q, truth, trial.fs, starts[trial.name], HORIZONS, trial.movement)
                    for truth in truths
                ]
            )
        progress(f"[{i + 1}/{len(trials)}] {trial.name}: done, {time.perf_counter() - began:.0f} s so far\n")
    return Results(trials, errors, cost, starts, time.perf_counter() - began, os.getloadavg()[0])


# ---- summaries ----------------------------------------------------------------------------------------


def nanmean(a: np.ndarray, axis: int) -> np.ndarray:
    """Mean over `axis` ignoring NaN; NaN where every entry is NaN (no valid start point)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.nanmean(a, axis=axis)


def trial_means(res: Results, method: str, column: str) -> np.ndarray:
    """(trials, shifts, horizons): each trial's mean over its start points."""
    return np.stack([nanmean(res.errors[(method, column, t.name)], axis=-1) for t in res.trials])


def pooled(res: Results, method: str, column: str) -> np.ndarray:
    """(shifts, horizons): the mean over trials of the per-trial means."""
    return nanmean(trial_means(res, method, column), axis=0)


def pooled_all_starts(res: Results, method: str, column: str) -> np.ndarray:
    """(shifts, horizons): the mean over every start point of every trial."""
    return nanmean(
        np.concatenate([res.errors[(method, column, t.name)] for t in res.trials], axis=-1), axis=-1
    )


def has(res: Results, method: str, column: str) -> bool:
    return (method, column, res.trials[0].name) in res.errors


def best_shift(res: Results, method: str) -> int:
    """The shift (half samples) minimising the pooled oracle-bias error at SHIFT_FIT_HORIZON."""
    return SHIFTS[int(np.nanargmin(pooled(res, method, "oracle")[:, HORIZONS.index(SHIFT_FIT_HORIZON)]))]


# ---- the report ---------------------------------------------------------------------------------------

NO_SHIFT = SHIFTS.index(0)
TABLE_COLUMNS = [HORIZONS.index(h) for h in TABLE_HORIZONS]


def fmt(x: float) -> str:
    return "—" if not np.isfinite(x) else f"{x:.2f}"


def error_table(res: Results, summary, shift_of) -> List[str]:
    """Rows: methods; columns: the bias columns × TABLE_HORIZONS. shift_of(method) → shift index."""
    head = "| method | " + " | ".join(f"{c} {h:g} s" for c in ("(a)", "(b)", "(c)") for h in TABLE_HORIZONS)
    lines = [head + " |", "|---" * (1 + 3 * len(TABLE_HORIZONS)) + "|"]
    for m in METHODS:
        cells = []
        for column in BIAS_COLUMNS:
            if has(res, m.name, column):
                values = summary(res, m.name, column)[shift_of(m.name), TABLE_COLUMNS]
                cells += [fmt(v) for v in values]
            else:
                cells += ["—"] * len(TABLE_HORIZONS)
        lines.append(f"| {m.name} | " + " | ".join(cells) + " |")
    return lines


def per_trial_table(res: Results, column: str, horizon: float) -> List[str]:
    h = HORIZONS.index(horizon)
    methods = [m for m in METHODS if has(res, m.name, column)]
    lines = [
        "| trial | pairs | " + " | ".join(m.name for m in methods) + " |",
        "|---" * (2 + len(methods)) + "|",
    ]
    means = {m.name: trial_means(res, m.name, column)[:, NO_SHIFT, h] for m in methods}
    for i, t in enumerate(res.trials):
        n = int(np.isfinite(res.errors[(methods[0].name, column, t.name)][NO_SHIFT, h]).sum())
        lines.append(f"| {t.name} | {n} | " + " | ".join(fmt(means[m.name][i]) for m in methods) + " |")
    lines.append(
        "| **mean over trials** | | "
        + " | ".join(f"**{fmt(np.nanmean(means[m.name]))}**" for m in methods)
        + " |"
    )
    return lines


def shift_curve_table(res: Results) -> List[str]:
    h = HORIZONS.index(SHIFT_FIT_HORIZON)
    lines = [
        "| method | " + " | ".join(f"{s / 2:+g}" for s in SHIFTS) + " |",
        "|---" * (1 + len(SHIFTS)) + "|",
    ]
    for m in METHODS:
        curve = pooled(res, m.name, "oracle")[:, h]
        best = int(np.nanargmin(curve))
        cells = [f"**{fmt(v)}**" if i == best else fmt(v) for i, v in enumerate(curve)]
        lines.append(f"| {m.name} | " + " | ".join(cells) + " |")
    return lines


def findings(res: Results) -> List[str]:
    """A few sentences with the run's own pooled figures."""

    def at(method: Method, column: str, horizon: float, aligned: bool) -> float:
        shift = SHIFTS.index(best_shift(res, method.name)) if aligned else NO_SHIFT
        return pooled(res, method.name, column)[shift, HORIZONS.index(horizon)]

    raw = [at(m, "none", 60.0, False) for m in METHODS]
    as_they_are = [at(m, "oracle", SHIFT_FIT_HORIZON, False) for m in METHODS]
    aligned = [at(m, "oracle", SHIFT_FIT_HORIZON, True) for m in METHODS]
    own = [f"{m.name} {at(m, 'own', 60.0, True):.2f}°" for m in METHODS if has(res, m.name, "own")]
    sigmas = sorted({best_shift(res, m.name) / 2 for m in METHODS})

    def span(values: List[float]) -> str:
        low, high = fmt(min(values)), fmt(max(values))
        return f"{low}°" if low == high else f"{low}–{high}°"

    return [
        f"- Without bias removal every method drifts alike: {span(raw)} at 60 s.",
        f"- With each method's own bias estimator, timing-aligned, at 60 s: {'; '.join(own)}.",
        "- On equal input (the oracle bias) the integrators differ only by where they place a sample in time: "
        f"{span(as_they_are)} at {SHIFT_FIT_HORIZON:g} s as they are, {span(aligned)} once each is shifted "
        "by its best σ "
        f"({', '.join(f'{s:+g}' for s in sigmas)} samples: a zero-order hold places a sample half a sample "
        "earlier than an integrator that reads it as the rate at its own time).",
        *semantics(res, at),
    ]


def semantics(res: Results, at: Callable[[Method, str, float, bool], float]) -> List[str]:
    """What a sample means, as the configurations that state it fit the reference (oracle bias, 10 s)."""
    named = {m.name: m for m in METHODS}
    instant = named.get("quatprop expmap+history f32")
    delayed = named.get("quatprop expmap+history f32, group delay 3.5 ms")
    means = named.get("quatprop expmap+interval means (two-sample coning) f64")
    best = next((m for m in METHODS if "motion bias" in m.name and has(res, m.name, "own")), None)
    vqf = named.get("vqf quat3D")
    if not (instant and delayed and means):
        return []
    h = SHIFT_FIT_HORIZON
    inst, mean = at(instant, "oracle", h, True), at(means, "oracle", h, True)
    verdict = (
        "this IMU's samples fit better as instants, late by the best σ"
        if inst < mean
        else "this IMU's samples fit better as interval means"
    )
    lines = [
        "- What a sample means (quatprop's `sample=` and `group_delay=`): read as the rate at its timestamp, "
        f"a sample fits the reference {fmt(at(instant, 'oracle', h, False))}° at {h:g} s as recorded and "
        f"{fmt(inst)}° shifted by its best σ ({best_shift(res, instant.name) / 2:+g} samples); stated as "
        f"delayed by one sample (`group_delay=3.5e-3`) it gives {fmt(at(delayed, 'oracle', h, False))}° with no "
        "shift at all. Read as a mean over the interval before it (`sample=\"interval_mean\"`), the best it "
        f"reaches is {fmt(mean)}°: {verdict}. The default stays the instant reading (what a rate gyro's "
        "register holds); a delay is the sensor's, to be measured like this or taken from its filter's "
        "datasheet.",
    ]
    if best and vqf:
        lines.append(
            f"- Bias with the accelerometer, attitude from the gyro alone: {best.name} "
            f"{fmt(at(best, 'own', 60.0, True))}° at 60 s (timing-aligned) beside vqf's strapdown with its bias "
            f"estimation {fmt(at(vqf, 'own', 60.0, True))}°; per trial below."
        )
    return lines


def versions() -> str:
    """The versions of everything that ran."""
    packages = ("quatprop", "imufusion", "vqf", "ahrs", "scipy", "numpy", "h5py", "matplotlib")
    return (
        ", ".join(f"{name} {package_version(name)}" for name in packages)
        + f"; Python {platform.python_version()}"
    )


def write_markdown(res: Results, path: Path) -> None:
    fs = res.trials[0].fs
    shifts = {m.name: SHIFTS.index(best_shift(res, m.name)) for m in METHODS}
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    cpu = platform.processor() or platform.machine()
    rest = [t.first_movement / t.fs for t in res.trials]
    out = [
        "<!-- Written by python/benchmarks/broad.py: do not edit by hand. Regenerate with "
        f"`{COMMAND}`. -->",
        "",
        "# Gyro-only orientation error on real IMU recordings (BROAD)",
        "",
        f"*Written by `python/benchmarks/broad.py` on {now}; regenerate with `{COMMAND}` "
        f"({res.seconds:.0f} s on this machine: {os.cpu_count()} cores, {cpu}, load average {res.load:.1f} at the "
        f"end). {versions()}.*",
        "",
        f"**Data:** {len(res.trials)} trials of BROAD, the Berlin Robust Orientation Estimation Assessment "
        f"Dataset: {bm.ATTRIBUTION}. The full dataset (39 trials, with the publishers' own evaluation code) is at "
        "[github.com/dlaidig/broad](https://github.com/dlaidig/broad); put its `.hdf5` trials in a folder and pass "
        "the folder to the command above (`--trials 02,05` picks trials by number). Each trial: an IMU (myon "
        f"aktos-t) at {fs:.3f} Hz, gyroscope in rad/s, and an optical reference (OptiTrack) as a quaternion, "
        "sensor → ENU, NaN where tracking was lost.",
        "",
        "![Pooled error against horizon for each bias column; per-trial error at 60 s](broad.png)",
        "",
        "## The metric",
        "",
        f"- From start points every {START_EVERY:g} s inside the movement phase (a grid from the first movement "
        "sample, s_j = m0 + round(j·5 s·fs), keeping grid points that are movement samples), each method's "
        "attitude is started at the optical truth at s, the gyro is integrated for a horizon h of "
        + ", ".join(f"{h:g}" for h in TABLE_HORIZONS)
        + " s, and the error is the rotation angle between that estimate and the optical truth at e = "
        "s + round(h·fs). A pair is skipped when the truth is NaN at s or e, or e is not a movement sample "
        "(past the end of the movement, or in a break).",
        "- Computed exactly from one run per method over the whole trial from identity, q_k = the attitude "
        "after sample k: the estimate is truth_s ⊗ q_s⁻¹ ⊗ q_e, so the error is the angle of "
        "truth_e⁻¹ ⊗ truth_s ⊗ q_s⁻¹ ⊗ q_e. This is exact for a method whose only state is the attitude; a "
        "bias estimator runs causally over the whole trial from its start (these trials start with "
        f"{min(rest):.0f}–{max(rest):.0f} s at rest), which is what a user streaming the data gets.",
        "- Per trial: the mean over its start points. **Pooled: the mean over trials** of the per-trial means "
        "(a second table gives the mean over all start points of all trials).",
        "- Bias columns: **(a)** the gyro as recorded; **(b)** each method's own bias estimator, run causally "
        'from the start of the trial (a method without one: —); **(c)** the "oracle": the mean gyro over the '
        "initial rest phase (the samples before the first movement sample) subtracted from the gyro before "
        "any method sees it, so every integrator gets the same input.",
        "",
        "## In short",
        "",
        *findings(res),
        "",
        "## Pooled error (degrees), mean over trials",
        "",
        "(a) no bias removal, (b) each method's own bias estimator, (c) the oracle bias; the timing as each "
        "method places its samples (no shift).",
        "",
        *error_table(res, pooled, lambda m: NO_SHIFT),
        "",
        "Mean over all start points of all trials (degrees):",
        "",
        *error_table(res, pooled_all_starts, lambda m: NO_SHIFT),
        "",
        "## Per trial at 60 s (degrees)",
        "",
        "Each trial's mean over its start points, no shift; pairs: the start points whose 60 s pair is valid "
        "(the truth not NaN at either end, the end inside the movement).",
        "",
    ]
    for column in BIAS_COLUMNS:
        out += [f"{COLUMN_TITLES[column]}:", "", *per_trial_table(res, column, 60.0), ""]
    out += [
        "## Timing-aligned",
        "",
        "The truth is shifted in time by σ samples (row k compared with the truth at t_k + σ·dt; a half "
        "sample is the slerp midpoint of the two neighbouring truth samples), for σ from −3 to +3 in half "
        f"samples. Each method's best σ minimises its pooled oracle-bias (c) error at {SHIFT_FIT_HORIZON:g} s "
        "(the shortest table horizon: the misalignment error does not grow with the horizon while the drift "
        "does), and every column is then evaluated with that σ. A negative σ: the method's attitude after "
        "sample k is the true attitude at an earlier time than t_k, i.e. the gyro lags the optical reference "
        f"(or the method places its samples too late). 1 sample = {1000.0 / fs:.2f} ms.",
        "",
        "| method | timing convention (how ω_k is placed in time; the attitude after sample k is compared "
        "with the truth at t_k) | best σ (samples) | best σ (ms) |",
        "|---|---|---|---|",
    ]
    for m in METHODS:
        s = best_shift(res, m.name) / 2
        out.append(f"| {m.name} | {m.timing} | {s:+g} | {s * 1000.0 / fs:+.2f} |")
    out += [
        "",
        "Pooled error (degrees), each method with its best σ:",
        "",
        *error_table(res, pooled, lambda m: shifts[m]),
        "",
        f"The fit: pooled oracle-bias (c) error at {SHIFT_FIT_HORIZON:g} s (degrees) against σ (samples), the "
        "minimum in bold:",
        "",
        *shift_curve_table(res),
        "",
        "## Cost per sample",
        "",
        f"Wall time of a whole-trial run divided by its samples (ns), best of {COST_REPEATS} runs on "
        f"{res.trials[0].name} ({len(res.trials[0].gyr)} samples), timed around the method's call(s) as listed "
        "above (input conversion included, file reading excluded). imufusion, ahrs and SciPy run a Python loop "
        "over the samples; quatprop and vqf loop in compiled code (vqf: updateBatchFullState, which also copies "
        "its whole state out after every sample, because quat3D is only there; vqf always runs its full "
        "6D filter). A quatprop run takes a few milliseconds, so on a shared machine its figures move by tens "
        f"of percent from run to run (the load average was {res.load:.1f} at the end of this one): read them "
        "as tens of ns against the peers' microseconds.",
        "",
        "| method | (a) no bias estimation | (b) with its own bias estimator |",
        "|---|---|---|",
    ]
    for m in METHODS:
        b = res.cost.get((m.name, "own"))
        out.append(f"| {m.name} | {res.cost[(m.name, 'none')]:,.0f} | {'—' if b is None else f'{b:,.0f}'} |")
    out += [
        "",
        "## Methods",
        "",
        "| method | how it is run | own bias estimator (column b) |",
        "|---|---|---|",
    ]
    for m in METHODS:
        out.append(f"| {m.name} | {m.how} | {m.own_bias or '— (none)'} |")
    out += [
        "",
        "Every method is an installed package run through its own API; nothing of a peer is re-implemented. "
        "imufusion's Ahrs with gain 0 is checked by the program, at every run, to give the same attitudes for "
        "two different accelerometer streams (gyro-only); ahrs and SciPy have no bias estimator.",
        "",
        "---",
        "",
        f"Data: {bm.ATTRIBUTION}. The tables and the figure are derived from it.",
        "",
    ]
    path.write_text("\n".join(out))


def write_plot(res: Results, path: Path) -> None:
    """Top: pooled error against horizon (log y) for each bias column, and for (c) with each method's best
    timing shift; bottom: per-trial error at 60 s with each method's own bias estimator."""
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    style = {
        m.name: dict(
            color=colours[i % len(colours)],
            ls="--" if m.name.startswith("quatprop") else "-",
            marker="o",
            ms=3,
        )
        for i, m in enumerate(METHODS)
    }
    fig = plt.figure(figsize=(16, 10))
    grid = fig.add_gridspec(2, 4, hspace=0.3, wspace=0.06, top=0.86)
    panels = [(column, NO_SHIFT, COLUMN_TITLES[column]) for column in BIAS_COLUMNS]
    panels.append(("oracle", None, "(c) oracle bias, timing-aligned (best σ each)"))
    top = [fig.add_subplot(grid[0, 0])]
    top += [fig.add_subplot(grid[0, i], sharey=top[0]) for i in range(1, len(panels))]
    for ax, (column, shift, title) in zip(top, panels):
        for m in METHODS:
            if has(res, m.name, column):
                s = SHIFTS.index(best_shift(res, m.name)) if shift is None else shift
                ax.plot(HORIZONS, pooled(res, m.name, column)[s], label=m.name, **style[m.name])
        ax.set_yscale("log")
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("horizon (s)")
        ax.yaxis.set_major_locator(ticker.LogLocator(subs=(1.0, 2.0, 5.0)))
        ax.yaxis.set_major_formatter(ticker.FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(ticker.NullFormatter())
        ax.grid(True, which="both", alpha=0.3)
        if ax is not top[0]:
            ax.tick_params(labelleft=False)
    top[0].set_ylabel("pooled error (deg, mean over trials)")
    handles, labels = top[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=4, fontsize=9, bbox_to_anchor=(0.5, 0.95))

    bars = fig.add_subplot(grid[1, :])
    methods = [m for m in METHODS if has(res, m.name, "own")]
    width = 0.8 / len(methods)
    x = np.arange(len(res.trials))
    h = HORIZONS.index(60.0)
    for j, m in enumerate(methods):
        bars.bar(
            x + (j - (len(methods) - 1) / 2) * width,
            trial_means(res, m.name, "own")[:, NO_SHIFT, h],
            width,
            color=style[m.name]["color"],
            label=m.name,
        )
    bars.set_xticks(x, [t.name for t in res.trials], rotation=15, ha="right", fontsize=8)
    bars.set_ylabel("error at 60 s (deg)")
    bars.set_title(
        "Per trial at 60 s, (b) each method's own bias estimator, no shift (mean over the trial's start points)",
        fontsize=10,
    )
    bars.grid(True, axis="y", alpha=0.3)
    bars.legend(fontsize=8, ncol=3)
    fig.suptitle(
        "Gyro-only orientation error on BROAD: started at the optical truth, gyro integrated for a horizon",
        y=0.985,
    )
    fig.text(0.5, 0.01, "Data: " + bm.ATTRIBUTION, ha="center", va="bottom", fontsize=8)
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def main(argv: Optional[Sequence[str]] = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder", type=Path, help="a folder of BROAD trials (NN_name.hdf5)")
    parser.add_argument("--out", type=Path, default=Path("docs"), help="where broad.md and broad.png go")
    parser.add_argument("--trials", help="comma-separated trial numbers, e.g. 02,05 (default: all)")
    args = parser.parse_args(argv)

    paths = sorted(args.folder.glob("*.hdf5"))
    if args.trials:
        wanted = {n.strip().zfill(2) for n in args.trials.split(",")}
        paths = [p for p in paths if p.name[:2] in wanted]
    if not paths:
        parser.error(f"no trials found in {args.folder}")
    trials = [bm.read_trial(p) for p in paths]
    check_imufusion_gyro_only(trials[0].fs)
    res = run_all(trials)
    args.out.mkdir(parents=True, exist_ok=True)
    write_markdown(res, args.out / "broad.md")
    write_plot(res, args.out / "broad.png")
    print(
        f"wrote {args.out / 'broad.md'} and {args.out / 'broad.png'} in {res.seconds:.0f} s", file=sys.stderr
    )


if __name__ == "__main__":
    main()
