"""The typed stubs (`__init__.pyi`, `py.typed`) as a type checker sees them: correct calls pass, wrong ones
(the 0.3 estimator's arguments, names that are not quatprop's) are flagged, and mypy's stubtest finds the
stub and the package the same."""

import subprocess
import sys
import textwrap

import pytest

pytest.importorskip("mypy")

GOOD = """
    import numpy as np
    import quatprop

    gyr = np.zeros((10, 3))
    q = quatprop.integrate(gyr, dt=1e-3, scheme="rk4", stabilizer="every:5", precision="f64")
    q2, refused = quatprop.integrate(gyr, t=np.arange(10) * 1e-3, on_refused="mask")
    e = quatprop.to_euler_zyx(q)
    b = quatprop.BiasEstimator(1.0, 0.05, drift=2e-5, initial=[0.0, 0.01, 0.0], initial_sigma=1e-3)
    window: float = b.window
    s = quatprop.Stream(dt=1e-3, bias=quatprop.BiasEstimator(0.5, 0.05, noise_density=1e-4, motion=True))
    bias = s.bias
    try:
        quatprop.integrate(gyr, dt=1e-3, bias=b, alignment="PyNxPz")
    except quatprop.RefusedSample as err:
        index: int = err.index
        kind: str = err.kind
"""

BAD = """
    import numpy as np
    import quatprop

    quatprop.integrate(np.zeros((10, 3)), dt=1e-3, scheme="rk9")
    q, refused = quatprop.integrate(np.zeros((10, 3)), dt=1e-3)
    quatprop.BiasEstimator(100, 0.05, memory=8)
    quatprop.np.zeros(3)
    s: quatprop.Scheme = "rk4"
"""


def mypy(tmp_path, source):
    path = tmp_path / "use.py"
    path.write_text(textwrap.dedent(source))
    return subprocess.run(
        [sys.executable, "-m", "mypy", "--no-incremental", "--cache-dir", str(tmp_path / "cache"), str(path)],
        capture_output=True,
        text=True,
    )


def test_stubs_accept_correct_calls(tmp_path):
    result = mypy(tmp_path, GOOD)
    assert result.returncode == 0, result.stdout


def test_stubs_flag_a_wrong_scheme(tmp_path):
    result = mypy(tmp_path, BAD)
    assert result.returncode == 1
    assert "use.py:5: error" in result.stdout, result.stdout  # the unknown scheme
    assert "use.py:7: error" in result.stdout, result.stdout  # the 0.3 estimator's `memory`
    assert "use.py:8: error" in result.stdout, result.stdout  # numpy is not quatprop's
    assert "use.py:9: error" in result.stdout, result.stdout  # nor are the stub's aliases


def test_stubs_match_the_runtime(tmp_path):
    """mypy's stubtest: every public name, signature and default of `__init__.pyi` (the dataclasses' fields
    included) is the package's, and `__all__` is the same in both. The extension's own stub (`_native.pyi`,
    private) is left out: its classes come from PyO3."""
    allow = tmp_path / "allowlist.txt"
    allow.write_text("quatprop\\._native(\\..*)?\n")
    result = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "quatprop", "--allowlist", str(allow)],
        capture_output=True, text=True, cwd=tmp_path,
    )
    assert result.returncode == 0, result.stdout + result.stderr
