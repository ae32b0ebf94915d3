/* A state that checks itself (gcc -fsanitize=address,undefined): in every configuration — input model (and
 * each coning correction of the delta angles) x scheme x stabilizer x accumulator, with every front-end part
 * set and samples integrated — every bit of the state is flipped on its own, every byte is inverted (xor
 * 0xff), 4096 random pairs of bits are flipped and 1024 random runs of 2 to 32 bytes changed, and each
 * changed state is handed to a getter, a single push and a burst. Each call must return an error code
 * (QUATPROP_NOT_INITIALIZED when the tag's 4 bytes changed, QUATPROP_CORRUPTED_STATE otherwise), leave the
 * bytes as they were, and never crash (the sanitizers and the signal handlers would end the run). Every pair
 * of bits of two states, and random multi-byte damage, are tried against the check itself by
 * ffi/src/tests/check.rs. The calibration estimator's block is changed the same ways, fresh, while its
 * low-pass filters average and while it learns, and handed to every one of its functions but init
 * (ffi/src/tests/calibration.rs tries its check itself). */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "quatprop.h"
#include "tumble.h"

static void crashed(int sig) {
    printf("FAIL flip: signal %d\n", sig);
    fflush(stdout);
    _Exit(2);
}

static unsigned long calls, refused, wrong, changed;

/* Where the tag is (ffi/src/lib.rs's TAG): a state whose tag changed is not a state (NOT_INITIALIZED). */
#define TAG_AT (QUATPROP_STATE_SIZE - 12u)

/* A call on the changed block `flipped` (`size` bytes, its tag at `tag_at`) returned `got` and left
 * `after`. */
static void expect_block(quatprop_status_t got, const void *good, const void *flipped, const void *after, size_t size,
                         size_t tag_at) {
    int tag_changed = memcmp((const uint8_t *)good + tag_at, (const uint8_t *)flipped + tag_at, 4) != 0;
    quatprop_status_t want = tag_changed ? QUATPROP_NOT_INITIALIZED : QUATPROP_CORRUPTED_STATE;
    calls++;
    if (got == want) refused++;
    else if (wrong++ < 10) printf("FAIL got %s, want %s\n", quatprop_status_name((int32_t)got), quatprop_status_name((int32_t)want));
    if (memcmp(flipped, after, size) != 0) changed++;
}

static void expect(quatprop_status_t got, const quatprop_t *good, const quatprop_t *flipped, const quatprop_t *after) {
    expect_block(got, good, flipped, after, sizeof *after, TAG_AT);
}

/* The calibration estimator's tag (ffi/src/calibration.rs's TAG). */
#define EST_TAG_AT (QUATPROP_CALIBRATION_ESTIMATOR_SIZE - 12u)
typedef quatprop_calibration_estimator_t est_t;

static void expect_est(quatprop_status_t got, const est_t *good, const est_t *flipped, const est_t *after) {
    expect_block(got, good, flipped, after, sizeof *after, EST_TAG_AT);
}

/* Hands the changed block `bad` to every function of the estimator but init: none may write an output.
 * (`unused`: the signature of `try_block`.) */
static void try_est(const void *good, const void *bad, int unused) {
    (void)unused;
    est_t after;
    memcpy(&after, bad, sizeof after);
    const float r[3] = {0.1f, 0.2f, 0.3f}, a[3] = {0.0f, 0.0f, 9.81f};
    float out[9], out2[9], out3[9];
    for (int i = 0; i < 9; i++) out[i] = out2[i] = out3[i] = 7.0f;
    expect_est(quatprop_calibration_estimator_update(&after, r, a, 0.01), good, bad, &after);
    expect_est(quatprop_calibration_estimator_correct(&after, r, out), good, bad, &after);
    expect_est(quatprop_calibration_estimator_at_rest(&after), good, bad, &after);
    expect_est(quatprop_calibration_estimator_get_gain(&after, out, out2), good, bad, &after);
    expect_est(quatprop_calibration_estimator_get_bias(&after, out), good, bad, &after);
    expect_est(quatprop_calibration_estimator_get_calibration(&after, out, out2, out3), good, bad, &after);
    for (int i = 0; i < 9; i++)
        if (out[i] != 7.0f || out2[i] != 7.0f || out3[i] != 7.0f) wrong++;
}

/* Hands the changed state `bad` to a getter, a single push (a delta angle if `deltas`) and a burst. */
static void try_state(const void *good, const void *bad, int deltas) {
    quatprop_t after;
    quatprop_quat_t q;
    memcpy(&after, bad, sizeof after);
    expect(quatprop_get_attitude(&after, &q), good, bad, &after);
    quatprop_sample_t one = {0.1f, 0.2f, 0.3f, 0};
    expect(deltas ? quatprop_push_delta(&after, &one, 1e-3f) : quatprop_push_rate(&after, &one, 1e-3f), good, bad, &after);
    const int16_t counts[2][3] = {{10, -20, 30}, {11, -21, 31}};
    size_t n = 99;
    expect(quatprop_push_counts_burst(&after, &counts[0][0], 2, &n), good, bad, &after);
    if (n != 99) wrong++; /* not written: the state could not be read */
}

