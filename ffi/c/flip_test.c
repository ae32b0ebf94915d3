/* A state that checks itself (gcc -fsanitize=address,undefined): in every configuration — input model (and
 * each coning correction of the delta angles) x scheme x stabilizer x accumulator, with every front-end part
 * set and samples integrated — every byte of the state is changed (xor 0x01, 0x80, 0xff), and each changed
 * state is handed to a getter, a single push and a burst. Each call must return an error code
 * (QUATPROP_NOT_INITIALIZED for the tag's 4 bytes, QUATPROP_CORRUPTED_STATE for the others), leave the
 * bytes as they were, and never crash (the sanitizers and the signal handlers would end the run). */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "quatprop.h"

static void crashed(int sig) {
    printf("FAIL flip: signal %d\n", sig);
    fflush(stdout);
    _Exit(2);
}

static unsigned long calls, refused, wrong, changed;

static void expect(quatprop_status_t got, size_t byte, const quatprop_t *flipped, const quatprop_t *after) {
    quatprop_status_t want = byte < 4 ? QUATPROP_NOT_INITIALIZED : QUATPROP_CORRUPTED_STATE;
    calls++;
    if (got == want) refused++;
    else if (wrong++ < 10) printf("FAIL byte %zu: got %s\n", byte, quatprop_status_name((int32_t)got));
    if (memcmp(flipped, after, sizeof *after) != 0) changed++;
}

/* A state in configuration `c` with every front-end part, after 40 samples. 0 if init refused it. */
static int prepare(quatprop_t *s, const quatprop_config_t *c) {
    static const float r[9] = {0.0f, 0.6f, 0.8f, -1.0f, 0.0f, 0.0f, 0.0f, -0.8f, 0.6f};
    if (quatprop_init(s, c) != QUATPROP_OK) return 0;
    int ok = quatprop_set_count_scale_dps(s, 2000.0) == QUATPROP_OK && quatprop_set_alignment_matrix(s, r) == QUATPROP_OK
             && quatprop_set_bias_estimator(s, 8e-3, 1e-3, 0.05f, QUATPROP_DEFAULT_DRIFT) == QUATPROP_OK && quatprop_set_fixed_period(s, 1e-3) == QUATPROP_OK
             && quatprop_set_tick_clock(s, 1e6, 32) == QUATPROP_OK;
    quatprop_sample_t w[40];
    for (int i = 0; i < 40; i++) w[i] = (quatprop_sample_t){1e-3f * i, 2e-3f, 0.5f + 1e-2f * i, 0};
    size_t n;
    if (c->input == QUATPROP_INPUT_DELTA_ANGLES) {
        for (int i = 0; i < 40; i++) { w[i].x *= 1e-3f; w[i].y *= 1e-3f; w[i].z *= 1e-3f; }
        ok = ok && quatprop_push_delta_burst(s, w, 40, &n) == QUATPROP_OK;
    } else {
        ok = ok && quatprop_push_rate_burst(s, w, 40, &n) == QUATPROP_OK;
    }
    return ok;
}

int main(void) {
    signal(SIGSEGV, crashed);
    signal(SIGBUS, crashed);
    signal(SIGILL, crashed);
    signal(SIGTRAP, crashed);
    signal(SIGFPE, crashed);
    static const uint8_t flips[3] = {0x01, 0x80, 0xff};
    unsigned configs = 0, states = 0;
    for (uint32_t in = 0; in <= QUATPROP_INPUT_DELTA_ANGLES; in++)
        for (uint32_t cn = 0; cn <= (in == QUATPROP_INPUT_DELTA_ANGLES ? QUATPROP_CONING_FIVE_SAMPLE : 0); cn++)
            for (uint32_t sc = 0; sc <= QUATPROP_SCHEME_CF4; sc++)
                for (uint32_t st = 0; st <= QUATPROP_STABILIZER_EVERY; st++)
                    for (uint32_t acc = 0; acc <= QUATPROP_ACCUMULATOR_FLOAT_FLOAT; acc++) {
                        quatprop_config_t c;
                        quatprop_config_default(&c);
                        c.input = in; c.coning = cn; c.scheme = sc; c.stabilizer = st; c.every = 3; c.accumulator = acc;
                        quatprop_t good;
                        if (!prepare(&good, &c)) {
                            printf("FAIL configuration %u/%u/%u/%u/%u\n", in, cn, sc, st, acc);
                            return 1;
                        }
                        configs++;
                        for (size_t byte = 0; byte < sizeof good; byte++)
                            for (int f = 0; f < 3; f++) {
                                quatprop_t bad, after;
                                memcpy(&bad, &good, sizeof bad);
                                ((uint8_t *)&bad)[byte] ^= flips[f];
                                states++;
                                quatprop_quat_t q;
                                memcpy(&after, &bad, sizeof after);
                                expect(quatprop_get_attitude(&after, &q), byte, &bad, &after);
                                quatprop_sample_t one = {0.1f, 0.2f, 0.3f, 0};
                                expect(in == QUATPROP_INPUT_DELTA_ANGLES ? quatprop_push_delta(&after, &one, 1e-3f)
                                                                         : quatprop_push_rate(&after, &one, 1e-3f),
                                       byte, &bad, &after);
                                const int16_t counts[2][3] = {{10, -20, 30}, {11, -21, 31}};
                                size_t n = 99;
                                expect(quatprop_push_counts_burst(&after, &counts[0][0], 2, &n), byte, &bad, &after);
                                if (n != 99) wrong++; /* not written: the state could not be read */
                            }
                    }
    printf("flip: %u configurations, %u changed states (every byte of %zu, 3 changes each), %lu calls: "
           "%lu refused with the expected code, %lu not, %lu changed a state, 0 crashes\n",
           configs, states, sizeof(quatprop_t), calls, refused, wrong, changed);
    return wrong != 0 || changed != 0;
}
