//! A scripted ICM-42688-P on an SPI bus: the registers the `icm426xx` driver touches (WHO_AM_I, the
//! configuration registers of banks 0–4, REG_BANK_SEL, INT_STATUS, FIFO_COUNT, FIFO_DATA) and a FIFO that
//! serves a deterministic script of gyro bursts in the chip's 20-byte "packet 4" (20-bit gyro and accel,
//! temperature, 16 µs ODR delta timestamps).
//!
//! Compiled into the firmware (the `driver` program runs it on the board, behind the same
//! `embedded_hal::spi::SpiDevice` a real bus would implement) and into the host test
//! (`tests/firmware_snapshot.rs`, which also replays its transactions through `embedded-hal-mock`). All
//! integer arithmetic: the script is the same on every target. No allocation, no panic.
//!
//! The script ([`counts`]): 1.5 s still with a constant bias (the quick start's estimator learns it), then
//! three sinusoid-like rates whose phase steps are in irrational-looking ratios (incommensurate: coning that
//! never repeats), and one sample with the y axis at the positive rail (a 20-bit full-scale packet, i.e.
//! `i16::MAX` in the top 16 bits). The samples come in FIFO bursts of the lengths in [`BURSTS`], cycled.

use embedded_hal::delay::DelayNs;
use embedded_hal::spi::{ErrorKind, ErrorType, Operation, SpiDevice};

/// The chip's WHO_AM_I value (ICM-42688-P).
pub const WHO_AM_I_VALUE: u8 = 0x47;
/// Bytes per FIFO packet ("packet 4": header, accel, gyro, temperature, timestamp, 20-bit extensions).
pub const PACKET: usize = 20;
/// FIFO burst lengths (samples), cycled through the script; one above the quick start's batch of 32.
pub const BURSTS: [usize; 7] = [25, 7, 32, 1, 40, 13, 16];
/// The longest burst.
pub const MAX_BURST: usize = 40;
/// Samples in the script (1 kHz).
pub const SAMPLES: usize = 4000;
/// Samples at rest at the start.
pub const STILL: usize = 1500;
/// The sample whose y axis sits at the rail.
pub const RAIL_SAMPLE: usize = 2718;
/// Constant gyro bias (counts, sensor axes).
pub const BIAS: [i16; 3] = [14, -9, 5];
/// ODR delta timestamps of a 1 kHz stream in 16 µs ticks alternate 62 and 63 (62.5 on average).
pub const TICKS: [u16; 2] = [62, 63];

/// Register addresses (bank 0, except REG_BANK_SEL which every bank has).
const INT_STATUS: u8 = 0x2D;
const FIFO_COUNTH: u8 = 0x2E;
const FIFO_DATA: u8 = 0x30;
const WHO_AM_I: u8 = 0x75;
const REG_BANK_SEL: u8 = 0x76;

/// A parabolic sine of a 32-bit phase: ±8192 at a quarter turn, exact integers.
fn wave(phase: u32) -> i32 {
    let x = (phase >> 16) as u16 as i16 as i32; // −32768 ..= 32767, one turn
    (x * (32768 - x.abs())) >> 15
}

/// The gyro counts of sample `i` (sensor axes, the top 16 bits of the 20-bit packet value).
pub fn counts(i: usize) -> [i16; 3] {
    if i == RAIL_SAMPLE {
        return [BIAS[0], i16::MAX, BIAS[2]];
    }
    if i < STILL {
        return BIAS;
    }
    let k = (i - STILL) as u32;
    // Phase steps per sample: 3.1 Hz, 3.1·√2 Hz and 3.1·φ Hz of a 1 kHz stream (rounded to integers).
    let p = [
        k.wrapping_mul(13_314_398),
        k.wrapping_mul(18_829_520),
        k.wrapping_mul(21_543_412),
    ];
    let w = [
        wave(p[0]) / 3,
        wave(p[1].wrapping_add(0x4000_0000)) / 3,
        wave(p[2]) / 5 + 700,
    ];
    [0, 1, 2].map(|a| (w[a] + i32::from(BIAS[a])) as i16)
}

/// The accelerometer counts of every sample: 1 g on z at ±16 g (20-bit).
const ACCEL_Z_20BIT: i32 = 1 << 15;

/// The 20-byte FIFO packet of sample `i`: header 0x78 (accel, gyro, 20-bit, ODR timestamp), big-endian
/// data, the gyro's low 4 bits (below the i16 counts) varying with `i`.
pub fn packet(i: usize) -> [u8; PACKET] {
    let g = counts(i).map(|c| (i32::from(c) << 4) | (i as i32 & 0xF));
    let a = [0, 0, ACCEL_Z_20BIT];
    let hi = |v: i32| (v >> 12) as u8;
    let mid = |v: i32| (v >> 4) as u8;
    let ext = |acc: i32, gyr: i32| (((acc & 0xF) << 4) | (gyr & 0xF)) as u8;
    let tick = TICKS[i & 1];
    // Byte by byte as the datasheet lays the packet out.
    [
        0x78,
        hi(a[0]),
        mid(a[0]),
        hi(a[1]),
        mid(a[1]),
        hi(a[2]),
        mid(a[2]),
        hi(g[0]),
        mid(g[0]),
        hi(g[1]),
        mid(g[1]),
        hi(g[2]),
        mid(g[2]),
        0, // temperature 25 °C
        0,
        (tick >> 8) as u8,
        tick as u8,
        ext(a[0], g[0]),
        ext(a[1], g[1]),
        ext(a[2], g[2]),
    ]
}

/// The bus error of the model: a transaction it cannot serve (a read of an unknown shape).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelError;

