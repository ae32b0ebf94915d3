//! Shared code of the QEMU programs: the smoke scenes and the quick start (both also compiled on the host by
//! `tests/firmware_snapshot.rs`), every propagator configuration as types (for the programs that must cover
//! them all), the SysTick instruction counter, and the one exit/panic module every program uses.
#![no_std]

pub mod configs;
pub mod quickstart;
pub mod scenes;

#[cfg(target_os = "none")]
pub mod exit;
#[cfg(target_os = "none")]
pub mod icount;
