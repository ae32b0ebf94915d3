//! The fuzz targets' inputs replayed on the stable toolchain in `cargo test`: every file of the committed
//! seed corpora (`fuzz/corpus/<target>/`) and every input a target ever crashed on (`fuzz/regressions/<target>/`),
//! each through the same decoding and invariants the fuzz target runs (this crate). The library bugs among the
//! crashes are pinned by tests of their own in the library's `tests/fuzz_regressions.rs`.

use quatprop_fuzz_checks as checks;
use std::path::Path;

/// The check of each fuzz target, by its name.
fn target(name: &str) -> fn(&[u8]) {
    match name {
        "push" => checks::push::run,
        "burst" => checks::burst::run,
        "frontend" => checks::frontend::run,
        "conversions" => checks::conversions::run,
        "delta" => checks::delta::run,
        "dispatch" => checks::dispatch::run,
        "precision" => checks::precision::run,
        "kahan" => checks::kahan::run,
        "estimator" => checks::estimator::run,
        "calibration" => checks::calibration::run,
        other => panic!("no fuzz target {other}"),
    }
}

const TARGETS: [&str; 10] = [
    "push",
    "burst",
    "frontend",
    "conversions",
    "delta",
    "dispatch",
    "precision",
    "kahan",
    "estimator",
    "calibration",
];

#[test]
fn every_seed_corpus_file_passes_its_target() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../corpus");
    let mut replayed = 0;
    for name in TARGETS {
        let run = target(name);
        let dir = root.join(name);
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.expect("a directory entry").path())
            .collect();
        files.sort();
        assert!(!files.is_empty(), "no seed in {}", dir.display());
        for f in files {
            let data = std::fs::read(&f).expect("a corpus file");
            run(&data);
            replayed += 1;
        }
    }
    println!("{replayed} seed inputs replayed");
}

/// Every input a target crashed on (`fuzz/regressions/<target>/`, copied from libFuzzer's artifacts) replays
/// through its target without a failure. Each was a crash once; docs/fuzzing.md says why, and the tests
/// below pin the library bugs among them directly.
#[test]
fn every_crash_input_passes_its_target_now() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../regressions");
    let mut replayed = 0;
    for name in TARGETS {
        let Ok(entries) = std::fs::read_dir(root.join(name)) else {
            continue;
        };
        let mut files: Vec<_> = entries
            .map(|e| e.expect("a directory entry").path())
            .collect();
        files.sort();
        for f in files {
            let data = std::fs::read(&f).expect("a regression file");
            println!("{}", f.display());
            target(name)(&data);
            replayed += 1;
        }
    }
    println!("{replayed} crash inputs replayed");
}
