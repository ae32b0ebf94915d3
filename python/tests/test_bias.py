"""The bias estimator through the binding (`quatprop.BiasEstimator`, the core's `frontend::BiasEstimator`):
what each parameter does, in its unit, with numbers the core's design fixes.

The scenes are gyros at 1 kHz with 0.1 °/s of white noise per sample and a bias of (0.6, −0.4, 0.25) °/s
(the core's tests' sensor). Most give the sensor's noise density (`noise_density`), so that what is
tested does not depend on how the first still windows happen to show the scatter at rest
(test_still_windows_are_learned and test_stream.py's step test learn it).
"""

import numpy as np
import pytest

import quatprop

DEG = np.pi / 180
B0 = np.array([0.6, -0.4, 0.25]) * DEG
SIGMA = 0.1 * DEG  # per sample
N01 = SIGMA * 1e-3**0.5  # its density (rad/√s): σ·√dt
GATE = 3 * DEG


def ramp(t, start, seconds):
    """A raised cosine from 0 at `start` to 1 `seconds` later."""
    x = np.clip((t - start) / seconds, 0.0, 1.0)
    return 0.5 * (1.0 - np.cos(np.pi * x))


def scene(seconds, rate=None, bias=B0, seed=0):
    """(t, gyr): `rate(t)` (rad/s, (n, 3)) plus the bias plus the noise, float64."""
    n = int(round(seconds * 1000))
    t = (np.arange(n) + 1) * 1e-3
    gyr = np.broadcast_to(bias, (n, 3)) + SIGMA * np.random.default_rng(seed).standard_normal((n, 3))
    if rate is not None:
        gyr = gyr + rate(t)
    return t, gyr


