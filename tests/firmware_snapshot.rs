//! Host half of the firmware checks: runs the firmware's own scene code (`firmware/src/scenes.rs`) and the
//! README's quick start (`firmware/src/quickstart.rs`), compiled here for the host, and asserts that every
//! result is bit-identical to `firmware/expected/*.txt`. `firmware/check-boards` runs the same code on each
//! QEMU board and diffs its output against the same files. IEEE binary32 on both sides, no FMA contraction,
//! the same libm code: any difference is a bug to explain.
//!
//! The expected files are written by this test, from the host:
//! `QUATPROP_BLESS=1 cargo test --test firmware_snapshot` (then run `firmware/check-boards`).

#[path = "../firmware/src/scenes.rs"]
#[allow(dead_code)]
mod scenes;

#[path = "../firmware/src/quickstart.rs"]
mod quickstart;

use scenes::{bits, run, Config, Outcome, Scene};
use std::path::PathBuf;

fn expected_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("firmware")
        .join("expected")
        .join(name)
}

/// Compares `got` with `firmware/expected/<name>`, or writes it there under `QUATPROP_BLESS=1`.
fn check_or_bless(name: &str, got: &str) {
    let path = expected_path(name);
    if std::env::var_os("QUATPROP_BLESS").is_some_and(|v| v != "0") {
        std::fs::write(&path, got).expect("write the expected file");
        return;
    }
    let want = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (QUATPROP_BLESS=1 writes it)", path.display()));
    for (i, (g, w)) in got.lines().zip(want.lines()).enumerate() {
        assert_eq!(
            g,
            w,
            "{name} line {}: host differs from the expected file",
            i + 1
        );
    }
    assert_eq!(
        got.lines().count(),
        want.lines().count(),
        "{name}: line count"
    );
    assert_eq!(got, want, "{name}");
}

fn quat_bits(o: &Outcome) -> String {
    format!(
        "{:08x} {:08x} {:08x} {:08x}",
        bits(o.q.w),
        bits(o.q.x),
        bits(o.q.y),
        bits(o.q.z)
    )
}

/// What `firmware/src/bin/smoke.rs` prints for `steps` steps per run.
fn smoke_output(steps: u32) -> String {
    let mut out = format!("smoke steps={steps}\n");
    let mut runs = 0;
    for scene in Scene::ALL {
        for c in Config::all() {
            let o = run(scene, c, steps);
            assert_eq!(o.refused, 0, "{} {c:?} refused samples", scene.name());
            assert_eq!(o.steps, u64::from(steps));
            out += &format!(
                "{} {} {} {} steps={} corrections={} refused={}\n",
                scene.name(),
                c.scheme_name(),
                c.stabilizer_name(),
                quat_bits(&o),
                o.steps,
                o.corrections,
                o.refused
            );
            runs += 1;
        }
    }
    assert_eq!(runs, Scene::ALL.len() * Config::COUNT);
    out + "smoke done\n"
}

#[test]
fn smoke_matches_the_firmware_bit_for_bit() {
    check_or_bless("smoke.txt", &smoke_output(scenes::STEPS));
}

#[test]
fn smoke_soft_float_matches_the_firmware_bit_for_bit() {
    check_or_bless("smoke-soft.txt", &smoke_output(scenes::STEPS_SOFT));
}

#[test]
fn isr_path_result_equals_the_direct_propagation() {
    let o = run(
        Scene::ConingHistory,
        Config::Post(
            quatprop::scheme::SchemeKind::ExpMap,
            quatprop::stabilize::StabilizerKind::FirstOrder,
        ),
        scenes::ISR_STEPS,
    );
    assert_eq!(o.refused, 0);
    // The firmware also prints max_backlog=N (emulator timing): check-boards drops it before comparing.
    let got = format!(
        "isr coning-history ExpMap FirstOrder {} steps={}\n\
         isr samples={} overflows=0 out_of_order=0 refused=0 identical_to_direct=true\n",
        quat_bits(&o),
        o.steps,
        scenes::ISR_STEPS + 1
    );
    check_or_bless("isr.txt", &got);
}

#[test]
fn quickstart_matches_the_firmware_bit_for_bit() {
    let mut attitude = quickstart::Attitude::new().expect("starts");
    for burst in scenes::quickstart_fifo() {
        attitude.on_fifo(&burst);
    }
    let (q, refused) = attitude.attitude();
    assert_eq!(refused, 0, "raw counts are always finite");
    assert!(q.norm_error().abs() < 1e-6);
    let got = format!(
        "quickstart samples={} {:08x} {:08x} {:08x} {:08x} refused={}\nquickstart done\n",
        scenes::QUICKSTART_BURSTS * scenes::QUICKSTART_BURST as u32,
        bits(q.w),
        bits(q.x),
        bits(q.y),
        bits(q.z),
        refused
    );
    check_or_bless("quickstart.txt", &got);
}
