"""Leading-order coning drift of each coning correction (small cone half-angle α), by series expansion.

Pure coning at frequency Ω, sample interval h, λ = Ωh, N samples per update (T = N h). To order α²:
  exact relative rotation about the cone axis over one update:  -(α²/2) sin(Nλ)
  sum of the increments' axial parts:                             -(α²/2) Nλ
  (Δθ_a × Δθ_b)·axis = α² · 2 sin((b−a)λ) (1 − cos λ)
Per-update error δ = φ_alg − φ_exact; drift rate = δ / T. Prints the drift as α²Ω (ΩT)^p · c, the closed
forms quoted in src/coning.rs and checked by tests/coning.rs.
Run: python3 lab/derivations/coning_drift.py   (needs sympy)
"""
import sympy as sp

lam = sp.symbols("lambda", positive=True)


def cross(d):
    return 2 * sp.sin(d * lam) * (1 - sp.cos(lam))


def delta(N, k, den, one_plus_previous=False):
    e = -sp.Rational(N, 2) * lam + sp.sin(N * lam) / 2
    if one_plus_previous:
        e += sp.Rational(1, 12) * cross(1)
    else:
        for i, ki in enumerate(k, start=1):
            e += sp.Rational(ki, den) * cross(N - i)
    return e


cases = [
    ("Uncorrected (1 sample)", 1, [], 1, False),
    ("OnePlusPrevious", 1, [], 1, True),
    ("TwoSample", 2, [2], 3, False),
    ("ThreeSample", 3, [9, 27], 20, False),
    ("FourSample", 4, [54, 92, 214], 105, False),
    ("FiveSample", 5, [250, 525, 650, 1375], 504, False),
]
for name, N, k, den, opp in cases:
    s = sp.series(delta(N, k, den, opp), lam, 0, 2 * N + 5).removeO()
    lead = sp.Poly(s, lam).terms()[-1]  # lowest power
    power, coef = lead[0][0], lead[1]
    # drift = δ/T = coef λ^power / (N h) = Ω coef λ^(power-1) / N; with ΩT = Nλ: = α²Ω (ΩT)^(power-1) coef / N^power
    c = sp.nsimplify(coef / sp.Integer(N) ** power)
    print(f"{name:24s} drift = α²Ω (ΩT)^{power - 1} · {c}   (= 1/{sp.nsimplify(1 / c)})")
