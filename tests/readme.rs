//! The README is a front door: at most 10 KiB, and its Rust code pastes. Each of its `rust` blocks is a
//! whole program (no rustdoc-hidden lines); this test writes each into a new crate that depends on this
//! one, builds it and runs it, as a user who pastes it would. `firmware/check-host` checks that the
//! firmware's `quickstart` program is the FIFO block's code verbatim.

use std::path::Path;
use std::process::Command;

const README: &str = include_str!("../README.md");

/// The README's ```rust blocks, in order.
fn rust_blocks() -> Vec<&'static str> {
    let mut blocks = Vec::new();
    let mut rest = README;
    while let Some(start) = rest.find("```rust\n") {
        let body = &rest[start + "```rust\n".len()..];
        let end = body.find("```\n").expect("a closed code block");
        blocks.push(&body[..end]);
        rest = &body[end..];
    }
    blocks
}

#[test]
fn readme_is_a_front_door() {
    let size = README.len();
    assert!(
        size <= 10 * 1024,
        "README.md is {size} bytes (at most 10 KiB)"
    );
}

#[test]
fn readme_code_has_no_hidden_lines_and_a_main() {
    let blocks = rust_blocks();
    assert!(blocks.len() >= 2, "the push and FIFO examples");
    for (i, block) in blocks.iter().enumerate() {
        for line in block.lines() {
            assert!(
                !(line.starts_with("# ") || line == "#"),
                "block {i}: a rustdoc-hidden line does not paste: {line:?}"
            );
        }
        assert!(block.contains("fn main()"), "block {i} is not a program");
    }
}

#[test]
fn readme_code_pastes_into_a_new_crate_and_runs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let scratch = Path::new(env!("CARGO_TARGET_TMPDIR")).join("readme-paste");
    let bins = scratch.join("src").join("bin");
    let _ = std::fs::remove_dir_all(&bins);
    std::fs::create_dir_all(&bins).expect("scratch crate");
    std::fs::write(
        scratch.join("Cargo.toml"),
        format!(
            "[package]\nname = \"readme-paste\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n\
             [dependencies]\nquatprop = {{ path = {:?} }}\n\n[workspace]\n",
            root.display().to_string()
        ),
    )
    .expect("manifest");
    // The versions this repository's own build resolved: no registry access needed.
    if root.join("Cargo.lock").exists() {
        std::fs::copy(root.join("Cargo.lock"), scratch.join("Cargo.lock")).expect("lock file");
    }
    let blocks = rust_blocks();
    for (i, block) in blocks.iter().enumerate() {
        std::fs::write(bins.join(format!("block{i}.rs")), block).expect("a pasted block");
    }
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    for i in 0..blocks.len() {
        let out = Command::new(&cargo)
            .args(["run", "--quiet", "--offline", "--bin", &format!("block{i}")])
            .current_dir(&scratch)
            .env("CARGO_TARGET_DIR", scratch.join("target"))
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "README block {i}, pasted into a new crate, fails:\n{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
