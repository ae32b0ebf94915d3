/* The calibration estimator's scene, as ffi/src/tests/calibration.rs `Tumble` makes it (same f32
 * arithmetic, same order): a body tumbling with the rate (cos t, sin 0.37t, 0.6 cos 0.21t) rad/s (rotation
 * recurrences, no sin or cos), its attitude from the identity (each step's quaternion from its rotation
 * vector by Taylor series), read at 100 Hz for 2 min by a gyro 1 % high on x and an ideal accelerometer
 * (gravity in the body at the sample's end). Build with -ffp-contract=off (no fused multiply-add), as Rust
 * computes. */
#ifndef TUMBLE_H
#define TUMBLE_H
#include <stdint.h>
#define TUMBLE_SAMPLES 12000u
#define TUMBLE_DT 0.01f

typedef struct { float c[3], s[3], q[4]; uint32_t k; } tumble_t;
void tumble_init(tumble_t *t);
/* The next sample: the gyro's reading `rate` (rad/s) and the accelerometer `accel` (m/s^2). Returns 0
 * after the last one. */
int tumble_next(tumble_t *t, float rate[3], float accel[3]);
#endif
