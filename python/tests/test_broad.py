"""The BROAD reader and the gyro-only error metric (python/benchmarks/broad_metric.py) on the committed
excerpt tests/data/broad_excerpt.hdf5 (5 s of rest and 62 s of movement of BROAD trial 07; see
tests/data/README.md). Needs numpy, scipy, h5py and quatprop only.

Data: D. Laidig, M. Caruso, A. Cereatti, T. Seel. BROAD — A Benchmark for Robust Inertial Orientation
Estimation. Data 6(7):72, 2021. doi:10.3390/data6070072. github.com/dlaidig/broad (CC BY 4.0)
"""

import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

import quatprop

# h5py is pinned in requirements-ci.txt: a missing reader is a failure, not a skip.
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import broad_metric as bm  # noqa: E402  (after the path to python/benchmarks)

EXCERPT = Path(__file__).resolve().parent / "data" / "broad_excerpt.hdf5"
HORIZONS = (10.0, 30.0, 60.0)
FS = 2000.0 / 7.0  # BROAD's sampling rate, Hz


@pytest.fixture(scope="module")
def trial():
    return bm.read_trial(EXCERPT)


def rot(q):
    """[w, x, y, z] → SciPy Rotation (scalar last)."""
    return Rotation.from_quat(np.asarray(q)[..., [1, 2, 3, 0]])


def same_rotation(p, q, tol=1e-12):
    """p and q (…, 4) are the same rotation (q or −q) within tol."""
    return np.all(np.minimum(np.abs(p - q).max(axis=-1), np.abs(p + q).max(axis=-1)) < tol)


def test_reader_gives_the_layout_in_float64(trial):
    n = 19143  # samples 6144:25287 of trial 07
    assert trial.name == "broad_excerpt"
    assert trial.fs == pytest.approx(FS, rel=1e-15)
    assert trial.dt == pytest.approx(0.0035, rel=1e-12)
    assert trial.gyr.shape == (n, 3) and trial.acc.shape == (n, 3) and trial.quat.shape == (n, 4)
    assert trial.gyr.dtype == trial.acc.dtype == trial.quat.dtype == np.float64
    assert trial.movement.dtype == bool and trial.movement.shape == (n,)
    # 5 s of rest (round(5 fs) = 1429 samples), then movement to the end
    assert trial.first_movement == 1429
    assert not trial.movement[:1429].any() and trial.movement[1429:].all()
    np.testing.assert_allclose(np.linalg.norm(trial.quat, axis=1), 1.0, atol=1e-6)
    # at rest the accelerometer reads gravity and the gyro only its bias
    assert np.linalg.norm(trial.acc[:1429].mean(axis=0)) == pytest.approx(9.81, abs=0.05)
    np.testing.assert_array_equal(trial.rest_bias(), trial.gyr[:1429].mean(axis=0))
    assert np.abs(trial.rest_bias()).max() < np.radians(0.5)


def test_start_points_every_5_s_inside_the_movement(trial):
    starts = bm.start_points(trial.movement, trial.fs)
    # 1429 + round(j · 5 s · 2000/7 Hz): 0, 1428.57… → 1429, 2857.14… → 2857, … up to the last sample (19142)
    expected = 1429 + np.array(
        [0, 1429, 2857, 4286, 5714, 7143, 8571, 10000, 11429, 12857, 14286, 15714, 17143]
    )
    np.testing.assert_array_equal(starts, expected)


def test_start_points_skip_a_break():
    movement = np.zeros(100, dtype=bool)
    movement[10:40] = movement[60:90] = True  # a break at 40..59
    # fs = 1 Hz, every 10 s: grid 10, 20, …, 80 (≤ 89); 40 and 50 fall in the break
    np.testing.assert_array_equal(bm.start_points(movement, 1.0, every=10.0), [10, 20, 30, 60, 70, 80])


