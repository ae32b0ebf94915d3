"""Cut the IMU excerpt the firmware's `estimator` program runs on (it is committed; this records how).

    python firmware/data/make_imu_excerpt.py PATH/TO/broad/07_undisturbed_fast_rotation_B.hdf5 \\
        firmware/data/broad07_imu.bin

Writes `--seconds` seconds (default 7) of the trial's gyroscope and accelerometer (`imu_gyr` in rad/s,
`imu_acc` in m/s², sensor frame), from `--before` seconds (default 1) before its first movement sample, as
float32 little-endian rows `gx gy gz ax ay az` (24 bytes per sample, no header: the firmware includes the
file with `include_bytes!`). Needs h5py and numpy.

Data: D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation
Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0)
"""

import argparse
from pathlib import Path

import h5py
import numpy as np


def main() -> None:
    # The command line spelled out: a one-off script, alike in shape to python/benchmarks/make_excerpt.py's.
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("source", type=Path, help="a BROAD trial (HDF5)")
    ap.add_argument("target", type=Path, help="the binary file to write")
    ap.add_argument("--seconds", type=float, default=7.0, help="length of the excerpt (s)")
    ap.add_argument("--before", type=float, default=1.0, help="rest kept before the first movement (s)")
    a = ap.parse_args()
    with h5py.File(a.source, "r") as f:
        fs = float(f.attrs["sampling_rate"])
        first = int(np.flatnonzero(f["movement"][()])[0]) - int(round(a.before * fs))
        n = int(round(a.seconds * fs))
        imu = np.hstack([f["imu_gyr"][first : first + n], f["imu_acc"][first : first + n]]).astype("<f4")
    if first < 0 or len(imu) < n or not np.all(np.isfinite(imu)):
        raise ValueError(f"{a.source.name}: no {n} finite samples from sample {first}")
    a.target.write_bytes(imu.tobytes())
    print(f"{a.target}: {n} samples from sample {first} at {fs!r} Hz")


if __name__ == "__main__":
    main()
