#include "scene.h"

/* Omega sin(alpha), -2 Omega sin^2(alpha/2) (rad/s) for alpha = 0.3, Omega = 10 pi; cos and sin of Omega dt/2. */
#define CONE_AMPLITUDE 9.284041f
#define CONE_AXIAL (-1.4031456f)
#define HALF_STEP_COS 0.9998766f
#define HALF_STEP_SIN 0.015707317f
/* Counts per rad/s at +-2000 deg/s: 32768 / (2000 pi / 180). */
#define COUNTS_PER_RAD_S 938.7346f

static const int16_t BIAS[3] = {12, -3, 7};

void scene_init(scene_t *sc) {
    sc->c = 1.0f;
    sc->s = 0.0f;
    sc->k = 0;
}

static void half(scene_t *sc) {
    float c = sc->c * HALF_STEP_COS - sc->s * HALF_STEP_SIN;
    float s = sc->s * HALF_STEP_COS + sc->c * HALF_STEP_SIN;
    sc->c = c;
    sc->s = s;
}

int scene_next(scene_t *sc, int16_t burst[QUICKSTART_BURST][3]) {
    if (sc->k >= QUICKSTART_BURSTS) return 0;
    for (unsigned i = 0; i < QUICKSTART_BURST; i++) {
        for (unsigned a = 0; a < 3; a++) burst[i][a] = BIAS[a];
        if (sc->k >= QUICKSTART_STILL_BURSTS) {
            half(sc);
            half(sc);
            float wx = -CONE_AMPLITUDE * sc->s, wy = CONE_AMPLITUDE * sc->c, wz = CONE_AXIAL;
            /* Body x = sensor y, body y = -sensor x (PY_NX_PZ): sensor = (-body y, body x, z). */
            float sensor[3] = {-wy, wx, wz};
            for (unsigned a = 0; a < 3; a++)
                burst[i][a] = (int16_t)((int16_t)(sensor[a] * COUNTS_PER_RAD_S) + BIAS[a]);
        }
    }
    sc->k++;
    return 1;
}

uint32_t scene_bits(float v) {
    union { float f; uint32_t u; } b;
    if (v != v) return 0x7fc00000u;
    b.f = v;
    return b.u;
}
