"""The typed stubs (`__init__.pyi`, `py.typed`) as a type checker sees them: correct calls pass, wrong ones
are flagged."""

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
    b = quatprop.BiasEstimator(100, 0.05)
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
