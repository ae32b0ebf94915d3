"""The BROAD reader and the gyro-only error metric of `broad.py`, importable without any peer library.

Data: the Berlin Robust Orientation Estimation Assessment Dataset (BROAD),

    D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation
    Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0)

Conventions (quatprop's): a quaternion is [w, x, y, z] (scalar first), Hamilton product, an attitude maps
body (sensor) vectors to the reference frame (BROAD's optical ENU frame); rates are body-frame, rad/s;
times in seconds; errors in degrees.

The metric. From start points every `every` seconds inside the movement phase, each method's attitude is
started at the optical truth at the start sample s, the gyro is integrated for a horizon of h seconds, and
the error is the rotation angle between that estimate and the truth at the end sample e = s + round(h·fs).
A method is integrated once over the whole trial from identity, giving q_k (the attitude after sample k);
the estimate at e started at s is then truth_s ⊗ q_s⁻¹ ⊗ q_e, exact for a method whose only state is the
attitude (a bias estimator runs causally over the whole trial, as it would for a user streaming the data).
"""

from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Sequence, Union

import h5py
import numpy as np

ATTRIBUTION = (
    "D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation "
    "Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0)"
)

#: The datasets `read_trial` reads (a BROAD file also holds imu_mag and opt_pos).
DATASETS = ("imu_gyr", "imu_acc", "opt_quat", "movement")


@dataclass(frozen=True)
class Trial:
    """One BROAD recording, every array float64 (movement: bool), N samples at `fs`."""

    name: str
    fs: float  # sampling rate, Hz (BROAD: 2000/7 = 285.714… Hz)
    gyr: np.ndarray  # (N, 3) body rates, rad/s, sensor frame
    acc: np.ndarray  # (N, 3) specific force, m/s²
    quat: np.ndarray  # (N, 4) optical truth [w, x, y, z], sensor → ENU; a NaN row where tracking was lost
    movement: np.ndarray  # (N,) bool: the samples of the movement phase

    @property
    def dt(self) -> float:
        """The sample period, s."""
        return 1.0 / self.fs

    @property
    def first_movement(self) -> int:
        """Index of the first movement sample: the samples before it are the initial rest phase."""
        return int(np.flatnonzero(self.movement)[0])

    def rest_bias(self) -> np.ndarray:
        """The mean gyro (rad/s, (3,)) over the initial rest phase: the "oracle" bias."""
        return self.gyr[: self.first_movement].mean(axis=0)


def read_trial(path: Union[str, Path]) -> Trial:
    """Read a BROAD trial (or an excerpt of one with the same layout) from its HDF5 file."""
    path = Path(path)
    with h5py.File(path, "r") as f:
        arrays = {name: f[name][()] for name in DATASETS}
        fs = float(f.attrs["sampling_rate"])
    return Trial(
        name=path.stem,
        fs=fs,
        gyr=np.ascontiguousarray(arrays["imu_gyr"], dtype=np.float64),
        acc=np.ascontiguousarray(arrays["imu_acc"], dtype=np.float64),
        quat=np.ascontiguousarray(arrays["opt_quat"], dtype=np.float64),
        movement=np.asarray(arrays["movement"], dtype=bool),
    )