def per_window(stream, gyr, **companions):
    """Feeds 1 s at a time (the windows below are 1 s); the estimate after each second."""
    out = []
    for w in range(len(gyr) // 1000):
        part = slice(w * 1000, (w + 1) * 1000)
        stream.update(gyr[part], **{k: v[part] for k, v in companions.items()})
        out.append(stream.bias)
    return np.array(out)


def yaw(q):
    return 2.0 * np.arctan2(q[..., 3], q[..., 0])


def about_z(d):
    """A turn about z from 20.2 s, reaching `d` rad/s over 0.5 s and held."""
    return lambda t: np.stack([0 * t, 0 * t, d * ramp(t, 20.2, 0.5)], axis=1)


@pytest.mark.parametrize("dps, believed_at", [(0.5, 25), (1.0, 34)])
def test_drift_is_how_long_a_slow_turn_is_kept(dps, believed_at):
    """A turn of `dps` °/s (below the 3 °/s gate, its onset a ramp) after 20 s at rest. Its windows are
    still and flat, but `d` off the estimate: with `drift` D (rad/s/√s) one is believed once
    `5·D·√t ≥ d`, `t` counted from the last window that agreed (20 s) to the start of the window judged:
    with D = 1e-3, t = (d / 5D)² = 3.05 s (0.5 °/s) and 12.18 s (1 °/s), so the windows from 24 s and
    from 33 s, taken at their ends (25 s, 34 s). Quadrupling t for twice the rate is the √t of a random
    walk. With the default drift the turn is kept: the estimate does not move, and the attitude turns by
    the whole angle."""
    d = dps * DEG
    t, gyr = scene(80.0, about_z(d), seed=21)
    turned = d * (80.0 - 20.2 - 0.25)  # the raised cosine's mean is ½: 0.25 s of its 0.5 s
    assert believed_at == np.ceil(20.0 + (d / (5 * 1e-3)) ** 2) + 1

    fast = quatprop.Stream(dt=1e-3, precision="f64",
                           bias=quatprop.BiasEstimator(1.0, GATE, drift=1e-3, noise_density=N01))
    b = per_window(fast, gyr)
    moved = np.flatnonzero(np.abs(b[:, 2] - b[19, 2]) > 0.5 * d)
    assert moved[0] + 1 == believed_at
    np.testing.assert_allclose(b[-1] - B0, [0.0, 0.0, d], atol=0.01 * DEG)  # the turn taken for bias

    kept = quatprop.Stream(dt=1e-3, precision="f64", bias=quatprop.BiasEstimator(1.0, GATE, noise_density=N01))
    before = kept.update(gyr[:20_000])[-1]
    at_rest = kept.bias
    np.testing.assert_allclose(at_rest, B0, atol=0.002 * DEG)
    q = kept.update(gyr[20_000:])[-1]
    np.testing.assert_array_equal(kept.bias, at_rest)  # nothing learned in 60 s of turn
    # The whole turn is in the attitude (to the noise's random walk, 0.025° in 60 s, and the rest
    # estimate's error, 0.001 °/s).
    assert abs(yaw(q) - yaw(before) - turned) < 0.15 * DEG, (yaw(q) - yaw(before) - turned) / DEG
    # Taken for bias from `believed_at` on, the same turn loses that much of its angle.
    q = quatprop.integrate(gyr, dt=1e-3, precision="f64",
                           bias=quatprop.BiasEstimator(1.0, GATE, drift=1e-3, noise_density=N01))
    seen = yaw(q[-1]) - yaw(q[19_999])
    assert abs(turned - seen - d * (80.0 - believed_at)) < 0.15 * DEG, (turned - seen) / DEG


def test_the_default_drift_is_the_documented_one():
    """drift=None is the core's DEFAULT_DRIFT, 2e-5 rad/s/√s (docs/python.md, the docstring), bit for bit;
    another drift changes the estimate after a motion (the time unseen grows its uncertainty by drift²)."""
    motion = lambda t: np.stack([2.0 * ((t > 10.0) & (t < 12.5)), 0 * t, 0 * t], axis=1)  # above the gate
    _, gyr = scene(30.0, motion, seed=5)

    def run(**kw):
        return quatprop.integrate(gyr, dt=1e-3, precision="f64", bias=quatprop.BiasEstimator(1.0, GATE, **kw))

    default = run()
    assert default.tobytes() == run(drift=2e-5).tobytes()
    assert default.tobytes() != run(drift=1e-4).tobytes()
    assert default.tobytes() != run(drift=1e-5).tobytes()


def test_a_known_bias_is_refined_within_its_sigma_and_otherwise_stepped_to():
    """`initial` with `initial_sigma`: a first window within five sigmas refines it at once (its Kalman
    gain is near one: sigma² against the window mean's 3e-9 (rad/s)²); a start 20 sigmas off is held for
    a window (a candidate step) and left when the second window confirms the level: at 2 s."""
    _, gyr = scene(4.0, seed=8)
    off = B0 + np.array([0.1, -0.1, 0.05]) * DEG  # about 0.15 °/s = 2.6e-3 rad/s off

    s = quatprop.Stream(dt=1e-3, precision="f64",
                        bias=quatprop.BiasEstimator(1.0, GATE, initial=off, initial_sigma=0.01, noise_density=N01))
    np.testing.assert_array_equal(s.bias, off)  # the start, before any sample
    b = per_window(s, gyr)
    np.testing.assert_allclose(b[0], B0, atol=0.01 * DEG)

    s = quatprop.Stream(dt=1e-3, precision="f64",
                        bias=quatprop.BiasEstimator(1.0, GATE, initial=off, initial_sigma=1.3e-4, noise_density=N01))
    b = per_window(s, gyr)
    np.testing.assert_array_equal(b[0], off)  # 20 sigmas: not believed from one window
    np.testing.assert_allclose(b[1], B0, atol=0.01 * DEG)  # confirmed by the second
    # And the attitude: the first second integrates the start's error, nothing after.
    q = quatprop.integrate(gyr, dt=1e-3, precision="f64",
                           bias=quatprop.BiasEstimator(1.0, GATE, initial=off, initial_sigma=0.01, noise_density=N01))
    assert abs(yaw(q[999])) > 0.04 * DEG  # 0.05 °/s of z error for a second (and the noise)


def test_the_noise_density_judges_the_first_window():
    """A first second that holds a slow ramp (0 → 2 °/s about y, still within the gate, the body settling):
    given the sensor's noise density, its block means are not flat, and nothing is learned until the next,
    still, second; learning the scatter from it instead, the estimator takes that first window as it is
    (about 1 °/s off on y)."""
    settle = lambda t: np.stack([0 * t, 2.0 * DEG * (1.0 - ramp(t, 0.2, 0.6)), 0 * t], axis=1)
    _, gyr = scene(3.0, settle, seed=23)
    given = per_window(quatprop.Stream(dt=1e-3, precision="f64",
                                       bias=quatprop.BiasEstimator(1.0, GATE, noise_density=N01)), gyr)
    np.testing.assert_array_equal(given[0], [0.0, 0.0, 0.0])
    np.testing.assert_allclose(given[1], B0, atol=0.01 * DEG)
    learned = per_window(quatprop.Stream(dt=1e-3, precision="f64", bias=quatprop.BiasEstimator(1.0, GATE)), gyr)
    assert abs(learned[0][1] - B0[1]) > 0.5 * DEG


def test_the_accelerometer_gate_keeps_a_window_with_a_bump_out():
    """The gyro still throughout; in the second second the acceleration jumps by 1 m/s² on x for 1 ms (a
    knock). With accel_gate=0.5 m/s² that window is not still: the estimate after 2 s is the one after
    1 s, bit for bit; without the gate (the accelerations' block means still flat: the bump moves one by
    8 mm/s², under their scatter) and without accelerations it is learned."""
    _, gyr = scene(3.0, seed=31)
    acc = np.tile([0.0, 0.0, 9.81], (3000, 1)) + 0.05 * np.random.default_rng(32).standard_normal((3000, 3))
    acc[1500, 0] += 1.0

    def run(acc=None, **kw):
        s = quatprop.Stream(dt=1e-3, precision="f64", bias=quatprop.BiasEstimator(1.0, GATE, noise_density=N01, **kw))
        return per_window(s, gyr, **({} if acc is None else {"acc": acc}))

    gated = run(acc, accel_gate=0.5)
    np.testing.assert_array_equal(gated[1], gated[0])
    assert not np.array_equal(gated[2], gated[1])  # the third second is still again
    for b in (run(acc), run()):
        assert not np.array_equal(b[1], b[0])


def quat_angle(p, q):
    """The angle (rad) of the rotation between unit quaternions p and q."""
    return 2.0 * np.arccos(min(1.0, abs(float(np.dot(p, q)))))


def relative(p, q):
    """p* ⊗ q: the rotation from p to q, in p's body axes."""
    w1, x1, y1, z1 = p * [1, -1, -1, -1]
    w2, x2, y2, z2 = q
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def test_the_temperature_line_is_applied_beyond_the_rests():
    """A bias linear in temperature (0.02 °/s per °C on x, −0.01 on y): learned at rest while the sensor
    warms from 25 to 35 °C over 30 s and holds; then 20 s turning at 10 °/s about x (above the gate: nothing
    is learned) while it warms on to 45 °C. With temperature_span=1 °C the bias subtracted follows the
    fitted line: the turn's attitude is within 0.15° of the truth; without, the bias stays at 35 °C's and
    the turn is off by the mean error (|(0.02, −0.01)| °/s/°C · 5 °C · 20 s = 2.2°)."""
    slope = np.array([0.02, -0.01, 0.0]) * DEG
    n = 60_000
    t = (np.arange(n) + 1) * 1e-3
    temperature = 25.0 + 10.0 * np.clip(t / 30.0, 0.0, 1.0) + 10.0 * np.clip((t - 40.0) / 20.0, 0.0, 1.0)
    truth = B0 + slope * (temperature - 25.0)[:, None]
    turn = np.zeros((n, 3))
    turn[:, 0] = 10.0 * DEG * (t > 40.0)
    gyr = turn + truth + SIGMA * np.random.default_rng(41).standard_normal((n, 3))
    exact = quatprop.integrate(gyr - truth, dt=1e-3, precision="f64")

    def turn_error(**kw):
        s = quatprop.Stream(dt=1e-3, precision="f64", bias=quatprop.BiasEstimator(1.0, GATE, noise_density=N01, **kw))
        q = s.update(gyr, temperature=temperature)
        return quat_angle(relative(q[39_999], q[-1]), relative(exact[39_999], exact[-1]))

    assert turn_error(temperature_span=1.0) < 0.15 * DEG
    assert 1.8 * DEG < turn_error() < 2.6 * DEG


def test_the_reported_bias_is_what_is_subtracted_with_motion():
    """With motion=True, Stream.bias is the rest estimate plus the residual learned in motion from the
    accelerometer: what the next sample has subtracted. In a body turning under gravity, at 50 points
    through the motion: the next sample integrated by the stream gives the attitude that the same sample
    gives with a fixed bias equal to the reported one (input "hold": a step sees only its sample), to
    rounding; with the rest estimate alone as the fixed bias it would differ by the residual's turn."""
    dt = 0.01
    n = 30_500  # 5 s still, then 5 min turning (the core's test: the residual's filter takes minutes)
    t = (np.arange(n) + 1) * dt
    rng = np.random.default_rng(51)
    # Still for 5 s, then turning about all axes; the accelerometer reads gravity in body axes
    # (q* ⊗ g ⊗ q along the true attitude) plus noise.
    w = np.stack([0.3 * np.sin(0.7 * t), 0.4 * np.cos(0.5 * t), 0.2 + 0 * t], axis=1)
    w[t <= 5.0] = 0.0
    q_true = quatprop.integrate(w, dt=dt, precision="f64", input="hold")
    g = np.array([0.0, 0.0, 9.81])
    qw, qv = q_true[:, :1], -q_true[:, 1:]
    tv = 2.0 * np.cross(qv, g)
    acc = g + qw * tv + np.cross(qv, tv) + 0.01 * rng.standard_normal((n, 3))
    # The bias at rest, and a residual that appears with the motion (e.g. the g-sensitivity of the rates).
    gyr = w + B0 + np.array([0.3, -0.2, 0.1]) * DEG * (t > 5.0)[:, None] + 0.02 * DEG * rng.standard_normal((n, 3))

    with_motion = quatprop.Stream(dt=dt, precision="f64", input="hold",
                                  bias=quatprop.BiasEstimator(1.0, GATE, motion=True))
    rest = quatprop.Stream(dt=dt, precision="f64", input="hold", bias=quatprop.BiasEstimator(1.0, GATE))
    largest = 0.0
    a = 0
    for k in range(600, n, 599):
        with_motion.update(gyr[a:k], acc=acc[a:k])
        rest.update(gyr[a:k])
        b, q0 = with_motion.bias, with_motion.attitude
        residual = b - rest.bias  # the rest estimate is the same with or without motion=True
        largest = max(largest, np.abs(residual).max())
        q = with_motion.update(gyr[k : k + 1], acc=acc[k : k + 1])[-1]
        rest.update(gyr[k : k + 1])
        a = k + 1
        fixed = quatprop.Stream(dt=dt, precision="f64", input="hold", q0=q0, bias=b).update(gyr[k : k + 1])[-1]
        np.testing.assert_allclose(q, fixed, rtol=0, atol=1e-15)
        rest_alone = quatprop.Stream(dt=dt, precision="f64", input="hold", q0=q0,
                                     bias=rest.bias).update(gyr[k : k + 1])[-1]
        # The residual's turn in one step: |residual|·dt, half of it in the quaternion (to the noise).
        assert np.abs(rest_alone - fixed).max() > 0.25 * np.abs(residual).max() * dt
    # The residual reported is the one learned in motion: on its way to the injected one (80 % of it after
    # 5 min on every axis: the filter's minutes), never beyond.
    ratio = residual / (np.array([0.3, -0.2, 0.1]) * DEG)
    assert np.all((0.7 < ratio) & (ratio < 0.9)), ratio
    assert largest <= 0.3 * DEG


@pytest.mark.parametrize(
    "noise_density, acc_seed",
    [(N01, None), (None, None), (N01, 3)],
    ids=["noise_given", "gyro_scatter_learned", "accel_scatter_learned"],
)
def test_still_windows_are_learned(noise_density, acc_seed):
    """30 s at rest: every window after the first is still, flat and agrees, so each updates the estimate
    (the flatness test's false alarms are p = 1e-4 per axis). The same draw of the gyro's noise as the
    step test (seed 3), whose first window shows 0.17x the scatter on z; accelerations of 0.05 m/s² noise,
    whose draw 3 does the same. With the scatter at rest learned from that first window alone (7 degrees
    of freedom) and tested against χ²'s bound, most windows after it failed the flatness test and nothing
    was learned (gyro and accelerations alike); against the F(7, 7k) bound every one is learned."""
    _, gyr = scene(30.0, seed=3)
    companions = {}
    if acc_seed is not None:
        rng = np.random.default_rng(acc_seed)
        companions["acc"] = np.tile([0.0, 0.0, 9.81], (30_000, 1)) + 0.05 * rng.standard_normal((30_000, 3))
    s = quatprop.Stream(dt=1e-3, precision="f64",
                        bias=quatprop.BiasEstimator(1.0, GATE, noise_density=noise_density))
    b = per_window(s, gyr, **companions)
    refused = [k + 1 for k in range(1, 30) if np.array_equal(b[k], b[k - 1])]
    assert refused == [], f"still windows not learned (ending at these seconds): {refused}"
    np.testing.assert_allclose(b[-1], B0, atol=0.005 * DEG)


def test_bias_variance_is_the_estimators():
    """`Stream.bias_variance`: float max before the first still window, then the estimator's variance,
    shrinking as still windows are learned and growing by the drift while the body moves."""
    rng = np.random.default_rng(5)
    s = quatprop.Stream(dt=1e-3, precision="f64", bias=quatprop.BiasEstimator(1.0, 0.05, drift=1e-3))
    s.update(1e-3 * rng.standard_normal((500, 3)))
    assert np.all(s.bias_variance == np.finfo(np.float64).max)
    s.update(1e-3 * rng.standard_normal((1500, 3)))
    after_one = s.bias_variance
    assert np.all(after_one > 0) and np.all(after_one < 1e-8)
    s.update(1e-3 * rng.standard_normal((3000, 3)))
    # Four more windows: smaller on the whole (each axis's first figure rests on its own 7-dof scatter).
    assert s.bias_variance.mean() < after_one.mean()
    moving = s.bias_variance
    s.update(np.tile([0.5, 0.0, 0.0], (2000, 1)))  # 2 s of motion: +drift² · 2 s
    np.testing.assert_allclose(s.bias_variance - moving, 1e-6 * 2.0, rtol=1e-6)
    assert quatprop.Stream(dt=1e-3).bias_variance is None


def test_the_gain_is_learned_in_motion_and_handed_over_as_a_calibration():
    """BiasEstimator(motion=CalibrationEstimator(...)): a gyro reading 1 % high on x and with a 0.3°
    cross-axis term, tumbling under gravity (the accelerometer at each sample's end), 2 min at 100 Hz.
    The learned gain approaches the truth; Stream.learned_calibration hands it over as a Calibration that
    gives the estimator's own correction; motion=True has none."""
    dt = 0.01
    n = 12_000
    t = np.arange(n) * dt
    w = np.stack([np.cos(t), np.sin(0.37 * t), 0.6 * np.cos(0.21 * t)], axis=1)
    truth = np.array([[1 / 1.01, 0.0, 0.0], [np.radians(0.3), 1.0, 0.0], [0.0, 0.0, 1.0]])  # I − G
    readings = w @ np.linalg.inv(truth).T
    q = quatprop.integrate(w, dt=dt, precision="f64", input="hold")
    up = np.array([0.0, 0.0, 9.81])
    acc = np.array([rotate_back(qi, up) for qi in q])
    cal = quatprop.CalibrationEstimator(0.01, 0.0087, motion_noise=np.radians(0.001))
    s = quatprop.Stream(dt=dt, precision="f64", input="hold", bias=quatprop.BiasEstimator(1.0, GATE, motion=cal))
    s.update(readings, acc=acc)
    learned = s.learned_calibration
    gain, sd = learned["gain"], learned["gain_std_dev"]
    start = np.abs(np.eye(3) - truth).max()
    err = np.abs(gain - truth).max()
    # Every term ten times closer than at the start; the two the sensor has wrong, to 2e-4.
    assert start > 9e-3 and err < 1e-3, (start, gain - truth)
    assert abs(gain[0, 0] - truth[0, 0]) < 2e-4 and abs(gain[1, 0] - truth[1, 0]) < 2e-4, gain - truth
    assert np.all(sd < 0.0087) and sd[0, 0] < 1e-3
    # The calibration it hands over is its correction: applied to a reading, the estimator's rate.
    c = learned["calibration"]
    assert isinstance(c, quatprop.Calibration)
    r = np.array([[1.01, 0.0, 0.0], [0.2, -0.4, 0.9]])
    np.testing.assert_allclose(quatprop.calibrate(r, c, precision="f64"),
                               (r - np.array(c.offset)) @ gain.T, rtol=0, atol=1e-15)
    plain = quatprop.Stream(dt=dt, bias=quatprop.BiasEstimator(1.0, GATE, motion=True))
    plain.update(readings[:10], acc=acc[:10])
    assert plain.learned_calibration is None


def rotate_back(q, v):
    """q* ⊗ v ⊗ q: a reference-frame vector in body axes."""
    w, x, y, z = q
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    return r.T @ v
