"""quatprop: gyroscope samples to attitude quaternions, bit for bit the quatprop Rust library.

Conventions (the Rust library's, unchanged):

- A quaternion is an array ``[w, x, y, z]``: **scalar first** (SciPy's ``Rotation.as_quat()`` is scalar
  last: ``q[..., [1, 2, 3, 0]]`` converts), **Hamilton** product (``ij = k``).
- An attitude maps **body** vectors to the reference frame: ``v_ref = q ⊗ (0, v_body) ⊗ q*``
  (SciPy: ``Rotation.from_quat(q[[1, 2, 3, 0]]).apply(v_body)``).
- Rates are **body-frame** and compose on the right: ``q' = ½ q ⊗ (0, ω)``; a constant rate ω held for
  ``t`` seconds turns ``q0`` into ``q0 ⊗ exp(ω t / 2)`` (SciPy: ``R0 * Rotation.from_rotvec(ω t)``).
- Units: radians, rad/s, seconds.
- Euler angles: ``zyx`` = aerospace (yaw, pitch, roll), ``R = Rz(yaw) Ry(pitch) Rx(roll)`` (SciPy:
  ``as_euler("ZYX")``); ``zxz`` = classical (psi, theta, phi), ``R = Rz(psi) Rx(theta) Rz(phi)``
  (SciPy: ``as_euler("ZXZ")``).

The integration runs in Rust, in the core library's own loop over the whole buffer, with the GIL
released; no Python code runs per sample.
"""

# Imported under private names: the package's namespace is its public API (`__all__`) and nothing else.
from dataclasses import dataclass as _dataclass
from typing import List as _List, Optional as _Optional, Sequence as _Sequence, Tuple as _Tuple

import numpy as _np

from . import _native

__all__ = [
    "integrate",
    "Stream",
    "Calibration",
    "calibrate",
    "RefusedSample",
    "BiasEstimator",
    "CalibrationEstimator",
    "CountScale",
    "allan",
    "to_euler_zyx",
    "from_euler_zyx",
    "to_euler_zxz",
    "from_euler_zxz",
    "SCHEMES",
    "STABILIZERS",
    "INPUTS",
    "CONINGS",
    "AXIS_REMAPS",
    "SAMPLES",
]

__version__ = "0.3.0"

SCHEMES = ("euler", "rk2", "rk3", "rk4", "rk5", "expmap", "magnus4", "cf4")
"""Integration schemes (the core's ``SchemeKind``)."""
STABILIZERS = ("off", "normalize", "first_order", "every:N")
"""Post-step stabilizers (the core's ``StabilizerKind``); ``"every:N"`` normalizes every N-th step."""
INPUTS = ("hold", "linear", "history", "twice_rate", "gauss_points", "delta_angles")
"""Input models (the core's ``input`` module); ``delta_angles`` takes increments (rad), not rates."""
CONINGS = ("uncorrected", "one_plus_previous", "two_sample", "three_sample", "four_sample", "five_sample")
"""Coning corrections for ``input="delta_angles"`` (the core's ``ConingKind``)."""
AXIS_REMAPS = tuple(_native.AXIS_REMAPS)
#: What a sample means in time (``sample=``): the rate at its timestamp, or the mean over the interval before it.
SAMPLES = ("instant", "interval_mean")
"""The 24 axis remaps (the core's ``AxisRemap``): ``"PyNxPz"`` means body x = +sensor y,
body y = −sensor x, body z = +sensor z."""


class RefusedSample(ValueError):
    """A sample the propagator refused (``on_refused="raise"``).

    Attributes:
        index: the index of the refused sample in ``gyr``.
        kind: the core's ``Error`` variant, e.g. ``"NonFiniteRate"``, ``"TimestampNotIncreasing"``,
            ``"StepAngleBeyondStability"``.
        reason: the core's message for it.
    """

    def __init__(self, index: int, kind: str, reason: str) -> None:
        super().__init__(f"sample {index} refused: {reason} ({kind})")
        self.index = index
        self.kind = kind
        self.reason = reason

    def __reduce__(self):  # picklable (multiprocessing)
        return (RefusedSample, (self.index, self.kind, self.reason))


