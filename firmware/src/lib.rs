//! Shared code of the QEMU programs: the smoke scenes (also compiled on the host by the snapshot test)
//! and the SysTick instruction counter.
#![no_std]

pub mod scenes;

#[cfg(target_os = "none")]
pub mod icount;
