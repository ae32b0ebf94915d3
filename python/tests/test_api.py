"""Refused samples, mask mode, argument errors, the GIL, the front end and the time bases."""

import threading
import time

import numpy as np
import pytest

import quatprop


def spin(n=1000, rate=(0.3, -0.2, 1.0)):
    return np.tile(np.asarray(rate, dtype=np.float64), (n, 1))


def test_refused_sample_raises_with_index_and_reason():
    gyr = spin()
    gyr[417, 2] = np.inf
    with pytest.raises(quatprop.RefusedSample) as info:
        quatprop.integrate(gyr, dt=1e-3)
    e = info.value
    assert isinstance(e, ValueError)
    assert (e.index, e.kind) == (417, "NonFiniteRate")
    assert "NaN or infinite" in e.reason and "sample 417" in str(e)


def test_step_angle_refusal_names_its_bound():
    gyr = spin()
    gyr[10] = [1e4, 0, 0]  # 10 rad in one 1 ms step: beyond RK4's 4√2
    with pytest.raises(quatprop.RefusedSample) as info:
        quatprop.integrate(gyr, dt=1e-3, scheme="rk4")
    assert (info.value.index, info.value.kind) == (10, "StepAngleBeyondStability")
    assert "5.65" in info.value.reason
    quatprop.integrate(gyr, dt=1e-3, scheme="expmap")  # no bound: accepted


def test_mask_keeps_the_state_and_carries_the_interval():
    gyr = spin()
    bad = gyr.copy()
    bad[[100, 101, 600]] = np.nan
    q, refused = quatprop.integrate(bad, dt=1e-3, input="hold", precision="f64", on_refused="mask")
    assert refused.dtype == bool and np.flatnonzero(refused).tolist() == [100, 101, 600]
    np.testing.assert_array_equal(q[101], q[99])  # unchanged while refused
    np.testing.assert_array_equal(q[600], q[599])
    # A held constant rate: the refused intervals go into the next sample, so no time is lost.
    full = quatprop.integrate(gyr, dt=1e-3, input="hold", precision="f64")
    np.testing.assert_allclose(q[-1], full[-1], atol=1e-13)
    assert not np.allclose(q[-1], full[-4], atol=1e-6)