@_dataclass(frozen=True)
class BiasEstimator:
    """Learns the gyro bias while the body is still, follows it as it drifts and when it steps at rest —
    without taking a slow turn or the end of a motion for a bias (the core's ``frontend::BiasEstimator``).

    Samples are taken in windows of ``window`` **seconds** (the window holds ``round(window / period)``
    samples: change the rate and the window stays as long), each cut into 8 blocks. A window is *still*
    when every sample (minus the estimate) stays within ``gate`` rad/s on every axis and none is saturated
    (with ``accel_gate``, also every acceleration within that gate of the window's first), and it is flat:
    its block means scatter no more than at rest (the scatter at rest is learned from the still windows,
    or given by ``noise_density``); when ``acc`` is given, the accelerations' block means must be flat
    too. Each still window is a measurement of a bias that walks with density ``drift``: a Kalman filter.
    A still window more than five standard deviations off the estimate is taken for a slow turn, not a
    bias, until the drift says the bias could have moved that far: ``drift`` is the one knob between
    following a changing bias and keeping a slow turn (docs/bias.md plots it against Fusion's and VQF's).
    A step at rest (two flat levels in one window, the first at the estimate, confirmed by the next still
    window) is followed within two windows.

    Attributes:
        window: the window's length (s), e.g. 1.0. An integer above 100 is refused as a likely sample
            count (the 0.3 API's unit): give ``samples * dt``, or a float for a window that long.
        gate: stillness gate (rad/s), e.g. 3 °/s = 0.0524 rad/s.
        drift: how fast the bias may wander, as the density of a random walk (rad/s/√s): after ``t``
            seconds without a still window that agrees, the bias may be about ``drift·√t`` away, and a
            still window ``5·drift·√t`` off the estimate (beyond the estimate's and the window's own
            uncertainty) is believed; one farther off is kept out as a turn. None: the core's
            ``DEFAULT_DRIFT``, 2e-5 rad/s/√s (a window 0.044 °/s off is believed after a minute without
            an agreeing one, 0.34 °/s after an hour). Larger follows a warming sensor sooner and keeps a
            slow turn for less long; 0 takes the bias for a constant (changed by a step at rest only).
            The gyro's own rate random walk is the least it can be.
        rest_drift: how fast the bias wanders while the body stays still (rad/s/√s): the filter's
            process noise between still windows that agree (it sets how closely a drift at rest is
            followed and how much noise the estimate keeps; it lets no slow turn in). The gyro's rate
            random walk and bias instability (:func:`allan`) are its physical value; None: the core's
            ``DEFAULT_REST_DRIFT``, 2e-5 rad/s/√s.
        noise_density: the gyro's white noise (rad/√s = rad/s/√Hz, a datasheet's or identified from a
            rest recording with :func:`allan`); None: the scatter at rest is learned from the still
            windows (the first still window is then taken as it is).
        initial: a known bias to start from (rad/s, body axes, e.g. stored at the last shutdown), with
            ``initial_sigma``.
        initial_sigma: the standard deviation of ``initial`` (rad/s): how far the bias may have moved
            since. A first still window within five of it refines ``initial``; one farther off is
            followed as a step only (the next still window must confirm it).
        accel_gate: acceleration gate per axis, in the unit of the ``acc`` given to :meth:`Stream.update`
            (e.g. 0.5 m/s²); None: no gate (the accelerations' flatness is tested whenever ``acc`` is given).
        temperature_span: the temperature spread (standard deviation, the unit of ``temperature``) from
            which the bias(T) line is applied; None: no temperature model.
        motion: also learn the residual bias in motion from the accelerometer (``True``: the core's
            ``frontend::MotionBias``, VQF's motion bias estimation, on the rates corrected at rest; it
            restarts at zero whenever a still window is learned), or the gyro's gain (scale and
            misalignment) with it (a :class:`CalibrationEstimator`; :attr:`Stream.learned_calibration`
            shows what it learned). Needs ``acc`` (in the gyro's axes, m/s² or any unit) and a fixed
            period (``dt=``). The accelerometer informs the rates only; the attitude is the gyro's.
            :attr:`Stream.bias` is then the sum of both biases: what is subtracted.
        period: the sample period (s), from which the window's samples are counted; None: the stream's
            ``dt``. Needed with timestamps and with ticks (``tick_hz`` is the counter's rate, not the
            sample rate).
    """

    window: float
    gate: float
    drift: _Optional[float] = None
    rest_drift: _Optional[float] = None
    noise_density: _Optional[float] = None
    initial: _Optional[_Sequence[float]] = None
    initial_sigma: _Optional[float] = None
    accel_gate: _Optional[float] = None
    temperature_span: _Optional[float] = None
    motion: "bool | CalibrationEstimator" = False
    period: _Optional[float] = None

    def _native(self):
        initial = None
        if self.initial is not None:
            ia = _np.asarray(self.initial, dtype=_np.float64)
            if ia.shape != (3,):
                raise ValueError("BiasEstimator.initial must be [bx, by, bz]")
            if self.initial_sigma is None:
                raise ValueError("BiasEstimator.initial needs initial_sigma (rad/s)")
            initial = ([float(c) for c in ia], float(self.initial_sigma))
        elif self.initial_sigma is not None:
            raise ValueError("BiasEstimator.initial_sigma needs initial (rad/s)")
        if isinstance(self.window, (int, _np.integer)) and not isinstance(self.window, bool) and self.window > 100:
            raise ValueError(
                f"BiasEstimator.window is in seconds, got the integer {self.window!r}: a sample count? "
                f"give window={self.window} * dt (or a float for a window that many seconds long)"
            )

        def opt(v):
            return None if v is None else float(v)

        return _EstimatorArgs(float(self.window), float(self.gate), opt(self.period), opt(self.drift),
                              opt(self.rest_drift), opt(self.noise_density), initial, opt(self.accel_gate),
                              opt(self.temperature_span), bool(self.motion),
                              self.motion._native() if isinstance(self.motion, CalibrationEstimator) else None)


@_dataclass(frozen=True)
class CalibrationEstimator:
    """Learns the gyro's gain — per-axis scale factor and axis misalignment, ``ω = (I − G)(ω_c − b)`` —
    and its residual bias in motion from the accelerometer (the core's ``frontend::CalibrationEstimator``):
    give it as ``BiasEstimator(motion=CalibrationEstimator(...))``.

    The accelerometer, low-passed (τ = 3 s) in the shadow attitude's frame, shows how the inclination
    drifts; a wrong gain makes it drift in proportion to how the body turns, which a Kalman filter on
    twelve states (three of bias, nine of gain) learns. A term shows only while the body turns about its
    axis at an attitude where that turn tilts: what has not been seen stays at its prior, and
    :attr:`Stream.learned_calibration` gives each term's standard deviation.

    Attributes:
        sensitivity_sigma: prior standard deviation of each scale factor (dimensionless; a datasheet's
            sensitivity tolerance, e.g. 0.01 for ±1 %).
        misalignment_sigma: prior standard deviation of each cross-axis term (rad; a datasheet's
            cross-axis sensitivity, e.g. 0.0087 for ±0.5°).
        motion_noise: the measurement noise (rad/s): the spread of the low-passed inclination drift that
            is not the gyro's (linear acceleration). None: the core's ``DEFAULT_MOTION_NOISE``
            (0.173 °/s, chosen by leave-one-trial-out on BROAD; docs/calibration.md). Smaller learns
            faster and trusts the accelerometer more.
    """

    sensitivity_sigma: float
    misalignment_sigma: float
    motion_noise: _Optional[float] = None

    def _native(self):
        return (float(self.sensitivity_sigma), float(self.misalignment_sigma),
                None if self.motion_noise is None else float(self.motion_noise))