def quat_mul(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Hamilton product p ⊗ q of [..., (w, x, y, z)] arrays (broadcast)."""
    pw, px, py, pz = np.moveaxis(p, -1, 0)
    qw, qx, qy, qz = np.moveaxis(q, -1, 0)
    return np.stack(
        [
            pw * qw - px * qx - py * qy - pz * qz,
            pw * qx + px * qw + py * qz - pz * qy,
            pw * qy - px * qz + py * qw + pz * qx,
            pw * qz + px * qy - py * qx + pz * qw,
        ],
        axis=-1,
    )


def quat_conj(q: np.ndarray) -> np.ndarray:
    """The conjugate (the inverse of a unit quaternion) of [..., (w, x, y, z)]."""
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def quat_angle(q: np.ndarray) -> np.ndarray:
    """The rotation angle (rad, in [0, π]) of [..., (w, x, y, z)]: 2·atan2(|v|, |w|), accurate near 0."""
    q = np.asarray(q, dtype=np.float64)
    return 2.0 * np.arctan2(np.linalg.norm(q[..., 1:], axis=-1), np.abs(q[..., 0]))


def shift_truth(quat: np.ndarray, half_samples: int) -> np.ndarray:
    """The truth shifted in time: row k is the attitude at t_k + (half_samples/2)·dt.

    A whole-sample shift takes a neighbouring row; a half-sample shift is the slerp midpoint of the two
    rows around it (each normalised), (a ± b)/|a ± b| with the sign of a·b (the shorter arc). Rows whose
    neighbours fall outside the record, or are NaN, are NaN.
    """
    n = len(quat)
    lo, odd = divmod(half_samples, 2)  # floor: t_k + σ·dt lies between rows k + lo and k + lo + odd

    def rows(offset: int) -> np.ndarray:
        out = np.full_like(quat, np.nan)
        k = np.arange(n) + offset
        inside = (k >= 0) & (k < n)
        out[inside] = quat[k[inside]]
        return out

    a = rows(lo)
    if not odd:
        return a
    a = a / np.linalg.norm(a, axis=-1, keepdims=True)
    b = rows(lo + 1)
    b = b / np.linalg.norm(b, axis=-1, keepdims=True)
    b = b * np.where(np.sum(a * b, axis=-1, keepdims=True) < 0.0, -1.0, 1.0)
    mid = a + b
    return mid / np.linalg.norm(mid, axis=-1, keepdims=True)


def start_points(movement: np.ndarray, fs: float, every: float = 5.0) -> np.ndarray:
    """Start samples on a grid of `every` seconds from the first movement sample, s_j = m0 + round(j·every·fs),
    up to the last movement sample, keeping those that are movement samples (a trial with breaks loses the
    grid points inside a break)."""
    moving = np.flatnonzero(movement)
    first, last = moving[0], moving[-1]
    grid = first + np.round(np.arange(0.0, (last - first) / fs + every, every) * fs).astype(np.int64)
    grid = grid[grid <= last]
    return grid[movement[grid]]


def errors(
    q_est: np.ndarray,
    truth: np.ndarray,
    fs: float,
    starts: np.ndarray,
    horizons: Sequence[float],
    movement: Optional[np.ndarray] = None,
) -> np.ndarray:
    """Gyro-only orientation errors (degrees), shape (len(horizons), len(starts)).

    q_est: (N, 4) attitudes after each sample of a run from identity; truth: (N, 4) the reference (NaN rows
    allowed); starts: sample indices; horizons: seconds (h → round(h·fs) samples). Entry [i, j] is the angle
    of truth_e⁻¹ ⊗ truth_s ⊗ q_s⁻¹ ⊗ q_e with s = starts[j], e = s + round(horizons[i]·fs): NaN when e is
    past the record, when the truth is NaN at s or e, or (if `movement` is given) when e is not a movement
    sample.
    """
    q_est = np.asarray(q_est, dtype=np.float64)
    starts = np.asarray(starts, dtype=np.int64)
    out = np.full((len(horizons), len(starts)), np.nan)
    for i, horizon in enumerate(horizons):
        ends = starts + int(round(horizon * fs))
        ok = ends < len(truth)
        s, e = starts[ok], ends[ok]
        relative = quat_mul(quat_conj(q_est[s]), q_est[e])  # q_s⁻¹ ⊗ q_e
        estimate = quat_mul(truth[s], relative)
        angle = np.degrees(quat_angle(quat_mul(quat_conj(truth[e]), estimate)))  # NaN where a truth is
        if movement is not None:
            angle[~movement[e]] = np.nan
        out[i, ok] = angle
    return out
