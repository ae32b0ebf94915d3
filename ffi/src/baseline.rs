//! The Rust quick start with its static types (feature `rust-baseline`, tests and figures only): the
//! README's `Attitude` (the crate `quatprop-quickstart`, firmware/quickstart/), behind three C functions, so the C
//! firmware harness can time the statically typed Rust code against the C API's run-time dispatch with
//! the same compiler, startup and measurement.

use crate::{check, quatprop_quat_t, quatprop_t};
use quatprop_quickstart::Attitude;

const _: () = assert!(core::mem::size_of::<Attitude>() <= core::mem::size_of::<quatprop_t>());
const _: () = assert!(core::mem::align_of::<Attitude>() <= core::mem::align_of::<quatprop_t>());
const _: () = assert!(core::mem::size_of::<KindAttitude>() <= core::mem::size_of::<quatprop_t>());
const _: () = assert!(core::mem::align_of::<KindAttitude>() <= core::mem::align_of::<quatprop_t>());

/// The three C functions of one quick start `$ty`: set up, feed a FIFO read, read back.
macro_rules! c_functions {
    ($ty:ty, $init:ident, $on_fifo:ident, $attitude:ident) => {
        /// Writes a new quick start into `s`; 1 on success.
        ///
        /// # Safety
        /// `s` must be NULL or point to a writable `quatprop_t` not in use elsewhere.
        #[no_mangle]
        pub unsafe extern "C" fn $init(s: *mut quatprop_t) -> u32 {
            match (check(s), <$ty>::new()) {
                (Ok(()), Ok(a)) => {
                    // SAFETY: non-null and aligned (checked), writable per the contract; it fits
                    // (asserted above).
                    unsafe { s.cast::<$ty>().write(a) };
                    1
                }
                _ => 0,
            }
        }

        /// `on_fifo` on `n` samples `counts[3 * n]`.
        ///
        /// # Safety
        /// `s` must point to a `quatprop_t` set up by this quick start's init; `counts` to `3 * n` int16s.
        #[no_mangle]
        pub unsafe extern "C" fn $on_fifo(s: *mut quatprop_t, counts: *const i16, n: usize) {
            if check(s).is_err() || check(counts).is_err() {
                return;
            }
            // SAFETY: checked non-null and aligned; initialized and exclusive, `3 * n` readable per the
            // contract.
            let (a, fifo) = unsafe {
                (
                    &mut *s.cast::<$ty>(),
                    core::slice::from_raw_parts(counts.cast::<[i16; 3]>(), n),
                )
            };
            a.on_fifo(fifo);
        }

        /// The attitude and the refused count.
        ///
        /// # Safety
        /// `s` must point to a `quatprop_t` set up by this quick start's init; `out` and `refused`
        /// writable.
        #[no_mangle]
        pub unsafe extern "C" fn $attitude(
            s: *const quatprop_t,
            out: *mut quatprop_quat_t,
            refused: *mut u32,
        ) {
            if check(s).is_err() || check(out).is_err() || check(refused).is_err() {
                return;
            }
            // SAFETY: checked non-null and aligned; initialized, `out`/`refused` writable per the contract.
            unsafe {
                let (q, r) = (*s.cast::<$ty>()).attitude();
                out.write(quatprop_quat_t {
                    w: q.w,
                    x: q.x,
                    y: q.y,
                    z: q.z,
                });
                refused.write(r);
            }
        }
    };
}

c_functions!(
    Attitude,
    quatprop_baseline_init,
    quatprop_baseline_on_fifo,
    quatprop_baseline_attitude
);
// The same with the run-time scheme and stabilizer.
c_functions!(
    KindAttitude,
    quatprop_baseline_kinds_init,
    quatprop_baseline_kinds_on_fifo,
    quatprop_baseline_kinds_attitude
);

/// The quick start's `Attitude` with the core's own run-time scheme and stabilizer (`SchemeKind`,
/// `StabilizerKind`) and everything else static: splits the C API's cost into the core's run-time dispatch
/// and the C layer's own.
// The quick start's struct and `on_fifo` again, with other types: the quick start (firmware/quickstart/) is
// the README's code as a user writes it, with static types, so it is not made generic for this comparison.
mod kinds {
    use quatprop::frontend::{AxisRemap, BiasEstimator, CountScale, FixedPeriod};
    use quatprop::scheme::SchemeKind;
    use quatprop::stabilize::StabilizerKind;
    use quatprop::{input::History, Error, GyroSample, Propagator, Quat};

    /// As the quick start's (firmware/quickstart/src/lib.rs): 8 samples kept in the struct.
    const BATCH: usize = 8;

    pub struct KindAttitude {
        scale: CountScale<f32>,
        mounting: AxisRemap,
        bias: BiasEstimator<f32>,
        period: FixedPeriod<f32>,
        propagator: Propagator<f32, SchemeKind, History<f32>, StabilizerKind>,
        batch: [GyroSample<f32>; BATCH],
        refused: u32,
    }

    impl KindAttitude {
        pub fn new() -> Result<Self, Error> {
            Ok(Self {
                scale: CountScale::full_scale_dps(2000.0)?,
                mounting: AxisRemap::PyNxPz,
                bias: BiasEstimator::new(1.0, 1.0e-3, 0.05)?,
                period: FixedPeriod::new(1.0e-3)?,
                propagator: Propagator::new(
                    Quat::IDENTITY,
                    SchemeKind::ExpMap,
                    History::new(),
                    StabilizerKind::FirstOrder,
                )?,
                batch: [GyroSample::default(); BATCH],
                refused: 0,
            })
        }

        pub fn on_fifo(&mut self, fifo: &[[i16; 3]]) {
            for batch in fifo.chunks(BATCH) {
                for (slot, &counts) in self.batch.iter_mut().zip(batch) {
                    let sample = self.mounting.apply(self.scale.sample(counts));
                    *slot = self.bias.update(sample).unwrap_or(sample);
                }
                let mut rest = self.batch.get(..batch.len()).unwrap_or(&[]);
                while let Err(refused) = self.propagator.push_burst(rest, &mut self.period) {
                    self.refused += 1;
                    rest = rest.get(refused.index + 1..).unwrap_or(&[]);
                }
            }
        }

        pub fn attitude(&self) -> (Quat<f32>, u32) {
            (self.propagator.attitude(), self.refused)
        }
    }
}
use kinds::KindAttitude;
