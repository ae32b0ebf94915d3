"""Cut the gyro excerpt the lab's recorded-motion scene runs on (it is committed; this records how).

    python lab/data/broad/make_gyro_excerpt.py PATH/TO/broad/07_undisturbed_fast_rotation_B.hdf5 \\
        lab/data/broad/07_fast_rotation_gyro.csv

Writes `--seconds` seconds (default 21) of the trial's gyroscope (`imu_gyr`, rad/s, sensor frame) from its
first movement sample, one sample per line (x, y, z), each value rounded once to float32 and printed with 9
significant digits (so it reads back as that float32 exactly; the gyro's resolution is about 1e-3 rad/s).
Comment lines (`#`) give the source, the sampling rate and the attribution. Needs h5py and numpy.

Data: D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation
Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0)
"""

import argparse
from pathlib import Path

import h5py
import numpy as np

ATTRIBUTION = (
    "D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation "
    "Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad"
)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("source", type=Path, help="a BROAD trial (HDF5)")
    ap.add_argument("target", type=Path, help="the CSV to write")
    ap.add_argument("--seconds", type=float, default=21.0, help="length of the excerpt (s)")
    a = ap.parse_args()
    with h5py.File(a.source, "r") as f:
        fs = float(f.attrs["sampling_rate"])
        first = int(np.flatnonzero(f["movement"][()])[0])
        n = int(round(a.seconds * fs))
        gyr = f["imu_gyr"][first : first + n].astype(np.float32)
    if len(gyr) < n or not np.all(np.isfinite(gyr)):
        raise ValueError(f"{a.source.name}: no {n} finite gyro samples from sample {first}")
    with open(a.target, "w", encoding="utf-8", newline="\n") as out:
        out.write(f"# BROAD trial {a.source.stem}: imu_gyr (rad/s, sensor frame), samples {first}:{first + n}\n")
        out.write(f"# (the first movement sample is {first}), made by lab/data/broad/make_gyro_excerpt.py\n")
        out.write(f"# sampling rate (Hz): {fs!r}\n")
        out.write(f"# Data: {ATTRIBUTION}. Licence: CC BY 4.0 (creativecommons.org/licenses/by/4.0)\n")
        out.write("x,y,z\n")
        for x, y, z in gyr:
            out.write(f"{x:.9g},{y:.9g},{z:.9g}\n")


if __name__ == "__main__":
    main()
