"""Throughput: `quatprop.integrate` against the same loop written in Rust, side by side in one run.

The Rust loop (`quatprop._native.rust_loop_f32/_f64`) is what a Rust user writes for the default
configuration — `Propagator<T, ExpMap, History<T>, FirstOrder>`, a `FixedPeriod`, `push` per sample, the
attitude stored after each — with concrete types, on the same buffer, timed in Rust (output allocation
included). `integrate` is timed from Python around the whole call (argument checks, dispatch, output
array). The two alternate (which goes first alternates too), several rounds; the ratio is of the fastest round of each (the least
disturbed by other processes), and the results must be bit for bit equal.

    python bench.py                 # 10^7 samples, 5 rounds, f32 and f64; writes docs/python.md
    python bench.py --quick         # 10^6 samples, 2 rounds, f32 (CI: prints the ratio, checks the bits)
"""

from __future__ import annotations

import argparse
import datetime as _dt
import os
import platform
import re
import sys
import time
from pathlib import Path

import numpy as np

import quatprop
from quatprop import _native

BEGIN = "<!-- bench.py: begin (generated; do not edit) -->"
END = "<!-- bench.py: end -->"


def stream(n: int, dtype) -> np.ndarray:
    """A coning motion at incommensurate frequencies plus noise (rad/s), 1 kHz."""
    t = np.arange(n) * 1e-3
    rng = np.random.default_rng(2026)
    gyr = np.stack(
        [0.8 * np.sin(7.3 * t), 0.8 * np.cos(7.3 * t) + 0.3 * np.sin(4.38 * t), 0.4 + 0.2 * np.cos(2.236 * t)],
        axis=1,
    )
    gyr += 0.01 * rng.standard_normal(gyr.shape)
    return np.ascontiguousarray(gyr, dtype=dtype)


def measure(n: int, rounds: int, precision: str) -> dict:
    dtype = np.float32 if precision == "f32" else np.float64
    gyr = stream(n, dtype)
    rust_loop = _native.rust_loop_f32 if precision == "f32" else _native.rust_loop_f64
    py_s, rust_s = [], []
    for k in range(rounds):
        # Alternate which runs first, so neither always follows the other's memory release.
        if k % 2:
            seconds, q_rust = rust_loop(gyr, 1e-3)
        t0 = time.perf_counter()
        q = quatprop.integrate(gyr, dt=1e-3, precision=precision)
        py_s.append(time.perf_counter() - t0)
        if not k % 2:
            seconds, q_rust = rust_loop(gyr, 1e-3)
        rust_s.append(seconds)
        if not np.array_equal(q.view(np.uint8), q_rust.view(np.uint8)):
            raise SystemExit("integrate and the Rust loop differ: not bit for bit")
        del q, q_rust
    return {
        "precision": precision,
        "n": n,
        "python_min": min(py_s),
        "rust_min": min(rust_s),
        "python_median": float(np.median(py_s)),
        "rust_median": float(np.median(rust_s)),
        "ratio_min": min(py_s) / min(rust_s),
        "ratio_median": float(np.median(py_s)) / float(np.median(rust_s)),
    }


def cpu_name() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def table(results: list, rounds: int, command: str) -> str:
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    lines = [
        BEGIN,
        "",
        f"Measured {_dt.datetime.now(_dt.timezone.utc):%Y-%m-%d %H:%M} UTC by `{command}` on {cpu_name()} "
        f"({os.cpu_count()} cores, load average {load:.1f} at the end; Python {platform.python_version()}, "
        f"numpy {np.__version__}). {rounds} alternating rounds; the ratio is of the fastest round of each.",
        "",
        "| precision | samples | `integrate` (Python call) | the same Rust loop | ratio (fastest) | ratio (median) | ns per sample (Python) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in results:
        lines.append(
            f"| {r['precision']} | {r['n']:.0e} | {r['python_min']:.3f} s | {r['rust_min']:.3f} s | "
            f"**{r['ratio_min']:.3f}×** | {r['ratio_median']:.3f}× | {1e9 * r['python_min'] / r['n']:.0f} |"
        )
    lines += ["", "Both results are bit for bit equal in every round (checked by the script).", "", END]
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="10^6 samples, 2 rounds, f32; no docs written")
    ap.add_argument("--n", type=int, default=None, help="samples (default 10^7, 10^6 with --quick)")
    ap.add_argument("--rounds", type=int, default=None, help="alternating rounds (default 5, 2 with --quick)")
    ap.add_argument("--docs", type=Path, default=Path(__file__).resolve().parent.parent / "docs" / "python.md")
    args = ap.parse_args()
    n = args.n or (10**6 if args.quick else 10**7)
    rounds = args.rounds or (2 if args.quick else 5)
    precisions = ["f32"] if args.quick else ["f32", "f64"]
    results = [measure(n, rounds, p) for p in precisions]
    for r in results:
        print(
            f"{r['precision']}: {r['n']:.0e} samples  integrate {r['python_min']:.3f} s  Rust loop {r['rust_min']:.3f} s  "
            f"ratio {r['ratio_min']:.3f} (fastest)  {r['ratio_median']:.3f} (median)"
        )
    if not args.quick:
        command = "python python/bench.py"
        text = args.docs.read_text()
        block = table(results, rounds, command)
        pattern = re.compile(re.escape(BEGIN) + ".*?" + re.escape(END), re.S)
        if not pattern.search(text):
            raise SystemExit(f"{args.docs}: markers not found")
        args.docs.write_text(pattern.sub(lambda _: block, text))
        print(f"wrote {args.docs}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