impl embedded_hal::spi::Error for ModelError {
    fn kind(&self) -> ErrorKind {
        ErrorKind::Other
    }
}

/// The scripted chip.
pub struct Icm42688Model {
    /// Register file of banks 0–4 (7-bit addresses).
    banks: [[u8; 128]; 5],
    bank: usize,
    /// Next script sample to enter the FIFO.
    next: usize,
    /// Which entry of [`BURSTS`] comes next.
    burst: usize,
    /// The FIFO: samples `fifo_start..fifo_end` of the script, read up to byte `fifo_pos`.
    fifo_start: usize,
    fifo_end: usize,
    fifo_pos: usize,
    /// Bytes in the FIFO latched by the last FIFO_COUNTH read.
    latched: u16,
    transactions: u32,
}

impl Default for Icm42688Model {
    fn default() -> Self {
        Self::new()
    }
}

impl Icm42688Model {
    /// The chip after power-up, its FIFO empty and the script at its start.
    pub fn new() -> Self {
        let mut banks = [[0u8; 128]; 5];
        banks[0][WHO_AM_I as usize] = WHO_AM_I_VALUE;
        Self {
            banks,
            bank: 0,
            next: 0,
            burst: 0,
            fifo_start: 0,
            fifo_end: 0,
            fifo_pos: 0,
            latched: 0,
            transactions: 0,
        }
    }

    /// Script samples that have entered the FIFO so far, and whether the script is over (every sample
    /// served and read out).
    pub fn served(&self) -> (usize, bool) {
        (self.next, self.next >= SAMPLES && self.fifo_bytes() == 0)
    }

    /// SPI transactions served.
    pub fn transactions(&self) -> u32 {
        self.transactions
    }

    fn fifo_bytes(&self) -> usize {
        ((self.fifo_end - self.fifo_start) * PACKET).saturating_sub(self.fifo_pos)
    }

    /// The sensor's next burst enters the (drained) FIFO: the samples of the time since the last read.
    fn refill(&mut self) {
        if self.fifo_bytes() > 0 || self.next >= SAMPLES {
            return;
        }
        let len = BURSTS.get(self.burst % BURSTS.len()).copied().unwrap_or(1);
        self.burst += 1;
        self.fifo_start = self.next;
        self.fifo_end = (self.next + len).min(SAMPLES);
        self.fifo_pos = 0;
        self.next = self.fifo_end;
    }

    fn pop_fifo(&mut self) -> u8 {
        if self.fifo_bytes() == 0 {
            return 0xFF;
        }
        let i = self.fifo_start + self.fifo_pos / PACKET;
        let byte = packet(i)
            .get(self.fifo_pos % PACKET)
            .copied()
            .unwrap_or(0xFF);
        self.fifo_pos += 1;
        byte
    }

    fn read(&mut self, addr: u8) -> u8 {
        match (self.bank, addr) {
            (_, REG_BANK_SEL) => self.bank as u8,
            (0, INT_STATUS) => 0x04, // FIFO threshold reached; never FIFO full
            (0, FIFO_COUNTH) => {
                // Reading the high byte latches both (big-endian count: INTF_CONFIG0's FIFO_COUNT_ENDIAN).
                self.refill();
                self.latched = self.fifo_bytes().min(usize::from(u16::MAX)) as u16;
                (self.latched >> 8) as u8
            }
            (0, 0x2F) => self.latched as u8,
            (0, FIFO_DATA) => self.pop_fifo(),
            (b, a) => self
                .banks
                .get(b)
                .and_then(|r| r.get(usize::from(a & 0x7F)))
                .copied()
                .unwrap_or(0),
        }
    }

    fn write(&mut self, addr: u8, value: u8) {
        if addr == REG_BANK_SEL {
            self.bank = usize::from(value & 0x7).min(4);
            return;
        }
        if let Some(r) = self
            .banks
            .get_mut(self.bank)
            .and_then(|r| r.get_mut(usize::from(addr & 0x7F)))
        {
            *r = value;
        }
    }

    /// One chip-select frame: the first byte is the address (bit 7: read); the address then increments,
    /// except at FIFO_DATA, which streams the FIFO.
    fn frame(&mut self, bytes: &mut [u8], write: bool) -> Result<(), ModelError> {
        let Some((&mut first, rest)) = bytes.split_first_mut() else {
            return Ok(());
        };
        let read = first & 0x80 != 0;
        let mut addr = first & 0x7F;
        for b in rest {
            if read {
                *b = self.read(addr);
            } else if write {
                self.write(addr, *b);
            } else {
                return Err(ModelError);
            }
            if !(self.bank == 0 && addr == FIFO_DATA) {
                addr = (addr + 1) & 0x7F;
            }
        }
        Ok(())
    }
}

impl ErrorType for Icm42688Model {
    type Error = ModelError;
}

impl SpiDevice for Icm42688Model {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), ModelError> {
        self.transactions += 1;
        for op in operations {
            match op {
                Operation::TransferInPlace(buf) => self.frame(buf, false)?,
                Operation::Write(buf) => {
                    let mut frame = [0u8; 8];
                    let Some(f) = frame.get_mut(..buf.len()) else {
                        return Err(ModelError);
                    };
                    f.copy_from_slice(buf);
                    self.frame(f, true)?;
                }
                Operation::DelayNs(_) => {}
                // The driver only uses the two above; a read-only or split transfer is not modeled.
                Operation::Read(_) | Operation::Transfer(_, _) => return Err(ModelError),
            }
        }
        Ok(())
    }
}

/// A delay that returns at once (the model needs no settling time).
pub struct NoDelay;

impl DelayNs for NoDelay {
    fn delay_ns(&mut self, _ns: u32) {}
}
