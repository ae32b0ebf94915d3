//! Instruction counting with SysTick under QEMU's `-icount shift=N` (deterministic virtual time).
//!
//! On the mps2 boards SysTick counts the 25 MHz core clock. With `-icount shift=10` every instruction
//! advances virtual time by 2¹⁰ ns, so one instruction is 25.6 ticks and
//! `instructions = ticks · 40 / 1024`. The 24-bit counter wraps after 2²⁴ / 25.6 ≈ 655 000 instructions:
//! measure shorter regions. On the microbit (nRF51, Cortex-M0) SysTick counts QEMU's 16 MHz system clock:
//! 16.384 ticks per instruction, a wrap after about 1 020 000. These are executed instructions, not
//! cycles.

use crate::exit::fail;
use cortex_m::peripheral::{syst::SystClkSource, SYST};

/// The `-icount shift` the runner passes to QEMU for the bench.
pub const ICOUNT_SHIFT: u32 = 10;
/// SysTick clock (Hz): the mps2 boards' 25 MHz, the microbit's 16 MHz.
const SYSTICK_HZ: u64 = if cfg!(microbit) {
    16_000_000
} else {
    25_000_000
};

/// A free-running SysTick on the core clock.
pub struct Counter {
    syst: SYST,
}

impl Counter {
    /// Takes SysTick and starts it counting down from 2²⁴ − 1.
    pub fn new(mut syst: SYST) -> Self {
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(0x00FF_FFFF);
        syst.clear_current();
        syst.enable_counter();
        Self { syst }
    }

    /// Takes the core peripherals for their SysTick (see [`Counter::new`]); exits 1 if they were taken
    /// already.
    pub fn take() -> Self {
        let Some(cp) = cortex_m::Peripherals::take() else {
            fail("peripherals")
        };
        Self::new(cp.SYST)
    }

    /// Current counter value (counts down).
    #[inline(always)]
    pub fn now(&self) -> u32 {
        SYST::get_current()
    }

    /// Ticks elapsed from `start` to `end` (one wrap at most).
    #[inline(always)]
    pub fn ticks(start: u32, end: u32) -> u32 {
        start.wrapping_sub(end) & 0x00FF_FFFF
    }

    /// Converts ticks to executed instructions (rounded to nearest).
    pub fn instructions(ticks: u32) -> u32 {
        let ns = ticks as u64 * 1_000_000_000 / SYSTICK_HZ; // 40 or 62.5 ns per tick
        ((ns + (1 << (ICOUNT_SHIFT - 1))) >> ICOUNT_SHIFT) as u32
    }

    /// Gives SysTick back.
    pub fn free(self) -> SYST {
        self.syst
    }
}

/// Instructions ×100 per call (or step, or sample) over `n` of them: `(with − without) · 100 / n`, where
/// `with` counts a loop with the calls and `without` the same loop without them (0 if it counted more).
pub fn per_x100(with: u32, without: u32, n: u32) -> u32 {
    ((u64::from(with.saturating_sub(without)) * 100) / u64::from(n)) as u32
}
