"""Typed interface of quatprop. Conventions: quaternions are [w, x, y, z] (scalar first), Hamilton product,
the attitude maps body vectors to the reference frame, rates are body-frame (q' = ½ q ⊗ (0, ω)),
radians, rad/s, seconds."""

# The stub repeats the package's signatures (`__init__.py`) with their types: mypy's stubtest
# (tests/test_stubs.py) holds the two the same.

from dataclasses import dataclass
from typing import Any, Dict, Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

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

__version__: str

SCHEMES: Tuple[str, ...]
STABILIZERS: Tuple[str, ...]
INPUTS: Tuple[str, ...]
CONINGS: Tuple[str, ...]
AXIS_REMAPS: Tuple[str, ...]
SAMPLES: Tuple[str, ...]

_Scheme = Literal["euler", "rk2", "rk3", "rk4", "rk5", "expmap", "magnus4", "cf4"]
# "off", "normalize", "first_order", or "every:N" (N >= 1).
_Stabilizer = str
_Input = Literal["hold", "linear", "history", "twice_rate", "gauss_points", "delta_angles"]
_Coning = Literal["uncorrected", "one_plus_previous", "two_sample", "three_sample", "four_sample", "five_sample"]
_Accumulator = Literal["plain", "kahan"]
_Precision = Literal["f32", "f64"]
_SampleMeaning = Literal["instant", "interval_mean"]
_FloatArray = npt.NDArray[np.floating]

class RefusedSample(ValueError):
    """A sample the propagator refused: its index in gyr, the core's Error variant and its message."""

    index: int
    kind: str
    reason: str
    def __init__(self, index: int, kind: str, reason: str) -> None: ...

@dataclass(frozen=True)
class BiasEstimator:
    """Learns the gyro bias (rad/s) over still windows of `window` seconds (every axis within `gate` rad/s,
    the 8 block means flat against the scatter at rest, learned or given by `noise_density`, rad/√s): a
    Kalman filter on a bias that walks with density `drift` (rad/s/√s; None: 2e-5), so a slow turn is kept
    until the bias could have moved as far; a step at rest is followed within two windows. `initial` with
    `initial_sigma` starts from a known bias; `accel_gate` also needs the acceleration still;
    `temperature_span` fits bias(T); `motion` adds the residual learned in motion from `acc`; `period` (s)
    is the sample period when the stream has none (timestamps)."""

    window: float
    gate: float
    drift: Optional[float] = None
    rest_drift: Optional[float] = None
    noise_density: Optional[float] = None
    initial: Optional[Sequence[float]] = None
    initial_sigma: Optional[float] = None
    accel_gate: Optional[float] = None
    temperature_span: Optional[float] = None
    motion: Union[bool, CalibrationEstimator] = False
    period: Optional[float] = None

@dataclass(frozen=True)
class CalibrationEstimator:
    """Learns the gyro's gain (scale, misalignment) and residual bias in motion from the accelerometer:
    `BiasEstimator(motion=CalibrationEstimator(...))`. Prior sigmas: `sensitivity_sigma` (dimensionless),
    `misalignment_sigma` (rad); `motion_noise` (rad/s; None: 0.173 °/s)."""

    sensitivity_sigma: float
    misalignment_sigma: float
    motion_noise: Optional[float] = None

@dataclass(frozen=True)
class CountScale:
    """A 16-bit gyro's scale: counts → rad/s (exactly one of full_scale_dps, sensitivity); a count at a rail
    marks the sample saturated."""

    full_scale_dps: Optional[float] = None
    sensitivity: Optional[float] = None

@dataclass(frozen=True)
class Calibration:
    """A gyro's calibration in the sensor's axes: ω = M · (s ⊙ (r − o)) (Fusion's model_inertial)."""

    offset: Sequence[float] = ...
    sensitivity: Sequence[float] = ...
    misalignment: Sequence[Sequence[float]] = ...

def calibrate(gyr: npt.ArrayLike, calibration: Calibration, precision: Optional[_Precision] = None) -> _FloatArray:
    """(N, 3) readings (rad/s, sensor axes) → (N, 3) calibrated rates."""

def allan(samples: npt.ArrayLike, dt: float, min_tau: float = 0.0) -> Dict[str, Any]:
    """The Allan variance of (N, 3) samples at rest and the white noise, bias instability and random walk
    fitted to it, each with its standard error (the core's `noise`)."""

