//! The Rust quick start with its static types (feature `rust-baseline`, tests and figures only): the
//! README's `Attitude`, verbatim from firmware/src/quickstart.rs, behind three C functions, so the C
//! firmware harness can time the statically typed Rust code against the C API's run-time dispatch with
//! the same compiler, startup and measurement.

mod quickstart {
    include!("../../firmware/src/quickstart.rs");
}
use crate::{check, quatprop_quat_t, quatprop_t};
use quickstart::Attitude;

const _: () = assert!(core::mem::size_of::<Attitude>() <= core::mem::size_of::<quatprop_t>());
const _: () = assert!(core::mem::align_of::<Attitude>() <= core::mem::align_of::<quatprop_t>());

/// Writes a new `Attitude` into `s`; 1 on success.
///
/// # Safety
/// `s` must be NULL or point to a writable `quatprop_t` not in use elsewhere.
#[no_mangle]
pub unsafe extern "C" fn quatprop_baseline_init(s: *mut quatprop_t) -> u32 {
    match (check(s), Attitude::new()) {
        (Ok(()), Ok(a)) => {
            // SAFETY: non-null and aligned (checked), writable per the contract; Attitude fits (asserted).
            unsafe { s.cast::<Attitude>().write(a) };
            1
        }
        _ => 0,
    }
}

/// `Attitude::on_fifo` on `n` samples `counts[3 * n]`.
///
/// # Safety
/// `s` must point to a `quatprop_t` set up by `quatprop_baseline_init`; `counts` to `3 * n` int16s.
#[no_mangle]
pub unsafe extern "C" fn quatprop_baseline_on_fifo(
    s: *mut quatprop_t,
    counts: *const i16,
    n: usize,
) {
    if check(s).is_err() || check(counts).is_err() {
        return;
    }
    // SAFETY: checked non-null and aligned; initialized and exclusive, `3 * n` readable per the contract.
    let (a, fifo) = unsafe {
        (
            &mut *s.cast::<Attitude>(),
            core::slice::from_raw_parts(counts.cast::<[i16; 3]>(), n),
        )
    };
    a.on_fifo(fifo);
}

/// The attitude and the refused count.
///
/// # Safety
/// `s` must point to a `quatprop_t` set up by `quatprop_baseline_init`; `out` and `refused` writable.
#[no_mangle]
pub unsafe extern "C" fn quatprop_baseline_attitude(
    s: *const quatprop_t,
    out: *mut quatprop_quat_t,
    refused: *mut u32,
) {
    if check(s).is_err() || check(out).is_err() || check(refused).is_err() {
        return;
    }
    // SAFETY: checked non-null and aligned; initialized, `out`/`refused` writable per the contract.
    unsafe {
        let (q, r) = (*s.cast::<Attitude>()).attitude();
        out.write(quatprop_quat_t {
            w: q.w,
            x: q.x,
            y: q.y,
            z: q.z,
        });
        refused.write(r);
    }
}
