//! Every scene × the comparison set, f32, one gyro sample per step at 1 kHz: attitude error after the horizon
//! against the exact motion, with every refused step reported.

use crate::configs::{error_kind, scheme_set, Config};
use crate::report::Ctx;
use crate::scene::{attitude_error, stream, Scene};
use crate::scenes;
use crate::study::{CsvFile, NoArgs, Study};
use crate::table::{self, cell, Csv, Table};
use quatprop::Quat;
use serde::{Deserialize, Serialize};

/// Every scene at 1 kHz in f32 (sub-command `scenes`).
pub struct Scenes;

impl Study for Scenes {
    type Args = NoArgs;
    const NAME: &'static str = "scenes";
    const ABOUT: &'static str = "Every scene × the comparison set at 1 kHz, f32";
    const CSV: &'static [CsvFile] = &[CsvFile::table::<SceneRow>()];
    fn run(&self, ctx: &mut Ctx, _: &NoArgs) {
        // Seconds of each scene: the full 20.37 s cost a fraction of a second.
        let horizon = ctx.scale.pick(2.37, 20.37, 20.37);
        let catalogue = scenes::catalogue(70.0);
        ctx.section("scenes", |c| scene_table(c, &catalogue, horizon));
    }
}

/// One configuration on one scene.
#[derive(Serialize, Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SceneRow {
    pub scene: String,
    pub scene_name: String,
    pub configuration: String,
    /// Attitude error after the horizon (rad); empty when the configuration does not exist.
    pub error_rad: Option<f64>,
    pub refused_steps: u64,
    /// The first refusal's error (empty: none).
    pub first_error: String,
    /// Its kind, in words (empty: none).
    pub error_kind: String,
}
// A row type names its file and renders its table through the `Csv` and `Table` impls (alike in each).
impl Csv for SceneRow {
    const FILE: &'static str = "scenes_f32_1khz.csv";
}
impl Table for SceneRow {
    /// Configurations down, scenes across, in the order of the file.
    fn render(rows: &[Self]) -> String {
        let scenes = table::distinct(rows, |r| r.scene_name.as_str());
        let configs = table::distinct(rows, |r| r.configuration.as_str());
        let mut t = table::header(&[&["configuration"], &scenes[..]].concat());
        for c in &configs {
            t += &format!("| {} |", cell(c));
            for s in &scenes {
                let r = rows
                    .iter()
                    .find(|r| r.configuration == *c && r.scene_name == *s);
                t += &match r {
                    Some(r) => match r.error_rad {
                        None => " – |".to_string(),
                        Some(e) if r.refused_steps > 0 => format!(
                            " {e:.2e}, **{} steps refused** ({}) |",
                            r.refused_steps, r.error_kind
                        ),
                        Some(e) => format!(" {e:.2e} |"),
                    },
                    None => " – |".to_string(),
                };
            }
            t += "\n";
        }
        t
    }
}

fn scene_table(ctx: &mut Ctx, scenes: &[Box<dyn Scene>], horizon: f64) -> String {
    let hz = 1000;
    let configs: Vec<Config> = scheme_set();
    let mut rows = Vec::new();
    for s in scenes {
        let (samples, dt) = stream::<f32>(s.as_ref(), hz, horizon);
        let n = samples.len() - 1;
        let q0 = Quat::<f32>::from_f64(s.attitude(0.0));
        let exact = s.attitude(n as f64 * dt);
        for c in &configs {
            ctx.tick();
            let mut row = SceneRow {
                scene: s.key().into(),
                scene_name: s.name().into(),
                configuration: c.label(),
                error_rad: None,
                refused_steps: 0,
                first_error: String::new(),
                error_kind: String::new(),
            };
            if let Ok(mut run) = c.build::<f32>(q0, samples[1].dt) {
                run.feed(&samples);
                let (refused, first) = run.refused();
                row.error_rad = Some(attitude_error(run.attitude(), exact));
                row.refused_steps = refused;
                if first.is_some() {
                    row.error_kind = error_kind(first);
                }
                row.first_error = first.map_or(String::new(), |e| format!("{e:?}"));
            }
            rows.push(row);
        }
    }
    let table = ctx.table(&rows);
    format!(
        "### Every scene, f32, one gyro sample per step at 1 kHz\n\nAttitude error (rad) after {horizon} s against \
         the exact motion; every configuration fed the same f32 samples. References are closed forms (the scenes' \
         rates are checked against their attitudes' body rates by unit tests; the rigid bodies' also against \
         Euler's equations and a tight Magnus-4 run). A refused step (beyond the scheme's stability bound) leaves \
         the attitude where it was and is counted: at 1e4 rad/s and 1 kHz (H|ω| = 10) only the exponential map \
         may step.\n\n{table}"
    )
}
