//! Every file a report of some studies writes (the registry's, `studies::ALL`, for the lab report): each
//! study's CSV files (with their row types: read strictly, and the report's tables checked against them,
//! for a report just written and for the committed docs/report) and its figures, and the report's own files
//! (README.md, run_time.csv, summary.csv). [`check`] runs after every `report` (`Invocation::finish`).

use crate::study::{AnyStudy, CsvFile};
use crate::summary::SummaryRow;
use crate::table;
use crate::timing::StudyTimeRow;
use std::path::Path;

/// The report's own CSV files (not a study's).
pub const REPORT_CSV: &[CsvFile] = &[
    CsvFile::table::<StudyTimeRow>(),
    CsvFile::table::<SummaryRow>(),
];

/// Every CSV file a report of `studies` can write, with its row type.
pub fn csv_files<'a>(
    studies: &'a [&'a dyn AnyStudy],
) -> impl Iterator<Item = &'static CsvFile> + 'a {
    studies
        .iter()
        .flat_map(|s| s.csv().iter())
        .chain(REPORT_CSV)
}

/// The CSV file named `file`, if a row type of `studies` (or of the report itself) claims it.
pub fn csv_file(studies: &[&dyn AnyStudy], file: &str) -> Option<&'static CsvFile> {
    csv_files(studies).find(|c| c.file == file)
}

/// The files `studies` declare (CSV, and each figure as SVG and PNG), with whether each is optional.
pub fn declared(studies: &[&dyn AnyStudy]) -> Vec<(String, bool)> {
    let mut v = Vec::new();
    for s in studies {
        v.extend(s.csv().iter().map(|c| (c.file.to_string(), c.optional)));
        for f in s.figures() {
            v.push((format!("{f}.svg"), false));
            v.push((format!("{f}.png"), false));
        }
    }
    v
}

/// After a report of `studies` in `dir`: every file they declare exists (but the optional ones), every CSV
/// it wrote reads back strictly as its row type, and every table of README.md is what its CSV renders. The
/// failures.
pub fn check(dir: &Path, written: &[String], studies: &[&dyn AnyStudy]) -> Vec<String> {
    let mut failures = Vec::new();
    for (file, optional) in declared(studies) {
        if !optional && !dir.join(&file).exists() {
            failures.push(format!("{file}: declared by a study, not written"));
        }
    }
    for file in written {
        match csv_file(studies, file) {
            None => failures.push(format!("{file}: written, but no study declares it")),
            Some(c) => {
                if let Err(e) = c.read_strict(dir) {
                    failures.push(e);
                }
            }
        }
    }
    if let Err(e) = check_tables(dir, studies) {
        failures.push(e);
    }
    failures
}

/// Checks every table of `dir/README.md` against its CSV: each table must sit between markers naming a
/// CSV in `dir` that a row type of `studies` (or of the report itself) renders, and the lines between them
/// must be what that CSV renders. Returns the number of tables.
pub fn check_tables(dir: &Path, studies: &[&dyn AnyStudy]) -> Result<usize, String> {
    let md = std::fs::read_to_string(dir.join("README.md"))
        .map_err(|e| format!("{}/README.md: {e}", dir.display()))?;
    let open = table::open_marker("");
    let open = open.trim_end_matches(" -->");
    let mut rest = md.as_str();
    let mut outside = String::new();
    let mut count = 0;
    while let Some(i) = rest.find(open) {
        outside += &rest[..i];
        let after = &rest[i..];
        let line = after.lines().next().unwrap_or("");
        let file = line
            .trim_start_matches(open)
            .trim_end_matches(" -->")
            .trim();
        let end = after
            .find(table::CLOSE_MARKER)
            .ok_or_else(|| format!("table from {file}: no end marker"))?
            + table::CLOSE_MARKER.len();
        let committed = &after[..end];
        let expected = csv_file(studies, file)
            .and_then(|c| c.render(dir))
            .ok_or_else(|| format!("table from {file}: no row type renders that file"))??;
        if committed != expected.trim_end_matches('\n') {
            let diff = committed
                .lines()
                .zip(expected.lines())
                .find(|(a, b)| a != b)
                .map_or("(length differs)".to_string(), |(a, b)| {
                    format!("README: {a}\nCSV:    {b}")
                });
            return Err(format!(
                "the table from {file} differs from what the CSV renders:\n{diff}"
            ));
        }
        count += 1;
        rest = &after[end..];
    }
    outside += rest;
    if let Some(l) = outside.lines().find(|l| l.starts_with('|')) {
        return Err(format!("a table line not rendered from a CSV: {l}"));
    }
    Ok(count)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::Csv as _;

    /// A changed cell is caught (the report's own table, which every report has).
    #[test]
    fn a_table_that_differs_from_its_csv_fails() {
        let dir = crate::table::scratch_dir("quatprop-lab-tamper");
        let rows = vec![StudyTimeRow {
            study: "x".into(),
            wall_s: 1.5,
            cpu_s: 3.0,
            threads: 2,
        }];
        table::write(&dir.join(StudyTimeRow::FILE), &rows).unwrap();
        let t = table::rendered::<StudyTimeRow>(&dir).unwrap();
        std::fs::write(dir.join("README.md"), format!("# r\n\n{t}\ntext\n")).unwrap();
        assert_eq!(check_tables(&dir, &[]), Ok(1));
        std::fs::write(
            dir.join("README.md"),
            format!("# r\n\n{}\n", t.replace("| x | 1.5 |", "| x | 1.4 |")),
        )
        .unwrap();
        assert!(check_tables(&dir, &[]).is_err());
        std::fs::write(dir.join("README.md"), "# r\n\n| a |\n|---|\n").unwrap();
        assert!(check_tables(&dir, &[]).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
