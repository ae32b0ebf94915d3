#include <math.h>
#include "tumble.h"

/* cos and sin of w * TUMBLE_DT for w = 1, 0.37 and 0.21 rad/s (float, correctly rounded; the shortest
 * decimals that give them, as ffi/src/tests/calibration.rs writes them). */
static const float STEP[3][2] = {
    {0.99995f, 0.009999833f},
    {0.99999315f, 0.0036999916f},
    {0.9999978f, 0.0020999985f},
};

void tumble_init(tumble_t *t) {
    for (int i = 0; i < 3; i++) {
        t->c[i] = 1.0f;
        t->s[i] = 0.0f;
    }
    t->q[0] = 1.0f;
    t->q[1] = t->q[2] = t->q[3] = 0.0f;
    t->k = 0;
}

int tumble_next(tumble_t *t, float rate[3], float accel[3]) {
    if (t->k >= TUMBLE_SAMPLES) return 0;
    const float w[3] = {t->c[0], t->s[1], 0.6f * t->c[2]};
    const float h = 0.5f * TUMBLE_DT;
    const float v[3] = {w[0] * h, w[1] * h, w[2] * h};
    const float x2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    const float cp = 1.0f - x2 / 2.0f + x2 * x2 / 24.0f;
    const float sc = 1.0f - x2 / 6.0f + x2 * x2 / 120.0f;
    const float d[4] = {cp, v[0] * sc, v[1] * sc, v[2] * sc};
    const float *q = t->q;
    const float p[4] = {
        q[0] * d[0] - q[1] * d[1] - q[2] * d[2] - q[3] * d[3],
        q[0] * d[1] + q[1] * d[0] + q[2] * d[3] - q[3] * d[2],
        q[0] * d[2] - q[1] * d[3] + q[2] * d[0] + q[3] * d[1],
        q[0] * d[3] + q[1] * d[2] - q[2] * d[1] + q[3] * d[0],
    };
    const float n = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3]);
    for (int i = 0; i < 4; i++) t->q[i] = p[i] / n;
    const float g = 9.81f;
    accel[0] = 2.0f * (q[1] * q[3] - q[0] * q[2]) * g;
    accel[1] = 2.0f * (q[2] * q[3] + q[0] * q[1]) * g;
    accel[2] = (1.0f - 2.0f * (q[1] * q[1] + q[2] * q[2])) * g;
    for (int i = 0; i < 3; i++) {
        const float c = t->c[i], s = t->s[i];
        t->c[i] = c * STEP[i][0] - s * STEP[i][1];
        t->s[i] = s * STEP[i][0] + c * STEP[i][1];
    }
    t->k++;
    rate[0] = 1.01f * w[0];
    rate[1] = w[1];
    rate[2] = w[2];
    return 1;
}
