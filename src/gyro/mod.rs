//! Gyro drivers over `embedded-hal` 1.0 (feature `embedded-hal`), delivering [`crate::GyroSample`]s in rad/s.

mod mpu6050;

pub use mpu6050::{GyroError, GyroRange, Mpu6050, Mpu6050Model};
