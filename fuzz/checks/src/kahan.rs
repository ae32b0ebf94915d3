//! Target `kahan`: an f32 state with `Kahan` compensation against an f64 `Plain` state fed the same
//! samples, within the compensated bound derived in [`super::precision`] (256 steps).

/// Decodes and checks one input.
pub fn run(data: &[u8]) {
    super::precision::run_with(data, true)
}
