//! What the instruction-counting programs (`bench`, `burst`, `predict`) feed the calls they count: the same
//! body rates, and the same rates as a FIFO read of raw counts.

use quatprop::Vec3;

/// The benches' 8 body rates (rad/s, |omega| about 1.2 rad/s: the exponential maps' Taylor branch at 1 kHz).
pub fn rates() -> [Vec3<f32>; 8] {
    let mut r = [Vec3::ZERO; 8];
    for (i, w) in r.iter_mut().enumerate() {
        let a = i as f32 * 0.7;
        *w = Vec3::new(0.3 + 0.1 * a, -0.2 + 0.05 * a, 1.0 - 0.03 * a);
    }
    r
}

/// A FIFO read of 32 samples: [`rates`] repeated, as raw 16-bit counts at ±2000 °/s (what the README's
/// quick start takes).
pub fn fifo_counts() -> [[i16; 3]; 32] {
    let w = rates();
    let mut fifo = [[0i16; 3]; 32];
    for (i, s) in fifo.iter_mut().enumerate() {
        let r = w[i & 7];
        *s = [r.x, r.y, r.z].map(|v| (v * 938.734_6) as i16); // counts at ±2000 °/s
    }
    fifo
}
