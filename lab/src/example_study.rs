//! The minimal study of lab/README.md ("Adding a study"), verbatim: the tests compile it, check that the
//! README shows this file's code, and run it as the registry would. It is not in the registry (it would
//! be `example_study::InputModels,` in `studies/mod.rs`, with this file under `studies/`).

use crate::configs::{Config, Input, Stab};
use crate::report::Ctx;
use crate::scene::{attitude_error, stream, Scene};
use crate::scenes::Coning;
use crate::study::{CsvFile, Study};
use crate::table::{self, Csv, Table};
use quatprop::{scheme::SchemeKind, Quat};
use serde::{Deserialize, Serialize};

/// The study (a unit struct: the registry holds a reference to it).
pub struct InputModels;

/// Its sub-command's arguments (clap derive; `study::NoArgs` when there are none).
#[derive(clap::Args, Debug, Clone)]
pub struct Args {
    /// Gyro sample rate (Hz).
    #[arg(long, default_value_t = 1000)]
    pub rate: u32,
}

/// One row of its CSV file, which the report also shows as a table.
#[derive(Serialize, Deserialize, Debug, Clone)]
pub struct Row {
    pub input: String,
    pub final_error_rad: f64,
}

impl Csv for Row {
    const FILE: &'static str = "example_inputs.csv";
}

impl Table for Row {
    fn render(rows: &[Self]) -> String {
        let mut t = table::header(&["input model", "final error (rad)"]);
        for r in rows {
            t += &format!("| {} | {:.2e} |\n", r.input, r.final_error_rad);
        }
        t
    }
}

impl Study for InputModels {
    type Args = Args;
    const NAME: &'static str = "example-inputs";
    const ABOUT: &'static str =
        "Example: the final error of each input model on coning, ExpMap in f32";
    const CSV: &'static [CsvFile] = &[CsvFile::table::<Row>()];
    fn run(&self, ctx: &mut Ctx, args: &Args) {
        // Seconds of coning: what each scale can afford.
        let horizon = ctx.scale.pick(1.37, 10.37, 100.37);
        let hz = args.rate;
        ctx.section("example inputs", |ctx| {
            let (samples, dt) = stream::<f32>(&Coning, hz, horizon);
            let exact = Coning.attitude(dt * (samples.len() - 1) as f64);
            let q0 = Quat::<f32>::from_f64(Coning.attitude(0.0));
            let mut rows = Vec::new();
            for input in Input::ALL {
                let config = Config::qp(SchemeKind::ExpMap, Stab::FirstOrder, input);
                let mut run = config
                    .build::<f32>(q0, samples[1].dt)
                    .expect("ExpMap exists");
                run.feed(&samples);
                rows.push(Row {
                    input: input.name().into(),
                    final_error_rad: attitude_error(run.attitude(), exact),
                });
            }
            let table = ctx.table(&rows);
            format!("### Example: input models on coning\n\n{hz} Hz, {horizon} s.\n\n{table}")
        });
    }
}
