"""Compare integration schemes and input models on a synthetic coning stream; plot the attitude error.

The body cones: ω(t) is the exact body rate of the attitude
    q(t) = qz(a t) ⊗ qx(β) ⊗ qz(b t) ⊗ qy(γ sin(c t))
(a, b, c incommensurate), so the true attitude is known at every sample. The stream is sampled at
`--rate` Hz; each configuration integrates it with `quatprop.integrate`, and the error is the rotation
angle between the integrated and the true attitude, 2·atan2(|vec(q_true* ⊗ q)|, |w|) (rad).

    python examples/compare_schemes.py                   # writes compare_schemes.png next to this file
    python examples/compare_schemes.py --rate 200 --seconds 60 --out errors.png

Needs matplotlib (an example dependency: pip install matplotlib).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import quatprop

A, B, C = 2.0 * np.pi * 0.7, 2.0 * np.pi * np.sqrt(2.0), 2.0 * np.pi * 0.5 * np.sqrt(5.0)
BETA, GAMMA = 0.4, 0.3


# Written out here (as in benchmarks/broad_metric.py) so that the example runs on quatprop and numpy alone.
def qmul(p, q):
    """Hamilton product of [..., 4] arrays, scalar first."""
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


def axis_quat(angle, axis):
    q = np.zeros(np.shape(angle) + (4,))
    q[..., 0] = np.cos(angle / 2)
    q[..., 1 + axis] = np.sin(angle / 2)
    return q


def truth(t):
    """The true attitude (body to reference) and the body rate ω = 2 vec(q* ⊗ q') (rad/s)."""
    def q_of(t):
        return qmul(
            qmul(qmul(axis_quat(A * t, 2), axis_quat(np.full_like(t, BETA), 0)), axis_quat(B * t, 2)),
            axis_quat(GAMMA * np.sin(C * t), 1),
        )

    q = q_of(t)
    # q' from the product rule, each factor differentiated analytically: d/dt qk(θ(t)) = qk(θ) ⊗ (0, ½θ' e_k).
    def d(angle_rate, axis):
        v = np.zeros(np.shape(angle_rate) + (4,))
        v[..., 1 + axis] = angle_rate / 2
        return v

    f1, f2, f3, f4 = axis_quat(A * t, 2), axis_quat(np.full_like(t, BETA), 0), axis_quat(B * t, 2), axis_quat(GAMMA * np.sin(C * t), 1)
    g1 = qmul(f1, d(np.full_like(t, A), 2))
    g3 = qmul(f3, d(np.full_like(t, B), 2))
    g4 = qmul(f4, d(GAMMA * C * np.cos(C * t), 1))
    dq = qmul(qmul(qmul(g1, f2), f3), f4) + qmul(qmul(qmul(f1, f2), g3), f4) + qmul(qmul(qmul(f1, f2), f3), g4)
    conj = q * np.array([1, -1, -1, -1])
    omega = 2 * qmul(conj, dq)[..., 1:]
    return q, omega


def angle_error(q, q_true):
    conj = q_true * np.array([1, -1, -1, -1])
    d = qmul(conj, q.astype(np.float64))
    return 2 * np.arctan2(np.linalg.norm(d[..., 1:], axis=-1), np.abs(d[..., 0]))


CONFIGS = [
    # (label, options)
    ("Euler, hold, normalize", dict(scheme="euler", input="hold", stabilizer="normalize")),
    ("RK4, hold (Geiger's setting)", dict(scheme="rk4", input="hold", stabilizer="off")),
    ("RK4, linear, normalize", dict(scheme="rk4", input="linear", stabilizer="normalize")),
    ("ExpMap, linear, first order", dict(scheme="expmap", input="linear")),
    ("ExpMap, history, first order (recommended)", dict(scheme="expmap", input="history")),
    ("ExpMap, history, f64", dict(scheme="expmap", input="history", precision="f64")),
    ("Magnus4, history, f64", dict(scheme="magnus4", input="history", precision="f64")),
]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rate", type=float, default=400.0, help="sample rate (Hz)")
    ap.add_argument("--seconds", type=float, default=120.0, help="duration (s)")
    ap.add_argument("--out", type=Path, default=Path(__file__).with_name("compare_schemes.png"))
    args = ap.parse_args()

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = int(args.seconds * args.rate) + 1
    t = np.arange(n) / args.rate
    q_true, omega = truth(t)
    fig, ax = plt.subplots(figsize=(9, 5.5))
    for label, opts in CONFIGS:
        opts = dict(opts)
        opts.setdefault("precision", "f32")
        q = quatprop.integrate(omega, dt=1.0 / args.rate, q0=q_true[0], **opts)
        # Every sample, the first included, is pushed with one period: row k is the attitude at t_k + 1/rate
        # for Hold (it steps on the first sample); Linear and History start on it and end at t_k.
        ref = q_true if opts["input"] != "hold" else truth(t + 1.0 / args.rate)[0]
        err = angle_error(q, ref)
        print(f"{label:45s} final error {err[-1]:.3e} rad, max {err.max():.3e} rad")
        style = "--" if "linear" in label and "ExpMap" in label else "-"
        ax.semilogy(t[1:], np.maximum(err[1:], 1e-12), style, label=label, lw=1.1)
    ax.set_ylim(1e-9, 1.0)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("attitude error (rad)")
    ax.set_title(
        f"quatprop on a coning stream at {args.rate:g} Hz (f32 unless marked; {quatprop.__name__} {quatprop.__version__})"
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
