//! One version everywhere it is stated: the crate's `Cargo.toml` is the reference, and the newest section of
//! CHANGELOG.md, every other crate's manifest in the repository (the C API's among them: its
//! `quatprop_version()` returns its manifest's version, and its header test writes that version into the
//! committed header as `QUATPROP_VERSION`, read here too), docs/c-api.md's statement of it, and the Python
//! package's `pyproject.toml` and `__version__` must all say the same.
//!
//! Not counted as stated versions:
//! - manifests with `version = "0.0.0"`: helper crates that are never released (the fuzz targets and their
//!   checks, the header test, Python's reference crate) say so with that placeholder;
//! - the generated pages under docs/ that name the version a benchmark ran with ("quatprop 0.2.0" in
//!   docs/bias.md, docs/broad.md, ...): each records its run and is rewritten by its program, not kept in
//!   step by hand.
//!
//! Inside the published crate (`.ci/package` runs the tests in the unpacked `.crate`) only the manifest,
//! CHANGELOG.md and the sources ship: without `ffi/` beside the manifest, the repository's other files are
//! skipped (and the test says so).

use std::fs;
use std::path::{Path, PathBuf};

fn read(path: &Path) -> String {
    fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The value of the first `key = "..."` line of `section` (e.g. `[package]`) in a TOML file.
fn toml_value(text: &str, section: &str, key: &str) -> Option<String> {
    let mut inside = false;
    for line in text.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            inside = line == section;
        } else if inside {
            if let Some(rest) = line.strip_prefix(key) {
                let rest = rest.trim_start();
                if let Some(value) = rest.strip_prefix('=') {
                    return quoted(value);
                }
            }
        }
    }
    None
}

/// The first double-quoted string in `text`.
fn quoted(text: &str) -> Option<String> {
    let start = text.find('"')? + 1;
    let len = text[start..].find('"')?;
    Some(text[start..start + len].to_string())
}

/// The newest section's version in CHANGELOG.md: the first `## [x.y.z]` heading (an `## [Unreleased]`
/// section above it holds what has come since).
fn changelog_version(text: &str) -> Option<String> {
    let line = text
        .lines()
        .find(|l| l.starts_with("## [") && !l.starts_with("## [Unreleased]"))?;
    let rest = &line[4..];
    Some(rest[..rest.find(']')?].to_string())
}

/// Every `Cargo.toml` and `pyproject.toml` under `dir`, leaving out build output and hidden directories.
fn manifests(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<_> = entries.filter_map(Result::ok).collect();
    entries.sort_by_key(|e| e.file_name());
    for e in entries {
        let name = e.file_name().to_string_lossy().into_owned();
        let path = e.path();
        if path.is_dir() {
            if !(name.starts_with('.') || name == "target" || name == "node_modules") {
                manifests(&path, out);
            }
        } else if name == "Cargo.toml" || name == "pyproject.toml" {
            out.push(path);
        }
    }
}

#[test]
fn every_stated_version_is_the_crates() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let version = env!("CARGO_PKG_VERSION");
    let manifest = toml_value(&read(&root.join("Cargo.toml")), "[package]", "version");
    assert_eq!(manifest.as_deref(), Some(version), "Cargo.toml");

    let mut stated: Vec<(String, Option<String>)> = Vec::new();
    stated.push((
        "CHANGELOG.md, newest section".into(),
        changelog_version(&read(&root.join("CHANGELOG.md"))),
    ));

    if root.join("ffi").is_dir() {
        let mut found = Vec::new();
        manifests(&root, &mut found);
        let mut crates = 0;
        for path in &found {
            let name = path.strip_prefix(&root).unwrap().display().to_string();
            let section = if name.ends_with("pyproject.toml") {
                "[project]"
            } else {
                "[package]"
            };
            let v = toml_value(&read(path), section, "version");
            if v.as_deref() == Some("0.0.0") {
                continue; // never released: no version stated
            }
            if v.is_none() && section == "[package]" && !read(path).contains("[package]") {
                continue; // a virtual workspace manifest
            }
            crates += 1;
            stated.push((name, v));
        }
        // The ones this repository has today must be among them (a walk that found nothing proves nothing).
        for expected in [
            "ffi/Cargo.toml",
            "firmware/Cargo.toml",
            "firmware/quickstart/Cargo.toml",
            "lab/Cargo.toml",
            "python/Cargo.toml",
            "python/pyproject.toml",
        ] {
            assert!(
                stated.iter().any(|(n, _)| n == expected),
                "{expected} was not read"
            );
        }
        let line_value = |file: &str, prefix: &str| {
            read(&root.join(file))
                .lines()
                .find_map(|l| l.trim().strip_prefix(prefix).and_then(quoted))
        };
        stated.push((
            "python/pysrc/quatprop/__init__.py, __version__".into(),
            line_value("python/pysrc/quatprop/__init__.py", "__version__ ="),
        ));
        stated.push((
            "ffi/include/quatprop.h, QUATPROP_VERSION".into(),
            line_value("ffi/include/quatprop.h", "#define QUATPROP_VERSION "),
        ));
        stated.push((
            "docs/c-api.md, quatprop_version()".into(),
            line_value(
                "docs/c-api.md",
                "`quatprop_version()` returns the library's version",
            ),
        ));
        println!(
            "{} stated versions ({crates} manifests) agree with {version}",
            stated.len() + 1
        );
    } else {
        println!(
            "no ffi/ beside {}: the published crate; only Cargo.toml and CHANGELOG.md checked",
            root.display()
        );
    }

    let wrong: Vec<String> = stated
        .iter()
        .filter(|(_, v)| v.as_deref() != Some(version))
        .map(|(name, v)| format!("{name}: {v:?}"))
        .collect();
    assert!(
        wrong.is_empty(),
        "not version {version}:\n{}",
        wrong.join("\n")
    );
}

/// The readers find what they should (a test of the test: a reader that found nothing would only fail
/// with a confusing message).
#[test]
fn the_readers_read() {
    let toml = "[package]\nname = \"x\"\nversion = \"1.2.3\"\n[dependencies]\nversion = \"9\"\n";
    assert_eq!(
        toml_value(toml, "[package]", "version").as_deref(),
        Some("1.2.3")
    );
    assert_eq!(toml_value(toml, "[project]", "version"), None);
    let log = "# Changelog\n\n## [0.3.0] — unreleased\n\n## [0.2.0] — unreleased\n";
    assert_eq!(changelog_version(log).as_deref(), Some("0.3.0"));
    let log = "# Changelog\n\n## [Unreleased]\n\n## [0.3.0] — 2026-11-28\n";
    assert_eq!(changelog_version(log).as_deref(), Some("0.3.0"));
    assert_eq!(quoted("x = \"0.3.0\" # y").as_deref(), Some("0.3.0"));
}
