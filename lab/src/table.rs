//! Every CSV the report writes, and every table it shows, go through here.
//!
//! A CSV file is a list of typed rows ([`Csv`]: serde `Serialize + Deserialize`, one file name per row
//! type) written with the `csv` crate. A table in the report is rendered from its CSV *as read back from
//! the file* ([`Table::render`]), between two markers naming the file, so that the committed
//! `docs/report/README.md` can be checked against the committed CSVs (test `committed_tables_match_csv`).

use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::Path;

/// A CSV file's row type.
pub trait Csv: Serialize + DeserializeOwned {
    /// The file name (in the report's directory).
    const FILE: &'static str;
}

/// A CSV file shown as a Markdown table.
pub trait Table: Csv {
    /// The Markdown table (header, separator, one line per row; no marker).
    fn render(rows: &[Self]) -> String;
}

/// Writes `rows` to `path` (header from the field names).
pub fn write<R: Csv>(path: &Path, rows: &[R]) -> Result<(), String> {
    let mut w = csv::Writer::from_path(path).map_err(|e| format!("{}: {e}", R::FILE))?;
    for r in rows {
        w.serialize(r).map_err(|e| format!("{}: {e}", R::FILE))?;
    }
    w.flush().map_err(|e| format!("{}: {e}", R::FILE))
}

/// Reads `path` strictly: a header, then records of exactly the header's column count, each field parsed
/// as the row type says (a missing, extra or mistyped column is an error).
pub fn read<R: Csv>(path: &Path) -> Result<Vec<R>, String> {
    let mut r = csv::ReaderBuilder::new()
        .flexible(false)
        .has_headers(true)
        .from_path(path)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let headers = r
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?
        .clone();
    // The columns must be exactly the row type's fields, in order: serialize a row back and compare.
    let rows: Vec<R> = r
        .deserialize()
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    if let Some(first) = rows.first() {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.serialize(first).map_err(|e| e.to_string())?;
        let bytes = w.into_inner().map_err(|e| e.to_string())?;
        let own = csv::Reader::from_reader(bytes.as_slice())
            .headers()
            .map_err(|e| e.to_string())?
            .clone();
        if own != headers {
            return Err(format!(
                "{}: columns {:?}, expected {:?}",
                path.display(),
                headers,
                own
            ));
        }
    }
    Ok(rows)
}

/// The marker line that opens a table rendered from `file`.
pub fn open_marker(file: &str) -> String {
    format!("<!-- table from {file} -->")
}

/// The marker line that closes it.
pub const CLOSE_MARKER: &str = "<!-- end of table -->";

/// The table as it stands in the report: markers around the rendering of the CSV read back from `dir`.
pub fn rendered<R: Table>(dir: &Path) -> Result<String, String> {
    let rows = read::<R>(&dir.join(R::FILE))?;
    Ok(format!(
        "{}\n{}{}\n",
        open_marker(R::FILE),
        R::render(&rows),
        CLOSE_MARKER
    ))
}

/// Markdown header and separator for these column titles.
pub fn header(cols: &[&str]) -> String {
    format!("| {} |\n|{}\n", cols.join(" | "), "---|".repeat(cols.len()))
}

/// The distinct values of `key` over `rows`, in the order they first appear: a pivot table's lines or
/// columns, in the order of its file.
pub fn distinct<'a, R, K: PartialEq>(rows: &'a [R], key: impl Fn(&'a R) -> K) -> Vec<K> {
    let mut v = Vec::new();
    for r in rows {
        let k = key(r);
        if !v.contains(&k) {
            v.push(k);
        }
    }
    v
}

/// A fresh, empty directory for a test's files: `name` and this process's id under the system's
/// temporary directory.
#[cfg(test)]
pub fn scratch_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A number in the report's short scientific form (`4.75e-3`), `–` for NaN, `∞` for infinities.
pub fn sci(v: f64, digits: usize) -> String {
    if v.is_nan() {
        "–".into()
    } else if v.is_infinite() {
        if v > 0.0 { "∞" } else { "−∞" }.into()
    } else {
        format!("{v:.digits$e}")
    }
}

/// Escapes `|` for a Markdown table cell.
pub fn cell(s: &str) -> String {
    s.replace('|', "\\|")
}
