//! Host half of the firmware smoke test: runs the firmware's own scene code (`firmware/src/scenes.rs`,
//! compiled here for x86-64) and asserts that every final quaternion is bit-identical to what the firmware
//! printed on the Cortex-M boards (`firmware/expected/*.txt`; CI re-runs the firmware on each board and diffs
//! its output against the same files). IEEE binary32 on both sides, no FMA contraction, the same libm code:
//! any difference is a bug to explain.

#[path = "../firmware/src/scenes.rs"]
#[allow(dead_code)]
mod scenes;

use quatprop::scheme::{Method, Scheme};
use quatprop::stabilize::Policy;
use scenes::{bits, policy_name, run, Scene, POLICIES, STEPS};

fn line(scene: &str, m: &str, p: &str, o: &scenes::Outcome) -> String {
    format!(
        "{scene} {m} {p} {:08x} {:08x} {:08x} {:08x} steps={} corrections={} refused={}",
        bits(o.q.w),
        bits(o.q.x),
        bits(o.q.y),
        bits(o.q.z),
        o.steps,
        o.corrections,
        o.refused
    )
}

#[test]
fn host_matches_the_firmware_smoke_output_bit_for_bit() {
    let expected = include_str!("../firmware/expected/smoke.txt");
    let mut lines = expected.lines();
    let mut compared = 0;
    for scene in Scene::ALL {
        for m in Method::ALL {
            for p in POLICIES {
                let o = run(scene, m, p, STEPS);
                let got = line(scene.name(), m.name(), policy_name(p), &o);
                let want = lines.next().expect("expected file has a line per run");
                assert_eq!(got, want, "host differs from firmware");
                assert_eq!(o.refused, 0);
                compared += 1;
            }
        }
    }
    assert_eq!(lines.next(), Some("smoke done"));
    assert_eq!(
        compared,
        Scene::ALL.len() * Method::ALL.len() * POLICIES.len()
    );
}

#[test]
fn isr_path_result_equals_the_direct_propagation() {
    let expected = include_str!("../firmware/expected/isr.txt");
    let first = expected.lines().next().unwrap();
    let o = run(Scene::ConingLinear, Method::Rk4, Policy::FirstOrder, 2_000);
    let got = format!(
        "isr coning-linear Rk4 FirstOrder {:08x} {:08x} {:08x} {:08x} steps={}",
        bits(o.q.w),
        bits(o.q.x),
        bits(o.q.y),
        bits(o.q.z),
        o.steps
    );
    assert_eq!(got, first);
    assert!(expected.contains("overflows=0 out_of_order=0 refused=0"));
}
