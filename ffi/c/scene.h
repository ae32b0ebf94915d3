/* The quick start's input, as firmware/src/scenes.rs `quickstart_fifo` makes it (same f32 arithmetic):
 * 400 bursts of 25 raw-count samples of a +-2000 deg/s gyro at 1 kHz: 2 s still with a bias of
 * (12, -3, 7) counts, then coning (a rotation recurrence, no sin/cos) in sensor axes. Build with
 * -ffp-contract=off (no fused multiply-add), as Rust computes. */
#ifndef SCENE_H
#define SCENE_H
#include <stdint.h>
#define QUICKSTART_BURSTS 400u
#define QUICKSTART_BURST 25u
#define QUICKSTART_STILL_BURSTS 80u

typedef struct { float c, s; uint32_t k; } scene_t;
void scene_init(scene_t *sc);
/* Fills the next burst; returns 0 after the last one. */
int scene_next(scene_t *sc, int16_t burst[QUICKSTART_BURST][3]);
/* Canonical bits of a float (one NaN pattern). */
uint32_t scene_bits(float v);
#endif
