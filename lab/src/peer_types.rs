//! The Rust peers' types as the lab meets them: the scalars they take ([`PeerReal`]) and the conversions
//! between quatprop's `Quat`/`Vec3` and nalgebra's (the nalgebra peers') and `ahrs`'s own nalgebra's. glam
//! converts through `mint` where it is called.

use quatprop::{Quat, Real, Vec3};

/// f32 and f64 as the Rust peers take them: quatprop's `Real` plus the scalar traits of nalgebra and of
/// `ahrs`'s own nalgebra (`nalgebra_ahrs::RealField`, a copy apart from the peers', lab/Cargo.toml).
pub trait PeerReal: Real + nalgebra::RealField + nalgebra_ahrs::RealField + Copy {}

impl<T: Real + nalgebra::RealField + nalgebra_ahrs::RealField + Copy> PeerReal for T {}

pub type NaQuat<T> = nalgebra::UnitQuaternion<T>;

// The conversions go through `mint` (quatprop's `mint` feature, nalgebra's `convert-mint`): component
// order and the scalar's place are the crates' business, not the lab's.
pub fn to_na<T: PeerReal>(q: Quat<T>) -> NaQuat<T> {
    NaQuat::new_normalize(nalgebra::Quaternion::from(mint::Quaternion::from(q)))
}
pub fn from_na<T: PeerReal>(q: &NaQuat<T>) -> Quat<T> {
    Quat::from_mint(*q.quaternion())
}
pub fn na_vec<T: PeerReal>(v: Vec3<T>) -> nalgebra::Vector3<T> {
    nalgebra::Vector3::from(mint::Vector3::from(v))
}

// `ahrs` 0.8 takes its own nalgebra's (0.34) types, a copy apart from the nalgebra peers' (lab/Cargo.toml):
// converted component by component.
pub type AhrsQuat<T> = nalgebra_ahrs::UnitQuaternion<T>;
pub fn to_ahrs<T: PeerReal>(q: Quat<T>) -> AhrsQuat<T> {
    AhrsQuat::new_normalize(nalgebra_ahrs::Quaternion::new(q.w, q.x, q.y, q.z))
}
pub fn from_ahrs<T: PeerReal>(q: &AhrsQuat<T>) -> Quat<T> {
    let q = q.quaternion();
    Quat::new(q.w, q.i, q.j, q.k)
}
pub fn ahrs_vec<T: PeerReal>(v: Vec3<T>) -> nalgebra_ahrs::Vector3<T> {
    nalgebra_ahrs::Vector3::new(v.x, v.y, v.z)
}
