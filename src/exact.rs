//! Error-free transformations in plain floating-point arithmetic (no FMA): Knuth's TwoSum and Dekker's
//! TwoProduct with Veltkamp's splitting (Dekker 1971; Joldes, Muller, Popescu 2017). Exact for finite
//! operands whose results do not overflow (TwoProduct also needs no underflow in the low part).

use crate::{Quat, Real, Vec3};

/// `(s, e)` with `s = fl(a + b)` and `a + b = s + e` exactly.
#[inline(always)]
pub(crate) fn two_sum<T: Real>(a: T, b: T) -> (T, T) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// Veltkamp's split `a = hi + lo` with `hi` holding the upper half of the significand.
#[inline(always)]
fn split<T: Real>(a: T) -> (T, T) {
    // 2^⌈p/2⌉ + 1: 4097 for f32 (p = 24), 134217729 for f64 (p = 53).
    let factor = if T::EPSILON > T::from_f64(1e-10) {
        T::from_f64(4097.0)
    } else {
        T::from_f64(134_217_729.0)
    };
    let c = factor * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `(p, e)` with `p = fl(a·b)` and `a·b = p + e` exactly (Dekker's TwoProduct, 17 flops).
#[inline(always)]
pub(crate) fn two_product<T: Real>(a: T, b: T) -> (T, T) {
    product_of_splits(a, split(a), b, split(b))
}

/// `(s, e)` with `s = fl(a + b)` and `a + b = s + e` exactly, per component.
#[inline(always)]
pub(crate) fn two_sum_vec<T: Real>(a: Vec3<T>, b: Vec3<T>) -> (Vec3<T>, Vec3<T>) {
    let (x, ex) = two_sum(a.x, b.x);
    let (y, ey) = two_sum(a.y, b.y);
    let (z, ez) = two_sum(a.z, b.z);
    (Vec3::new(x, y, z), Vec3::new(ex, ey, ez))
}

/// `(s, e)` with `s = fl(a + b)` and `a + b = s + e` exactly, per component.
#[inline(always)]
pub(crate) fn two_sum_quat<T: Real>(a: Quat<T>, b: Quat<T>) -> (Quat<T>, Quat<T>) {
    let (w, ew) = two_sum(a.w, b.w);
    let (v, ev) = two_sum_vec(a.vector(), b.vector());
    (Quat::from_parts(w, v), Quat::from_parts(ew, ev))
}

/// `(p, e)` with `p = fl(v·k)` and `v·k = p + e` exactly, per component (k split once).
#[inline(always)]
pub(crate) fn two_product_vec<T: Real>(v: Vec3<T>, k: T) -> (Vec3<T>, Vec3<T>) {
    let ks = split(k);
    let tp = |a: T| product_of_splits(a, split(a), k, ks);
    let ((x, ex), (y, ey), (z, ez)) = (tp(v.x), tp(v.y), tp(v.z));
    (Vec3::new(x, y, z), Vec3::new(ex, ey, ez))
}

/// TwoProduct of `a·b` from their splits.
#[inline(always)]
fn product_of_splits<T: Real>(a: T, (ah, al): (T, T), b: T, (bh, bl): (T, T)) -> (T, T) {
    let p = a * b;
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// The Hamilton product `q ⊗ (0, v)` as an unevaluated sum `hi + lo`, accurate as if computed in twice the
/// working precision and rounded (Ogita–Rump–Oishi's Dot2 per component: 12 TwoProducts over 7 splits,
/// the three terms summed with TwoSum, the low parts summed plainly). Written out term by term: no
/// indexing, so nothing on this path can panic.
#[inline(always)]
pub(crate) fn product_by_vector<T: Real>(q: Quat<T>, v: Vec3<T>) -> (Quat<T>, Quat<T>) {
    let (w, x, y, z) = (
        (q.w, split(q.w)),
        (q.x, split(q.x)),
        (q.y, split(q.y)),
        (q.z, split(q.z)),
    );
    let (vx, vy, vz) = ((v.x, split(v.x)), (v.y, split(v.y)), (v.z, split(v.z)));
    let tp = |(a, sa): (T, (T, T)), (b, sb): (T, (T, T))| product_of_splits(a, sa, b, sb);
    let neg = |(p, e): (T, T)| (-p, -e);
    // w = −(q⃗·v), x = q_w v_x + q_y v_z − q_z v_y, y = q_w v_y − q_x v_z + q_z v_x,
    // z = q_w v_z + q_x v_y − q_y v_x.
    let (hw, lw) = dot3(neg(tp(x, vx)), neg(tp(y, vy)), neg(tp(z, vz)));
    let (hx, lx) = dot3(tp(w, vx), tp(y, vz), neg(tp(z, vy)));
    let (hy, ly) = dot3(tp(w, vy), neg(tp(x, vz)), tp(z, vx));
    let (hz, lz) = dot3(tp(w, vz), tp(x, vy), neg(tp(y, vx)));
    (Quat::new(hw, hx, hy, hz), Quat::new(lw, lx, ly, lz))
}

/// Dot2's sum of three exact products `(p, e)`: the `p` summed with TwoSum, every low part gathered.
#[inline(always)]
fn dot3<T: Real>((p0, e0): (T, T), (p1, e1): (T, T), (p2, e2): (T, T)) -> (T, T) {
    let (s1, f1) = two_sum(p0, p1);
    let (s2, f2) = two_sum(s1, p2);
    (s2, (e0 + e1 + e2) + (f1 + f2))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift) for operands over many binades.
    fn operands(n: usize) -> impl Iterator<Item = (f32, f32)> {
        let mut s = 0x9E37_79B9_7F4A_7C15_u64;
        core::iter::repeat_with(move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let a = f32::from_bits(((s as u32) & 0x007F_FFFF) | 0x3F80_0000)
                * 2f32.powi((s >> 40) as i32 % 24 - 12);
            let b = f32::from_bits(((s >> 32) as u32 & 0x007F_FFFF) | 0x3F80_0000)
                * 2f32.powi((s >> 50) as i32 % 24 - 12);
            (if s & 1 == 0 { a } else { -a }, b)
        })
        .take(n)
    }

    #[test]
    fn two_product_is_exact_in_f32_without_fma() {
        // f32 products are exact in f64 (48-bit significands), so the check is exact.
        for (a, b) in operands(200_000) {
            let (p, e) = two_product(a, b);
            assert_eq!(p as f64 + e as f64, a as f64 * b as f64, "{a:e} * {b:e}");
        }
    }

    #[test]
    fn product_by_a_vector_is_accurate_to_twice_the_precision() {
        let mut ops = operands(40_000);
        let mut next = || ops.next().unwrap();
        for _ in 0..5_000 {
            let ((a, b), (c, d), (e, f), (g, _)) = (next(), next(), next(), next());
            let (q, v) = (Quat::new(a, b, c, d), Vec3::new(e, f, g));
            let (hi, lo) = product_by_vector(q, v);
            let (a, b) = (q.to_f64(), Quat::new(0.0, v.x, v.y, v.z).to_f64());
            // Each f32 product is exact in f64; their sum, exact to 2⁻¹⁰⁶ as an f64 TwoSum pair.
            let exact = |terms: [f64; 4]| {
                let (mut s, mut e) = (0.0, 0.0);
                for t in terms {
                    let (s1, e1) = two_sum(s, t);
                    s = s1;
                    e += e1;
                }
                (s, e)
            };
            let want = [
                exact([a.w * b.w, -a.x * b.x, -a.y * b.y, -a.z * b.z]),
                exact([a.w * b.x, a.x * b.w, a.y * b.z, -a.z * b.y]),
                exact([a.w * b.y, -a.x * b.z, a.y * b.w, a.z * b.x]),
                exact([a.w * b.z, a.x * b.y, -a.y * b.x, a.z * b.w]),
            ];
            let got = [(hi.w, lo.w), (hi.x, lo.x), (hi.y, lo.y), (hi.z, lo.z)];
            let scale = a.norm() * b.norm();
            for ((h, l), (s, e)) in got.into_iter().zip(want) {
                let err = ((f64::from(h) - s) + (f64::from(l) - e)).abs();
                // Dot2: the low parts (3 product errors, 2 sum errors) summed plainly in f32, each term
                // ≤ ε·scale, five roundings: ≤ 5·ε·(5ε·scale) with ε = 2⁻²⁴.
                let bound = 25.0 * 2f64.powi(-48) * scale;
                assert!(err <= bound, "{q:?} {v:?}: off by {err:e} > {bound:e}");
            }
        }
    }

    #[test]
    fn two_sum_is_exact_in_f32() {
        for (a, b) in operands(200_000) {
            let (s, e) = two_sum(a, b);
            assert_eq!(s as f64 + e as f64, a as f64 + b as f64, "{a:e} + {b:e}");
        }
    }
}
