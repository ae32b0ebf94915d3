//! The one dispatch macro behind every run-time choice ([`crate::scheme::SchemeKind`],
//! [`crate::stabilize::StabilizerKind`], [`crate::input::coning::ConingKind`]): each enum variant names the
//! zero-sized (or small) type it stands for, and a trait method forwards to it.

/// `dispatch!(value; Enum::A => A, Enum::B(n) => B(n); x => body)` matches `value` and evaluates `body`
/// with `x` bound to the type the variant stands for.
macro_rules! dispatch {
    ($value:expr; $($pat:pat => $make:expr),+ $(,)?; $bind:ident => $body:expr) => {
        match $value {
            $($pat => {
                let $bind = $make;
                $body
            })+
        }
    };
}
pub(crate) use dispatch;