@pytest.mark.parametrize(
    "kwargs, error, words",
    [
        (dict(gyr=np.zeros((5, 4)), dt=1e-3), ValueError, "shape (N, 3)"),
        (dict(gyr=np.zeros(5), dt=1e-3), ValueError, "shape (N, 3)"),
        (dict(gyr=np.array([["a", "b", "c"]]), dt=1e-3), TypeError, "numeric"),
        (dict(gyr=spin(5), dt=1e-3, scheme="rk9"), ValueError, "unknown scheme 'rk9'"),
        (dict(gyr=spin(5), dt=1e-3, input="cubic"), ValueError, "unknown input"),
        (dict(gyr=spin(5), dt=1e-3, precision="f16"), ValueError, "unknown precision"),
        (dict(gyr=spin(5), dt=1e-3, accumulator="neumaier"), ValueError, "unknown accumulator"),
        (dict(gyr=spin(5), dt=1e-3, on_refused="ignore"), ValueError, "unknown on_refused"),
        (dict(gyr=spin(5), dt=1e-3, stabilizer="every:0"), ValueError, "N must be"),
        (dict(gyr=spin(5), dt=1e-3, stabilizer="every:x"), ValueError, "integer N"),
        (dict(gyr=spin(5), dt=1e-3, scheme=4), TypeError, "must be a string"),
        (dict(gyr=spin(5)), ValueError, "exactly one of dt, t, ticks"),
        (dict(gyr=spin(5), dt=1e-3, t=np.arange(5.0)), ValueError, "exactly one of"),
        (dict(gyr=spin(5), dt=np.full(5, 1e-3)), TypeError, "per-sample times go in t"),
        (dict(gyr=spin(5), dt=0.0), ValueError, "NonPositiveStep"),
        (dict(gyr=spin(5), dt=float("nan")), ValueError, "NonFiniteStep"),
        (dict(gyr=spin(5), t=np.arange(4.0)), ValueError, "4 timestamps for 5 samples"),
        (dict(gyr=spin(5), dt=1e-3, q0=[0, 0, 0, 0]), ValueError, "ZeroQuaternion"),
        (dict(gyr=spin(5), dt=1e-3, q0=[1, 0, 0]), ValueError, "q0 must be"),
        (dict(gyr=spin(5), ticks=np.arange(5)), ValueError, "tick_hz"),
        (dict(gyr=spin(5), ticks=np.arange(5.0), tick_hz=1e3), TypeError, "integer array"),
        (dict(gyr=spin(5), ticks=np.arange(5), tick_hz=1e3, tick_bits=33), ValueError, "InvalidClock"),
        (dict(gyr=spin(5), dt=1e-3, input="delta_angles", bias=[0, 0, 0]), ValueError, "delta angles"),
        (dict(gyr=spin(5), dt=1e-3, alignment="XYZ"), ValueError, "unknown axis remap"),
        # The estimator's window is in seconds: none, under one sample (0.4 ms at 1 kHz), 2^31 samples.
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(0.0, 0.1)), ValueError, "InvalidEstimator"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(4e-4, 0.1)), ValueError, "InvalidEstimator"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(2.2e6, 0.1)), ValueError, "InvalidEstimator"),
        # An integer sample count of the 0.3 API is refused, not taken for 1000 seconds.
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1000, 0.1)), ValueError, "1000 * dt"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, -0.1)), ValueError, "InvalidEstimator"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, drift=-1e-5)), ValueError,
         "InvalidEstimator"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, drift=float("inf"))), ValueError,
         "InvalidEstimator"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, initial=[0, 0, 0])), ValueError,
         "needs initial_sigma"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, initial_sigma=0.01)), ValueError,
         "needs initial"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, initial=[0, 0, 0], initial_sigma=0.0)),
         ValueError, "InvalidEstimator"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, initial=[0, 0], initial_sigma=0.1)),
         ValueError, "[bx, by, bz]"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, noise_density=0.0)), ValueError,
         "InvalidEstimator"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, noise_density=-1e-3)), ValueError,
         "InvalidNoise"),
        (dict(gyr=spin(5), dt=1e-3, bias=quatprop.BiasEstimator(1.0, 0.1, period=0.0)), ValueError,
         "InvalidEstimator"),
        # With timestamps or ticks the estimator needs its own period (a tick is not a sample).
        (dict(gyr=spin(5), t=np.arange(5) * 1e-3, bias=quatprop.BiasEstimator(1.0, 0.1)), ValueError,
         "sample period"),
        (dict(gyr=spin(5), ticks=np.arange(5) * 1000, tick_hz=1e6, bias=quatprop.BiasEstimator(1.0, 0.1)),
         ValueError, "needs period="),
    ],
)
def test_bad_arguments_raise_clear_errors(kwargs, error, words):
    with pytest.raises(error) as info:
        quatprop.integrate(**kwargs)
    assert words in str(info.value)
    assert not isinstance(info.value, quatprop.RefusedSample)


def test_dtypes_and_layouts_are_accepted():
    base = spin(50)
    want = quatprop.integrate(base, dt=1e-3, precision="f32")
    assert want.dtype == np.float32 and want.shape == (50, 4)
    # float32 input, Fortran order, a strided view, a list: the same result (each rounded once to f32).
    for gyr in (base.astype(np.float32), np.asfortranarray(base), np.repeat(base, 2, axis=0)[::2], base.tolist()):
        np.testing.assert_array_equal(quatprop.integrate(gyr, dt=1e-3, precision="f32"), want)
    assert quatprop.integrate(np.zeros((0, 3)), dt=1e-3).shape == (0, 4)


