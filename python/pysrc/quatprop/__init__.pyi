"""Typed interface of quatprop. Conventions: quaternions are [w, x, y, z] (scalar first), Hamilton product,
the attitude maps body vectors to the reference frame, rates are body-frame (q' = ½ q ⊗ (0, ω)),
radians, rad/s, seconds."""

from typing import Literal, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

SCHEMES: Tuple[str, ...]
STABILIZERS: Tuple[str, ...]
INPUTS: Tuple[str, ...]
CONINGS: Tuple[str, ...]
AXIS_REMAPS: Tuple[str, ...]
SAMPLES: Tuple[str, ...]

Scheme = Literal["euler", "rk2", "rk3", "rk4", "rk5", "expmap", "magnus4", "cf4"]
# "off", "normalize", "first_order", or "every:N" (N >= 1).
Stabilizer = str
Input = Literal["hold", "linear", "history", "twice_rate", "gauss_points", "delta_angles"]
Coning = Literal["uncorrected", "one_plus_previous", "two_sample", "three_sample", "four_sample", "five_sample"]
Accumulator = Literal["plain", "kahan"]
Precision = Literal["f32", "f64"]
SampleMeaning = Literal["instant", "interval_mean"]
FloatArray = npt.NDArray[np.floating]

class RefusedSample(ValueError):
    """A sample the propagator refused: its index in gyr, the core's Error variant and its message."""

    index: int
    kind: str
    reason: str
    def __init__(self, index: int, kind: str, reason: str) -> None: ...

class BiasEstimator:
    """Learns the gyro bias (rad/s) over still windows of `window` samples, every axis within `gate` rad/s
    (and every acceleration within `accel_gate` of the window's first); a running mean over the last
    `memory` still windows; a change beyond `change` rad/s confirmed by two windows restarts it;
    `temperature_span` fits bias(T); `initial` starts from a known bias."""

    window: int
    gate: float
    memory: int
    initial: Optional[Sequence[float]]
    change: Optional[float]
    accel_gate: Optional[float]
    temperature_span: Optional[float]
    motion: bool
    def __init__(
        self,
        window: int,
        gate: float,
        memory: int = 64,
        initial: Optional[Sequence[float]] = None,
        change: Optional[float] = None,
        accel_gate: Optional[float] = None,
        temperature_span: Optional[float] = None,
        motion: bool = False,
    ) -> None: ...

class CountScale:
    """A 16-bit gyro's scale: counts → rad/s (exactly one of full_scale_dps, sensitivity); a count at a rail
    marks the sample saturated."""

    full_scale_dps: Optional[float]
    sensitivity: Optional[float]
    def __init__(self, full_scale_dps: Optional[float] = None, sensitivity: Optional[float] = None) -> None: ...

class Calibration:
    """A gyro's calibration in the sensor's axes: ω = M · (s ⊙ (r − o)) (Fusion's model_inertial)."""

    offset: Sequence[float]
    sensitivity: Sequence[float]
    misalignment: Sequence[Sequence[float]]
    def __init__(
        self,
        offset: Sequence[float] = ...,
        sensitivity: Sequence[float] = ...,
        misalignment: Sequence[Sequence[float]] = ...,
    ) -> None: ...

def calibrate(gyr: npt.ArrayLike, calibration: Calibration, precision: Optional[Precision] = None) -> FloatArray:
    """(N, 3) readings (rad/s, sensor axes) → (N, 3) calibrated rates."""

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
        scheme: Scheme = "expmap",
        stabilizer: Stabilizer = "first_order",
        input: Input = "history",
        coning: Coning = "two_sample",
        accumulator: Accumulator = "plain",
        precision: Optional[Precision] = None,
        q0: Optional[npt.ArrayLike] = None,
        alignment: Union[str, npt.ArrayLike, None] = None,
        bias: Union[BiasEstimator, npt.ArrayLike, None] = None,
        calibration: Optional[Calibration] = None,
        on_refused: Literal["raise", "mask"] = "raise",
        sample: SampleMeaning = "instant",
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
    ) -> Union[FloatArray, Tuple[FloatArray, npt.NDArray[np.bool_]]]:
        """(N, 3) samples → (N, 4) attitudes after each; (q, refused) when made with on_refused="mask"."""
    @property
    def attitude(self) -> npt.NDArray[np.float64]: ...
    @property
    def bias(self) -> Optional[npt.NDArray[np.float64]]: ...
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

@overload
def integrate(
    gyr: npt.ArrayLike,
    dt: Optional[float] = None,
    t: Optional[npt.ArrayLike] = None,
    *,
    ticks: Optional[npt.ArrayLike] = None,
    tick_hz: Optional[float] = None,
    tick_bits: int = 32,
    scheme: Scheme = "expmap",
    stabilizer: Stabilizer = "first_order",
    input: Input = "history",
    coning: Coning = "two_sample",
    accumulator: Accumulator = "plain",
    precision: Optional[Precision] = None,
    q0: Optional[npt.ArrayLike] = None,
    alignment: Union[str, npt.ArrayLike, None] = None,
    bias: Union[BiasEstimator, npt.ArrayLike, None] = None,
    calibration: Optional[Calibration] = None,
    on_refused: Literal["raise"] = "raise",
    acc: Optional[npt.ArrayLike] = None,
    temperature: Optional[npt.ArrayLike] = None,
    sample: SampleMeaning = "instant",
    group_delay: float = 0.0,
    count_scale: Optional[CountScale] = None,
) -> FloatArray:
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
    scheme: Scheme = "expmap",
    stabilizer: Stabilizer = "first_order",
    input: Input = "history",
    coning: Coning = "two_sample",
    accumulator: Accumulator = "plain",
    precision: Optional[Precision] = None,
    q0: Optional[npt.ArrayLike] = None,
    alignment: Union[str, npt.ArrayLike, None] = None,
    bias: Union[BiasEstimator, npt.ArrayLike, None] = None,
    calibration: Optional[Calibration] = None,
    on_refused: Literal["mask"],
    acc: Optional[npt.ArrayLike] = None,
    temperature: Optional[npt.ArrayLike] = None,
    sample: SampleMeaning = "instant",
    group_delay: float = 0.0,
    count_scale: Optional[CountScale] = None,
) -> Tuple[FloatArray, npt.NDArray[np.bool_]]:
    """As above; a refused sample is skipped (state kept, interval carried into the next sample) and
    flagged True in the returned (N,) boolean mask."""

def to_euler_zyx(q: npt.ArrayLike) -> FloatArray:
    """[..., (w, x, y, z)] → [..., (yaw, pitch, roll)] (rad), R = Rz(yaw) Ry(pitch) Rx(roll)."""

def from_euler_zyx(e: npt.ArrayLike) -> FloatArray:
    """[..., (yaw, pitch, roll)] (rad) → [..., (w, x, y, z)] = qz(yaw) ⊗ qy(pitch) ⊗ qx(roll)."""

def to_euler_zxz(q: npt.ArrayLike) -> FloatArray:
    """[..., (w, x, y, z)] → [..., (psi, theta, phi)] (rad), R = Rz(psi) Rx(theta) Rz(phi)."""

def from_euler_zxz(e: npt.ArrayLike) -> FloatArray:
    """[..., (psi, theta, phi)] (rad) → [..., (w, x, y, z)] = qz(psi) ⊗ qx(theta) ⊗ qz(phi)."""
