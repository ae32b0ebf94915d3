//! Every file the report writes, from the registry: each study's CSV files (with their row types: read
//! strictly, and the report's tables checked against them, here and for the committed docs/report) and its
//! figures, and the report's own files (README.md, run_time.csv). [`check`] runs after every `report`.

use crate::study::{AnyStudy, CsvFile};
use crate::table;
use crate::timing::StudyTimeRow;
use std::path::Path;

/// The report's own CSV files (not a study's).
const REPORT_CSV: &[CsvFile] = &[CsvFile::table::<StudyTimeRow>()];

/// Every CSV file the report can write, with its row type.
pub fn csv_files() -> impl Iterator<Item = &'static CsvFile> {
    crate::studies::ALL
        .iter()
        .flat_map(|s| s.csv().iter())
        .chain(REPORT_CSV)
}

/// The CSV file named `file`, if a row type claims it.
pub fn csv_file(file: &str) -> Option<&'static CsvFile> {
    csv_files().find(|c| c.file == file)
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

/// After a report in `dir`: every file the studies declare exists (but the optional ones), every CSV it
/// wrote reads back strictly as its row type, and every table of README.md is what its CSV renders. The
/// failures.
pub fn check(dir: &Path, written: &[String]) -> Vec<String> {
    let mut failures = Vec::new();
    for (file, optional) in declared(crate::studies::ALL) {
        if !optional && !dir.join(&file).exists() {
            failures.push(format!("{file}: declared by a study, not written"));
        }
    }
    for file in written {
        match csv_file(file) {
            None => failures.push(format!("{file}: written, but no study declares it")),
            Some(c) => {
                if let Err(e) = c.read_strict(dir) {
                    failures.push(e);
                }
            }
        }
    }
    if let Err(e) = check_tables(dir) {
        failures.push(e);
    }
    failures
}

/// Checks every table of `dir/README.md` against its CSV: each table must sit between markers naming a
/// CSV in `dir`, and the lines between them must be what that CSV renders. Returns the number of tables.
pub fn check_tables(dir: &Path) -> Result<usize, String> {
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
        let expected = csv_file(file)
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
    use crate::studies::{self, time_base::TimeBaseRow};
    use crate::table::Csv as _;
    use std::collections::BTreeSet;

    /// The quick report, run in-process as `main` runs it: it passes its own [`check`], and the directory
    /// holds exactly the files the registry declares (README.md and the optional files aside), every CSV
    /// with rows.
    #[test]
    fn quick_report_writes_exactly_the_declared_files() {
        let dir = std::env::temp_dir().join(format!("quatprop-lab-quick-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.to_str().unwrap();
        let inv =
            crate::cli::parse_from(["quatprop-lab", "report", "--quick", "--out", out]).unwrap();
        let mut ctx = crate::report::Ctx::new(dir.clone(), inv.cli.scale());
        inv.run(&mut ctx).unwrap();
        let failures = crate::report::finish(&mut ctx, "report --quick", true);
        assert!(failures.is_empty(), "{failures:?}");
        let written: BTreeSet<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        let declared = declared(studies::ALL);
        let mut expected: BTreeSet<String> = declared
            .iter()
            .filter(|(_, optional)| !optional)
            .map(|(f, _)| f.clone())
            .collect();
        expected.extend(["README.md".to_string(), StudyTimeRow::FILE.to_string()]);
        let optional: BTreeSet<String> = declared
            .iter()
            .filter(|(_, optional)| *optional)
            .map(|(f, _)| f.clone())
            .collect();
        let extra: Vec<&String> = written
            .difference(&expected)
            .filter(|f| !optional.contains(*f))
            .collect();
        let missing: Vec<&String> = expected.difference(&written).collect();
        assert!(extra.is_empty(), "written, not declared: {extra:?}");
        assert!(missing.is_empty(), "declared, not written: {missing:?}");
        for f in written.iter().filter(|f| f.ends_with(".csv")) {
            let rows = csv_file(f).unwrap().read_strict(&dir).unwrap();
            assert!(rows > 0, "{f}: no rows");
        }
        let tables = check_tables(&dir).unwrap_or_else(|e| panic!("{e}"));
        assert!(tables >= 15, "{tables} tables");
        // The check catches a missing file.
        std::fs::remove_file(dir.join("time_base.png")).unwrap();
        assert!(check(&dir, &[]).iter().any(|f| f.contains("time_base.png")));
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// One registry line per file under studies/, and no two studies share a name or a file.
    #[test]
    fn every_study_file_is_registered_once_and_names_are_unique() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/studies");
        let files: BTreeSet<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|f| f != "mod.rs")
            .map(|f| f.trim_end_matches(".rs").to_string())
            .collect();
        let modules: BTreeSet<String> = studies::MODULES.iter().map(|m| m.to_string()).collect();
        assert_eq!(
            files, modules,
            "files under src/studies/ against the registry's lines"
        );
        assert_eq!(studies::MODULES.len(), studies::ALL.len());
        let names: BTreeSet<&str> = studies::ALL.iter().map(|s| s.name()).collect();
        assert_eq!(names.len(), studies::ALL.len(), "two studies share a name");
        let all = declared(studies::ALL);
        let files: BTreeSet<&String> = all.iter().map(|(f, _)| f).collect();
        assert_eq!(files.len(), all.len(), "two outputs share a file name");
        assert!(csv_files().count() > 20);
    }

    /// The committed report (docs/report): every table is what its committed CSV renders.
    #[test]
    fn committed_tables_match_csv() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/report");
        let tables = check_tables(&dir).unwrap_or_else(|e| panic!("docs/report: {e}"));
        assert!(tables >= 15, "{tables} tables in docs/report/README.md");
        for c in csv_files() {
            if dir.join(c.file).exists() {
                c.read_strict(&dir).unwrap_or_else(|e| panic!("{e}"));
            }
        }
    }

    /// A changed cell is caught.
    #[test]
    fn a_table_that_differs_from_its_csv_fails() {
        let dir = std::env::temp_dir().join(format!("quatprop-lab-tamper-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let rows = vec![TimeBaseRow {
            time_base: "x".into(),
            steps: 1_000_000,
            error_rad: 1.5e-3,
            time_error_s: 0.0,
        }];
        table::write(&dir.join(TimeBaseRow::FILE), &rows).unwrap();
        let t = table::rendered::<TimeBaseRow>(&dir).unwrap();
        std::fs::write(dir.join("README.md"), format!("# r\n\n{t}\ntext\n")).unwrap();
        assert_eq!(check_tables(&dir), Ok(1));
        std::fs::write(
            dir.join("README.md"),
            format!("# r\n\n{}\n", t.replace("1.50e-3", "1.40e-3")),
        )
        .unwrap();
        assert!(check_tables(&dir).is_err());
        std::fs::write(dir.join("README.md"), "# r\n\n| a |\n|---|\n").unwrap();
        assert!(check_tables(&dir).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
