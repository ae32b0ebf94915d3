//! Shared code of the QEMU programs: the smoke scenes and the quick start (both also compiled on the host by
//! `tests/firmware_snapshot.rs`), every propagator configuration as types (for the programs that must cover
//! them all), the SysTick instruction counter, the one exit/panic module every program uses, and the
//! embedded-hal driver demo: a scripted ICM-42688-P on SPI (`device_model`) read by the `icm426xx` driver into
//! the quick start (`driver_demo`; both also compiled on the host).
#![no_std]

pub mod configs;
pub mod device_model;
pub mod driver_demo;
pub mod quickstart;
pub mod scenes;

#[cfg(target_os = "none")]
pub mod exit;
#[cfg(target_os = "none")]
pub mod icount;
