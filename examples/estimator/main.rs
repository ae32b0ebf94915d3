//! An attitude estimator on quatprop's predict step (gyroscope + accelerometer, 6D), run over a CSV file.
//!
//! ```text
//! cargo run --release --example estimator -- <input.csv> <output.csv> [--set name=value ...]
//! cargo run --release --example estimator -- --params [--set name=value ...]
//! ```
//!
//! - **Input**: one sample a line, `t,gx,gy,gz,ax,ay,az`: time (s), body rates (rad/s), specific force
//!   (m/s², `+g` up at rest). A first line that does not parse as numbers is a header and is skipped. The
//!   samples are taken as evenly spaced: the period is `(t_last − t_first)/(N − 1)` (the timestamps are
//!   not otherwise read).
//! - **Output**: one line per input sample, after it is taken:
//!   `t,qw,qx,qy,qz,bx,by,bz,sigma_inclination,pxx,pxy,pyy`
//!   — the attitude (body to reference, reference z up, heading the filter's own; Hamilton, scalar first),
//!   the gyro bias estimate (rad/s) and the inclination's 1σ (rad), all as the `f32` filter holds them
//!   (printed in the shortest form that reads back to the same `f32`).
//! - **Parameters**: [`filter::Params::mems`] for the input's period; `--set name=value` overrides one
//!   (the names of `--params`' output). `--params` prints the set and exits.
//! - A sample the filter refuses (a non-finite value, ...) is reported on stderr and its line carries the
//!   state as it was; the exit code is then 2.
//!
//! The filter itself is `filter.rs` beside this file: `no_std`, `f32`, no heap, for the firmware too.

// The filter's whole API is for its users (the firmware, tests/estimator.rs); this binary uses part of it.
#[allow(dead_code)]
mod filter;

use std::fmt::Write as _;
use std::process::ExitCode;

use filter::{Filter, Params};
use quatprop::Vec3;

fn usage() -> ExitCode {
    eprintln!(
        "usage: estimator <input.csv> <output.csv> [--set name=value ...]\n       estimator --params [--set name=value ...]"
    );
    ExitCode::from(1)
}

/// The parameters as `name = value` lines.
fn describe(p: &Params) -> String {
    format!(
        "sample_period = {}\npredict_every = {}\ngyro_arw = {}\ngyro_bias_walk = {}\ngyro_scale = {}\naccel_noise = {}\n\
         accel_floor = {}\ngravity = {}\ndynamic = {}\nrotating = {}\ngate = {}\ngate_timeout = {}\ninitial_tilt = {}\n\
         initial_bias = {}\naccel_tau = {}\nupdate_every = {}\nrest_window = {}\nrest_gate = {}\ngroup_delay = {}\n",
        p.sample_period,
        p.predict_every,
        p.gyro_arw,
        p.gyro_bias_walk,
        p.gyro_scale,
        p.accel_noise,
        p.accel_floor,
        p.gravity,
        p.dynamic,
        p.rotating,
        p.gate,
        p.gate_timeout,
        p.initial_tilt,
        p.initial_bias,
        p.accel_tau,
        p.update_every,
        p.rest_window,
        p.rest_gate,
        p.group_delay
    )
}

fn set(p: &mut Params, assignment: &str) -> Result<(), String> {
    let (name, value) = assignment
        .split_once('=')
        .ok_or_else(|| format!("--set {assignment}: expected name=value"))?;
    let v: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("--set {assignment}: not a number"))?;
    match name.trim() {
        "sample_period" => p.sample_period = v,
        "predict_every" => {
            p.predict_every = value
                .trim()
                .parse()
                .map_err(|_| format!("--set {assignment}: not a whole number"))?
        }
        "gyro_arw" => p.gyro_arw = v,
        "gyro_bias_walk" => p.gyro_bias_walk = v,
        "gyro_scale" => p.gyro_scale = v,
        "accel_noise" => p.accel_noise = v,
        "accel_floor" => p.accel_floor = v,
        "gravity" => p.gravity = v,
        "dynamic" => p.dynamic = v,
        "rotating" => p.rotating = v,
        "gate" => p.gate = v,
        "gate_timeout" => p.gate_timeout = v,
        "initial_tilt" => p.initial_tilt = v,
        "initial_bias" => p.initial_bias = v,
        "accel_tau" => p.accel_tau = v,
        "update_every" => {
            p.update_every = value
                .trim()
                .parse()
                .map_err(|_| format!("--set {assignment}: not a whole number"))?
        }
        "rest_window" => p.rest_window = v,
        "rest_gate" => p.rest_gate = v,
        "group_delay" => p.group_delay = v,
        other => return Err(format!("--set: unknown parameter {other}")),
    }
    Ok(())
}