@_dataclass(frozen=True)
class _EstimatorArgs:
    """What the native layer reads (by attribute) from a :class:`BiasEstimator`."""

    window: float
    gate: float
    period: _Optional[float]
    drift: _Optional[float]
    rest_drift: _Optional[float]
    noise: _Optional[float]
    initial: _Optional[tuple]
    accel_gate: _Optional[float]
    span: _Optional[float]
    motion: bool
    calibrate: _Optional[tuple]


def _fit(f) -> _Optional[dict]:
    if f is None:
        return None
    names = ("value", "coefficient", "std_error", "identified", "lower", "upper")
    white, instability, walk, points, tau_range, misfit = f
    return {
        "white": dict(zip(names, white)),
        "instability": dict(zip(names, instability)),
        "random_walk": dict(zip(names, walk)),
        "points": points,
        "tau_range": tau_range,
        "misfit": misfit,
    }


def allan(samples, dt: float, min_tau: float = 0.0) -> dict:
    """The noise of a 3-axis sensor at rest, from its Allan variance (the core's ``noise::AllanVariance``
    and ``noise::NoiseFit``): white noise ``N``, bias instability ``B`` and random walk ``K``, each with its
    standard error.

    The Allan variance is the non-overlapping one at octave cluster times ``τ = 2^k·dt``, computed as the
    samples stream (no buffer: the same code runs on a microcontroller). The model
    ``σ²(τ) = N²/τ + (2 ln 2/π) B² + K² τ/3`` is fitted at once to every cluster with ``τ ≥ min_tau``
    (weighted by each point's own uncertainty, iterated, every coefficient non-negative); a term the
    recording is too short to show is reported as not identified, with an upper bound.

    Args:
        samples: (N, 3) readings at rest, float64: a gyroscope in rad/s or an accelerometer in m/s² (any
            fixed axes; a constant offset does not matter).
        dt: the sample period (s).
        min_tau: the shortest cluster time fitted (s), e.g. ``16 * dt`` to skip the octaves where the
            sensor's own low-pass filter makes its samples correlated.

    Returns:
        ``{"tau": (K,), "variance": (K, 3), "differences": (K,), "pooled": fit, "axes": [fit, fit, fit]}``,
        each fit ``{"white", "instability", "random_walk": term, "points", "tau_range", "misfit"}`` (or None
        with fewer than two clusters), each term ``{"value": density, "coefficient", "std_error",
        "identified": bool, "lower", "upper"}`` (the density's interval at two standard errors). Units: a
        gyroscope's ``white`` in rad/√s (× 180/π × 60 for °/√h), ``instability`` in rad/s, ``random_walk``
        in rad/s/√s; an accelerometer's in m/s/√s, m/s², m/s²/√s. ``pooled`` (the mean of the three axes'
        variances, three times the differences) is also at the top level: ``allan(x, dt)["white"]``.

    Raises:
        ValueError: a NaN or infinite sample (``NonFiniteRate``), or a ``dt`` not finite and positive.
    """
    a = _array("samples", samples, _np.float64, 2, 3)
    clusters, pooled, axes = _native.allan(a, float(dt), float(min_tau))
    fit = _fit(pooled)
    out = {
        "tau": _np.array([c[0] for c in clusters], dtype=_np.float64),
        "variance": _np.array([c[1] for c in clusters], dtype=_np.float64).reshape(-1, 3),
        "differences": _np.array([c[2] for c in clusters], dtype=_np.int64),
        "pooled": fit,
        "axes": [_fit(f) for f in axes],
    }
    if fit is not None:
        out.update(fit)
    return out


@_dataclass(frozen=True)
class CountScale:
    """The scale of a 16-bit gyro (the core's ``frontend::CountScale``): raw counts → rad/s, and a count at
    a rail (-32768 or 32767) on any axis marks the sample saturated (counted in :attr:`Stream.saturated`).

    Give exactly one: ``full_scale_dps`` (±FS °/s spans the 16-bit range, one count = FS/32768 °/s: the
    ICM-426xx and BMI088 convention) or ``sensitivity`` (counts per °/s as a datasheet prints it, e.g. 131
    for the MPU-6050's ±250 °/s). The scale per count is formed in float64 and rounded once to the
    stream's precision; each rate is that times the count, bit for bit the Rust core and the C API.
    """

    full_scale_dps: _Optional[float] = None
    sensitivity: _Optional[float] = None

    def _native(self):
        if (self.full_scale_dps is None) == (self.sensitivity is None):
            raise ValueError("CountScale: give exactly one of full_scale_dps and sensitivity")
        if self.full_scale_dps is not None:
            return (True, float(self.full_scale_dps))
        return (False, float(self.sensitivity))


_DTYPES = {"f32": _np.float32, "f64": _np.float64}


@_dataclass(frozen=True)
class Calibration:
    """A gyro's own calibration, in the sensor's axes (the core's ``frontend::Calibration``):
    ``ω = M · (s ⊙ (r − o))`` for a reading ``r`` (rad/s), before the mounting (``alignment``).

    Fusion's ``FusionModelInertial`` (imufusion's ``model_inertial``) in the same order and arithmetic:
    the same numbers give the same bits in float32.

    Attributes:
        offset: ``o`` (rad/s), the zero-rate output, subtracted first.
        sensitivity: ``s``, per-axis scale factors (near 1).
        misalignment: ``M``, 3×3 (near the identity): the non-orthogonality of the sensor's axes.

    Refused (``ValueError``, ``InvalidCalibration``) when a number is not finite or ``M · diag(s)`` is
    singular or has a condition number ``‖A‖∞‖A⁻¹‖∞`` above 100.
    """

    offset: _Sequence[float] = (0.0, 0.0, 0.0)
    sensitivity: _Sequence[float] = (1.0, 1.0, 1.0)
    misalignment: _Sequence[_Sequence[float]] = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))

    def _native(self):
        o = _np.asarray(self.offset, dtype=_np.float64)
        s = _np.asarray(self.sensitivity, dtype=_np.float64)
        m = _np.asarray(self.misalignment, dtype=_np.float64)
        if o.shape != (3,) or s.shape != (3,) or m.shape != (3, 3):
            raise ValueError(
                f"Calibration: offset and sensitivity must have 3 values and misalignment 3x3, got "
                f"{o.shape}, {s.shape}, {m.shape}"
            )
        return ([float(c) for c in o], [float(c) for c in s], [[float(e) for e in row] for row in m])


