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

/// Where a parameter lives in [`Params`]: a real number or a whole one.
enum Field<'a> {
    Real(&'a mut f64),
    Whole(&'a mut u32),
}

/// Every parameter with its name: the names `--set` takes, in the order `--params` prints them.
fn fields(p: &mut Params) -> [(&'static str, Field<'_>); 19] {
    use Field::{Real, Whole};
    [
        ("sample_period", Real(&mut p.sample_period)),
        ("predict_every", Whole(&mut p.predict_every)),
        ("gyro_arw", Real(&mut p.gyro_arw)),
        ("gyro_bias_walk", Real(&mut p.gyro_bias_walk)),
        ("gyro_scale", Real(&mut p.gyro_scale)),
        ("accel_noise", Real(&mut p.accel_noise)),
        ("accel_floor", Real(&mut p.accel_floor)),
        ("gravity", Real(&mut p.gravity)),
        ("dynamic", Real(&mut p.dynamic)),
        ("rotating", Real(&mut p.rotating)),
        ("gate", Real(&mut p.gate)),
        ("gate_timeout", Real(&mut p.gate_timeout)),
        ("initial_tilt", Real(&mut p.initial_tilt)),
        ("initial_bias", Real(&mut p.initial_bias)),
        ("accel_tau", Real(&mut p.accel_tau)),
        ("update_every", Whole(&mut p.update_every)),
        ("rest_window", Real(&mut p.rest_window)),
        ("rest_gate", Real(&mut p.rest_gate)),
        ("group_delay", Real(&mut p.group_delay)),
    ]
}

/// The parameters as `name = value` lines.
fn describe(p: &Params) -> String {
    let mut p = *p;
    let mut out = String::new();
    for (name, field) in fields(&mut p) {
        match field {
            Field::Real(v) => writeln!(out, "{name} = {v}"),
            Field::Whole(v) => writeln!(out, "{name} = {v}"),
        }
        .unwrap();
    }
    out
}

fn set(p: &mut Params, assignment: &str) -> Result<(), String> {
    let (name, value) = assignment
        .split_once('=')
        .ok_or_else(|| format!("--set {assignment}: expected name=value"))?;
    let v: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("--set {assignment}: not a number"))?;
    let name = name.trim();
    let (_, field) = fields(p)
        .into_iter()
        .find(|(n, _)| *n == name)
        .ok_or_else(|| format!("--set: unknown parameter {name}"))?;
    match field {
        Field::Real(x) => *x = v,
        Field::Whole(x) => {
            *x = value
                .trim()
                .parse()
                .map_err(|_| format!("--set {assignment}: not a whole number"))?
        }
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
