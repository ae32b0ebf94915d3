//! quatprop lab: the report a user runs to choose a scheme.
//!
//! `cargo run --release -p quatprop-lab -- report [--quick | --full] [--out DIR]` writes `DIR/README.md`
//! (default `report/`) with plots (SVG and PNG) and CSV files. Sub-commands run one study, with parameters
//! (scene, schemes, stabilizers, inputs, precision, rates, horizon, steps): see `quatprop-lab help` and
//! `quatprop-lab help <command>`. `--quick` shrinks every study (CI checks that each one runs and writes
//! its files), `--full` runs the sizes of record. lab/README.md says how to add a study.
//!
//! Layout, top to bottom (each file uses only the files after it; lab/README.md has the table): `cli.rs`
//! (the command line), `studies/mod.rs` (the registry), `studies/` (one file per study), `outputs.rs` (the
//! files a report writes, and their checks), `study.rs` (what a study is), `args.rs` (arguments the studies
//! share), `report.rs` (the report being written) and `summary.rs` (its opening summary, from the run's
//! CSV files); what studies share: configurations and peers
//! (`configs.rs`, `peer_loops.rs`, `peers.rs`, `peer_types.rs`); scenes and their exact references
//! (`scenes.rs`: the synthetic ones and the catalogue; `rigid_body.rs`, `recorded.rs`; `scene.rs`: what a
//! scene is; `sample.rs`: a stream's sample); and the leaves: the scale (`scale.rs`), double-double time
//! (`dd.rs`), checkpoints and log-log slopes (`series.rs`), unchecked steps (`unchecked.rs`), random
//! numbers (`rng.rs`), host timing (`quiet.rs`, `timing.rs`), the firmware bench's counts
//! (`m4f_bench.rs`), CSV and tables (`table.rs`) and plots (`plot.rs`).

mod args;
mod cli;
mod configs;
mod dd;
#[cfg(test)]
mod example_study;
mod m4f_bench;
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
mod scale;
mod scene;
mod scenes;
mod series;
mod studies;
mod study;
mod summary;
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
    let failures = inv.finish(&mut ctx, &command);
    if failures.is_empty() {
        eprintln!("written to {}/{}", out.display(), ctx.markdown_file());
    } else {
        for f in &failures {
            eprintln!("error: {f}");
        }
        std::process::exit(1);
    }
}