def test_quat_angle_of_known_rotations():
    for angle in (0.0, 1e-9, 0.3, 2.0, np.pi):
        q = np.array([np.cos(angle / 2), 0.0, np.sin(angle / 2), 0.0])
        assert bm.quat_angle(q) == pytest.approx(angle, rel=1e-14, abs=1e-300)
        assert bm.quat_angle(-q) == pytest.approx(angle, rel=1e-14, abs=1e-300)  # q and −q: one rotation


def test_quat_mul_is_scipys_composition():
    p, q = Rotation.random(50, random_state=1), Rotation.random(50, random_state=2)
    ours = bm.quat_mul(p.as_quat(scalar_first=True), q.as_quat(scalar_first=True))
    assert same_rotation(ours, (p * q).as_quat(scalar_first=True))


def test_the_truth_against_itself_has_no_error(trial):
    starts = bm.start_points(trial.movement, trial.fs)
    e = bm.errors(trial.quat, trial.quat, trial.fs, starts, HORIZONS, trial.movement)
    valid = np.isfinite(e)
    assert valid.sum() == 11 + 7 + 1  # ends within the 62 s of movement: starts 0…50 s, 0…30 s, 0 s
    assert e[valid].max() < 1e-9


def test_the_run_may_start_from_any_attitude(trial):
    """A fixed rotation C of the whole run in the reference frame (C ⊗ truth) changes nothing."""
    c = Rotation.from_rotvec([0.3, -1.1, 2.0]).as_quat(scalar_first=True)
    starts = bm.start_points(trial.movement, trial.fs)
    e = bm.errors(bm.quat_mul(c, trial.quat), trial.quat, trial.fs, starts, HORIZONS, trial.movement)
    assert np.nanmax(e) < 1e-9


def test_a_known_body_rotation_at_the_end_gives_exactly_its_angle(trial):
    """The estimate C ⊗ truth_k ⊗ R from sample k0 on (C ⊗ truth_k before it): every pair straddling k0
    ends rotated by R in the body frame, so its error is exactly angle(R)."""
    r = Rotation.from_rotvec(np.radians(7.5) * np.array([2.0, -1.0, 2.0]) / 3.0)  # 7.5°
    c = Rotation.from_rotvec([-0.4, 0.9, 0.1]).as_quat(scalar_first=True)
    k0 = trial.first_movement + 8000
    q_est = bm.quat_mul(c, trial.quat)
    q_est[k0:] = bm.quat_mul(q_est[k0:], r.as_quat(scalar_first=True))
    starts = bm.start_points(trial.movement, trial.fs)
    e = bm.errors(q_est, trial.quat, trial.fs, starts, HORIZONS, trial.movement)
    ends = starts[None, :] + np.round(np.array(HORIZONS)[:, None] * trial.fs).astype(int)
    straddle = np.isfinite(e) & (starts[None, :] < k0) & (ends >= k0)
    assert straddle.sum() == 9  # 10 s: starts 20 and 25 s; 30 s: 0…25 s; 60 s: 0 s
    np.testing.assert_allclose(e[straddle], 7.5, rtol=0, atol=1e-9)
    before = np.isfinite(e) & (ends < k0)
    assert before.any() and e[before].max() < 1e-9


def test_half_sample_shift_is_the_slerp_midpoint(trial):
    q = trial.quat
    k = np.arange(2000, 2400)
    half = bm.shift_truth(q, 1)  # the truth at t_k + dt/2
    for i in k[::37]:
        midpoint = Slerp([0.0, 1.0], rot(q[i : i + 2]))([0.5]).as_quat(scalar_first=True)[0]
        assert same_rotation(half[i], midpoint)
    back = bm.shift_truth(q, -1)  # t_k − dt/2: the midpoint of rows k−1 and k
    np.testing.assert_array_equal(back[k], half[k - 1])
    np.testing.assert_array_equal(bm.shift_truth(q, 2)[k], q[k + 1])  # a whole sample: the next row
    np.testing.assert_array_equal(bm.shift_truth(q, -6)[k], q[k - 3])
    np.testing.assert_array_equal(bm.shift_truth(q, 0), q)
    assert np.isnan(half[-1]).all() and np.isnan(back[0]).all()  # outside the record
    assert np.isnan(bm.shift_truth(q, 4)[-2:]).all() and np.isfinite(bm.shift_truth(q, 4)[-3]).all()


