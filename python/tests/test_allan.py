"""quatprop.allan: the core's streaming Allan variance and noise fit, from Python."""

import numpy as np
import pytest

import quatprop


def direct_avar(x: np.ndarray, m: int) -> np.ndarray:
    """The non-overlapping Allan variance of clusters of m samples, per axis, from the stored samples."""
    means = x[: len(x) // m * m].reshape(-1, m, 3).mean(axis=1)
    return 0.5 * np.mean(np.diff(means, axis=0) ** 2, axis=0)


def test_the_octaves_are_the_direct_formula_and_white_noise_is_identified():
    rng = np.random.default_rng(7)
    dt = 0.01
    x = 0.02 + 0.01 * rng.standard_normal((100_000, 3))  # N = 0.01·√0.01 = 1e-3 rad/√s
    r = quatprop.allan(x, dt, min_tau=16 * dt)
    for k, (tau, var) in enumerate(zip(r["tau"], r["variance"])):
        m = 2**k
        assert tau == pytest.approx(m * dt, rel=1e-12)
        np.testing.assert_allclose(var, direct_avar(x, m), rtol=1e-9)
    assert r["differences"][0] == len(x) - 1
    white = r["white"]
    assert white["identified"]
    assert abs(white["value"] / 1e-3 - 1) < 0.03
    assert white["lower"] <= 1e-3 <= white["upper"]
    assert not r["random_walk"]["identified"]
    assert r["random_walk"]["upper"] > 0
    assert len(r["axes"]) == 3 and all(abs(a["white"]["value"] / 1e-3 - 1) < 0.05 for a in r["axes"])


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="NonFiniteRate"):
        quatprop.allan(np.array([[0.0, np.nan, 0.0]] * 10), 0.01)
    with pytest.raises(ValueError, match="NonPositiveStep"):
        quatprop.allan(np.zeros((10, 3)), 0.0)
    with pytest.raises(ValueError, match="shape"):
        quatprop.allan(np.zeros((10, 2)), 0.01)
    # Too short to fit: the curve, no fit.
    r = quatprop.allan(np.zeros((3, 3)), 0.01)
    assert r["pooled"] is None and len(r["tau"]) == 1