fn read(path: &str) -> Result<Vec<[f64; 7]>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let fields: Result<Vec<f64>, _> = line.split(',').map(|f| f.trim().parse()).collect();
        match fields {
            Ok(f) if f.len() == 7 => rows.push([f[0], f[1], f[2], f[3], f[4], f[5], f[6]]),
            _ if i == 0 => {} // a header
            _ => return Err(format!("{path}:{}: expected 7 numbers", i + 1)),
        }
    }
    if rows.len() < 2 {
        return Err(format!("{path}: fewer than 2 samples"));
    }
    Ok(rows)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut files = Vec::new();
    let mut sets = Vec::new();
    let mut print_params = false;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--set" => match it.next() {
                Some(s) => sets.push(s.clone()),
                None => return usage(),
            },
            "--params" => print_params = true,
            "-h" | "--help" => return usage(),
            _ => files.push(a.clone()),
        }
    }
    let rows = if print_params {
        None
    } else if files.len() == 2 {
        match read(&files[0]) {
            Ok(r) => Some(r),
            Err(e) => {
                eprintln!("estimator: {e}");
                return ExitCode::from(1);
            }
        }
    } else {
        return usage();
    };
    let period = match &rows {
        Some(r) => (r[r.len() - 1][0] - r[0][0]) / (r.len() - 1) as f64,
        None => 1.0 / (2000.0 / 7.0), // BROAD's rate, for --params alone
    };
    let mut params = Params::mems(period);
    for s in &sets {
        if let Err(e) = set(&mut params, s) {
            eprintln!("estimator: {e}");
            return ExitCode::from(1);
        }
    }
    if print_params {
        print!("{}", describe(&params));
        return ExitCode::SUCCESS;
    }
    let Some(rows) = rows else {
        return usage();
    };
    let mut filter = match Filter::<f32>::new(params) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("estimator: {e}");
            return ExitCode::from(1);
        }
    };
    let mut out = String::with_capacity(rows.len() * 120);
    out.push_str("t,qw,qx,qy,qz,bx,by,bz,sigma_inclination,pxx,pxy,pyy\n");
    let mut refused = 0_u64;
    for (k, r) in rows.iter().enumerate() {
        let v = |i: usize| Vec3::new(r[i] as f32, r[i + 1] as f32, r[i + 2] as f32);
        if let Err(e) = filter.push(v(1), v(4)) {
            refused += 1;
            if refused <= 10 {
                eprintln!("estimator: sample {k} (t = {}): {e}", r[0]);
            }
        }
        let q = filter.attitude();
        let b = filter.bias();
        let sigma = filter.inclination_sigma().unwrap_or(f32::NAN);
        let p = filter.inclination_covariance().unwrap_or([f32::NAN; 3]);
        // Writing to a String cannot fail.
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            r[0], q.w, q.x, q.y, q.z, b.x, b.y, b.z, sigma, p[0], p[1], p[2]
        );
    }
    if let Err(e) = std::fs::write(&files[1], out) {
        eprintln!("estimator: {}: {e}", files[1]);
        return ExitCode::from(1);
    }
    let c = filter.counts();
    eprintln!(
        "estimator: {} samples, {} predicts, {} updates ({} forced), {} rejected, {} rest updates ({} restarts), {} refused",
        c.samples, c.predicts, c.updates, c.forced, c.rejected, c.rests, c.restarts, refused
    );
    if refused > 0 {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    }
}
