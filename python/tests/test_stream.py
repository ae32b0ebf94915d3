"""`quatprop.Stream`: any chunking of a stream gives the bits of one `integrate` call over the whole of it."""

import numpy as np
import pytest

import quatprop

N = 2000


def coning(n=N, seed=7):
    """Rates at incommensurate frequencies (rad/s) plus a bias and noise; a still first second."""
    t = np.arange(n) * 1e-3
    rng = np.random.default_rng(seed)
    w = np.stack([0.9 * np.sin(7.3 * t), 0.7 * np.cos(4.38 * t), 0.4 + 0.3 * np.sin(2.236 * t)], axis=1)
    w[: n // 2] = 0.0  # still: the estimator learns the bias there
    return w + np.array([0.01, -0.02, 0.005]) + 0.001 * rng.standard_normal((n, 3))


def chunked(stream, gyr, size, **stamps):
    """Feeds `gyr` (and its timestamps) in pieces of `size`; the attitudes (and refused flags) joined."""
    qs, masks = [], []
    for a in range(0, len(gyr), size):
        part = {k: v[a : a + size] for k, v in stamps.items()}
        r = stream.update(gyr[a : a + size], **part)
        if isinstance(r, tuple):
            qs.append(r[0])
            masks.append(r[1])
        else:
            qs.append(r)
    return np.concatenate(qs), (np.concatenate(masks) if masks else None)


CASES = {
    "period": (dict(dt=1e-3), dict(dt=1e-3), {}),
    "seconds": (dict(timestamps=True), dict(), {"t": np.arange(N) * 1e-3 + 17.0}),
    "ticks": (dict(tick_hz=1e6, tick_bits=16), dict(tick_hz=1e6, tick_bits=16),
              {"ticks": (np.arange(N) * 1000 + 60000) % 65536}),
}


def companions(n=N, seed=11):
    """Accelerations (m/s², a shake in the second half) and a warming temperature (°C)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 1e-3
    acc = np.tile([0.0, 0.0, 9.81], (n, 1)) + 0.02 * rng.standard_normal((n, 3))
    acc[n // 2 :, 0] += np.sin(31.0 * t[n // 2 :])
    return {"acc": acc, "temperature": 25.0 + 10.0 * t}


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("precision", ["f32", "f64"])
@pytest.mark.parametrize("size", [1, 7, 400])
@pytest.mark.parametrize("aux", [False, True])
def test_any_chunking_is_one_call_bit_for_bit(case, precision, size, aux):
    made, given, stamps = CASES[case]
    gyr = coning()
    gyr[[300, 301, 1500]] = np.nan  # refused and skipped: the clock and the estimator carry over
    # Windows of 0.1 s (100 samples, blocks of 12); the timestamped stream needs the period.
    estimator = quatprop.BiasEstimator(window=0.1, gate=0.05, period=1e-3)
    if aux:  # the accelerometer gate, the temperature model, a drift, a noise density and a start: their
        # state is kept between calls too
        stamps = {**stamps, **companions()}
        estimator = quatprop.BiasEstimator(window=0.1, gate=0.05, period=1e-3, accel_gate=0.5,
                                           temperature_span=0.1, drift=1e-3, noise_density=1e-3 * 1e-3**0.5,
                                           initial=[-0.019, -0.011, 0.006], initial_sigma=2e-3)
    options = dict(
        precision=precision,
        alignment="PyNxPz",
        bias=estimator,
        on_refused="mask",
    )
    whole, whole_mask = quatprop.integrate(gyr, **given, **stamps, **options)
    s = quatprop.Stream(**made, **options)
    q, mask = chunked(s, gyr, size, **stamps)
    assert q.dtype == np.dtype(precision.replace("f", "float"))
    np.testing.assert_array_equal(mask, whole_mask)
    assert np.flatnonzero(mask).tolist() == [300, 301, 1500]
    assert q.tobytes() == whole.tobytes(), f"chunks of {size} differ from one call"
    assert s.refused == 3
    # The estimator learned the still second's bias (body axes: PyNxPz maps sensor (x, y, z) to (y, -x, z)).
    np.testing.assert_allclose(s.bias, [-0.02, -0.01, 0.005], atol=3e-4)


def test_raise_leaves_the_stream_ready_for_the_rest_of_the_rows():
    gyr = coning()
    gyr[1777] = np.inf
    options = dict(dt=1e-3, bias=quatprop.BiasEstimator(window=0.1, gate=0.05), precision="f64")
    whole, _ = quatprop.integrate(gyr, on_refused="mask", **options)
    s = quatprop.Stream(**options)
    first = s.update(gyr[:1700])
    with pytest.raises(quatprop.RefusedSample) as info:
        s.update(gyr[1700:1900])
    assert (info.value.index, info.value.kind) == (77, "NonFiniteRate")
    rest = s.update(gyr[1778:])
    # Before and after the refused sample, as the masked call over the whole stream.
    assert first.tobytes() == whole[:1700].tobytes()
    assert rest.tobytes() == whole[1778:].tobytes()
    assert s.refused == 1


def test_counters_set_attitude_and_reset():
    gyr = coning(500)
    s = quatprop.Stream(dt=1e-3, input="linear", precision="f64")
    first = s.update(gyr)
    assert s.steps == 499  # Linear: the first sample only starts the model
    np.testing.assert_array_equal(s.attitude, first[-1])
    assert s.bias is None and s.refused == 0 and s.saturated == 0
    s.set_attitude([0.0, 2.0, 0.0, 0.0])
    np.testing.assert_array_equal(s.attitude, [0.0, 1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="ZeroQuaternion"):
        s.set_attitude([0.0, 0.0, 0.0, 0.0])
    s.reset()
    assert s.steps == 0
    np.testing.assert_array_equal(s.update(gyr), first)


def test_an_estimators_corrections():
    # Rotations: q ⊗ exp(d) in the body frame, exp(d) ⊗ q in the reference frame.
    s = quatprop.Stream(dt=1e-3, precision="f64")
    s.rotate_reference([0.1, 0.0, 0.0])
    s.rotate_body([0.0, 0.0, 0.2])
    c1, s1, c2, s2 = np.cos(0.05), np.sin(0.05), np.cos(0.1), np.sin(0.1)
    np.testing.assert_allclose(s.attitude, [c1 * c2, s1 * c2, -s1 * s2, c1 * s2], atol=1e-15)
    before = s.attitude
    with pytest.raises(ValueError, match="NonFiniteRate"):
        s.rotate_body([np.nan, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"\[x, y, z\]"):
        s.correct_bias([1.0, 2.0])
    np.testing.assert_array_equal(s.attitude, before)
    # A bias found after 10 samples: the fixed bias moves, the history's samples with it, and the next
    # step turns by exactly 1 mrad.
    b = quatprop.Stream(dt=1e-3, precision="f64")
    raw = np.tile([0.0, 0.0, 1.01], (10, 1))
    b.update(raw)
    b.correct_bias([0.0, 0.0, 0.01])
    np.testing.assert_array_equal(b.bias, [0.0, 0.0, 0.01])
    q0 = b.attitude
    q1 = b.update(raw[:1])[-1]
    turned = 2.0 * np.arctan2(q0[0] * q1[3] - q0[3] * q1[0], q0[0] * q1[0] + q0[3] * q1[3])
    assert abs(turned - 1e-3) < 1e-15


def test_a_fixed_bias_is_reported():
    s = quatprop.Stream(dt=1e-3, bias=[0.1, 0.0, -0.2], precision="f64")
    np.testing.assert_array_equal(s.bias, [0.1, 0.0, -0.2])


@pytest.mark.parametrize(
    "made, call, words",
    [
        (dict(dt=1e-3), dict(t=np.zeros(5)), "no timestamps"),
        (dict(timestamps=True), dict(), "timestamps=True"),
        (dict(tick_hz=1e6), dict(t=np.zeros(5)), "tick_hz"),
    ],
)
def test_timestamps_must_match_the_time_base(made, call, words):
    s = quatprop.Stream(**made)
    with pytest.raises(ValueError, match=words):
        s.update(np.zeros((5, 3)), **call)


@pytest.mark.parametrize("made", [dict(), dict(dt=1e-3, timestamps=True), dict(dt=1e-3, tick_hz=1e6)])
def test_exactly_one_time_base(made):
    with pytest.raises(ValueError, match="exactly one time base"):
        quatprop.Stream(**made)


def test_calibration_is_applied_first_and_refused_when_ill_conditioned():
    cal = quatprop.Calibration(
        offset=[0.01, -0.02, 0.005], sensitivity=[1.02, 0.98, 1.01],
        misalignment=[[1.0, 0.004, -0.002], [0.003, 1.0, 0.001], [-0.001, 0.002, 1.0]],
    )
    gyr = coning(500)
    calibrated = quatprop.calibrate(gyr, cal, precision="f64")
    direct = quatprop.integrate(calibrated, dt=1e-3, precision="f64", alignment="PyNxPz")
    via = quatprop.integrate(gyr, dt=1e-3, precision="f64", calibration=cal, alignment="PyNxPz")
    assert via.tobytes() == direct.tobytes()
    with pytest.raises(ValueError, match="InvalidCalibration"):
        quatprop.Stream(dt=1e-3, calibration=quatprop.Calibration(sensitivity=[1.0, 1.0, 0.005]))
    with pytest.raises(ValueError, match="InvalidCalibration"):
        quatprop.calibrate(gyr, quatprop.Calibration(offset=[np.nan, 0.0, 0.0]))


def test_calibration_agrees_with_imufusion_model_inertial_bit_for_bit():
    imufusion = pytest.importorskip("imufusion")
    rng = np.random.default_rng(11)
    for _ in range(200):
        offset = rng.normal(0.0, 0.05, 3).astype(np.float32)
        sensitivity = (1.0 + rng.normal(0.0, 0.03, 3)).astype(np.float32)
        m = (np.eye(3) + rng.normal(0.0, 0.01, (3, 3))).astype(np.float32)
        raw = rng.normal(0.0, 2.0, (1, 3)).astype(np.float32)
        cal = quatprop.Calibration(offset, sensitivity, m)
        ours = quatprop.calibrate(raw, cal)[0]
        theirs = np.asarray(
            imufusion.model_inertial(raw[0].astype(np.float64), m.astype(np.float64),
                                     sensitivity.astype(np.float64), offset.astype(np.float64)),
            dtype=np.float64,
        )
        # Fusion computes in float: its float64 result holds a float32 value.
        assert theirs.astype(np.float32).astype(np.float64).tobytes() == theirs.tobytes()
        assert ours.tobytes() == theirs.astype(np.float32).tobytes(), (ours, theirs)


def test_refused_delta_angles_report_the_angle_they_took():
    d = np.tile([1e-3, -2e-3, 0.5e-3], (100, 1))
    d[40] = [6.0, 0.0, 0.0]  # beyond Rk4's step-angle bound (4√2 rad): refused, its angle not integrated
    d[41] = [np.nan, 0.0, 0.0]  # refused, its angle unknown: not counted
    s = quatprop.Stream(dt=1e-3, input="delta_angles", scheme="rk4", precision="f64", on_refused="mask")
    q, refused = s.update(d)
    assert np.flatnonzero(refused).tolist() == [40, 41]
    np.testing.assert_array_equal(s.lost_angle, [6.0, 0.0, 0.0])
    # What was integrated is the other 98 increments: the rotation about the common axis, to rounding.
    angle = 2.0 * np.arccos(min(1.0, abs(q[-1][0])))
    np.testing.assert_allclose(angle, 98 * np.linalg.norm(d[0]), rtol=1e-9)
    with pytest.raises(quatprop.RefusedSample):
        quatprop.Stream(dt=1e-3, input="delta_angles", scheme="rk4").update(d)
    rates = quatprop.Stream(dt=1e-3, precision="f64", on_refused="mask")
    rates.update(np.where(np.isfinite(d), d, np.nan) * 1e3)
    np.testing.assert_array_equal(rates.lost_angle, [0.0, 0.0, 0.0])  # rates: no angle is lost, time carries


# The sensor's white noise: 0.1 °/s per sample at 1 kHz is 0.1 °/s / √(1 kHz) (rad/√s).
NOISE_01DPS_1KHZ = 0.1 * np.pi / 180 * 1e-3**0.5
@pytest.mark.parametrize(
    "noise_density",
    [NOISE_01DPS_1KHZ, None],
    ids=["noise_given", "scatter_learned"],
)
def test_a_bias_step_at_rest_is_followed_and_readable(noise_density):
    """(+0.3, 0, -0.2) °/s at rest 20.37 s in, f32 at 1 kHz with 0.1 °/s noise, windows of 1 s: the window
    from 20 to 21 s holds two flat levels, the next confirms the new one, so the estimate is within
    0.05 °/s from 22 s on: 1.63 s after the step (the Rust test's figure, through the binding). The step
    back at 30 s, on a window's boundary, is confirmed by the two windows after it: followed at 32 s. With
    the sensor's noise density given, and with the scatter at rest learned (this draw's first window shows
    a sixth of the scatter on z: the F(7, 7k) bound keeps the windows after it flat)."""
    rng = np.random.default_rng(3)
    deg = np.pi / 180
    n = 40_000
    t = (np.arange(n) + 1) * 1e-3
    stepped = (t >= 20.37) & (t <= 30.0)
    bias = np.where(stepped[:, None], [0.9, -0.4, 0.05], [0.6, -0.4, 0.25]) * deg
    gyr = (bias + 0.1 * deg * rng.standard_normal((n, 3))).astype(np.float32)
    s = quatprop.Stream(dt=1e-3, bias=quatprop.BiasEstimator(window=1.0, gate=3 * deg, noise_density=noise_density))
    est = np.empty((n, 3))
    for k in range(n):  # one sample per call: the estimate after each
        s.update(gyr[k : k + 1])
        est[k] = s.bias
    off = np.linalg.norm(est - bias, axis=1) > 0.05 * deg
    assert np.flatnonzero(off[:20_000])[-1] + 1 == 999  # the first window sets it at 1 s
    after_step = np.flatnonzero(off[:30_000])[-1] + 1  # the first sample from which it holds
    assert t[after_step] == pytest.approx(22.0) and t[after_step] - 20.37 == pytest.approx(1.63)
    assert np.flatnonzero(off)[-1] + 1 == 31_999  # back at 32 s, 2 s after the step back
    assert not off[after_step:30_000].any() and not off[32_000:].any()
    np.testing.assert_allclose(s.bias, [0.6 * deg, -0.4 * deg, 0.25 * deg], atol=0.01 * deg)


def test_companions_are_checked_before_anything_is_taken():
    s = quatprop.Stream(dt=1e-3, bias=quatprop.BiasEstimator(window=0.01, gate=0.05, accel_gate=0.5))
    gyr = np.zeros((20, 3))
    acc = np.tile([0.0, 0.0, 9.81], (20, 1))
    s.update(gyr[:5], acc=acc[:5])
    steps, q = s.steps, s.attitude
    acc[7, 1] = np.nan
    with pytest.raises(ValueError, match="NonFiniteAux"):
        s.update(gyr[5:] + 0.01, acc=acc[5:])
    assert s.steps == steps and s.steps > 0  # nothing of the refused call was taken
    np.testing.assert_array_equal(s.attitude, q)
    with pytest.raises(ValueError, match="shape"):
        s.update(gyr[5:], acc=acc[5:10])
    plain = quatprop.Stream(dt=1e-3)
    with pytest.raises(ValueError, match="bias estimator"):
        plain.update(gyr, temperature=np.full(20, 25.0))
    with pytest.raises(ValueError, match="InvalidEstimator"):  # 2^31 samples: too long a window
        quatprop.Stream(dt=1e-3, bias=quatprop.BiasEstimator(window=2.0**31 * 1e-3, gate=0.05))
    quatprop.Stream(dt=1e-3, bias=quatprop.BiasEstimator(window=(2.0**31 - 1) * 1e-3, gate=0.05))  # the longest


def test_interval_means_are_integrated_exactly_as_increments():
    """Samples that are the means of ω(t) = 0.1 + 2 t rad/s (one axis) over each 10 ms interval: as
    increments (sample="interval_mean") the angle is exact; read as rates at their timestamps (History)
    each is the rate 5 ms earlier, and the angle misses about 2 · 0.005 rad/s over the 1 s."""
    h, n = 0.01, 100
    t1 = (np.arange(n) + 1) * h
    t0 = t1 - h
    mean = ((0.1 * t1 + t1**2) - (0.1 * t0 + t0**2)) / h  # exact interval means
    gyr = np.zeros((n, 3))
    gyr[:, 2] = mean
    exact = 0.1 + 1.0  # ∫0^1 (0.1 + 2 t) dt
    q = quatprop.integrate(gyr, dt=h, precision="f64", input="delta_angles", sample="interval_mean")
    angle = 2 * np.arctan2(q[-1, 3], q[-1, 0])
    assert abs(angle - exact) < 1e-12
    q = quatprop.integrate(gyr, dt=h, precision="f64")
    angle = 2 * np.arctan2(q[-1, 3], q[-1, 0])
    assert 0.008 < exact - angle < 0.012  # History on means read as instants: about 0.01 rad short
    with pytest.raises(ValueError, match="delta_angles"):
        quatprop.Stream(dt=h, sample="interval_mean")


def test_a_group_delay_carries_each_attitude_forward_by_the_delay():
    """1 rad/s about z with a 7 ms delay: each attitude is the undelayed one turned 7 mrad further."""
    gyr = np.tile([0.0, 0.0, 1.0], (50, 1))
    q0 = quatprop.integrate(gyr, dt=1e-3, precision="f64")
    q = quatprop.integrate(gyr, dt=1e-3, precision="f64", group_delay=7e-3)
    a0 = 2 * np.arctan2(q0[:, 3], q0[:, 0])
    a = 2 * np.arctan2(q[:, 3], q[:, 0])
    np.testing.assert_allclose(a - a0, 7e-3, rtol=0, atol=1e-14)
    with pytest.raises(ValueError, match="group_delay"):
        quatprop.Stream(dt=1e-3, group_delay=-1e-3)
    with pytest.raises(ValueError, match="needs rates"):
        quatprop.Stream(dt=1e-3, input="delta_angles", group_delay=1e-3)


@pytest.mark.parametrize("size", [1, 7, 400])
def test_timing_is_kept_between_calls(size):
    gyr = coning()
    gyr[[300, 1500]] = np.nan
    t = np.arange(N) * 1e-3 + 3.0
    options = dict(precision="f32", input="delta_angles", coning="three_sample", sample="interval_mean",
                   group_delay=2.5e-3, bias=quatprop.BiasEstimator(window=0.1, gate=0.05, period=1e-3),
                   on_refused="mask")
    whole, _ = quatprop.integrate(gyr, t=t, **options)
    q, _ = chunked(quatprop.Stream(timestamps=True, **options), gyr, size, t=t)
    assert q.tobytes() == whole.tobytes()


def test_counts_through_the_count_scale_are_the_scaled_rates_and_rails_are_counted():
    """int16 counts with count_scale give the bits of the same counts times the scale (rounded once to
    the precision, as the core does), and a count at a rail is counted as saturated."""
    rng = np.random.default_rng(5)
    counts = rng.integers(-3000, 3000, size=(500, 3)).astype(np.int16)
    counts[[10, 20]] = [32767, 0, 0]
    counts[30] = [0, -32768, 5]
    scale = quatprop.CountScale(full_scale_dps=2000.0)
    s = quatprop.Stream(dt=1e-3, count_scale=scale, precision="f32")
    q = s.update(counts)
    k = np.float32(np.radians(2000.0) / 32768.0)
    rates = counts.astype(np.float32) * k
    q_rates = quatprop.integrate(rates, dt=1e-3, precision="f32")
    assert q.tobytes() == q_rates.tobytes()
    assert s.saturated == 3
    with pytest.raises(TypeError, match="integer"):
        s.update(rates)
    with pytest.raises(ValueError, match="exactly one"):
        quatprop.Stream(dt=1e-3, count_scale=quatprop.CountScale())
    with pytest.raises(ValueError, match="InvalidScale"):
        quatprop.Stream(dt=1e-3, count_scale=quatprop.CountScale(sensitivity=-131.0))


@pytest.mark.parametrize("size", [1, 7, 400])
@pytest.mark.parametrize("motion", [True, quatprop.CalibrationEstimator(0.01, 0.0087)], ids=["bias", "gain"])
def test_the_motion_bias_state_is_kept_between_calls(size, motion):
    """What is learned in motion (BiasEstimator(motion=True): the residual bias; motion=
    CalibrationEstimator: the gain too; the accelerometer in the gyro's axes): chunks give the bits of one
    call, alignment and a refused sample included; 6 s, so that the gain's filter is past its 3 s start."""
    gyr = coning(6000)
    gyr[[300, 4500]] = np.nan
    acc = companions(6000)["acc"]
    options = dict(precision="f32", alignment="PyNxPz", on_refused="mask",
                   bias=quatprop.BiasEstimator(window=0.1, gate=0.05, motion=motion))
    whole, _ = quatprop.integrate(gyr, dt=1e-3, acc=acc, **options)
    q, _ = chunked(quatprop.Stream(dt=1e-3, **options), gyr, size, acc=acc)
    assert q.tobytes() == whole.tobytes()
    plain, _ = quatprop.integrate(gyr, dt=1e-3, **options)  # without acc: the rest estimate alone
    assert plain.tobytes() != whole.tobytes()
    with pytest.raises(ValueError, match="fixed period"):
        quatprop.Stream(timestamps=True, bias=quatprop.BiasEstimator(window=0.01, gate=0.05, motion=True,
                                                                     period=1e-3))
