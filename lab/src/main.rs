//! quatprop lab: the report a user runs to choose a scheme.
//!
//! `cargo run --release -p quatprop-lab -- report [--quick | --full] [--out DIR]` writes `DIR/README.md`
//! (default `report/`) with plots (SVG and PNG) and CSV files. Sub-commands run one study, with parameters
//! (scene, schemes, stabilizers, inputs, precision, rates, horizon, steps): see `quatprop-lab help` and
//! `quatprop-lab help <command>`. `--quick` shrinks every study (CI checks that each one runs and writes
//! its files), `--full` runs the sizes of record. lab/README.md says how to add a study.
//!
//! Layout: `studies/` holds one file per study and the registry (`studies/mod.rs`); `study.rs` says what a
//! study is; `cli.rs`, `report.rs` and `outputs.rs` are the command line, the report being written and the
//! check of its files; the rest is what studies share: configurations and peers (`configs.rs`, `peers.rs`,
//! `peer_loops.rs`), scenes and their exact references (`scenes.rs`, `rigid_body.rs`, `dd.rs`,
//! `recorded.rs`), unchecked steps (`unchecked.rs`), random numbers (`rng.rs`), host timing (`quiet.rs`,
//! `timing.rs`), CSV and tables (`table.rs`) and plots (`plot.rs`).

mod cli;
mod configs;
mod dd;
#[cfg(test)]
mod example_study;
mod outputs;
mod peer_loops;
mod peer_types;
mod peers;
mod plot;
mod quiet;
mod recorded;
mod report;
mod rigid_body;
mod rng;
mod sample;
mod scene;
mod scenes;
mod studies;
mod study;
mod table;
mod timing;
mod unchecked;

fn main() {
    let inv = cli::parse_from(std::env::args_os()).unwrap_or_else(|e| e.exit());
    let out = inv.cli.out.clone();
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("cannot create {}: {e}", out.display());
        std::process::exit(1);
    }
    let mut ctx = report::Ctx::new(out.clone(), inv.cli.scale());
    if let Err(e) = inv.run(&mut ctx) {
        e.exit();
    }
    ctx.clear_progress();
    let command = std::env::args().skip(1).collect::<Vec<_>>().join(" ");
    let failures = report::finish(&mut ctx, &command, inv.subcommand().0 == "report");
    if failures.is_empty() {
        eprintln!("written to {}/{}", out.display(), ctx.markdown_file());
    } else {
        for f in &failures {
            eprintln!("error: {f}");
        }
        std::process::exit(1);
    }
}
