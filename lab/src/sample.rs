//! A gyro sample stream's element, as the scenes make them and the integrators and peers consume them.

use quatprop::Vec3;

/// One gyro sample of a stream: rate (rad/s, body frame) and the time since the previous sample (s).
#[derive(Clone, Copy, Debug)]
pub struct Sample<T> {
    pub w: Vec3<T>,
    pub dt: T,
}
