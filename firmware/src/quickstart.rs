// The README's quick start, verbatim between the markers (tests/readme.rs checks that the README shows
// exactly this code). Compiled into the M4F firmware (`quickstart` program) and into the host test, so the
// two run the same f32 arithmetic.
// quick start: begin
use quatprop::{input::History, scheme::ExpMap, stabilize::FirstOrder};
use quatprop::{Error, GyroSample, Propagator, Quat};

/// The gyro's sample period (s): 1 kHz.
const DT: f32 = 1.0e-3;

/// Integrates body-frame gyro samples (rad/s, one every `DT`) into the attitude (body to reference).
/// Returns the attitude and how many samples were refused.
pub fn attitude_from(
    samples: impl IntoIterator<Item = GyroSample<f32>>,
) -> Result<(Quat<f32>, u32), Error> {
    let mut p = Propagator::new(Quat::IDENTITY, ExpMap, History::new(), FirstOrder)?;
    let mut dt = 0.0; // time since the last accepted sample
    let mut refused = 0;
    for sample in samples {
        dt += DT;
        match p.push(sample, dt) {
            Ok(()) => dt = 0.0,
            // The state is unchanged; the next sample covers this interval too.
            Err(_) => refused += 1,
        }
    }
    Ok((p.attitude(), refused))
}
// quick start: end
