"""The conventions against SciPy's Rotation (scalar *last* there): Hamilton product, scalar-first
[w, x, y, z], attitude body → reference, body-frame rates composing on the right, Euler angles."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import quatprop


def to_scipy(q):
    """quatprop [w, x, y, z] → SciPy Rotation (which takes [x, y, z, w])."""
    return Rotation.from_quat(np.asarray(q, dtype=np.float64)[..., [1, 2, 3, 0]])


def from_scipy(r):
    return r.as_quat()[..., [3, 0, 1, 2]]


def same_rotation(a, b, tol):
    """Unit quaternions a, b equal up to sign (q and -q are the same rotation)."""
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return min(np.abs(a - b).max(), np.abs(a + b).max()) <= tol


def test_yaw_rate_gives_scalar_first_quaternion_mapping_body_to_reference():
    # 90 deg of yaw at 1 rad/s about body z: q = (cos 45, 0, 0, sin 45), scalar first.
    n = 1000
    gyr = np.tile([0.0, 0.0, np.pi / 2], (n, 1))
    q = quatprop.integrate(gyr, dt=1.0 / n, input="hold", precision="f64")[-1]
    np.testing.assert_allclose(q, [np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)], atol=1e-13)
    # Body x now points along reference y: the attitude maps body vectors to the reference frame.
    np.testing.assert_allclose(to_scipy(q).apply([1.0, 0.0, 0.0]), [0.0, 1.0, 0.0], atol=1e-13)


@pytest.mark.parametrize("scheme", ["expmap", "magnus4", "cf4", "rk4"])
def test_constant_body_rate_composes_on_the_right(scheme):
    q0 = np.array([0.8, 0.2, -0.4, 0.4])
    q0 /= np.linalg.norm(q0)
    omega = np.array([0.7, -1.1, 0.4])  # rad/s, body frame
    n, dt = 2000, 1.0e-3
    q = quatprop.integrate(np.tile(omega, (n, 1)), dt=dt, input="hold", scheme=scheme, precision="f64", q0=q0)
    r0 = to_scipy(q0)
    right = r0 * Rotation.from_rotvec(omega * n * dt)  # q0 ⊗ exp(ωt/2): body rates
    left = Rotation.from_rotvec(omega * n * dt) * r0  # what reference-frame rates would give
    tol = 1e-12 if scheme != "rk4" else 1e-9  # RK4's local error x^5/120 per step
    assert same_rotation(q[-1], from_scipy(right), tol)
    assert not same_rotation(q[-1], from_scipy(left), 1e-3), "the test must tell the two apart"
    # Every row is the attitude after that sample: row k is q0 composed with ω (k+1) dt.
    k = 499
    assert same_rotation(q[k], from_scipy(r0 * Rotation.from_rotvec(omega * (k + 1) * dt)), tol)


def test_hamilton_product_via_successive_rotations():
    # Yaw 90 deg then (body) roll 90 deg: q = qz ⊗ qx in Hamilton's product; body z ends along reference x...
    n = 1000
    gyr = np.vstack([np.tile([0, 0, np.pi / 2], (n, 1)), np.tile([np.pi / 2, 0, 0], (n, 1))])
    q = quatprop.integrate(gyr, dt=1.0 / n, input="hold", precision="f64")[-1]
    h = np.sqrt(0.5)
    qz, qx = np.array([h, 0, 0, h]), np.array([h, h, 0, 0])
    w1, v1, w2, v2 = qz[0], qz[1:], qx[0], qx[1:]
    hamilton = np.concatenate([[w1 * w2 - v1 @ v2], w1 * v2 + w2 * v1 + np.cross(v1, v2)])
    assert same_rotation(q, hamilton, 1e-12)
    np.testing.assert_allclose(to_scipy(q).apply([0.0, 0.0, 1.0]), [1.0, 0.0, 0.0], atol=1e-12)


def random_quaternions(n, seed=7):
    q = np.random.default_rng(seed).standard_normal((n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return q


def test_euler_zyx_matches_scipy():
    q = random_quaternions(500)
    e = quatprop.to_euler_zyx(q)
    np.testing.assert_allclose(e, to_scipy(q).as_euler("ZYX"), atol=1e-12)  # yaw, pitch, roll
    back = quatprop.from_euler_zyx(e)
    assert all(same_rotation(a, b, 1e-12) for a, b in zip(back, q))
    np.testing.assert_allclose(
        np.abs(quatprop.from_euler_zyx(e)), np.abs(from_scipy(Rotation.from_euler("ZYX", e))), atol=1e-12
    )


def test_euler_zxz_matches_scipy():
    q = random_quaternions(500, seed=11)
    e = quatprop.to_euler_zxz(q)
    np.testing.assert_allclose(e, to_scipy(q).as_euler("ZXZ"), atol=1e-12)  # psi, theta, phi
    back = quatprop.from_euler_zxz(e)
    assert all(same_rotation(a, b, 1e-12) for a, b in zip(back, q))


def test_euler_keeps_float32_and_leading_shape():
    q = random_quaternions(12).astype(np.float32).reshape(3, 4, 4)
    e = quatprop.to_euler_zyx(q)
    assert e.dtype == np.float32 and e.shape == (3, 4, 3)
    np.testing.assert_allclose(e.reshape(-1, 3), to_scipy(q.reshape(-1, 4)).as_euler("ZYX"), atol=2e-6)
    assert quatprop.from_euler_zxz(np.zeros(3)).shape == (4,)
