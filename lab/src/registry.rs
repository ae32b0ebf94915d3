//! Every CSV file the report writes, by name, with its row type: what the tests read strictly and what
//! the committed report's tables are checked against.

use crate::table::{self, Csv};
use crate::{
    atlas, baumgarte_sweep, bias, coning_drift, geiger, long_horizon, scene_table, sensor,
};
use crate::{time_base, timing, work_precision as wp};
use std::path::Path;

macro_rules! registry {
    (data: [$($d:ty),* $(,)?], tables: [$($t:ty),* $(,)?]) => {
        /// Every file name the report can write.
        pub const FILES: &[&str] = &[$(<$d as Csv>::FILE,)* $(<$t as Csv>::FILE,)*];

        /// Reads `file` in `dir` strictly as its row type; `None` for a file no row type claims.
        pub fn read_strict(dir: &Path, file: &str) -> Option<Result<usize, String>> {
            $(if file == <$d as Csv>::FILE {
                return Some(table::read::<$d>(&dir.join(file)).map(|r| r.len()));
            })*
            $(if file == <$t as Csv>::FILE {
                return Some(table::read::<$t>(&dir.join(file)).map(|r| r.len()));
            })*
            None
        }

        /// The table of `file` as the report shows it (markers included), rendered from the file in `dir`.
        pub fn render(dir: &Path, file: &str) -> Option<Result<String, String>> {
            $(if file == <$t as Csv>::FILE {
                return Some(table::rendered::<$t>(dir));
            })*
            None
        }
    };
}

registry!(
    data: [
        geiger::Fig1Row,
        geiger::Fig2Row,
        baumgarte_sweep::CurveRow,
        atlas::AtlasRow,
        wp::WpScenes,
        wp::WpGrid,
        coning_drift::DriftRow,
        bias::SeriesRow,
        long_horizon::PointRow,
    ],
    tables: [
        geiger::GainRow,
        baumgarte_sweep::SweepRow,
        atlas::BoundRow,
        wp::WpHeadline,
        wp::EqualCostRow,
        wp::SceneSummaryRow,
        wp::WpStabilizers,
        wp::M4fRow,
        scene_table::SceneRow,
        sensor::SensorRow,
        coning_drift::FitRow,
        bias::ConvergenceRow,
        bias::RotationRow,
        bias::FusionCRow,
        time_base::TimeBaseRow,
        long_horizon::SummaryRow,
        timing::StudyTimeRow,
    ]
);

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
        let expected = render(dir, file)
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
    use clap::Parser as _;

    /// The quick report, run in-process: every CSV it writes is claimed by a row type and reads back
    /// strictly (fixed column count, the type's columns in order, every field parsed as its type), and
    /// every table in its README is what its CSV renders.
    #[test]
    fn quick_report_csvs_read_strictly_and_tables_match() {
        let dir = std::env::temp_dir().join(format!("quatprop-lab-quick-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.to_str().unwrap();
        let cli =
            crate::cli::Cli::try_parse_from(["quatprop-lab", "report", "--quick", "--out", out])
                .unwrap();
        let mut ctx = crate::Ctx::new(dir.clone());
        let sections = crate::cli::run(&cli, &mut ctx);
        let failures = crate::finish(&mut ctx, &sections, "report --quick");
        assert!(failures.is_empty(), "{failures:?}");
        let mut n = 0;
        for e in std::fs::read_dir(&dir).unwrap() {
            let name = e.unwrap().file_name().into_string().unwrap();
            if name.ends_with(".csv") {
                let rows = read_strict(&dir, &name)
                    .unwrap_or_else(|| panic!("{name}: no row type claims this CSV"))
                    .unwrap_or_else(|e| panic!("{e}"));
                assert!(rows > 0, "{name}: no rows");
                n += 1;
            }
        }
        // Every registered file is written (the M4F table only when the firmware figures exist).
        for f in FILES {
            let optional = *f == wp::M4fRow::FILE;
            assert!(optional || dir.join(f).exists(), "{f} not written");
        }
        assert!(n >= FILES.len() - 1, "{n} CSV files");
        let tables = check_tables(&dir).unwrap_or_else(|e| panic!("{e}"));
        assert!(tables >= 15, "{tables} tables");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The committed report (docs/report): every table is what its committed CSV renders.
    #[test]
    fn committed_tables_match_csv() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/report");
        let tables = check_tables(&dir).unwrap_or_else(|e| panic!("docs/report: {e}"));
        assert!(tables >= 15, "{tables} tables in docs/report/README.md");
        for f in FILES {
            if dir.join(f).exists() {
                read_strict(&dir, f)
                    .unwrap()
                    .unwrap_or_else(|e| panic!("{e}"));
            }
        }
    }

    /// A changed cell is caught.
    #[test]
    fn a_table_that_differs_from_its_csv_fails() {
        let dir = std::env::temp_dir().join(format!("quatprop-lab-tamper-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let rows = vec![time_base::TimeBaseRow {
            time_base: "x".into(),
            steps: 1_000_000,
            error_rad: 1.5e-3,
            time_error_s: 0.0,
        }];
        table::write(&dir.join(time_base::TimeBaseRow::FILE), &rows).unwrap();
        let t = table::rendered::<time_base::TimeBaseRow>(&dir).unwrap();
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
