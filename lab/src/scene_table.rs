//! Every scene, every configuration of the work-precision study, f32, one gyro sample per step at 1 kHz:
//! attitude error after the horizon against the exact motion.

use crate::rigid_body::RigidBody;
use crate::scenes::{fast_spin, symmetric_top, Coning, EarthRate, RateStep, Scene};
use crate::work_precision::CONFIGS;
use crate::Ctx;
use quatprop::{Quat, Vec3};
use std::fmt::Write as _;

pub fn scene_table(ctx: &mut Ctx, quick: bool) -> String {
    let horizon = if quick { 2.37 } else { 20.37 };
    let hz = 1000.0;
    let scenes: Vec<Box<dyn Scene>> = vec![
        Box::new(Coning),
        Box::new(symmetric_top()),
        Box::new(RigidBody::asymmetric(horizon + 1.0)),
        Box::new(fast_spin()),
        Box::new(RateStep),
        Box::new(EarthRate),
    ];
    let mut head = String::from("| configuration |");
    let mut sep = String::from("|---|");
    for s in &scenes {
        let _ = write!(head, " {} |", s.name());
        sep.push_str("---|");
    }
    let mut rows = vec![String::new(); CONFIGS.len()];
    for (i, (name, _, _)) in CONFIGS.iter().enumerate() {
        rows[i] = format!("| {name} |");
    }
    let mut csv = String::from("scene,config,error_rad\n");
    for s in &scenes {
        let steps = (horizon * hz) as usize;
        let dt = 1.0 / hz;
        let samples: Vec<Vec3<f32>> = (0..=steps)
            .map(|k| Vec3::<f32>::from_f64(s.rate(k as f64 * dt)))
            .collect();
        let q0 = Quat::<f32>::from_f64(s.attitude(0.0));
        let exact = s.attitude(steps as f64 * dt);
        for (i, (name, _, run)) in CONFIGS.iter().enumerate() {
            ctx.tick();
            let q = run(&samples, dt as f32, q0);
            let e = q
                .to_f64()
                .normalized()
                .map_or(f64::NAN, |u| u.angle_to(exact));
            let _ = write!(rows[i], " {e:.2e} |");
            let _ = writeln!(csv, "{},{name},{e}", s.name());
        }
    }
    ctx.csv("scenes_f32_1khz.csv", &csv);
    format!(
        "### Every scene, f32, one gyro sample per step at 1 kHz\n\nAttitude error (rad) after {horizon} s against the \
         exact motion; every configuration fed the same f32 samples. References are closed forms (the scenes' \
         rates are checked against their attitudes' body rates by a unit test).\n\n{head}\n{sep}\n{}\n",
        rows.join("\n")
    )
}
