//! quatprop lab: the report a user runs to choose a scheme.
//!
//! `cargo run --release -p quatprop-lab -- report [--quick] [--out DIR]` writes `DIR/README.md` (default
//! `report/`) with plots (SVG and PNG) and CSV files. Sub-commands run one study, with parameters (scene,
//! schemes, stabilizers, inputs, precision, rates, horizon, steps): see `quatprop-lab help`. `--quick` shrinks
//! every study (CI checks that each one runs and writes its figures).

mod atlas;
mod baumgarte_sweep;
mod configs;
mod coning_drift;
mod geiger;
mod long_horizon;
mod peers;
mod plot;
mod rigid_body;
mod scene_table;
mod scenes;
mod sensor;
mod unchecked;
mod work_precision;

use quatprop::scheme::SchemeKind;
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
        "usage: quatprop-lab <command> [options]\n\
         commands:\n\
         report          every study below: DIR/README.md + plots (SVG, PNG) + CSV (default DIR report/)\n\
         geiger          the seed paper's Fig. 1 and Fig. 2, and Baumgarte k swept to divergence in propagation\n\
         atlas           per-step norm factor and error against the step angle, measured stability bounds\n\
         work-precision  error against cost per scene and precision, quatprop against the peers\n\
         scenes          every scene x the comparison set at 1 kHz, f32\n\
         sensor          sensor realism: noise, bias, 16-bit counts, saturation, dropped samples, dt jitter\n\
         coning-drift    coning drift coefficient of every rate scheme and input model\n\
         long-horizon    error and |N| growth to 1e8 steps (1e9 with --long), f32 and f64, every post-step stabilizer\n\
         options:\n\
         --quick                 small grids and horizons (what CI runs)\n\
         --long                  long-horizon to 1e9 steps\n\
         --out DIR               output directory\n\
         --scene a,b             scenes by key: {}\n\
         --schemes a,b           {}\n\
         --stabilizers a,b       Off, Normalize, FirstOrder, Every16 (or EveryN), Baumgarte (k = 0.5) or Baumgarte=K\n\
         \x20                       (Baumgarte: the Runge-Kutta schemes only)\n\
         --inputs a,b            hold, linear, history, mid\n\
         --precision a,b         f32, f64\n\
         --rates a,b             gyro sample rates (Hz) of a work-precision sweep\n\
         --horizon S             seconds per run (work-precision, sensor)\n\
         --steps N               steps of long-horizon (overrides the default 1e8)",
        scenes::catalogue(0.0)
            .iter()
            .map(|s| s.key())
            .collect::<Vec<_>>()
            .join(", "),
        SchemeKind::ALL
            .iter()
            .map(|&m| configs::scheme_name(m))
            .collect::<Vec<_>>()
            .join(", ")
    );
    std::process::exit(2)
}

/// Splits a comma-separated option value and parses each item, or exits with the usage.
fn list<T>(v: Option<&String>, what: &str, parse: impl Fn(&str) -> Option<T>) -> Vec<T> {
    let Some(v) = v else { usage() };
    v.split(',')
        .map(|x| {
            parse(x.trim()).unwrap_or_else(|| {
                eprintln!("unknown {what}: {x}");
                usage()
            })
        })
        .collect()
}

