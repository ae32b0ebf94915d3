//! The embedded-hal path end to end: a kept driver crate (`icm426xx`, blocking SPI) reads FIFO bursts of an
//! ICM-42688-P, the raw counts go into the README's quick start (`Attitude::on_fifo`). Generic over the bus:
//! the `driver` program runs it on the board against `device_model::Icm42688Model`, the host test against
//! the same model and against `embedded-hal-mock` expectations recorded from it.

use crate::device_model::{NoDelay, MAX_BURST, PACKET};
use crate::quickstart::Attitude;
use embedded_hal::spi::SpiDevice;
use icm426xx::fifo::FifoPacket4;
use icm426xx::{Config, OutputDataRate, Timestamp, ICM42688};
use quatprop::frontend::CountScale;
use quatprop::{Quat, Sample};

/// What one run of the FIFO stream gave.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outcome {
    /// Gyro samples read from the FIFO.
    pub samples: u32,
    /// FIFO reads that returned data.
    pub bursts: u32,
    /// Samples with an axis at a rail (`CountScale::sample` flags them saturated).
    pub rails: u32,
    /// Sum of the packets' ODR delta timestamps (16 µs ticks).
    pub ticks: u32,
    /// The quick start's attitude and refused count.
    pub q: Quat<f32>,
    /// Samples the quick start refused (raw counts are always finite: none).
    pub refused: u32,
}

/// Why the run stopped early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DemoError {
    /// The driver's initialization failed (bus error or WHO_AM_I mismatch).
    Init,
    /// A bus error while reading the FIFO.
    Bus,
    /// A packet without gyro data, or without an ODR timestamp.
    Packet,
    /// The quick start refused its configuration.
    Start,
    /// More FIFO reads than `max_reads`.
    Endless,
}

/// Words of the driver's FIFO read buffer: 4 bytes (address, INT_STATUS, FIFO_COUNT) + the packets.
const WORDS: usize = 1 + MAX_BURST * PACKET / 4;

/// Initializes the chip through the driver (1 kHz, 16 µs delta timestamps), then reads FIFO bursts until
/// the FIFO stays empty and feeds each burst's raw gyro counts to the quick start. Gives the bus back.
pub fn run<SPI: SpiDevice>(spi: SPI, max_reads: u32) -> Result<(Outcome, SPI), DemoError> {
    let config = Config {
        rate: OutputDataRate::Hz1000,
        timestamps_are_absolute: false,
        ..Config::default()
    };
    let mut icm = ICM42688::new(spi)
        .initialize(NoDelay, config)
        .map_err(|_| DemoError::Init)?;
    let mut attitude = Attitude::new().map_err(|_| DemoError::Start)?;
    let scale = CountScale::<f32>::full_scale_dps(2000.0).map_err(|_| DemoError::Start)?;
    let mut out = Outcome {
        samples: 0,
        bursts: 0,
        rails: 0,
        ticks: 0,
        q: Quat::IDENTITY,
        refused: 0,
    };
    let mut buffer = [0u32; WORDS];
    for _ in 0..max_reads {
        let bytes = usize::from(icm.read_fifo_count().map_err(|_| DemoError::Bus)?);
        let n = (bytes / PACKET).min(MAX_BURST);
        if n == 0 {
            out.q = attitude.attitude().0;
            out.refused = attitude.attitude().1;
            return Ok((out, icm.release()));
        }
        let words = buffer.get_mut(..1 + n * PACKET / 4).ok_or(DemoError::Bus)?;
        let in_fifo = icm.read_fifo(words).map_err(|_| DemoError::Bus)?;
        let n = n.min(in_fifo);
        let raw: &[u8] = bytemuck::cast_slice(words);
        let mut fifo = [[0i16; 3]; MAX_BURST];
        for (k, slot) in fifo.iter_mut().take(n).enumerate() {
            let at = 4 + k * PACKET;
            let bytes = raw.get(at..at + PACKET).ok_or(DemoError::Packet)?;
            let p: &FifoPacket4 = bytemuck::try_from_bytes(bytes).map_err(|_| DemoError::Packet)?;
            // Header: bit 7 = FIFO empty, bit 5 = gyro present.
            if p.fifo_header & 0xA0 != 0x20 {
                return Err(DemoError::Packet);
            }
            let Timestamp::OdrTimestamp(t) = p.timestamp() else {
                return Err(DemoError::Packet);
            };
            out.ticks = out.ticks.wrapping_add(u32::from(t));
            // 20-bit gyro at ±2000 °/s: the top 16 bits are the 16-bit counts at ±2000 °/s.
            *slot = [p.gyro_data_x(), p.gyro_data_y(), p.gyro_data_z()].map(|v| (v >> 4) as i16);
            out.rails += u32::from(scale.sample(*slot).is_saturated());
        }
        let burst = fifo.get(..n).ok_or(DemoError::Packet)?;
        attitude.on_fifo(burst);
        out.samples += n as u32;
        out.bursts += 1;
    }
    Err(DemoError::Endless)
}