def calibrate(gyr, calibration: Calibration, precision: _Optional[str] = None) -> _np.ndarray:
    """(N, 3) readings (rad/s, sensor axes) → (N, 3) calibrated rates, in the dtype of ``precision``
    (``None``: float32 for float32 readings, else float64)."""
    if not isinstance(calibration, Calibration):
        raise TypeError(f"calibration must be a quatprop.Calibration, got {type(calibration).__name__}")
    if precision is None:
        precision = "f32" if _np.asarray(gyr).dtype == _np.float32 else "f64"
    precision = _choice("precision", precision, tuple(_DTYPES))
    rows = _array("gyr", gyr, _DTYPES[precision], 2, 3)
    fn = _native.calibrate_f32 if precision == "f32" else _native.calibrate_f64
    return fn(rows, calibration._native())


def _array(name: str, value, dtype, ndim: int, last: _Optional[int] = None) -> _np.ndarray:
    try:
        a = _np.asarray(value)
    except Exception as e:  # pragma: no cover - numpy's own message is clear
        raise TypeError(f"{name}: cannot be converted to an array ({e})") from None
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must be a real numeric array, got dtype {a.dtype}")
    if a.ndim != ndim or (last is not None and a.shape[-1] != last):
        want = "(N,)" if ndim == 1 else f"(N, {last})"
        raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    return _np.ascontiguousarray(a, dtype=dtype)


def _counts(value) -> _np.ndarray:
    """(N, 3) raw gyro counts as int16 (integers in -32768 .. 32767)."""
    a = _np.asarray(value)
    if a.dtype.kind not in "iu":
        raise TypeError(f"a stream with count_scale takes integer counts, got dtype {a.dtype}")
    if a.ndim != 2 or a.shape[-1] != 3:
        raise ValueError(f"counts must have shape (N, 3), got {a.shape}")
    if a.size and (a.min() < -32768 or a.max() > 32767):
        raise ValueError("counts must be in -32768 .. 32767 (16-bit)")
    return _np.ascontiguousarray(a, dtype=_np.int16)


def _stabilizer(stabilizer: str) -> _Tuple[str, int]:
    if not isinstance(stabilizer, str):
        raise TypeError(f"stabilizer must be a string, got {type(stabilizer).__name__}")
    if stabilizer.startswith("every:"):
        try:
            n = int(stabilizer[len("every:"):])
        except ValueError:
            raise ValueError(f"stabilizer {stabilizer!r}: 'every:N' needs an integer N >= 1") from None
        if not 1 <= n <= 2**32 - 1:
            raise ValueError(f"stabilizer {stabilizer!r}: N must be in 1 .. 2**32-1")
        return "every", n
    if stabilizer not in ("off", "normalize", "first_order"):
        raise ValueError(f"unknown stabilizer {stabilizer!r}; choose one of {STABILIZERS}")
    return stabilizer, 0


def _choice(name: str, value: str, choices: _Sequence[str]) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, got {type(value).__name__}")
    if value not in choices:
        raise ValueError(f"unknown {name} {value!r}; choose one of {tuple(choices)}")
    return value


_OPTIONS_DOC = """
        scheme: one of :data:`SCHEMES`.
        stabilizer: ``"off"``, ``"normalize"``, ``"first_order"`` or ``"every:N"``.
        input: one of :data:`INPUTS`. ``history`` (cubic through the last four samples, fourth order, no
            latency) is the recommended model for a rate gyro.
        coning: the coning correction of ``input="delta_angles"``, one of :data:`CONINGS`.
        accumulator: ``"plain"`` or ``"kahan"`` (compensated addition of each increment).
        precision: ``"f32"`` or ``"f64"``: the working precision and the dtype of the result; ``None``
            (the default): the samples' dtype decides, float32 → ``"f32"``, anything else → ``"f64"``
            (for a stream, the first update's; one whose attitude is set before it is ``"f64"``).
        q0: initial attitude ``[w, x, y, z]`` (body to reference; normalized), identity by default.
        calibration: a :class:`Calibration` (offset, sensitivity, misalignment in the sensor's axes),
            applied to each sample first.
        alignment: sensor → body axes, applied after the calibration: an axis remap name (one of
            :data:`AXIS_REMAPS`) or a 3×3 rotation matrix ``R`` with ``ω_body = R ω_sensor``; a matrix
            that is not a rotation (within 1e-4) raises ``ValueError``.
        bias: subtracted after the alignment (body axes): a fixed ``[bx, by, bz]`` (rad/s) or a
            :class:`BiasEstimator`. Not with ``delta_angles``.
        sample: what a sample means in time (the core's ``frontend::SampleTiming``): ``"instant"`` (the
            default), the rate at its timestamp, which the rate input models interpolate; or
            ``"interval_mean"``, the mean rate over the interval that ends at its timestamp, integrated
            exactly as the increment ``ω·dt`` by ``input="delta_angles"`` (required) with its ``coning``
            correction. The front end (calibration, alignment, bias) applies to these rates first.
        count_scale: a :class:`CountScale`: ``gyr`` is then raw int16 counts (N, 3), scaled first (before
            the calibration); a count at a rail marks its sample saturated.
        group_delay: seconds the samples lag the motion (a low-pass filter's group delay; 0 by default):
            each returned attitude is the propagated one (at ``t − group_delay``) carried forward by
            ``group_delay`` at the last accepted sample's rate.
        on_refused: ``"raise"``: a refused sample raises :class:`RefusedSample` (its index, kind and
            reason). ``"mask"``: a refused sample is skipped — the state stays as after the last
            accepted sample and its interval carries into the next sample, as the Rust docs prescribe —
            and ``(q, refused)`` is returned, ``refused`` a boolean (N,) array.
"""