def test_the_default_precision_follows_the_input():
    base = spin(50)
    f64 = quatprop.integrate(base, dt=1e-3)
    assert f64.tobytes() == quatprop.integrate(base, dt=1e-3, precision="f64").tobytes()
    assert quatprop.integrate(base.tolist(), dt=1e-3).dtype == np.float64
    f32 = quatprop.integrate(base.astype(np.float32), dt=1e-3)
    assert f32.dtype == np.float32
    # An explicit precision wins over the input's dtype.
    assert quatprop.integrate(base.astype(np.float32), dt=1e-3, precision="f64").dtype == np.float64
    # A stream decides at its first update; setting its attitude first decides f64.
    s = quatprop.Stream(dt=1e-3)
    assert s.update(base.astype(np.float32)).dtype == np.float32
    assert s.update(base).dtype == np.float32  # decided: later samples are converted
    s = quatprop.Stream(dt=1e-3)
    s.set_attitude([1.0, 0.0, 0.0, 0.0])
    assert s.update(base.astype(np.float32)).dtype == np.float64
    assert quatprop.calibrate(base.astype(np.float32), quatprop.Calibration()).dtype == np.float32
    assert quatprop.calibrate(base, quatprop.Calibration()).dtype == np.float64


def test_the_gil_is_released_while_integrating():
    gyr = np.random.default_rng(3).standard_normal((3_000_000, 3)).astype(np.float32)
    done = threading.Event()
    took = []

    def work():
        t0 = time.perf_counter()
        quatprop.integrate(gyr, dt=1e-3)
        took.append(time.perf_counter() - t0)
        done.set()

    worker = threading.Thread(target=work)
    ticks = []
    worker.start()
    while not done.is_set():
        ticks.append(time.perf_counter())  # runs only while this thread holds the GIL
    worker.join()
    gaps = np.diff(ticks)
    # Held GIL: the main thread stalls for the whole call. Released: it keeps ticking.
    assert took[0] > 0.05 and len(ticks) > 1000
    assert gaps.max() < 0.8 * took[0], (gaps.max(), took[0])


def test_fixed_bias_and_remap_equal_the_corrected_samples():
    gyr = np.random.default_rng(5).standard_normal((400, 3))
    b = np.array([0.01, -0.03, 0.02])
    np.testing.assert_array_equal(
        quatprop.integrate(gyr, dt=1e-3, bias=b, precision="f64"),
        quatprop.integrate(gyr - b, dt=1e-3, precision="f64"),
    )
    # PyNxPz: body x = sensor y, body y = -sensor x, body z = sensor z.
    np.testing.assert_array_equal(
        quatprop.integrate(gyr, dt=1e-3, alignment="PyNxPz", precision="f64"),
        quatprop.integrate(gyr[:, [1, 0, 2]] * [1, -1, 1], dt=1e-3, precision="f64"),
    )


def test_alignment_matrix_must_be_a_rotation():
    gyr = spin(10)
    c, s = np.cos(0.3), np.sin(0.3)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    q = quatprop.integrate(gyr, dt=1e-3, alignment=rot, precision="f64")
    # ω_body = R ω_sensor, each row summed left to right as the core does (not BLAS's order).
    body = gyr[:, 0:1] * rot[:, 0] + gyr[:, 1:2] * rot[:, 1] + gyr[:, 2:3] * rot[:, 2]
    np.testing.assert_array_equal(q, quatprop.integrate(body, dt=1e-3, precision="f64"))
    for bad in (np.diag([1.0, 1.0, -1.0]), 1.01 * np.eye(3), np.full((3, 3), np.nan)):
        with pytest.raises(ValueError, match="not a rotation"):
            quatprop.integrate(gyr, dt=1e-3, alignment=bad)
    with pytest.raises(ValueError, match="3x3"):
        quatprop.integrate(gyr, dt=1e-3, alignment=np.eye(2))


