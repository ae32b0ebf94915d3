//! The firmware bench's Cortex-M4F instruction counts per step (`firmware/bench-m4f.csv`, written by
//! `python3 firmware/figures.py`), as the work–precision study and the report's summary read them.

use std::path::{Path, PathBuf};

/// One row: precision (`f32`, `f32-kahan`, `f32-floatfloat`), scheme, stabilizer, input model,
/// instructions per step.
pub type BenchRow = (String, String, String, String, f64);

/// The committed bench file.
pub fn path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../firmware/bench-m4f.csv")
}

/// The rows of the bench file at `path` after its header (a line that does not parse is skipped).
pub fn read(path: &Path) -> Result<Vec<BenchRow>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(text
        .lines()
        .skip(1)
        .filter_map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            Some((
                f.first()?.to_string(),
                f.get(1)?.to_string(),
                f.get(2)?.to_string(),
                f.get(3)?.to_string(),
                f.get(4)?.parse().ok()?,
            ))
        })
        .collect())
}