class Stream:
    """A stream of gyro samples integrated call by call, for data that arrives in pieces.

    Everything is kept between calls — the attitude, the input model's last samples, the clock (the
    period's exact time, the last timestamp), the bias estimator, the counters — so any chunking of a
    stream gives the same bits as one :func:`integrate` call over the whole of it (``integrate`` is one
    :meth:`update` of a new ``Stream``).

    Give exactly one time base: ``dt`` (a fixed period, s), ``timestamps=True`` (each :meth:`update`
    takes ``t``, float64 seconds) or ``tick_hz`` (each :meth:`update` takes ``ticks``, a counter of
    ``tick_bits`` bits that wraps). The timing rules are :func:`integrate`'s.

    Args (besides the time base):{options}
    A refused sample with ``on_refused="raise"`` raises :class:`RefusedSample` with its index in that
    call's ``gyr``; the stream is then as after the last accepted sample (its interval carried into the
    next one) and its front end (alignment, bias estimator) as after the refused sample, so the rows after
    it can be given next.

    Example::

        s = quatprop.Stream(dt=1e-3, bias=quatprop.BiasEstimator(window=1.0, gate=0.02))
        for chunk in fifo_reads:            # (n, 3) rad/s each
            q = s.update(chunk)             # (n, 4): the attitude after each sample
        s.attitude, s.bias, s.steps, s.refused
    """

    def __init__(
        self,
        dt: _Optional[float] = None,
        *,
        timestamps: bool = False,
        tick_hz: _Optional[float] = None,
        tick_bits: int = 32,
        scheme: str = "expmap",
        stabilizer: str = "first_order",
        input: str = "history",
        coning: str = "two_sample",
        accumulator: str = "plain",
        precision: _Optional[str] = None,
        q0=None,
        alignment=None,
        bias=None,
        calibration: _Optional[Calibration] = None,
        on_refused: str = "raise",
        sample: str = "instant",
        group_delay: float = 0.0,
        count_scale: _Optional[CountScale] = None,
    ) -> None:
        self._precision = None if precision is None else _choice("precision", precision, tuple(_DTYPES))
        if count_scale is not None and not isinstance(count_scale, CountScale):
            raise TypeError(f"count_scale must be a quatprop.CountScale, got {type(count_scale).__name__}")
        self._counts = count_scale is not None
        sample = _choice("sample", sample, SAMPLES)
        interval_mean = sample == "interval_mean"
        if interval_mean and input != "delta_angles":
            raise ValueError(
                'sample="interval_mean" rates are integrated as angle increments: give input="delta_angles"'
            )
        group_delay = float(group_delay)
        if not (_np.isfinite(group_delay) and group_delay >= 0.0):
            raise ValueError(f"group_delay must be a finite number of seconds >= 0, got {group_delay!r}")
        if group_delay > 0.0 and input == "delta_angles" and not interval_mean:
            raise ValueError('group_delay needs rates: not with raw delta angles (use sample="interval_mean")')
        if self._counts and input == "delta_angles" and not interval_mean:
            raise ValueError("count_scale gives rates: not with raw delta angles")
        # Rates (rad/s) come in unless the rows are raw increments.
        rates_in = input != "delta_angles" or interval_mean
        scheme = _choice("scheme", scheme, SCHEMES)
        stab, every = _stabilizer(stabilizer)
        input = _choice("input", input, INPUTS)
        coning = _choice("coning", coning, CONINGS)
        accumulator = _choice("accumulator", accumulator, ("plain", "kahan"))
        self._mask = _choice("on_refused", on_refused, ("raise", "mask")) == "mask"

        if not isinstance(timestamps, (bool, _np.bool_)):
            raise TypeError(f"timestamps must be True or False, got {type(timestamps).__name__}")
        given = [n for n, v in (("dt", dt is not None), ("timestamps", bool(timestamps)), ("tick_hz", tick_hz is not None)) if v]
        if len(given) != 1:
            raise ValueError(f"give exactly one time base: dt, timestamps=True or tick_hz (got {given or 'none'})")
        period = None
        if dt is not None:
            if isinstance(dt, (bool, _np.bool_)) or not isinstance(dt, (int, float, _np.integer, _np.floating)):
                raise TypeError(f"dt must be a number (s), got {type(dt).__name__}; per-sample times go in t")
            period = float(dt)
        self._time = "dt" if dt is not None else ("t" if timestamps else "ticks")
        if isinstance(tick_bits, bool) or not isinstance(tick_bits, (int, _np.integer)) or not 0 <= tick_bits < 2**32:
            raise ValueError(f"tick_bits must be the counter width in bits (1 to 32), got {tick_bits!r}")

        if q0 is None:
            q0v = [1.0, 0.0, 0.0, 0.0]
        else:
            q0a = _np.asarray(q0, dtype=_np.float64)
            if q0a.shape != (4,):
                raise ValueError(f"q0 must be [w, x, y, z], got shape {q0a.shape}")
            q0v = [float(c) for c in q0a]

        remap = None
        matrix = None
        if alignment is not None:
            if isinstance(alignment, str):
                if alignment not in AXIS_REMAPS:
                    raise ValueError(f"unknown axis remap {alignment!r}; e.g. 'PyNxPz' (see AXIS_REMAPS)")
                remap = alignment
            else:
                m = _np.asarray(alignment, dtype=_np.float64)
                if m.shape != (3, 3):
                    raise ValueError(f"alignment matrix must be 3x3, got shape {m.shape}")
                matrix = [[float(e) for e in row] for row in m]

        fixed_bias = None
        estimator = None
        if bias is not None:
            if not rates_in:
                raise ValueError("bias (rad/s) does not apply to delta angles")
            if isinstance(bias, BiasEstimator):
                if tick_hz is not None and bias.period is None:
                    # tick_hz is the counter's rate (e.g. 1 MHz), not the sample rate: a window in seconds
                    # needs the sample period.
                    raise ValueError("a BiasEstimator on a tick_hz stream needs period= (the sample period, s)")
                estimator = bias._native()
            else:
                ba = _np.asarray(bias, dtype=_np.float64)
                if ba.shape != (3,):
                    raise ValueError(f"bias must be [bx, by, bz] (rad/s) or a BiasEstimator, got shape {ba.shape}")
                fixed_bias = [float(c) for c in ba]

        cal = None
        if calibration is not None:
            if not isinstance(calibration, Calibration):
                raise TypeError(f"calibration must be a quatprop.Calibration, got {type(calibration).__name__}")
            if not rates_in:
                raise ValueError("calibration (rad/s readings) does not apply to delta angles")
            cal = calibration._native()

        self._args = dict(
            period=period,
            timestamps=bool(timestamps),
            tick_hz=float(tick_hz) if tick_hz is not None else None,
            tick_bits=int(tick_bits),
            scheme=scheme,
            stabilizer=stab,
            every=every,
            input=input,
            coning=coning,
            kahan=accumulator == "kahan",
            q0=q0v,
            remap=remap,
            matrix=matrix,
            bias=fixed_bias,
            estimator=estimator,
            calibration=cal,
            interval_mean=interval_mean,
            group_delay=group_delay,
            count_scale=None if count_scale is None else count_scale._native(),
        )
        # Made now, so a bad option fails here; remade in f32 if the first samples decide so.
        self._native = _native.NativeStream(self._precision or "f64", self._mask, self._args)

    def _decide(self, precision: str) -> None:
        """Fixes the precision left open (``precision=None``) before the state first changes."""
        if self._precision is None:
            if precision != "f64":
                self._native = _native.NativeStream(precision, self._mask, self._args)
            self._precision = precision

    def update(self, gyr, t=None, *, ticks=None, acc=None, temperature=None):
        """Integrates the next samples; row ``k`` of the result is the attitude after sample ``k``.

        Args:
            gyr: (N, 3) body rates ω (rad/s), or angle increments Δθ (rad) for ``input="delta_angles"``;
                rounded once to the stream's precision.
            t: (N,) timestamps (s, float64) for a stream made with ``timestamps=True``.
            ticks: (N,) counter values for a stream made with ``tick_hz``.
            acc: (N, 3) accelerations at the samples (any fixed axes; the unit of the estimator's
                ``accel_gate``), for the bias estimator's rest detection. They never touch the attitude.
            temperature: (N,) the sensor's temperature at the samples (the unit of the estimator's
                ``temperature_span``), for its bias(T) model.

        Returns:
            q: (N, 4) attitudes ``[w, x, y, z]``; or ``(q, refused)`` with ``on_refused="mask"``.

        Raises:
            RefusedSample: a sample was refused (``on_refused="raise"``); its index is in this call's
                ``gyr``.
            ValueError: a bad shape, timestamps that do not match the stream's time base, ``acc`` or
                ``temperature`` without a bias estimator, or NaN or infinite in them (``NonFiniteAux``:
                nothing of the call is taken).
        """
        if self._precision is None:
            self._decide("f32" if _np.asarray(gyr).dtype == _np.float32 else "f64")
        counts = None
        if self._counts:
            counts = _counts(gyr)
            gyr = _np.empty((0, 3), dtype=_DTYPES[self._precision])
            n = counts.shape[0]
        else:
            gyr = _array("gyr", gyr, _DTYPES[self._precision], 2, 3)
            n = gyr.shape[0]
        t_arr = None
        tick_arr = None
        if (t is not None) != (self._time == "t") or (ticks is not None) != (self._time == "ticks"):
            want = {"dt": "no timestamps (the stream has a period)", "t": "t (the stream was made with timestamps=True)",
                    "ticks": "ticks (the stream was made with tick_hz)"}[self._time]
            raise ValueError(f"this stream takes {want}")
        if t is not None:
            t_arr = _array("t", t, _np.float64, 1)
            if t_arr.shape[0] != n:
                raise ValueError(f"t has {t_arr.shape[0]} timestamps for {n} samples")
        if ticks is not None:
            a = _np.asarray(ticks)
            if a.dtype.kind not in "iu":
                raise TypeError(f"ticks must be an integer array, got dtype {a.dtype}")
            if a.ndim != 1 or a.shape[0] != n:
                raise ValueError(f"ticks must have shape ({n},), got {a.shape}")
            if a.size and (a.min() < 0 or a.max() > 2**32 - 1):
                raise ValueError("ticks must be in 0 .. 2**32-1 (counter values)")
            tick_arr = _np.ascontiguousarray(a, dtype=_np.uint32)
        dtype = _DTYPES[self._precision]
        acc_arr = None if acc is None else _array("acc", acc, dtype, 2, 3)
        temp_arr = None if temperature is None else _array("temperature", temperature, dtype, 1)
        arrays = dict(gyr=gyr, t=t_arr, ticks=tick_arr, acc=acc_arr, temperature=temp_arr, counts=counts)
        q, mask, refused = self._native.update(arrays)
        if refused is not None:
            raise RefusedSample(*refused)
        if self._mask:
            return q, mask
        return q

    @property
    def attitude(self) -> _np.ndarray:
        """The attitude ``[w, x, y, z]`` after the last accepted sample (float64 copy of the state)."""
        return _np.array(self._native.attitude())

    @property
    def bias(self) -> _Optional[_np.ndarray]:
        """The bias subtracted from the next sample (rad/s, body axes): the fixed bias; or the estimator's
        estimate (zero before its first still window or ``initial``) plus, with ``motion=True``, the
        residual learned in motion — both are subtracted (each rounded to the precision on its own); None
        without a bias. With ``temperature_span`` the estimate is the bias at the learned windows' mean
        temperature: a sample's is moved along the fitted bias(T) line to its temperature."""
        b = self._native.bias()
        return None if b is None else _np.array(b)

    @property
    def learned_calibration(self) -> _Optional[dict]:
        """What a :class:`CalibrationEstimator` has learned so far; None without one. A dict:
        ``calibration`` (a :class:`Calibration` that applies the correction: offset = the residual bias,
        rad/s; give it with the rest bias removed), ``gain`` (``I − G``, 3×3: what multiplies the
        bias-free rate) and ``gain_std_dev`` (3×3, each term's standard deviation: a term still at its
        prior sigma has not been observed)."""
        c = self._native.learned_calibration()
        if c is None:
            return None
        (o, s, m), gain, sd = c
        return {"calibration": Calibration(tuple(o), tuple(s), tuple(tuple(r) for r in m)),
                "gain": _np.array(gain), "gain_std_dev": _np.array(sd)}

    @property
    def bias_variance(self) -> _Optional[_np.ndarray]:
        """The bias estimator's variance per axis ((rad/s)²): its last update's, grown by its drift since
        (``float`` max before its first still window); None without an estimator. The motion residual's
        uncertainty is not in it."""
        v = self._native.bias_variance()
        return None if v is None else _np.array(v)

    @property
    def steps(self) -> int:
        """Integration steps taken (an input model that starts on its first sample takes one fewer)."""
        return self._native.counts()[0]

    @property
    def refused(self) -> int:
        """Samples refused so far (skipped with ``on_refused="mask"``, or raised)."""
        return self._native.counts()[1]

    @property
    def lost_angle(self) -> _np.ndarray:
        """The sum of the refused delta angles ``[x, y, z]`` (rad, body axes): the rotation that refused
        increments took with them (``input="delta_angles"``; a refused rate sample loses no time, its
        interval goes into the next one, but a refused increment's angle is not integrated; with
        ``sample="interval_mean"`` the increment is the rate times its interval, not counted when the
        interval itself was refused, e.g. a timestamp going back). NaN or infinite increments are not
        counted: their angle is unknown."""
        return _np.array(self._native.lost_angle())

    @property
    def saturated(self) -> int:
        """Accepted samples flagged as saturated."""
        return self._native.counts()[2]

    def set_attitude(self, q) -> None:
        """Replaces the attitude (normalized); the input model's samples, the clock and the counters stay."""
        qa = _np.asarray(q, dtype=_np.float64)
        if qa.shape != (4,):
            raise ValueError(f"q must be [w, x, y, z], got shape {qa.shape}")
        self._decide("f64")
        self._native.set_attitude([float(c) for c in qa])

    def rotate_body(self, dtheta) -> None:
        """An estimator's attitude correction in the **body** frame: ``q ← q ⊗ exp(dtheta)`` (rotation
        vector ``[x, y, z]``, rad). The input model's samples, the clock and the counters stay."""
        self._decide("f64")
        self._native.rotate(_vector3(dtheta, "dtheta"), True)

    def rotate_reference(self, dtheta) -> None:
        """An estimator's attitude correction in the **reference** frame: ``q ← exp(dtheta) ⊗ q`` (rad)."""
        self._decide("f64")
        self._native.rotate(_vector3(dtheta, "dtheta"), False)

    def correct_bias(self, delta) -> None:
        """An estimator's bias correction: the bias subtracted from the samples grows by ``delta``
        (``[x, y, z]``, rad/s, body axes) — the fixed bias or the estimator's estimate moves (a fixed bias
        of ``delta`` is set where there was none) — and the samples the input model keeps move with it, so
        the next step integrates no jump. Both change or neither."""
        self._decide("f64")
        self._native.correct_bias(_vector3(delta, "delta"))

    def reset(self) -> None:
        """Back to the state the stream was made with."""
        self._native.reset()


