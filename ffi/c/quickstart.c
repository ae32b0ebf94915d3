/* quick start: begin */
#include "quatprop.h"

/* One attitude, fed from a gyro's FIFO: raw counts -> body axes -> bias removed -> integrated.
 * The caller owns the state (e.g. `static quatprop_t att;`): the library never allocates. */

/* A +-2000 deg/s, 16-bit gyro at 1 kHz, mounted turned 90 deg about z (body x = sensor y). */
quatprop_status_t attitude_init(quatprop_t *att) {
    quatprop_config_t cfg;
    quatprop_config_default(&cfg); /* EXPMAP, FIRST_ORDER, HISTORY, PLAIN, identity */
    quatprop_status_t e = quatprop_init(att, &cfg);
    if (e == QUATPROP_OK) e = quatprop_set_count_scale_dps(att, 2000.0);
    if (e == QUATPROP_OK) e = quatprop_set_axis_remap(att, QUATPROP_REMAP_PY_NX_PZ);
    /* Learns the bias over 1 s windows while every axis stays within 0.05 rad/s (2.9 deg/s). */
    if (e == QUATPROP_OK) e = quatprop_set_bias_estimator(att, 1.0, 1e-3, 0.05f, QUATPROP_DEFAULT_DRIFT);
    if (e == QUATPROP_OK) e = quatprop_set_fixed_period(att, 1.0e-3);
    return e;
}

/* Takes one FIFO read of raw counts {x, y, z} (sensor axes), one sample per period, any length. */
void attitude_on_fifo(quatprop_t *att, const int16_t (*fifo)[3], size_t n, uint32_t *refused) {
    size_t done = 0;
    while (done < n) {
        size_t integrated = 0;
        quatprop_status_t e = quatprop_push_counts_burst(att, &fifo[done][0], n - done, &integrated);
        if (e == QUATPROP_OK) break;
        /* A refused sample stops the burst with the state as it was; its interval carries into the next. */
        *refused += 1;
        done += integrated + 1;
    }
}
/* quick start: end */