/* xorshift32: the same random pairs on every run. */
static uint32_t rng_state = 0x9E3779B9u;
static uint32_t rng(void) {
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

/* What a damaged copy `bad` of the block `good` is handed to (`arg`: passed through). */
typedef void try_block(const void *good, const void *bad, int arg);

enum { PAIRS = 4096, RUNS = 1024 };

/* Hands `try_it` each damaged copy of the block `good` (`size` bytes), made in `bad`: each byte with each
 * bit flipped, and inverted; PAIRS random pairs of bits flipped; RUNS random runs of 2 to 32 bytes
 * changed. Returns how many damaged copies were tried. */
static unsigned damage_all(const void *good, void *bad, size_t size, try_block *try_it, int arg) {
    static const uint8_t flips[9] = {0x01, 0x02, 0x04, 0x08, 0x10, 0x20, 0x40, 0x80, 0xff};
    uint8_t *b = bad;
    unsigned tried = 0;
    for (size_t byte = 0; byte < size; byte++)
        for (int f = 0; f < 9; f++) {
            memcpy(bad, good, size);
            b[byte] ^= flips[f];
            tried++;
            try_it(good, bad, arg);
        }
    for (int k = 0; k < PAIRS; k++) {
        uint32_t i = rng() % (8 * size), j = rng() % (8 * size);
        if (i == j) continue;
        memcpy(bad, good, size);
        b[i / 8] ^= (uint8_t)(1u << (i % 8));
        b[j / 8] ^= (uint8_t)(1u << (j % 8));
        tried++;
        try_it(good, bad, arg);
    }
    for (int k = 0; k < RUNS; k++) {
        uint32_t len = 2 + rng() % 31, at = rng() % (uint32_t)(size - len + 1);
        memcpy(bad, good, size);
        for (uint32_t i = at; i < at + len; i++) b[i] ^= (uint8_t)(1u | rng());
        tried++;
        try_it(good, bad, arg);
    }
    return tried;
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
    unsigned configs = 0, states = 0;
    for (uint32_t in = 0; in <= QUATPROP_INPUT_DELTA_ANGLES; in++)
        for (uint32_t cn = 0; cn <= (in == QUATPROP_INPUT_DELTA_ANGLES ? QUATPROP_CONING_FIVE_SAMPLE : 0); cn++)
            for (uint32_t sc = 0; sc <= QUATPROP_SCHEME_CF4; sc++)
                for (uint32_t st = 0; st <= QUATPROP_STABILIZER_EVERY; st++)
                    for (uint32_t acc = 0; acc <= QUATPROP_ACCUMULATOR_FLOAT_FLOAT; acc++) {
                        quatprop_config_t c;
                        quatprop_config_default(&c);
                        c.input = in; c.coning = cn; c.scheme = sc; c.stabilizer = st; c.every = 3; c.accumulator = acc;
                        quatprop_t good, bad;
                        if (!prepare(&good, &c)) {
                            printf("FAIL configuration %u/%u/%u/%u/%u\n", in, cn, sc, st, acc);
                            return 1;
                        }
                        configs++;
                        states += damage_all(&good, &bad, sizeof good, try_state, c.input == QUATPROP_INPUT_DELTA_ANGLES);
                    }
    printf("flip: %u configurations, %u changed states (each of the %zu bytes: every bit flipped, and inverted;"
           " %d random pairs of bits; %d runs of 2 to 32 bytes each changed), %lu calls: %lu refused with the expected"
           " code, %lu not, %lu changed a state, 0 crashes\n",
           configs, states, sizeof(quatprop_t), PAIRS, RUNS, calls, refused, wrong, changed);
    const unsigned long calls0 = calls, refused0 = refused, wrong0 = wrong, changed0 = changed;
    /* The calibration estimator's block: fresh, averaging (150 samples of the tumbling body), learning (3000). */
    static const unsigned est_samples[3] = {0, 150, 3000};
    unsigned est_states = 0;
    for (int k = 0; k < 3; k++) {
        est_t good, bad;
        tumble_t t;
        float rate[3], accel[3];
        int ok = quatprop_calibration_estimator_init(&good, 0.01, 0.01, 0.0087, QUATPROP_DEFAULT_MOTION_NOISE) == QUATPROP_OK;
        tumble_init(&t);
        for (unsigned i = 0; i < est_samples[k] && tumble_next(&t, rate, accel); i++)
            ok = ok && quatprop_calibration_estimator_update(&good, rate, accel, TUMBLE_DT) == QUATPROP_OK;
        if (!ok) {
            printf("FAIL calibration estimator after %u samples\n", est_samples[k]);
            return 1;
        }
        est_states += damage_all(&good, &bad, sizeof good, try_est, 0);
    }
    printf("flip: calibration estimator: 3 blocks (fresh, averaging, learning), %u changed blocks (each of the %zu"
           " bytes: every bit flipped, and inverted; %d random pairs of bits; %d runs of 2 to 32 bytes each changed),"
           " %lu calls to its 6 functions but init: %lu refused with the expected code, %lu not (or wrote an output),"
           " %lu changed a block, 0 crashes\n",
           est_states, sizeof(est_t), PAIRS, RUNS, calls - calls0, refused - refused0, wrong - wrong0, changed - changed0);
    return wrong != 0 || changed != 0;
}