def test_half_sample_shift_takes_the_shorter_arc():
    a = Rotation.from_rotvec([0.0, 0.0, 0.2]).as_quat(scalar_first=True)
    b = -Rotation.from_rotvec([0.0, 0.0, 0.4]).as_quat(scalar_first=True)  # the same rotation as +b
    mid = bm.shift_truth(np.array([a, b]), 1)[0]
    assert same_rotation(mid, Rotation.from_rotvec([0.0, 0.0, 0.3]).as_quat(scalar_first=True))


def test_nan_truth_and_ends_outside_are_skipped(trial):
    truth = trial.quat.copy()
    starts = bm.start_points(trial.movement, trial.fs)
    q = quatprop.integrate(trial.gyr, dt=trial.dt)
    clean = bm.errors(q, truth, trial.fs, starts, HORIZONS, trial.movement)
    lost = [starts[2], starts[1] + round(30 * trial.fs)]  # a start point; the 30 s end of start 1
    truth[lost] = np.nan  # lost by the optical tracking
    e = bm.errors(q, truth, trial.fs, starts, HORIZONS, trial.movement)
    ends = starts[None, :] + np.round(np.array(HORIZONS)[:, None] * trial.fs).astype(int)
    touched = np.isin(starts, lost)[None, :] | np.isin(ends, lost)
    np.testing.assert_array_equal(np.isnan(e), np.isnan(clean) | touched)
    assert np.isnan(e[:, 2]).all() and np.isnan(e[1, 1]) and np.isfinite(e[0, 1])
    assert np.isnan(e[0, 0])  # start 0's 10 s end is start 2 (1429 + 2857 = 4286)
    both = np.isfinite(e)
    np.testing.assert_array_equal(e[both], clean[both])
    # an end past the record or outside the movement is skipped; without `movement` only the record bounds
    inside = bm.errors(q, trial.quat, trial.fs, starts, (60.0,), trial.movement)
    assert np.isfinite(inside).sum() == 1
    still = trial.movement.copy()
    still[starts[0] + round(60 * trial.fs)] = False
    assert np.isnan(bm.errors(q, trial.quat, trial.fs, starts[:1], (60.0,), still)).all()
    assert np.isfinite(bm.errors(q, trial.quat, trial.fs, starts[:1], (60.0,))).all()


def test_quatprop_default_error_equals_scipys(trial):
    """quatprop's default integrate (expmap, history, f64) on the excerpt; the metric against the same
    error formed independently with SciPy Rotation: truth_e⁻¹ · truth_s · q_s⁻¹ · q_e."""
    q = quatprop.integrate(trial.gyr, dt=1.0 / trial.fs)
    starts = bm.start_points(trial.movement, trial.fs)
    e = bm.errors(q, trial.quat, trial.fs, starts, HORIZONS, trial.movement)
    estimate, truth = rot(q), rot(trial.quat)
    for i, horizon in enumerate(HORIZONS):
        for j, s in enumerate(starts):
            end = s + int(round(horizon * FS))
            if end >= len(q):
                assert np.isnan(e[i, j])
                continue
            expected = (truth[end].inv() * truth[s] * estimate[s].inv() * estimate[end]).magnitude()
            assert e[i, j] == pytest.approx(np.degrees(expected), rel=0, abs=1e-9)
    # the excerpt's figures (a regression guard for the reader and the metric): gyro only, bias not removed
    np.testing.assert_allclose(np.nanmean(e, axis=1), [4.418, 7.679, 15.656], atol=2e-3)