def _vector3(v, name: str) -> _List[float]:
    a = _np.asarray(v, dtype=_np.float64)
    if a.shape != (3,):
        raise ValueError(f"{name} must be [x, y, z], got shape {a.shape}")
    return [float(c) for c in a]


if Stream.__doc__:  # None under python -OO
    Stream.__doc__ = Stream.__doc__.format(options=_OPTIONS_DOC)


# integrate's keywords are Stream's, written out: the signature is the documented API (help(), the stub).
def integrate(
    gyr,
    dt: _Optional[float] = None,
    t=None,
    *,
    ticks=None,
    tick_hz: _Optional[float] = None,
    tick_bits: int = 32,
    scheme: str = "expmap",
    stabilizer: str = "first_order",
    input: str = "history",
    coning: str = "two_sample",
    accumulator: str = "plain",
    precision: _Optional[str] = None,
    q0=None,
    alignment=None,
    bias=None,
    calibration: _Optional[Calibration] = None,
    on_refused: str = "raise",
    acc=None,
    temperature=None,
    sample: str = "instant",
    group_delay: float = 0.0,
    count_scale: _Optional[CountScale] = None,
):
    """Integrates body-frame gyro samples into attitude quaternions, bit for bit as the Rust library.

    Each sample goes through the core's ``Propagator::push`` in one Rust loop (GIL released); row ``k``
    of the result is the attitude after sample ``k``.

    Args:
        gyr: (N, 3) body rates ω (rad/s), or angle increments Δθ (rad) for ``input="delta_angles"``.
            float32 or float64 (any numeric dtype is converted); rounded once to ``precision``.
        dt: fixed sample period (s), given once and kept exactly (the core's ``FixedPeriod``: the ``dt``
            of the samples sum to ``k·dt`` within half an ulp). Every sample, the first included, is
            pushed with its period, as ``Propagator::push_burst`` does.
        t: (N,) timestamps (s, float64), strictly increasing. The first accepted sample only starts
            the stream (``Propagator::start``); each later one is pushed with
            ``dt_k = round(t_k − t_last + carry)``, ``t_last`` the last *accepted* timestamp, the
            difference formed in float64 and rounded once to ``precision``, and ``carry`` (float64) the
            part of earlier intervals that this rounding left out — so the ``dt`` sum to ``t_last − t_0``
            within half an ulp of one ``dt`` (in f64 ``dt_k = t_k − t_last`` exactly as float64 computes
            it; the carry stays zero). A timestamp that does not advance is refused
            (``TimestampNotIncreasing``), a NaN or infinite one too (``NonFiniteStep``).
        ticks: (N,) integer timestamps of the sensor's clock (``tick_hz`` ticks per second, a counter of
            ``tick_bits`` bits that wraps): the core's ``TickClock``, as ``Propagator::push_burst_timed``.
            Give exactly one of ``dt``, ``t``, ``ticks``.
        acc: (N, 3) accelerations for the bias estimator's rest detection (see :meth:`Stream.update`).
        temperature: (N,) temperatures for the bias estimator's bias(T) model (see :meth:`Stream.update`).
{options}
    Returns:
        q: (N, 4) attitudes ``[w, x, y, z]`` (scalar first, Hamilton, body to reference), dtype of
        ``precision``; or ``(q, refused)`` with ``on_refused="mask"``.

    Raises:
        RefusedSample: a sample was refused (``on_refused="raise"``).
        ValueError: a bad shape, option or parameter (e.g. ``every:0``, a zero ``q0``, ``dt <= 0``).
        TypeError: an argument of the wrong type.
    """
    given = [name for name, v in (("dt", dt), ("t", t), ("ticks", ticks)) if v is not None]
    if len(given) != 1:
        raise ValueError(f"give exactly one of dt, t, ticks (got {given or 'none'})")
    if ticks is not None and tick_hz is None:
        raise ValueError("ticks need tick_hz (ticks per second)")
    if tick_hz is not None and ticks is None:
        raise ValueError("tick_hz goes with ticks")
    stream = Stream(
        dt,
        timestamps=t is not None,
        tick_hz=tick_hz,
        tick_bits=tick_bits,
        scheme=scheme,
        stabilizer=stabilizer,
        input=input,
        coning=coning,
        accumulator=accumulator,
        precision=precision,
        q0=q0,
        alignment=alignment,
        bias=bias,
        calibration=calibration,
        on_refused=on_refused,
        sample=sample,
        group_delay=group_delay,
        count_scale=count_scale,
    )
    return stream.update(gyr, t, ticks=ticks, acc=acc, temperature=temperature)


