//! The registry: every study of the lab, one line each, in the report's order. A line `file::Type` declares
//! the module `studies/file.rs` and registers its [`Study`](crate::study::Study) `Type`: its sub-command,
//! its place in `report`, and its CSV files and figures in the tests' checks all come from here.

use crate::study::AnyStudy;

macro_rules! registry {
    ($($module:ident :: $study:ident),* $(,)?) => {
        $(pub mod $module;)*

        /// Every study, in the report's order.
        pub const ALL: &[&dyn AnyStudy] = &[$(&$module::$study),*];

        /// The registered modules (files under `studies/`).
        #[cfg(test)]
        pub const MODULES: &[&str] = &[$(stringify!($module)),*];
    };
}

registry! {
    geiger::Geiger,
    baumgarte_sweep::BaumgarteSweep,
    atlas::Atlas,
    work_precision::WorkPrecision,
    config_cost::ConfigCost,
    scene_table::Scenes,
    sensor::Sensor,
    noise::Noise,
    coning_drift::ConingDrift,
    time_base::TimeBaseStudy,
    long_horizon::LongHorizon,
    covariance::Covariance,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::args::ReportArgs;
    use crate::example_study::InputModels;
    use crate::outputs;
    use crate::report::{self, Ctx};
    use crate::scale::Scale;
    use std::collections::BTreeSet;
    use std::path::Path;

    const README: &str = include_str!("../../README.md");

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
        let modules: BTreeSet<String> = MODULES.iter().map(|m| m.to_string()).collect();
        assert_eq!(
            files, modules,
            "files under src/studies/ against the registry's lines"
        );
        assert_eq!(MODULES.len(), ALL.len());
        let names: BTreeSet<&str> = ALL.iter().map(|s| s.name()).collect();
        assert_eq!(names.len(), ALL.len(), "two studies share a name");
        let all = outputs::declared(ALL);
        let files: BTreeSet<&String> = all.iter().map(|(f, _)| f).collect();
        assert_eq!(files.len(), all.len(), "two outputs share a file name");
        assert!(outputs::csv_files(ALL).count() > 20);
    }

    /// The committed report (docs/report): every table is what its committed CSV renders.
    #[test]
    fn committed_tables_match_csv() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/report");
        let tables =
            outputs::check_tables(&dir, ALL).unwrap_or_else(|e| panic!("docs/report: {e}"));
        assert!(tables >= 15, "{tables} tables in docs/report/README.md");
        for c in outputs::csv_files(ALL) {
            if dir.join(c.file).exists() {
                c.read_strict(&dir).unwrap_or_else(|e| panic!("{e}"));
            }
        }
    }

    /// lab/README.md's example is `example_study.rs` from its first `use` on, verbatim.
    #[test]
    fn readme_example_is_the_example_study() {
        let file = include_str!("../example_study.rs");
        let code = &file[file.find("use ").unwrap()..];
        let block = README
            .split("```rust\n")
            .nth(1)
            .and_then(|b| b.split("```\n").next())
            .expect("a rust block in lab/README.md");
        assert_eq!(
            block, code,
            "lab/README.md's example against src/example_study.rs"
        );
    }

    /// lab/README.md lists every registered study with its sub-command and one-line description.
    #[test]
    fn readme_lists_every_study() {
        for s in ALL {
            let line = format!("| `{}` | {} |", s.name(), s.about());
            assert!(
                README.contains(&line),
                "lab/README.md lacks the line {line}"
            );
        }
    }

    /// The example runs as a registered study would: from its sub-command's arguments and in a report
    /// (its defaults), writing the files it declares, which read back strictly.
    #[test]
    fn the_example_study_runs_like_a_registered_one() {
        let dir = crate::table::scratch_dir("quatprop-lab-example");
        let study: &dyn AnyStudy = &InputModels;
        let matches = study
            .command()
            .try_get_matches_from(["example-inputs", "--rate", "500"])
            .unwrap();
        let mut ctx = Ctx::new(dir.clone(), Scale::Quick);
        study.run_matches(&mut ctx, &matches).unwrap();
        let failures = report::finish(&mut ctx, "example-inputs --quick");
        assert!(failures.is_empty(), "{failures:?}");
        let md = std::fs::read_to_string(dir.join("README.md")).unwrap();
        assert!(md.contains("500 Hz, 1.37 s."), "{md}");
        for c in study.csv() {
            assert_eq!(c.read_strict(&dir), Ok(4), "{}", c.file);
            assert!(md.contains(&c.render(&dir).unwrap().unwrap()));
        }
        let mut ctx = Ctx::new(dir.clone(), Scale::Quick);
        study.run_in_report(&mut ctx, &ReportArgs::default());
        report::finish(&mut ctx, "report --quick");
        let md = std::fs::read_to_string(dir.join("README.md")).unwrap();
        assert!(
            md.contains("1000 Hz, 1.37 s."),
            "the sub-command's default rate: {md}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
