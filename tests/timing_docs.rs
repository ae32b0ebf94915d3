//! docs/timing.md's examples (the tick clock, sample timing), each a whole program that runs here as a
//! test: the page's `rust` blocks must appear verbatim in `tests/timing_docs/*.rs` (skipped where docs/ is
//! absent, as in the published crate).

#[path = "timing_docs/sample_timing.rs"]
mod sample_timing;
#[path = "timing_docs/tick_clock.rs"]
mod tick_clock;

const SOURCES: [(&str, &str); 2] = [
    ("tick_clock.rs", include_str!("timing_docs/tick_clock.rs")),
    (
        "sample_timing.rs",
        include_str!("timing_docs/sample_timing.rs"),
    ),
];

#[test]
fn the_page_shows_the_tested_code() {
    let page = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/timing.md");
    let Ok(page) = std::fs::read_to_string(&page) else {
        eprintln!(
            "{} absent (the published crate): not checked",
            page.display()
        );
        return;
    };
    let mut blocks = Vec::new();
    let mut rest = page.as_str();
    while let Some(start) = rest.find("```rust\n") {
        let body = &rest[start + "```rust\n".len()..];
        let end = body.find("```\n").expect("a closed code block");
        blocks.push(&body[..end]);
        rest = &body[end..];
    }
    for block in &blocks {
        assert!(
            SOURCES.iter().any(|(_, source)| source.contains(block)),
            "docs/timing.md shows code that no file of tests/timing_docs/ has verbatim:\n{block}"
        );
    }
    for (name, source) in SOURCES {
        assert!(
            blocks.iter().any(|block| source.contains(block)),
            "docs/timing.md does not show tests/timing_docs/{name}"
        );
    }
}
