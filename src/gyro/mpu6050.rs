//! InvenSense MPU-6050 / MPU-6500 / MPU-9250 gyro over I²C (`embedded_hal::i2c::I2c`).
//!
//! Registers used (MPU-6000/6050 Register Map rev. 4.2; identical in the MPU-6500/9250 maps):
//!
//! | reg | name | use |
//! |---|---|---|
//! | 0x75 | `WHO_AM_I` | identifies the part: 0x68 (MPU-6050), 0x70 (MPU-6500), 0x71 (MPU-9250) |
//! | 0x6B | `PWR_MGMT_1` | written 0x01: leave sleep, clock from the X-gyro PLL |
//! | 0x1B | `GYRO_CONFIG` | bits 4:3 `FS_SEL`: full scale ±250, ±500, ±1000, ±2000 °/s |
//! | 0x43…0x48 | `GYRO_XOUT_H` … `GYRO_ZOUT_L` | rate, three big-endian two's-complement i16, read in one burst |
//!
//! Sensitivity (LSB per °/s) by `FS_SEL`: 131, 65.5, 32.8, 16.4. A sample is flagged saturated when any
//! axis reads −32768 or +32767 (the converter's rails).

use crate::{GyroSample, Vec3};
use core::fmt;
use embedded_hal::i2c::I2c;

const WHO_AM_I: u8 = 0x75;
const PWR_MGMT_1: u8 = 0x6B;
const GYRO_CONFIG: u8 = 0x1B;
const GYRO_XOUT_H: u8 = 0x43;
/// `PWR_MGMT_1`: SLEEP = 0, CLKSEL = 1 (PLL with X-axis gyro reference).
const WAKE_PLL_X: u8 = 0x01;

/// Full-scale range of the gyro.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum GyroRange {
    /// ±250 °/s, 131 LSB/(°/s).
    Dps250,
    /// ±500 °/s, 65.5 LSB/(°/s).
    Dps500,
    /// ±1000 °/s, 32.8 LSB/(°/s).
    Dps1000,
    /// ±2000 °/s, 16.4 LSB/(°/s).
    Dps2000,
}

impl GyroRange {
    /// `FS_SEL` field value.
    fn fs_sel(self) -> u8 {
        match self {
            GyroRange::Dps250 => 0,
            GyroRange::Dps500 => 1,
            GyroRange::Dps1000 => 2,
            GyroRange::Dps2000 => 3,
        }
    }

    /// Sensitivity in LSB per °/s (datasheet table 6.1).
    #[must_use]
    pub fn lsb_per_dps(self) -> f32 {
        match self {
            GyroRange::Dps250 => 131.0,
            GyroRange::Dps500 => 65.5,
            GyroRange::Dps1000 => 32.8,
            GyroRange::Dps2000 => 16.4,
        }
    }

    /// rad/s per LSB.
    #[must_use]
    pub fn rad_per_lsb(self) -> f32 {
        (core::f64::consts::PI / 180.0) as f32 / self.lsb_per_dps()
    }
}

/// Which part answered `WHO_AM_I`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Mpu6050Model {
    /// MPU-6050 (0x68).
    Mpu6050,
    /// MPU-6500 (0x70).
    Mpu6500,
    /// MPU-9250 (0x71).
    Mpu9250,
}

/// A driver error: the bus failed, or the device is not one of the supported parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum GyroError<E> {
    /// The I²C transaction failed (the bus's own error).
    Bus(E),
    /// `WHO_AM_I` returned an unknown value.
    UnknownDevice(u8),
}

impl<E: fmt::Debug> fmt::Display for GyroError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GyroError::Bus(e) => write!(f, "I2C bus error: {e:?}"),
            GyroError::UnknownDevice(id) => write!(f, "unknown WHO_AM_I 0x{id:02x}"),
        }
    }
}

impl<E: fmt::Debug> core::error::Error for GyroError<E> {}

/// MPU-6050-family gyro on an I²C bus.
#[derive(Debug)]
pub struct Mpu6050<I2C> {
    i2c: I2C,
    address: u8,
    range: GyroRange,
    model: Mpu6050Model,
}

impl<I2C: I2c> Mpu6050<I2C> {
    /// The address with AD0 low (0x69 with AD0 high).
    pub const DEFAULT_ADDRESS: u8 = 0x68;

    /// Checks `WHO_AM_I`, wakes the device and sets the full-scale range.
    ///
    /// # Errors
    /// [`GyroError::Bus`] on a bus failure, [`GyroError::UnknownDevice`] if `WHO_AM_I` is not a supported part.
    pub fn new(mut i2c: I2C, address: u8, range: GyroRange) -> Result<Self, GyroError<I2C::Error>> {
        let mut id = [0u8];
        i2c.write_read(address, &[WHO_AM_I], &mut id)
            .map_err(GyroError::Bus)?;
        let model = match id[0] {
            0x68 => Mpu6050Model::Mpu6050,
            0x70 => Mpu6050Model::Mpu6500,
            0x71 => Mpu6050Model::Mpu9250,
            other => return Err(GyroError::UnknownDevice(other)),
        };
        i2c.write(address, &[PWR_MGMT_1, WAKE_PLL_X])
            .map_err(GyroError::Bus)?;
        i2c.write(address, &[GYRO_CONFIG, range.fs_sel() << 3])
            .map_err(GyroError::Bus)?;
        Ok(Self {
            i2c,
            address,
            range,
            model,
        })
    }

    /// Reads one sample (rad/s, sensor axes) in a single burst of six bytes.
    ///
    /// # Errors
    /// [`GyroError::Bus`] on a bus failure; no sample is made up.
    pub fn read(&mut self) -> Result<GyroSample<f32>, GyroError<I2C::Error>> {
        let mut b = [0u8; 6];
        self.i2c
            .write_read(self.address, &[GYRO_XOUT_H], &mut b)
            .map_err(GyroError::Bus)?;
        let raw = [
            i16::from_be_bytes([b[0], b[1]]),
            i16::from_be_bytes([b[2], b[3]]),
            i16::from_be_bytes([b[4], b[5]]),
        ];
        Ok(Self::convert(raw, self.range))
    }

    /// Converts raw counts at `range` to a sample: rad/s, saturated if any axis is at a rail.
    #[must_use]
    pub fn convert(raw: [i16; 3], range: GyroRange) -> GyroSample<f32> {
        let k = range.rad_per_lsb();
        let saturated = raw.iter().any(|&r| r == i16::MIN || r == i16::MAX);
        GyroSample {
            rate: Vec3::new(raw[0] as f32 * k, raw[1] as f32 * k, raw[2] as f32 * k),
            saturated,
        }
    }

    /// The part that answered.
    #[must_use]
    pub fn model(&self) -> Mpu6050Model {
        self.model
    }

    /// The configured range.
    #[must_use]
    pub fn range(&self) -> GyroRange {
        self.range
    }

    /// Gives the bus back.
    pub fn release(self) -> I2C {
        self.i2c
    }
}