class Stream:
    """Samples integrated call by call, all state kept between calls: any chunking gives the bits of one
    `integrate` call over the whole stream. Exactly one time base: dt (s), timestamps=True (update takes t)
    or tick_hz (update takes ticks)."""
    def __init__(
        self,
        dt: Optional[float] = None,
        *,
        timestamps: bool = False,
        tick_hz: Optional[float] = None,
        tick_bits: int = 32,
        scheme: _Scheme = "expmap",
        stabilizer: _Stabilizer = "first_order",
        input: _Input = "history",
        coning: _Coning = "two_sample",
        accumulator: _Accumulator = "plain",
        precision: Optional[_Precision] = None,
        q0: Optional[npt.ArrayLike] = None,
        alignment: Union[str, npt.ArrayLike, None] = None,
        bias: Union[BiasEstimator, npt.ArrayLike, None] = None,
        calibration: Optional[Calibration] = None,
        on_refused: Literal["raise", "mask"] = "raise",
        sample: _SampleMeaning = "instant",
        group_delay: float = 0.0,
        count_scale: Optional[CountScale] = None,
    ) -> None: ...
    def update(
        self,
        gyr: npt.ArrayLike,
        t: Optional[npt.ArrayLike] = None,
        *,
        ticks: Optional[npt.ArrayLike] = None,
        acc: Optional[npt.ArrayLike] = None,
        temperature: Optional[npt.ArrayLike] = None,
    ) -> Union[_FloatArray, Tuple[_FloatArray, npt.NDArray[np.bool_]]]:
        """(N, 3) samples → (N, 4) attitudes after each; (q, refused) when made with on_refused="mask"."""
    @property
    def attitude(self) -> npt.NDArray[np.float64]: ...
    @property
    def bias(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def learned_calibration(self) -> Optional[Dict[str, Any]]: ...
    @property
    def bias_variance(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def steps(self) -> int: ...
    @property
    def refused(self) -> int: ...
    @property
    def lost_angle(self) -> npt.NDArray[np.float64]: ...
    @property
    def saturated(self) -> int: ...
    def set_attitude(self, q: npt.ArrayLike) -> None: ...
    def rotate_body(self, dtheta: npt.ArrayLike) -> None: ...
    def rotate_reference(self, dtheta: npt.ArrayLike) -> None: ...
    def correct_bias(self, delta: npt.ArrayLike) -> None: ...
    def reset(self) -> None: ...

# The two overloads repeat the whole signature: `on_refused` decides the return type, and an overload
# states every parameter.
@overload
def integrate(
    gyr: npt.ArrayLike,
    dt: Optional[float] = None,
    t: Optional[npt.ArrayLike] = None,
    *,
    ticks: Optional[npt.ArrayLike] = None,
    tick_hz: Optional[float] = None,
    tick_bits: int = 32,
    scheme: _Scheme = "expmap",
    stabilizer: _Stabilizer = "first_order",
    input: _Input = "history",
    coning: _Coning = "two_sample",
    accumulator: _Accumulator = "plain",
    precision: Optional[_Precision] = None,
    q0: Optional[npt.ArrayLike] = None,
    alignment: Union[str, npt.ArrayLike, None] = None,
    bias: Union[BiasEstimator, npt.ArrayLike, None] = None,
    calibration: Optional[Calibration] = None,
    on_refused: Literal["raise"] = "raise",
    acc: Optional[npt.ArrayLike] = None,
    temperature: Optional[npt.ArrayLike] = None,
    sample: _SampleMeaning = "instant",
    group_delay: float = 0.0,
    count_scale: Optional[CountScale] = None,
) -> _FloatArray:
    """(N, 3) body rates (rad/s; increments in rad for delta_angles) → (N, 4) attitudes [w, x, y, z]
    (scalar first, Hamilton, body to reference) after each sample, in the dtype of `precision`.
    Give exactly one of dt (fixed period, s), t (N timestamps, s, float64) or ticks (+ tick_hz).
    Raises RefusedSample for a refused sample (index, kind, reason)."""

@overload
def integrate(
    gyr: npt.ArrayLike,
    dt: Optional[float] = None,
    t: Optional[npt.ArrayLike] = None,
    *,
    ticks: Optional[npt.ArrayLike] = None,
    tick_hz: Optional[float] = None,
    tick_bits: int = 32,
    scheme: _Scheme = "expmap",
    stabilizer: _Stabilizer = "first_order",
    input: _Input = "history",
    coning: _Coning = "two_sample",
    accumulator: _Accumulator = "plain",
    precision: Optional[_Precision] = None,
    q0: Optional[npt.ArrayLike] = None,
    alignment: Union[str, npt.ArrayLike, None] = None,
    bias: Union[BiasEstimator, npt.ArrayLike, None] = None,
    calibration: Optional[Calibration] = None,
    on_refused: Literal["mask"],
    acc: Optional[npt.ArrayLike] = None,
    temperature: Optional[npt.ArrayLike] = None,
    sample: _SampleMeaning = "instant",
    group_delay: float = 0.0,
    count_scale: Optional[CountScale] = None,
) -> Tuple[_FloatArray, npt.NDArray[np.bool_]]:
    """As above; a refused sample is skipped (state kept, interval carried into the next sample) and
    flagged True in the returned (N,) boolean mask."""

def to_euler_zyx(q: npt.ArrayLike) -> _FloatArray:
    """[..., (w, x, y, z)] → [..., (yaw, pitch, roll)] (rad), R = Rz(yaw) Ry(pitch) Rx(roll)."""

def from_euler_zyx(e: npt.ArrayLike) -> _FloatArray:
    """[..., (yaw, pitch, roll)] (rad) → [..., (w, x, y, z)] = qz(yaw) ⊗ qy(pitch) ⊗ qx(roll)."""

def to_euler_zxz(q: npt.ArrayLike) -> _FloatArray:
    """[..., (w, x, y, z)] → [..., (psi, theta, phi)] (rad), R = Rz(psi) Rx(theta) Rz(phi)."""

def from_euler_zxz(e: npt.ArrayLike) -> _FloatArray:
    """[..., (psi, theta, phi)] (rad) → [..., (w, x, y, z)] = qz(psi) ⊗ qx(theta) ⊗ qz(phi)."""
