"""Cut the small BROAD excerpt that python/tests/test_broad.py runs on (it is committed; this records how).

    python python/benchmarks/make_excerpt.py PATH/TO/broad/07_undisturbed_fast_rotation_B.hdf5 \\
        python/tests/data/broad_excerpt.hdf5

The excerpt is a contiguous slice of one trial: `--rest` seconds before its first movement sample and
`--movement` seconds from it (defaults 5 s and 62 s: enough for the 60 s horizon from one start point, the
30 s horizon from seven and the 10 s horizon from eleven). It keeps only the datasets broad_metric.read_trial
reads (imu_gyr, imu_acc, opt_quat, movement), in the same layout; the float datasets are stored as float32
(each value rounded once, a relative 6e-8: far below the gyro's resolution of about 1e-3 rad/s) and gzip-9
with the shuffle filter, which makes the file about three times smaller than float64. Every file attribute
of the original is copied (sampling_rate, info), and three are added: attribution, license and excerpt (the
source trial and the sample range).

Data: D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation
Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0)
"""

import argparse
from pathlib import Path

import h5py
import numpy as np

import broad_metric as bm


def make_excerpt(source: Path, target: Path, rest: float, movement: float) -> slice:
    """Write the excerpt of `source` to `target`; return the slice of the source's samples it holds."""
    with h5py.File(source, "r") as f:
        fs = float(f.attrs["sampling_rate"])
        first = int(np.flatnonzero(f["movement"][()])[0])
        cut = slice(first - int(round(rest * fs)), first + int(round(movement * fs)))
        if cut.start < 0 or cut.stop > len(f["movement"]):
            raise ValueError(f"{source.name}: the excerpt {cut} does not fit in the trial")
        with h5py.File(target, "w") as out:
            for name in bm.DATASETS:
                data = f[name][cut]
                if data.dtype.kind == "f":
                    data = data.astype(np.float32)
                out.create_dataset(name, data=data, compression="gzip", compression_opts=9, shuffle=True)
            for key, value in f.attrs.items():
                out.attrs[key] = value
            out.attrs["attribution"] = bm.ATTRIBUTION
            out.attrs["license"] = "CC BY 4.0 (creativecommons.org/licenses/by/4.0), as the original dataset"
            out.attrs["excerpt"] = (
                f"samples {cut.start}:{cut.stop} of {source.stem} (the first movement sample is {first}: "
                f"{rest:g} s of rest, then {movement:g} s of movement), made by python/benchmarks/make_excerpt.py; "
                "datasets imu_gyr, imu_acc, opt_quat as float32, movement as bool"
            )
    return cut


# The command line of firmware/data/make_imu_excerpt.py in shape: each script stands alone.
def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("source", type=Path, help="a BROAD trial, e.g. 07_undisturbed_fast_rotation_B.hdf5")
    parser.add_argument("target", type=Path, help="the excerpt to write")
    parser.add_argument("--rest", type=float, default=5.0, help="seconds before the first movement sample")
    parser.add_argument("--movement", type=float, default=62.0, help="seconds from the first movement sample")
    args = parser.parse_args()
    cut = make_excerpt(args.source, args.target, args.rest, args.movement)
    print(f"wrote {args.target}: samples {cut.start}:{cut.stop}, {args.target.stat().st_size / 1024:.0f} KiB")


if __name__ == "__main__":
    main()