fn parse_stab(s: &str) -> Option<configs::Stab> {
    use configs::Stab;
    Some(match s {
        "Off" => Stab::Off,
        "Normalize" => Stab::Normalize,
        "FirstOrder" => Stab::FirstOrder,
        "Baumgarte" => Stab::Baumgarte(0.5),
        _ => {
            if let Some(n) = s.strip_prefix("Every") {
                Stab::Every(n.trim_matches(|c| c == '(' || c == ')').parse().ok()?)
            } else {
                Stab::Baumgarte(s.strip_prefix("Baumgarte=")?.parse().ok()?)
            }
        }
    })
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(cmd) = args.first().cloned() else {
        usage()
    };
    let mut quick = false;
    let mut long = false;
    let mut steps: Option<u64> = None;
    let mut out = PathBuf::from("report");
    let mut opt = work_precision::Options::default();
    let mut i = 1;
    while i < args.len() {
        let value = args.get(i + 1);
        let mut took_value = true;
        match args[i].as_str() {
            "--quick" => {
                quick = true;
                took_value = false;
            }
            "--long" => {
                long = true;
                took_value = false;
            }
            "--out" => out = value.map(PathBuf::from).unwrap_or_else(|| usage()),
            "--scene" => opt.scenes = list(value, "scene", |s| Some(s.to_string())),
            "--schemes" => {
                opt.methods = list(value, "scheme", |s| {
                    SchemeKind::ALL
                        .into_iter()
                        .find(|&m| configs::scheme_name(m).eq_ignore_ascii_case(s))
                })
            }
            "--stabilizers" => opt.stabs = list(value, "stabilizer", parse_stab),
            "--inputs" => {
                opt.inputs = list(value, "input", |s| {
                    configs::Input::ALL.into_iter().find(|i| i.name() == s)
                })
            }
            "--precision" => {
                opt.precisions = list(value, "precision", |s| match s {
                    "f32" => Some(work_precision::Precision::F32),
                    "f64" => Some(work_precision::Precision::F64),
                    _ => None,
                })
            }
            "--rates" => opt.rates = list(value, "rate", |s| s.parse().ok().filter(|&r| r > 0)),
            "--horizon" => {
                opt.horizon = Some(
                    list(value, "horizon", |s| {
                        s.parse::<f64>().ok().filter(|h| *h > 0.0 && h.is_finite())
                    })[0],
                )
            }
            "--steps" => {
                steps = Some(
                    list(value, "step count", |s| {
                        s.parse::<f64>()
                            .ok()
                            .filter(|n| *n >= 1e3)
                            .map(|n| n as u64)
                    })[0],
                )
            }
            other => {
                eprintln!("unknown argument: {other}");
                usage()
            }
        }
        i += if took_value { 2 } else { 1 };
    }
    opt.quick = quick;
    let known: Vec<&str> = scenes::catalogue(0.0).iter().map(|s| s.key()).collect();
    if let Some(bad) = opt.scenes.iter().find(|s| !known.contains(&s.as_str())) {
        eprintln!("unknown scene: {bad}");
        usage()
    }
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("cannot create {}: {e}", out.display());
        std::process::exit(1);
    }
    let mut ctx = Ctx::new(out.clone());
    let horizon: u64 = steps.unwrap_or(if quick {
        1_000_000
    } else if long {
        1_000_000_000
    } else {
        100_000_000
    });
    let mut sections = Vec::new();
    let run = |ctx: &mut Ctx, name: &'static str, f: &mut dyn FnMut(&mut Ctx) -> String| {
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
    // The rigid bodies' references are tabulated once, long enough for every study.
    let catalogue = scenes::catalogue(opt.horizon.unwrap_or(0.0).max(70.0));
    let coning = scenes::Coning;
    let all = cmd == "report";
    let mut did = false;
    if all || cmd == "geiger" {
        did = true;
        sections.push(run(&mut ctx, "geiger fig 1", &mut geiger::figure1));
        sections.push(run(&mut ctx, "geiger fig 2", &mut |c| {
            geiger::figure2(c, quick)
        }));
        sections.push(run(&mut ctx, "baumgarte sweep", &mut |c| {
            baumgarte_sweep::baumgarte_sweep(c, quick)
        }));
    }
    if all || cmd == "atlas" {
        did = true;
        sections.push(run(&mut ctx, "stability atlas", &mut |c| {
            atlas::atlas(c, quick)
        }));
    }
    if all || cmd == "work-precision" {
        did = true;
        if opt.scenes.is_empty() || opt.scenes.iter().any(|s| s == "coning") {
            let mut o = opt.clone();
            o.precisions = vec![work_precision::Precision::F32];
            sections.push(run(&mut ctx, "work-precision", &mut |c| {
                work_precision::headline(c, &coning, &o)
            }));
        }
        sections.push(run(&mut ctx, "wp per scene", &mut |c| {
            work_precision::per_scene(c, &catalogue, &opt)
        }));
        if opt.scenes.is_empty() {
            sections.push(run(&mut ctx, "wp stabilizers", &mut |c| {
                work_precision::stabilizers(c, &coning, &opt)
            }));
            sections.push(run(&mut ctx, "wp grid + M4F", &mut |c| {
                work_precision::grid_with_m4f(c, &coning, &opt)
            }));
        }
    }
    if all || cmd == "scenes" {
        did = true;
        sections.push(run(&mut ctx, "scenes", &mut |c| {
            scene_table::scene_table(c, &catalogue, quick)
        }));
    }
    if all || cmd == "sensor" {
        did = true;
        sections.push(run(&mut ctx, "sensor realism", &mut |c| {
            sensor::sensor_study(c, &catalogue, &opt)
        }));
    }
    if all || cmd == "coning-drift" {
        did = true;
        sections.push(run(&mut ctx, "coning drift", &mut |c| {
            coning_drift::coning_drift(c, quick)
        }));
    }
    if all || cmd == "long-horizon" {
        did = true;
        sections.push(run(&mut ctx, "long horizon", &mut |c| {
            long_horizon::long_horizon(c, horizon)
        }));
    }
    if !did {
        usage()
    }
    let md = format!(
        "# quatprop lab report\n\nGenerated by `cargo run --release -p quatprop-lab -- {}` in {:.1} s.\n\n{}\n\
         CSV data: {}.\n",
        args.join(" "),
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
