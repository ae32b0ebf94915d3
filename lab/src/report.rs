//! The report being written: [`Ctx`] (output directory, scale, progress, the sections so far, their times,
//! failures) and [`finish`], which writes `README.md` from the sections and checks every figure it links.
//! The check of a whole report's files against the registry (`outputs::check`) runs after it, from the
//! command line (`Invocation::finish`).

use crate::quiet::Quiet;
use crate::scale::Scale;
use crate::summary;
use crate::table;
use crate::timing::{self, StudyTimeRow};
use std::path::{Path, PathBuf};
use std::sync::mpsc::RecvTimeoutError;
use std::time::{Duration, Instant};

/// How often a section reports its progress on stderr when stderr is not a terminal.
const PROGRESS_EVERY: Duration = Duration::from_secs(10);

/// What the studies write through: output directory, scale, progress and failure bookkeeping.
pub struct Ctx {
    out: PathBuf,
    /// How big the studies make their grids and horizons.
    pub scale: Scale,
    started: Instant,
    /// A spinner on a terminal's stderr (the section and its work items); hidden when stderr is not a
    /// terminal, where it still counts the work items that [`Ctx::section`]'s lines report.
    bar: indicatif::ProgressBar,
    /// Whether stderr is a terminal (the spinner) or not (a line every [`PROGRESS_EVERY`]).
    on_terminal: bool,
    failures: Vec<String>,
    files: Vec<String>,
    /// The report's sections (Markdown), in order.
    sections: Vec<String>,
    /// Each section's wall and CPU time, in order.
    times: Vec<StudyTimeRow>,
    /// Whether host-time measurements ran at the core's quiet speed (the probe, watched over the process).
    pub quiet: Quiet,
    /// A study run alone that writes a page of its own (`DIR/<page>`, e.g. into docs/) instead of the
    /// lab report's `README.md` ([`Ctx::page`]).
    page: Option<String>,
}