if integrate.__doc__:  # None under python -OO
    integrate.__doc__ = integrate.__doc__.format(options=_OPTIONS_DOC.lstrip("\n"))


def _rows(name: str, a, width: int) -> _Tuple[_np.ndarray, tuple]:
    arr = _np.asarray(a)
    if arr.dtype.kind not in "fiu":
        raise TypeError(f"{name} must be a real numeric array, got dtype {arr.dtype}")
    if arr.shape[-1:] != (width,):
        raise ValueError(f"{name} must have shape (..., {width}), got {arr.shape}")
    dtype = _np.float32 if arr.dtype == _np.float32 else _np.float64
    return _np.ascontiguousarray(arr.reshape(-1, width), dtype=dtype), arr.shape[:-1]


def _map(fn32, fn64, name: str, a, win: int, wout: int) -> _np.ndarray:
    rows, lead = _rows(name, a, win)
    out = (fn32 if rows.dtype == _np.float32 else fn64)(rows)
    return out.reshape(lead + (wout,))


def to_euler_zyx(q) -> _np.ndarray:
    """Aerospace Euler angles ``[..., (yaw, pitch, roll)]`` (rad) of unit quaternions ``[..., (w, x, y, z)]``.

    ``R = Rz(yaw) Ry(pitch) Rx(roll)`` (intrinsic Z-Y'-X''; SciPy ``as_euler("ZYX")``); yaw and roll in
    (−π, π], pitch in [−π/2, π/2]. Computed from half-angle atan2 formulas: accurate up to the gimbal
    lock. float32 input stays float32 (computed in f32), anything else in float64.
    """
    return _map(_native.to_euler_zyx_f32, _native.to_euler_zyx_f64, "q", q, 4, 3)