def test_bias_estimator_learns_a_still_bias():
    b = np.array([0.0078125, -0.015625, 0.00390625])  # binary fractions: window sums are exact
    gyr = np.tile(b, (3000, 1))
    est = quatprop.BiasEstimator(window=1.0, gate=0.05)  # 1 s: 1000 samples at 1 kHz
    q = quatprop.integrate(gyr, dt=1e-3, bias=est, precision="f64")
    drift = q[999] - q[0]
    assert np.abs(drift).max() > 1e-3  # the first window integrates the bias
    np.testing.assert_array_equal(q[-1], q[1003])  # once learned (and out of the history), nothing moves
    s = quatprop.Stream(dt=1e-3, bias=est, precision="f64")
    s.update(gyr[:999])
    np.testing.assert_array_equal(s.bias, [0.0, 0.0, 0.0])  # nothing before the window closes
    s.update(gyr[999:1000])
    np.testing.assert_array_equal(s.bias, b)  # the first still window, exactly
    s.update(gyr[1000:])
    np.testing.assert_array_equal(s.bias, b)  # the next windows agree: a Kalman update by zero
    # A known bias (within its sigma): nothing is ever integrated.
    known = quatprop.BiasEstimator(1.0, 0.05, initial=b, initial_sigma=1e-3)
    q_known = quatprop.integrate(gyr, dt=1e-3, bias=known, precision="f64")
    np.testing.assert_array_equal(q_known[-1], [1.0, 0.0, 0.0, 0.0])


@pytest.mark.parametrize("dt", [1e-3, 2.5e-3, 1 / 285.0])
def test_the_estimators_window_is_in_seconds(dt):
    """The same BiasEstimator(window=1.0) at 1 kHz, 400 Hz and 285 Hz: learned after round(1 s / dt) still
    samples (1000, 400, 285), not one sample before; with timestamps, from its own period."""
    b = np.array([0.0078125, -0.015625, 0.00390625])
    n = round(1.0 / dt)
    est = quatprop.BiasEstimator(window=1.0, gate=0.05)
    s = quatprop.Stream(dt=dt, bias=est, precision="f64")
    s.update(np.tile(b, (n - 1, 1)))
    np.testing.assert_array_equal(s.bias, [0.0, 0.0, 0.0])
    s.update(np.tile(b, (1, 1)))
    np.testing.assert_array_equal(s.bias, b)
    timed = quatprop.Stream(timestamps=True, bias=quatprop.BiasEstimator(window=1.0, gate=0.05, period=dt),
                            precision="f64")
    timed.update(np.tile(b, (n - 1, 1)), t=np.arange(n - 1) * dt)
    np.testing.assert_array_equal(timed.bias, [0.0, 0.0, 0.0])
    timed.update(np.tile(b, (1, 1)), t=[(n - 1) * dt])
    np.testing.assert_array_equal(timed.bias, b)


def test_the_namespace_is_the_public_api():
    """``__all__`` names exactly what the package offers: every name exists, ``from quatprop import *``
    gives exactly those, and nothing else public is in the namespace (no ``np``, ``List``, ``dataclass``,
    ``Optional`` …), so a star import without ``__all__`` would give the same."""
    names = quatprop.__all__
    assert len(set(names)) == len(names)
    assert all(hasattr(quatprop, n) for n in names)
    star = {}
    exec("from quatprop import *", star)
    assert set(star) - {"__builtins__"} == set(names)
    public = {n for n in dir(quatprop) if not n.startswith("_")}
    assert public == set(names), public ^ set(names)
    for leaked in ("np", "List", "Optional", "Sequence", "Tuple", "Union", "dataclass", "annotations"):
        assert not hasattr(quatprop, leaked), leaked
    # The public classes and functions are quatprop's own (pickling finds them there).
    assert all(getattr(quatprop, n).__module__ == "quatprop" for n in names if callable(getattr(quatprop, n)))
    assert quatprop.__version__.count(".") == 2


def test_public_objects_pickle():
    import pickle

    est = quatprop.BiasEstimator(1.0, 0.05, drift=1e-4, initial=(0.0, 0.1, 0.0), initial_sigma=0.01)
    assert pickle.loads(pickle.dumps(est)) == est
    e = pickle.loads(pickle.dumps(quatprop.RefusedSample(3, "NonFiniteRate", "NaN")))
    assert (e.index, e.kind, e.reason) == (3, "NonFiniteRate", "NaN")


