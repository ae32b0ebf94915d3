#![doc = include_str!("../README.md")]
#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs, rust_2018_idioms, unused_qualifications)]
#![cfg_attr(docsrs, feature(doc_cfg))]
// Validation is written as `!(x > 0)`, `!(a <= b)` on purpose: a NaN fails every comparison and must land in
// the error branch. The lint's `partial_cmp` rewrite says the same less directly.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod accumulate;
pub mod config;
mod convert;
pub mod covariance;
mod dispatch;
mod error;
pub mod error_state;
mod exact;
pub mod fixed;
pub mod frontend;
mod gauss;
pub mod input;
mod interop;
pub mod noise;
mod propagator;
mod quat;
mod real;
mod sample;
pub mod scheme;
pub mod stabilize;
mod trig;
mod vec3;

pub use convert::{EulerZxz, EulerZyx};
pub use error::Error;
pub use propagator::{Propagator, Recommended, Refused};
pub use quat::Quat;
pub use real::Real;
pub use sample::{DeltaAngle, GyroSample, Sample};
pub use vec3::Vec3;