def from_euler_zyx(e) -> _np.ndarray:
    """Quaternions ``[..., (w, x, y, z)]`` of aerospace Euler angles ``[..., (yaw, pitch, roll)]`` (rad):
    ``qz(yaw) ⊗ qy(pitch) ⊗ qx(roll)``."""
    return _map(_native.from_euler_zyx_f32, _native.from_euler_zyx_f64, "e", e, 3, 4)


def to_euler_zxz(q) -> _np.ndarray:
    """Classical Euler angles ``[..., (psi, theta, phi)]`` (rad) of unit quaternions ``[..., (w, x, y, z)]``.

    ``R = Rz(psi) Rx(theta) Rz(phi)`` (intrinsic Z-X'-Z''; SciPy ``as_euler("ZXZ")``); psi, phi in
    (−π, π], theta in [0, π]; accurate at theta → 0 and π.
    """
    return _map(_native.to_euler_zxz_f32, _native.to_euler_zxz_f64, "q", q, 4, 3)


def from_euler_zxz(e) -> _np.ndarray:
    """Quaternions ``[..., (w, x, y, z)]`` of classical Euler angles ``[..., (psi, theta, phi)]`` (rad):
    ``qz(psi) ⊗ qx(theta) ⊗ qz(phi)``."""
    return _map(_native.from_euler_zxz_f32, _native.from_euler_zxz_f64, "e", e, 3, 4)
