//! Shared code of the QEMU programs: the smoke scenes and the quick start (both also compiled on the host, where
//! this library's tests compare their results with `expected/`: `firmware/check-host`), every propagator configuration as types (for the programs that must cover
//! them all), the SysTick instruction counter, the one exit/panic module every program uses, and the
//! embedded-hal driver demo: a scripted ICM-42688-P on SPI (`device_model`) read by the `icm426xx` driver into
//! the quick start (`driver_demo`; both also compiled on the host); the example estimator on a BROAD excerpt
//! (`estimator_run`, also compiled on the host); a body turning under gravity as the front end's in-motion
//! estimators see it (`motion`); the rates the instruction-counting programs feed (`bench_input`).
#![cfg_attr(not(test), no_std)]

pub mod bench_input;
pub mod configs;
pub mod device_model;
pub mod driver_demo;
pub mod estimator_run;
pub mod motion;
/// The README's quick start (the crate `quatprop-quickstart`, firmware/quickstart/).
pub use quatprop_quickstart as quickstart;
pub mod scenes;

#[cfg(target_os = "none")]
pub mod exit;
#[cfg(target_os = "none")]
pub mod icount;

/// The host half of the firmware checks (`firmware/check-host`): the scenes, the quick start and the driver
/// demo bit for bit against `expected/`, and the README's quick start as this crate's `quickstart` module.
#[cfg(test)]
mod tests {
    mod quick_start;
    mod snapshot;
}