def test_timestamps_backwards_or_repeated_are_refused():
    t = np.arange(100) * 1e-3
    t[40] = t[39]
    with pytest.raises(quatprop.RefusedSample) as info:
        quatprop.integrate(spin(100), t=t)
    assert (info.value.index, info.value.kind) == (40, "TimestampNotIncreasing")
    t[40] = t[30]
    q, refused = quatprop.integrate(spin(100), t=t, on_refused="mask")
    assert np.flatnonzero(refused).tolist() == [40]
    t[60] = np.nan
    _, refused = quatprop.integrate(spin(100), t=t, on_refused="mask")
    assert np.flatnonzero(refused).tolist() == [40, 60]


def test_timestamps_first_sample_starts_and_dt_is_exact_in_f32():
    # 10^5 samples of a constant rate at irregular times 10^5 s after the epoch, where an f32 timestamp
    # would be 8 ms coarse: the differences are formed in f64, rounded once, their rounding carried, so
    # the angle is ω (t_last − t_0) to f32 attitude rounding.
    rng = np.random.default_rng(9)
    t = 1.0e5 + np.cumsum(1e-3 * (1 + 0.2 * rng.uniform(-1, 1, 100_000)))
    w = 0.02
    q = quatprop.integrate(np.tile([0, 0, w], (t.size, 1)), t=t, input="hold", precision="f32", accumulator="kahan")
    angle = 2 * np.arctan2(q[-1, 3].astype(np.float64), q[-1, 0])
    assert abs(angle - w * (t[-1] - t[0])) < 2e-6
    np.testing.assert_array_equal(q[0], [1, 0, 0, 0])  # the first sample only starts the stream


def test_ticks_wrap_like_the_sensor_counter():
    t_ticks = (np.arange(500, dtype=np.int64) * 1000 + 65_000) % 65_536  # 16-bit counter at 1 MHz
    q16 = quatprop.integrate(spin(500), ticks=t_ticks, tick_hz=1e6, tick_bits=16, precision="f64")
    qt = quatprop.integrate(spin(500), t=np.arange(500) * 1e-3, precision="f64")
    np.testing.assert_allclose(q16, qt, atol=1e-14)


def test_delta_angles_integrate_increments():
    w = np.array([0.0, 0.0, 1.0])
    q = quatprop.integrate(np.tile(w * 1e-3, (1000, 1)), dt=1e-3, input="delta_angles", coning="two_sample", precision="f64")
    np.testing.assert_allclose(q[-1], [np.cos(0.5), 0, 0, np.sin(0.5)], atol=1e-14)
    assert np.array_equal(q[0], [1, 0, 0, 0])  # two increments per update: the first is pending


def test_a_refused_first_timestamp_lets_the_next_sample_start_the_stream():
    gyr = np.random.default_rng(4).standard_normal((300, 3))
    t = 5.0 + np.arange(300) * 1e-3
    t[0] = np.nan
    q, refused = quatprop.integrate(gyr, t=t, precision="f64", on_refused="mask")
    assert np.flatnonzero(refused).tolist() == [0]
    np.testing.assert_array_equal(q[1:], quatprop.integrate(gyr[1:], t=t[1:], precision="f64"))


def test_mask_mode_on_ticks_carries_the_clock():
    gyr = spin(200)
    ticks = np.arange(200, dtype=np.uint32) * 1000
    ticks[50] = ticks[49]  # duplicate: refused, the clock unchanged
    q, refused = quatprop.integrate(gyr, ticks=ticks, tick_hz=1e6, input="hold", precision="f64", on_refused="mask")
    assert np.flatnonzero(refused).tolist() == [50]
    full = quatprop.integrate(gyr, ticks=np.arange(200) * 1000, tick_hz=1e6, input="hold", precision="f64")
    np.testing.assert_allclose(q[-1], full[-1], atol=1e-14)  # a held constant rate: no time lost
