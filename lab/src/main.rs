//! quatprop lab: the report a user runs to choose a scheme.
//!
//! `cargo run --release -p quatprop-lab -- report [--quick] [--out DIR]` writes `DIR/README.md` (default
//! `report/`) with plots (SVG and PNG) and CSV files. Sub-commands run one study:
//! `geiger`, `atlas`, `work-precision`, `long-horizon`. `--quick` shrinks every study (CI checks that each one runs and writes
//! its figures).

mod atlas;
mod configs;
mod coning_drift;
mod geiger;
mod long_horizon;
mod peers;
mod plot;
mod rigid_body;
mod scene_table;
mod scenes;
mod work_precision;

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Output directory, progress and failure bookkeeping shared by the studies.
pub struct Ctx {
    out: PathBuf,
    study: &'static str,
    ticks: u64,
    started: Instant,
    last_progress: Instant,
    terminal: bool,
    failures: Vec<String>,
    files: Vec<String>,
}

impl Ctx {
    fn new(out: PathBuf) -> Self {
        use std::io::IsTerminal as _;
        Self {
            out,
            study: "",
            ticks: 0,
            started: Instant::now(),
            last_progress: Instant::now(),
            terminal: std::io::stderr().is_terminal(),
            failures: Vec::new(),
            files: Vec::new(),
        }
    }

    /// One unit of work done: a progress line on a terminal's stderr (at most four times a second).
    pub fn tick(&mut self) {
        self.ticks += 1;
        if self.terminal && self.last_progress.elapsed().as_secs_f64() > 0.25 {
            self.last_progress = Instant::now();
            eprint!(
                "\r[{:6.1} s] {:16} {:6} work items",
                self.started.elapsed().as_secs_f64(),
                self.study,
                self.ticks
            );
            let _ = std::io::stderr().flush();
        }
    }

    /// Writes a CSV file (failures are reported at the end, never silently dropped).
    pub fn csv(&mut self, name: &str, content: &str) {
        match std::fs::write(self.out.join(name), content) {
            Ok(()) => self.files.push(name.to_string()),
            Err(e) => self.failures.push(format!("{name}: {e}")),
        }
    }

    /// Runs a plotting closure that writes `<name>.svg` and `<name>.png`.
    pub fn plot(&mut self, f: impl FnOnce(&Path) -> std::io::Result<()>) {
        if let Err(e) = f(&self.out) {
            self.failures.push(format!("plot in {}: {e}", self.study));
        }
    }
}

fn usage() -> ! {
    eprintln!(
        "usage: quatprop-lab <report|geiger|atlas|work-precision|scenes|coning-drift|long-horizon> [--quick|--long] [--out DIR]\n\
         report          all studies, README.md + plots (SVG, PNG) + CSV in DIR (default report/)\n\
         geiger          the seed paper's Fig. 1 and Fig. 2 (N(t) under RK4; N-infinity against k)\n\
         atlas           per-step norm factor and error against the step angle, measured stability bounds\n\
         work-precision  coning in f32: error against host time, quatprop against the peers\n\
         scenes          every scene (coning, symmetric top, 2000 deg/s, rate step, Earth rate) x configuration\n\
         coning-drift    coning drift coefficient of every rate scheme and input model\n\
         long-horizon    error growth to 1e8 steps (f32 every scheme, compensated f32, f64)\n\
         --quick         small grids and horizons (what CI runs); --long: 1e9 steps in long-horizon"
    );
    std::process::exit(2)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(cmd) = args.first().cloned() else {
        usage()
    };
    let mut quick = false;
    let mut long = false;
    let mut out = PathBuf::from("report");
    let mut i = 1;
    while i < args.len() {
        match args[i].as_str() {
            "--quick" => quick = true,
            "--long" => long = true,
            "--out" => {
                i += 1;
                out = args.get(i).map(PathBuf::from).unwrap_or_else(|| usage());
            }
            other => {
                eprintln!("unknown argument: {other}");
                usage()
            }
        }
        i += 1;
    }
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("cannot create {}: {e}", out.display());
        std::process::exit(1);
    }
    let mut ctx = Ctx::new(out.clone());
    let horizon: u64 = if quick {
        1_000_000
    } else if long {
        1_000_000_000
    } else {
        100_000_000
    };
    let mut sections = Vec::new();
    let run = |ctx: &mut Ctx, name: &'static str, f: &dyn Fn(&mut Ctx) -> String| {
        ctx.study = name;
        let t0 = Instant::now();
        let s = f(ctx);
        eprintln!(
            "\r{name}: done in {:.1} s{:30}",
            t0.elapsed().as_secs_f64(),
            ""
        );
        s
    };
    match cmd.as_str() {
        "report" => {
            sections.push(run(&mut ctx, "geiger fig 1", &geiger::figure1));
            sections.push(run(&mut ctx, "geiger fig 2", &|c| {
                geiger::figure2(c, quick)
            }));
            sections.push(run(&mut ctx, "stability atlas", &|c| {
                atlas::atlas(c, quick)
            }));
            sections.push(run(&mut ctx, "work-precision", &|c| {
                work_precision::work_precision(c, quick)
            }));
            sections.push(run(&mut ctx, "scenes", &|c| {
                scene_table::scene_table(c, quick)
            }));
            sections.push(run(&mut ctx, "coning drift", &|c| {
                coning_drift::coning_drift(c, quick)
            }));
            sections.push(run(&mut ctx, "long horizon", &|c| {
                long_horizon::long_horizon(c, horizon)
            }));
        }
        "scenes" => sections.push(run(&mut ctx, "scenes", &|c| {
            scene_table::scene_table(c, quick)
        })),
        "coning-drift" => sections.push(run(&mut ctx, "coning drift", &|c| {
            coning_drift::coning_drift(c, quick)
        })),
        "geiger" => {
            sections.push(run(&mut ctx, "geiger fig 1", &geiger::figure1));
            sections.push(run(&mut ctx, "geiger fig 2", &|c| {
                geiger::figure2(c, quick)
            }));
        }
        "atlas" => sections.push(run(&mut ctx, "stability atlas", &|c| {
            atlas::atlas(c, quick)
        })),
        "long-horizon" => sections.push(run(&mut ctx, "long horizon", &|c| {
            long_horizon::long_horizon(c, horizon)
        })),
        "work-precision" => sections.push(run(&mut ctx, "work-precision", &|c| {
            work_precision::work_precision(c, quick)
        })),
        _ => usage(),
    }
    let md = format!(
        "# quatprop lab report\n\nGenerated by `cargo run --release -p quatprop-lab -- {cmd}{}` in {:.1} s.\n\n{}\n\
         CSV data: {}.\n",
        if quick { " --quick" } else { "" },
        ctx.started.elapsed().as_secs_f64(),
        sections.join("\n"),
        ctx.files.join(", ")
    );
    if let Err(e) = std::fs::write(out.join("README.md"), md) {
        ctx.failures.push(format!("README.md: {e}"));
    }
    // Every figure the sections link must exist.
    for s in &sections {
        for part in s.split("](").skip(1) {
            let file = part.split(')').next().unwrap_or("");
            if !out.join(file).exists() {
                ctx.failures.push(format!("missing figure {file}"));
            }
            let svg = file.replace(".png", ".svg");
            if !out.join(&svg).exists() {
                ctx.failures.push(format!("missing figure {svg}"));
            }
        }
    }
    if ctx.failures.is_empty() {
        eprintln!("report written to {}/README.md", out.display());
    } else {
        for f in &ctx.failures {
            eprintln!("error: {f}");
        }
        std::process::exit(1);
    }
}
