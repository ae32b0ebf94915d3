"""Bit identity with the Rust library: attitudes written by `reference/` (the core crate, concrete types,
`push_burst` / `push_burst_timed` / `push`) against `quatprop.integrate` on the same inputs."""

import json
from pathlib import Path

import numpy as np
import pytest

import quatprop

DATA = Path(__file__).parent / "data" / "reference"
MANIFEST = json.loads((DATA / "cases.json").read_text())
N = MANIFEST["n"]


def _inputs():
    raw = np.fromfile(DATA / "inputs.f64", dtype="<f8")
    gyr, t, gyr_bad, t_bad = np.split(raw, np.cumsum([3 * N, N, 3 * N]))
    ticks = np.fromfile(DATA / "ticks.u32", dtype="<u4")
    rest = np.fromfile(DATA / "rest.f64", dtype="<f8").reshape(N, 3)
    return {
        "gyr": (gyr.reshape(N, 3), t),
        "deltas": (gyr.reshape(N, 3) * MANIFEST["period"], t),
        "bad": (gyr_bad.reshape(N, 3), t_bad),
        "rest": (rest, None),
    }, ticks


INPUTS, TICKS = _inputs()


def _options(case):
    opts = dict(case["options"])
    _, t = INPUTS[case["inputs"]]
    if opts.pop("t", False):
        opts["t"] = t
    if opts.pop("ticks", False):
        opts["ticks"] = TICKS
    if isinstance(opts.get("bias"), dict):
        opts["bias"] = quatprop.BiasEstimator(**opts["bias"])
    return opts


def _call(case):
    return quatprop.integrate(INPUTS[case["inputs"]][0], **_options(case))


@pytest.mark.parametrize("case", MANIFEST["cases"], ids=[c["name"] for c in MANIFEST["cases"]])
def test_bit_identical_to_rust(case):
    dtype = np.float32 if case["options"]["precision"] == "f32" else np.float64
    want = np.fromfile(DATA / f"{case['name']}.q", dtype=np.dtype(dtype).newbyteorder("<")).reshape(N, 4)
    want_mask = np.fromfile(DATA / f"{case['name']}.mask", dtype=np.uint8).astype(bool)
    result = _call(case)
    if case["options"].get("on_refused") == "mask":
        q, mask = result
        np.testing.assert_array_equal(mask, want_mask)
        assert mask.any(), "a bad-input case must refuse something"
    else:
        q = result
        assert not want_mask.any()
    assert q.dtype == dtype and q.shape == (N, 4)
    # Bit for bit: compare the raw bits, so -0.0 vs 0.0 or a NaN would count as a difference.
    bits = np.uint32 if dtype == np.float32 else np.uint64
    np.testing.assert_array_equal(q.view(bits), want.view(bits))


@pytest.mark.parametrize("case", [c for c in MANIFEST["cases"] if "bias" in c], ids=lambda c: c["name"])
def test_the_estimators_final_bias_is_the_rust_one(case):
    """The bias estimator's estimate after the stream (``Stream.bias``), bit for bit the core's."""
    opts = _options(case)
    stream = quatprop.Stream(opts.pop("dt"), **opts)
    stream.update(INPUTS[case["inputs"]][0])
    assert stream.bias.tolist() == case["bias"]


def test_the_reference_covers_every_path():
    """The manifest exercises both precisions, the three time bases, refusals and the front end."""
    opts = [c["options"] for c in MANIFEST["cases"]]
    assert {o["precision"] for o in opts} == {"f32", "f64"}
    assert any("dt" in o for o in opts) and any("t" in o for o in opts) and any("ticks" in o for o in opts)
    assert any(o.get("on_refused") == "mask" for o in opts)
    assert any("alignment" in o for o in opts) and any("bias" in o for o in opts)
    # The estimator's window in seconds and every parameter a stream without accelerations takes.
    estimators = [o["bias"] for o in opts if isinstance(o.get("bias"), dict)]
    assert all(0 < e["window"] < 1 for e in estimators)
    assert {"drift", "noise_density", "initial", "initial_sigma"} <= {k for e in estimators for k in e}
    refused = {tuple(c["refused"]) for c in MANIFEST["cases"] if c["refused"]}
    assert refused, "some case must refuse samples"


def test_raise_mode_names_the_first_refused_sample_of_the_reference():
    case = next(c for c in MANIFEST["cases"] if c["name"] == "rk4_linear_bad_t_f32")
    raising = dict(case, options={k: v for k, v in case["options"].items() if k != "on_refused"})
    with pytest.raises(quatprop.RefusedSample) as info:
        _call(raising)
    assert info.value.index == case["refused"][0] == 300
    assert info.value.kind == "NonFiniteRate"