impl Ctx {
    pub fn new(out: PathBuf, scale: Scale) -> Self {
        use std::io::IsTerminal as _;
        let on_terminal = std::io::stderr().is_terminal();
        let bar = if on_terminal {
            let b = indicatif::ProgressBar::new_spinner();
            b.set_style(
                indicatif::ProgressStyle::with_template(
                    "[{elapsed:>4}] {msg:20} {pos:>7} work items",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
            );
            b.enable_steady_tick(std::time::Duration::from_millis(250));
            b
        } else {
            indicatif::ProgressBar::hidden()
        };
        Self {
            out,
            scale,
            started: Instant::now(),
            bar,
            on_terminal,
            failures: Vec::new(),
            files: Vec::new(),
            sections: Vec::new(),
            times: Vec::new(),
            quiet: Quiet::new(),
            page: None,
        }
    }

    /// Makes this run write its sections to `DIR/file` as a page of their own (with the command that
    /// wrote it, no run-time table) instead of `DIR/README.md`: for a study run alone into docs/.
    pub fn page(&mut self, file: &str) {
        self.page = Some(file.to_string());
    }

    /// The Markdown file this run writes (`README.md` unless a study asked for a page).
    pub fn markdown_file(&self) -> &str {
        self.page.as_deref().unwrap_or("README.md")
    }

    /// Whether a study asked for a page of its own ([`Ctx::page`]) instead of the report's `README.md`.
    pub fn writes_page(&self) -> bool {
        self.page.is_some()
    }

    /// The output directory.
    pub fn out(&self) -> &Path {
        &self.out
    }

    /// The CSV files written so far.
    pub fn files(&self) -> &[String] {
        &self.files
    }

    /// Runs one timed part of a study (a row of the run-time table, `name`) whose Markdown `f` returns; the
    /// Markdown becomes the report's next section.
    pub fn section(&mut self, name: &str, f: impl FnOnce(&mut Ctx) -> String) {
        self.bar.set_message(name.to_string());
        let clock = timing::Clock::start();
        // Without a terminal (CI, a pipe, a log file) a line every PROGRESS_EVERY while the section runs:
        // its time so far and the work items done in it.
        let (stop, stopped) = std::sync::mpsc::channel::<()>();
        let ticker = (!self.on_terminal).then(|| {
            let (name, bar, from) = (name.to_string(), self.bar.clone(), self.bar.position());
            let start = Instant::now();
            std::thread::spawn(move || {
                while stopped.recv_timeout(PROGRESS_EVERY) == Err(RecvTimeoutError::Timeout) {
                    eprintln!(
                        "{name}: {:.0} s so far, {} work items",
                        start.elapsed().as_secs_f64(),
                        bar.position() - from
                    );
                }
            })
        });
        let s = f(self);
        drop(stop);
        if let Some(t) = ticker {
            let _ = t.join();
        }
        let row = clock.row(name);
        self.bar.suspend(|| {
            eprintln!(
                "{name}: done in {:.1} s (CPU {:.1} s)",
                row.wall_s, row.cpu_s
            )
        });
        self.times.push(row);
        self.sections.push(s);
    }

    /// One unit of work done (the spinner on a terminal, the progress lines otherwise).
    pub fn tick(&mut self) {
        self.bar.inc(1);
    }

    /// The progress bar, for work that runs in parallel (`inc` from any thread).
    pub fn progress(&self) -> indicatif::ProgressBar {
        self.bar.clone()
    }

    /// Writes a CSV file of typed rows (failures are reported at the end).
    pub fn rows<R: table::Csv>(&mut self, rows: &[R]) {
        match table::write(&self.out.join(R::FILE), rows) {
            Ok(()) => self.files.push(R::FILE.to_string()),
            Err(e) => self.failures.push(e),
        }
    }

    /// Writes a table's CSV and returns the table as rendered from the file read back (with its markers).
    pub fn table<R: table::Table>(&mut self, rows: &[R]) -> String {
        self.rows(rows);
        table::rendered::<R>(&self.out).unwrap_or_else(|e| {
            self.failures.push(e.clone());
            format!("(table {} missing: {e})\n", R::FILE)
        })
    }

    /// Runs a plotting closure that writes `<name>.svg` and `<name>.png`.
    pub fn plot(&mut self, f: impl FnOnce(&Path) -> std::io::Result<()>) {
        if let Err(e) = f(&self.out) {
            self.failures.push(format!("plot: {e}"));
        }
    }

    /// Records a failure of a study's own check (reported at the end; the run exits non-zero).
    pub fn fail(&mut self, what: String) {
        self.failures.push(what);
    }

    /// Clears the progress bar (before the final messages).
    pub fn clear_progress(&self) {
        self.bar.finish_and_clear();
    }
}

/// Writes `README.md` (or the page a study asked for) from the sections and checks that every figure they
/// link exists; the failures so far.
pub fn finish(ctx: &mut Ctx, command: &str) -> Vec<String> {
    let out = ctx.out.clone();
    let times = std::mem::take(&mut ctx.times);
    let sections = std::mem::take(&mut ctx.sections);
    if let Some(page) = ctx.page.clone() {
        let md = format!(
            "_Written by `cargo run --release -p quatprop-lab -- {command}` ({:.0} s on this machine); do not \
             edit by hand, re-run it._\n\n{}",
            ctx.started.elapsed().as_secs_f64(),
            sections.join("\n")
        );
        if let Err(e) = std::fs::write(out.join(&page), md) {
            ctx.failures.push(format!("{page}: {e}"));
        }
        check_figures(ctx, &out, &sections);
        return ctx.failures.clone();
    }
    let run_time = format!(
        "### Run time\n\nEach study's wall time and this process's CPU time over all its threads: CPU / wall \
         near the thread count means the sweeps ran in parallel; near 1, serially (the timing measurements \
         always are). On a shared machine wall time also counts the other processes; CPU time does not. \
         `RAYON_NUM_THREADS=1` runs every sweep serially, for comparison.\n\n{}",
        ctx.table(&times)
    );
    // The opening summary, when this run wrote the grid it is computed from.
    let summary = if ctx.files.iter().any(|f| f == summary::GRID_FILE) {
        match summary::summary(&out, &crate::m4f_bench::path()) {
            Ok((text, rows)) => format!("{text}{}", ctx.table(&rows)),
            Err(e) => {
                ctx.failures.push(format!("summary: {e}"));
                String::new()
            }
        }
    } else {
        String::new()
    };
    let md = format!(
        "# quatprop lab report\n\nGenerated by `cargo run --release -p quatprop-lab -- {command}` in {:.1} s \
         (wall time on this machine, shared; the accuracy sweeps on {} threads, every timing measurement \
         serial).\n\n{summary}\n{}\n{run_time}\n\
         CSV data: {}.\n",
        ctx.started.elapsed().as_secs_f64(),
        rayon::current_num_threads(),
        sections.join("\n"),
        ctx.files.join(", ")
    );
    if let Err(e) = std::fs::write(out.join("README.md"), md) {
        ctx.failures.push(format!("README.md: {e}"));
    }
    check_figures(ctx, &out, &sections);
    ctx.failures.clone()
}

/// Every figure the sections link must exist, as PNG and SVG.
fn check_figures(ctx: &mut Ctx, out: &Path, sections: &[String]) {
    for s in sections {
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
}
