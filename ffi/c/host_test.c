/* Host test of the C API (gcc): the quick start's attitude bits (compared by ffi/ci with the Rust quick
 * start's, firmware/expected/quickstart.txt), the calibration estimator's bits on a tumbling body (compared
 * with the Rust estimator's, ffi/expected/calibration.txt) and the error contract: every error has its
 * code, NULL and bad enum values are refused, and the state's bytes are unchanged after every error. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "quickstart.h"
#include "scene.h"
#include "tumble.h"


static unsigned passed, failed;
#define CHECK(cond)                                                          \
    do {                                                                     \
        if (cond) passed++;                                                  \
        else { failed++; printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond); } \
    } while (0)
/* `call` returns `code` and leaves the bytes of the block `blk` points to (a state or a calibration
 * estimator) as they were. */
#define REFUSED(blk, call, code)                                             \
    do {                                                                     \
        unsigned char before_[sizeof *(blk)];                                \
        memcpy(before_, (blk), sizeof before_);                              \
        quatprop_status_t got_ = (call);                                     \
        if (got_ != (code)) printf("  got %s\n", quatprop_status_name((int32_t)got_)); \
        CHECK(got_ == (code));                                               \
        CHECK(memcmp(before_, (blk), sizeof before_) == 0);                  \
    } while (0)

static quatprop_config_t config(uint32_t input) {
    quatprop_config_t c;
    quatprop_config_default(&c);
    c.input = input;
    return c;
}

static void quick_start(void) {
    static quatprop_t state;
    quatprop_t *att = &state;
    uint32_t refused = 0;
    int16_t burst[QUICKSTART_BURST][3];
    scene_t sc;
    CHECK(attitude_init(att) == QUATPROP_OK);
    scene_init(&sc);
    while (scene_next(&sc, burst)) attitude_on_fifo(att, (const int16_t(*)[3])burst, QUICKSTART_BURST, &refused);
    quatprop_quat_t q;
    CHECK(quatprop_get_attitude(att, &q) == QUATPROP_OK);
    printf("quickstart samples=%u %08x %08x %08x %08x refused=%u\n", QUICKSTART_BURSTS * QUICKSTART_BURST,
           (unsigned)scene_bits(q.w), (unsigned)scene_bits(q.x), (unsigned)scene_bits(q.y),
           (unsigned)scene_bits(q.z), (unsigned)refused);
    quatprop_counters_t n;
    CHECK(quatprop_get_counters(att, &n) == QUATPROP_OK);
    CHECK(n.steps == 9999 && n.corrections == 9999 && n.saturated == 0 && n.bias_learned == 1);
    float b[3];
    CHECK(quatprop_get_bias(att, b) == QUATPROP_OK);
    /* Bias (12, -3, 7) counts in sensor axes is (-3, -12, 7) counts in body axes. */
    float k = (float)(2000.0 * 3.14159265358979 / 180.0 / 32768.0);
    CHECK(fabsf(b[0] + 3 * k) < 1e-6f && fabsf(b[1] + 12 * k) < 1e-6f && fabsf(b[2] - 7 * k) < 1e-6f);
}

static void not_initialized_and_null(void) {
    static quatprop_t zeroed; /* .bss: never initialized */
    quatprop_quat_t q;
    quatprop_sample_t w = {0, 0, 1, 0};
    size_t n = 7;
    REFUSED(&zeroed, quatprop_get_attitude(&zeroed, &q), QUATPROP_NOT_INITIALIZED);
    REFUSED(&zeroed, quatprop_push_rate(&zeroed, &w, 1e-3f), QUATPROP_NOT_INITIALIZED);
    REFUSED(&zeroed, quatprop_push_rate_burst(&zeroed, &w, 1, &n), QUATPROP_NOT_INITIALIZED);
    REFUSED(&zeroed, quatprop_set_fixed_period(&zeroed, 1e-3), QUATPROP_NOT_INITIALIZED);
    CHECK(n == 7);
    CHECK(quatprop_init(NULL, NULL) == QUATPROP_NULL_POINTER);
    quatprop_t s;
    quatprop_config_t c = config(QUATPROP_INPUT_HISTORY);
    CHECK(quatprop_init(&s, NULL) == QUATPROP_NULL_POINTER);
    CHECK(quatprop_init(NULL, &c) == QUATPROP_NULL_POINTER);
    CHECK(quatprop_init(&s, &c) == QUATPROP_OK);
    REFUSED(&s, quatprop_get_attitude(&s, NULL), QUATPROP_NULL_POINTER);
    CHECK(quatprop_get_attitude(NULL, &q) == QUATPROP_NULL_POINTER);
    REFUSED(&s, quatprop_push_rate(&s, NULL, 1e-3f), QUATPROP_NULL_POINTER);
    REFUSED(&s, quatprop_push_rate_burst(&s, NULL, 0, &n), QUATPROP_NULL_POINTER);
    REFUSED(&s, quatprop_push_rate_burst(&s, &w, 1, NULL), QUATPROP_NULL_POINTER);
    REFUSED(&s, quatprop_set_fixed_bias(&s, NULL), QUATPROP_NULL_POINTER);
    CHECK(quatprop_config_default(NULL) == QUATPROP_NULL_POINTER);
    /* A misaligned pointer is refused, not dereferenced. */
    _Alignas(4) unsigned char raw[16] = {0};
    REFUSED(&s, quatprop_push_counts(&s, (const int16_t *)(raw + 1), 1e-3f), QUATPROP_MISALIGNED_POINTER);
    REFUSED(&s, quatprop_get_attitude((const quatprop_t *)(raw + 4), &q), QUATPROP_MISALIGNED_POINTER);
}

static void bad_configuration(void) {
    quatprop_t s;
    quatprop_config_t c = config(QUATPROP_INPUT_HISTORY);
    CHECK(quatprop_init(&s, &c) == QUATPROP_OK);
    quatprop_config_t bad;
    bad = c; bad.scheme = 8;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_BAD_ENUM);
    bad = c; bad.stabilizer = 4;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_BAD_ENUM);
    bad = c; bad.input = 6;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_BAD_ENUM);
    bad = c; bad.accumulator = 3;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_BAD_ENUM);
    bad = c; bad.input = QUATPROP_INPUT_DELTA_ANGLES; bad.coning = 6;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_BAD_ENUM);
    bad = c; bad.scheme = 0xffffffffu;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_BAD_ENUM);
    bad = c; bad.stabilizer = QUATPROP_STABILIZER_EVERY; bad.every = 0;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_INVALID_STABILIZER);
    bad = c; bad.q0.w = 0.0f;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_ZERO_QUATERNION);
    bad = c; bad.q0.x = NAN;
    REFUSED(&s, quatprop_init(&s, &bad), QUATPROP_NON_FINITE_QUATERNION);
    REFUSED(&s, quatprop_set_axis_remap(&s, 24), QUATPROP_BAD_ENUM);
    const float shear[9] = {1, 0.1f, 0, 0, 1, 0, 0, 0, 1};
    REFUSED(&s, quatprop_set_alignment_matrix(&s, shear), QUATPROP_NOT_A_ROTATION);
    const float mirror[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1};
    REFUSED(&s, quatprop_set_alignment_matrix(&s, mirror), QUATPROP_NOT_A_ROTATION);
    REFUSED(&s, quatprop_set_bias_estimator(&s, 0.0, 1e-3, 0.05f, QUATPROP_DEFAULT_DRIFT), QUATPROP_INVALID_ESTIMATOR);
    REFUSED(&s, quatprop_set_bias_estimator(&s, 1.0, 1e-3, NAN, QUATPROP_DEFAULT_DRIFT), QUATPROP_INVALID_ESTIMATOR);
    REFUSED(&s, quatprop_set_bias_estimator(&s, 1.0, 1e-3, 0.05f, -1.0f), QUATPROP_INVALID_ESTIMATOR);
    /* A calibration that is singular, or not finite, is refused; the state stays as it was. */
    const float offset[3] = {0.01f, -0.02f, 0.005f}, unit[3] = {1, 1, 1}, flat[3] = {1, 0, 1};
    const float ident[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, nan_m[9] = {1, 0, 0, 0, NAN, 0, 0, 0, 1};
    REFUSED(&s, quatprop_set_calibration(&s, offset, flat, ident), QUATPROP_INVALID_CALIBRATION);
    REFUSED(&s, quatprop_set_calibration(&s, offset, unit, nan_m), QUATPROP_INVALID_CALIBRATION);
    REFUSED(&s, quatprop_set_calibration(&s, offset, unit, NULL), QUATPROP_NULL_POINTER);
    const float nan_bias[3] = {0, NAN, 0};
    REFUSED(&s, quatprop_set_fixed_bias(&s, nan_bias), QUATPROP_NON_FINITE_RATE);
    REFUSED(&s, quatprop_set_tick_clock(&s, 1e6, 33), QUATPROP_INVALID_CLOCK);
    REFUSED(&s, quatprop_set_tick_clock(&s, -1.0, 32), QUATPROP_NON_POSITIVE_STEP);
    REFUSED(&s, quatprop_set_fixed_period(&s, 0.0), QUATPROP_NON_POSITIVE_STEP);
    REFUSED(&s, quatprop_set_fixed_period(&s, INFINITY), QUATPROP_NON_FINITE_STEP);
    REFUSED(&s, quatprop_set_count_scale_dps(&s, -2000.0), QUATPROP_BAD_ARGUMENT);
    REFUSED(&s, quatprop_set_count_sensitivity(&s, NAN), QUATPROP_BAD_ARGUMENT);
    quatprop_quat_t zero = {0, 0, 0, 0};
    REFUSED(&s, quatprop_set_attitude(&s, &zero), QUATPROP_ZERO_QUATERNION);
    CHECK(strcmp(quatprop_status_name(QUATPROP_OK), "QUATPROP_OK") == 0);
    /* The library's version at run time: "major.minor.patch", the header's; and the header's ABI version. */
    const char *v = quatprop_version();
    const char *dot = v ? strchr(v, '.') : NULL;
    CHECK(dot != NULL && strchr(dot + 1, '.') != NULL);
    CHECK(strcmp(v, QUATPROP_VERSION) == 0);
    CHECK(quatprop_abi_version() == QUATPROP_ABI_VERSION);
    CHECK(strcmp(quatprop_status_name(QUATPROP_BAD_ENUM), "QUATPROP_BAD_ENUM") == 0);
    CHECK(strcmp(quatprop_status_name(999), "unknown status") == 0);
}

static void refused_samples(void) {
    quatprop_t s;
    quatprop_config_t c = config(QUATPROP_INPUT_HISTORY);
    CHECK(quatprop_init(&s, &c) == QUATPROP_OK);
    quatprop_sample_t w = {0, 0, 1, 0}, nan = {0, NAN, 1, 0}, fast = {0, 0, 1e6f, 0};
    for (int i = 0; i < 3; i++) CHECK(quatprop_push_rate(&s, &w, 1e-3f) == QUATPROP_OK);
    REFUSED(&s, quatprop_push_rate(&s, &nan, 1e-3f), QUATPROP_NON_FINITE_RATE);
    REFUSED(&s, quatprop_push_rate(&s, &w, 0.0f), QUATPROP_NON_POSITIVE_STEP);
    REFUSED(&s, quatprop_push_rate(&s, &w, -1e-3f), QUATPROP_NON_POSITIVE_STEP);
    REFUSED(&s, quatprop_push_rate(&s, &w, NAN), QUATPROP_NON_FINITE_STEP);
    REFUSED(&s, quatprop_push_rate(&s, &w, INFINITY), QUATPROP_NON_FINITE_STEP);
    /* ExpMap takes any step angle; RK4 refuses one beyond its stability bound (2.83 rad). */
    quatprop_t r4;
    quatprop_config_t c4 = c;
    c4.scheme = QUATPROP_SCHEME_RK4;
    CHECK(quatprop_init(&r4, &c4) == QUATPROP_OK);
    for (int i = 0; i < 3; i++) CHECK(quatprop_push_rate(&r4, &w, 1e-3f) == QUATPROP_OK);
    REFUSED(&r4, quatprop_push_rate(&r4, &fast, 1e-3f), QUATPROP_STEP_ANGLE_BEYOND_STABILITY);
    const quatprop_sample_t d = {0, 0, 1e-3f, 0};
    REFUSED(&s, quatprop_push_delta(&s, &d, 1e-3f), QUATPROP_WRONG_INPUT_KIND);
    size_t n = 9;
    REFUSED(&s, quatprop_push_rate_burst(&s, &w, 1, &n), QUATPROP_NOT_CONFIGURED);
    CHECK(n == 0);
    const int16_t counts[3] = {0, 0, 100};
    REFUSED(&s, quatprop_push_counts(&s, counts, 1e-3f), QUATPROP_NOT_CONFIGURED);
    quatprop_counters_t k;
    CHECK(quatprop_get_counters(&s, &k) == QUATPROP_OK && k.steps == 2);

    /* A burst with a NaN at index 5: stops there, 5 integrated; the rest goes on and covers the interval. */
    quatprop_sample_t burst[32];
    for (int i = 0; i < 32; i++) burst[i] = w;
    burst[5] = nan;
    quatprop_t b;
    CHECK(quatprop_init(&b, &c) == QUATPROP_OK && quatprop_set_fixed_period(&b, 1e-3) == QUATPROP_OK);
    CHECK(quatprop_push_rate_burst(&b, burst, 32, &n) == QUATPROP_NON_FINITE_RATE && n == 5);
    CHECK(quatprop_push_rate_burst(&b, burst + 6, 26, &n) == QUATPROP_OK && n == 26);
    quatprop_quat_t q;
    CHECK(quatprop_get_attitude(&b, &q) == QUATPROP_OK);
    float yaw = 2.0f * atan2f(q.z, q.w); /* 31 intervals of 1 ms at 1 rad/s */
    CHECK(fabsf(yaw - 31e-3f) < 1e-7f);
    quatprop_euler_zyx_t e;
    CHECK(quatprop_get_euler_zyx(&b, &e) == QUATPROP_OK && fabsf(e.yaw - 31e-3f) < 1e-7f && e.pitch == 0.0f);
    float ne;
    CHECK(quatprop_get_norm_error(&b, &ne) == QUATPROP_OK && fabsf(ne) < 1e-6f);

    /* A copy of a state goes on exactly as the original. */
    quatprop_t copy;
    memcpy(&copy, &b, sizeof copy);
    CHECK(quatprop_push_rate_burst(&b, burst, 5, &n) == QUATPROP_OK);
    CHECK(quatprop_push_rate_burst(&copy, burst, 5, &n) == QUATPROP_OK);
    CHECK(memcmp(&copy, &b, sizeof b) == 0);

    /* Timed burst: a repeated timestamp is refused at its index; the clock stays at the last accepted. */
    quatprop_t t;
    CHECK(quatprop_init(&t, &c) == QUATPROP_OK && quatprop_set_count_scale_dps(&t, 2000.0) == QUATPROP_OK);
    CHECK(quatprop_set_tick_clock(&t, 1e6, 32) == QUATPROP_OK);
    const int16_t fifo[5][3] = {{0, 0, 939}, {0, 0, 939}, {0, 0, 939}, {0, 0, 939}, {0, 0, 939}};
    const uint32_t ts[5] = {0, 1000, 2000, 2000, 4000};
    CHECK(quatprop_push_counts_burst_timed(&t, &fifo[0][0], ts, 5, &n) == QUATPROP_TIMESTAMP_NOT_INCREASING && n == 3);
    CHECK(quatprop_push_counts_burst_timed(&t, &fifo[4][0], ts + 4, 1, &n) == QUATPROP_OK && n == 1);
    CHECK(quatprop_get_counters(&t, &k) == QUATPROP_OK && k.steps == 3);

    /* Saturated counts are integrated and counted. */
    const int16_t rail[3] = {32767, 0, 0};
    CHECK(quatprop_push_counts(&t, rail, 1e-6f) == QUATPROP_OK);
    CHECK(quatprop_get_counters(&t, &k) == QUATPROP_OK && k.saturated == 1);
}

static void delta_angles_and_kahan(void) {
    quatprop_t s;
    quatprop_config_t c = config(QUATPROP_INPUT_DELTA_ANGLES);
    c.coning = QUATPROP_CONING_TWO_SAMPLE;
    c.accumulator = QUATPROP_ACCUMULATOR_KAHAN;
    CHECK(quatprop_init(&s, &c) == QUATPROP_OK && quatprop_set_fixed_period(&s, 1e-3) == QUATPROP_OK);
    quatprop_sample_t d[40];
    for (int i = 0; i < 40; i++) d[i] = (quatprop_sample_t){0, 0, 1e-3f, 0};
    size_t n;
    quatprop_sample_t w = {0, 0, 1, 0};
    REFUSED(&s, quatprop_push_rate(&s, &w, 1e-3f), QUATPROP_WRONG_INPUT_KIND);
    REFUSED(&s, quatprop_push_rate_burst(&s, &w, 1, &n), QUATPROP_WRONG_INPUT_KIND);
    CHECK(quatprop_push_delta_burst(&s, d, 40, &n) == QUATPROP_OK && n == 40);
    quatprop_euler_zyx_t e;
    CHECK(quatprop_get_euler_zyx(&s, &e) == QUATPROP_OK && fabsf(e.yaw - 40e-3f) < 1e-6f);
    d[33].y = INFINITY;
    CHECK(quatprop_push_delta_burst(&s, d, 40, &n) == QUATPROP_NON_FINITE_RATE && n == 33);
    /* Every configuration initializes and integrates. */
    for (uint32_t in = 0; in <= QUATPROP_INPUT_DELTA_ANGLES; in++)
        for (uint32_t sc = 0; sc <= QUATPROP_SCHEME_CF4; sc++)
            for (uint32_t acc = 0; acc <= QUATPROP_ACCUMULATOR_FLOAT_FLOAT; acc++) {
                quatprop_config_t k = config(in);
                k.scheme = sc;
                k.accumulator = acc;
                k.stabilizer = QUATPROP_STABILIZER_EVERY;
                k.every = 3;
                int ok = quatprop_init(&s, &k) == QUATPROP_OK && quatprop_set_fixed_period(&s, 1e-3) == QUATPROP_OK;
                ok = ok && (in == QUATPROP_INPUT_DELTA_ANGLES ? quatprop_push_delta_burst(&s, d, 20, &n)
                                                              : quatprop_push_rate_burst(&s, d, 20, &n)) == QUATPROP_OK;
                quatprop_euler_zxz_t z;
                ok = ok && quatprop_get_euler_zxz(&s, &z) == QUATPROP_OK && z.theta == z.theta;
                CHECK(ok);
            }
}

/* The calibration is applied to every rate sample first: a still sensor reading its offset does not turn;
 * its sensitivity scales each axis before the misalignment mixes them. */
static void calibration(void) {
    quatprop_config_t c = config(QUATPROP_INPUT_HOLD);
    quatprop_t s;
    CHECK(quatprop_init(&s, &c) == QUATPROP_OK);
    const float offset[3] = {0.01f, -0.02f, 0.005f}, sens[3] = {2, 1, 1};
    const float ident[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    CHECK(quatprop_set_calibration(&s, offset, sens, ident) == QUATPROP_OK);
    quatprop_sample_t still = {0.01f, -0.02f, 0.005f, 0};
    for (int i = 0; i < 100; i++) CHECK(quatprop_push_rate(&s, &still, 1e-3f) == QUATPROP_OK);
    quatprop_quat_t q;
    CHECK(quatprop_get_attitude(&s, &q) == QUATPROP_OK);
    CHECK(q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f);
    /* 0.5 rad/s above the offset on x, sensitivity 2: 1 rad/s for 0.1 s, a 0.1 rad turn about x. */
    quatprop_sample_t turn = {0.51f, -0.02f, 0.005f, 0};
    for (int i = 0; i < 100; i++) CHECK(quatprop_push_rate(&s, &turn, 1e-3f) == QUATPROP_OK);
    CHECK(quatprop_get_attitude(&s, &q) == QUATPROP_OK);
    CHECK(fabsf(2.0f * atan2f(q.x, q.w) - 0.1f) < 1e-5f && fabsf(q.y) < 1e-6f && fabsf(q.z) < 1e-6f);
    CHECK(quatprop_clear_calibration(&s) == QUATPROP_OK);
}

/* An estimator's corrections: a rotation in either frame, and a bias correction that moves the fixed bias
 * and the history's samples together; refusals leave the state as it was. */
static void corrections(void) {
    quatprop_t s;
    quatprop_config_t c = config(QUATPROP_INPUT_HISTORY);
    CHECK(quatprop_init(&s, &c) == QUATPROP_OK);
    const float roll[3] = {0.1f, 0, 0}, yaw[3] = {0, 0, 0.2f}, nan3[3] = {0, NAN, 0};
    CHECK(quatprop_rotate_reference(&s, roll) == QUATPROP_OK);
    CHECK(quatprop_rotate_body(&s, yaw) == QUATPROP_OK);
    quatprop_quat_t q;
    CHECK(quatprop_get_attitude(&s, &q) == QUATPROP_OK);
    /* exp(roll/2) (x) exp(yaw/2) = (c1 c2, s1 c2, -s1 s2, c1 s2) for half angles 0.05 and 0.1 */
    float c1 = cosf(0.05f), s1 = sinf(0.05f), c2 = cosf(0.1f), s2 = sinf(0.1f);
    CHECK(fabsf(q.w - c1 * c2) < 1e-6f && fabsf(q.x - s1 * c2) < 1e-6f);
    CHECK(fabsf(q.y + s1 * s2) < 1e-6f && fabsf(q.z - c1 * s2) < 1e-6f);
    REFUSED(&s, quatprop_rotate_body(&s, nan3), QUATPROP_NON_FINITE_RATE);
    REFUSED(&s, quatprop_rotate_reference(&s, nan3), QUATPROP_NON_FINITE_RATE);
    REFUSED(&s, quatprop_correct_bias(&s, nan3), QUATPROP_NON_FINITE_RATE);
    CHECK(quatprop_rotate_body(NULL, yaw) == QUATPROP_NULL_POINTER);
    CHECK(quatprop_correct_bias(&s, NULL) == QUATPROP_NULL_POINTER);

    /* A gyro reading 1 rad/s + 0.01 rad/s of bias on z; the bias found after 10 samples: the next step
     * turns by 1 mrad (the history's kept samples moved with the bias). */
    const quatprop_sample_t raw = {0, 0, 1.01f, 0};
    quatprop_t b;
    CHECK(quatprop_init(&b, &c) == QUATPROP_OK);
    for (int i = 0; i < 10; i++) CHECK(quatprop_push_rate(&b, &raw, 1e-3f) == QUATPROP_OK);
    const float delta[3] = {0, 0, 0.01f};
    CHECK(quatprop_correct_bias(&b, delta) == QUATPROP_OK);
    float bias[3];
    CHECK(quatprop_get_bias(&b, bias) == QUATPROP_OK && bias[2] == 0.01f);
    quatprop_quat_t before, after;
    CHECK(quatprop_get_attitude(&b, &before) == QUATPROP_OK);
    CHECK(quatprop_push_rate(&b, &raw, 1e-3f) == QUATPROP_OK);
    CHECK(quatprop_get_attitude(&b, &after) == QUATPROP_OK);
    /* Within the f32 attitude's rounding (the kept samples left alone would give a few 1e-6 rad). */
    float turned = 2.0f * (before.w * after.z - before.z * after.w);
    CHECK(fabsf(turned - 1e-3f) < 3e-7f);
}

static void print_bits(const char *label, const float *v, int n) {
    printf(" %s", label);
    for (int i = 0; i < n; i++) printf(" %08x", (unsigned)scene_bits(v[i]));
}

/* The calibration estimator on the tumbling body (tumble.c: a gyro 1 % high on x): its learned gain, bias,
 * calibration and a corrected rate, printed as bits (ffi/ci compares the line with the Rust estimator's,
 * ffi/expected/calibration.txt), the x scale learned to 2e-4; the calibration handed to a state corrects
 * as the estimator does, bit for bit. */
static void calibration_estimator(void) {
    static quatprop_calibration_estimator_t est; /* QUATPROP_CALIBRATION_ESTIMATOR_SIZE bytes */
    /* A still accelerometer: a measurement noise of 0.001 deg/sqrt(s) (the Rust doc example's). */
    const double noise = 0.001 * (3.14159265358979323846 / 180.0);
    CHECK(quatprop_calibration_estimator_init(&est, 0.01, 0.01, 0.0087, noise) == QUATPROP_OK);
    tumble_t t;
    float rate[3], accel[3];
    unsigned samples = 0, refused = 0;
    tumble_init(&t);
    while (tumble_next(&t, rate, accel)) {
        samples++;
        if (quatprop_calibration_estimator_update(&est, rate, accel, TUMBLE_DT) != QUATPROP_OK) refused++;
    }
    CHECK(samples == TUMBLE_SAMPLES && refused == 0);
    float gain[9], sd[9], bias[3], offset[3], sens[3], mis[9], corrected[3];
    const float one[3] = {1.01f, 0.0f, 0.0f};
    CHECK(quatprop_calibration_estimator_get_gain(&est, gain, sd) == QUATPROP_OK);
    CHECK(quatprop_calibration_estimator_get_bias(&est, bias) == QUATPROP_OK);
    CHECK(quatprop_calibration_estimator_get_calibration(&est, offset, sens, mis) == QUATPROP_OK);
    CHECK(quatprop_calibration_estimator_correct(&est, one, corrected) == QUATPROP_OK);
    printf("calibration samples=%u", samples);
    print_bits("gain", gain, 9);
    print_bits("sd", sd, 9);
    print_bits("bias", bias, 3);
    print_bits("offset", offset, 3);
    print_bits("sensitivity", sens, 3);
    print_bits("misalignment", mis, 9);
    print_bits("corrected", corrected, 3);
    printf("\n");
    printf("calibration x scale %.7f (1/1.01 = %.7f), its std dev %.2e (prior 0.01)\n", (double)gain[0],
           1.0 / 1.01, (double)sd[0]);
    CHECK(fabsf(gain[0] - 1.0f / 1.01f) < 2e-4f && sd[0] < 1e-3f);
    CHECK(fabsf(corrected[0] - 1.0f) < 5e-4f);
    for (int i = 0; i < 3; i++) CHECK(offset[i] == bias[i] && sens[i] == gain[4 * i]);

    /* The hand-over: a state with the learned calibration integrates what the estimator corrects. */
    quatprop_config_t c = config(QUATPROP_INPUT_HOLD);
    c.scheme = QUATPROP_SCHEME_EULER;
    quatprop_t with, without;
    CHECK(quatprop_init(&with, &c) == QUATPROP_OK && quatprop_init(&without, &c) == QUATPROP_OK);
    CHECK(quatprop_set_calibration(&with, offset, sens, mis) == QUATPROP_OK);
    const float raw[3] = {0.3f, -0.7f, 1.2f};
    float w[3];
    CHECK(quatprop_calibration_estimator_correct(&est, raw, w) == QUATPROP_OK);
    quatprop_sample_t r = {raw[0], raw[1], raw[2], 0}, k = {w[0], w[1], w[2], 0};
    quatprop_quat_t qa, qb;
    for (int i = 0; i < 10; i++) {
        CHECK(quatprop_push_rate(&with, &r, 1e-2) == QUATPROP_OK);
        CHECK(quatprop_push_rate(&without, &k, 1e-2) == QUATPROP_OK);
    }
    CHECK(quatprop_get_attitude(&with, &qa) == QUATPROP_OK && quatprop_get_attitude(&without, &qb) == QUATPROP_OK);
    CHECK(memcmp(&qa, &qb, sizeof qa) == 0 && qa.w != 1.0f);
    /* rate_out may be rate_in. */
    float same[3] = {raw[0], raw[1], raw[2]};
    CHECK(quatprop_calibration_estimator_correct(&est, same, same) == QUATPROP_OK && memcmp(same, w, sizeof w) == 0);

    /* A copy goes on exactly as the original. */
    static quatprop_calibration_estimator_t copy;
    memcpy(&copy, &est, sizeof copy);
    tumble_init(&t);
    for (int i = 0; i < 20 && tumble_next(&t, rate, accel); i++) {
        CHECK(quatprop_calibration_estimator_update(&est, rate, accel, TUMBLE_DT) == QUATPROP_OK);
        CHECK(quatprop_calibration_estimator_update(&copy, rate, accel, TUMBLE_DT) == QUATPROP_OK);
    }
    CHECK(memcmp(&copy, &est, sizeof est) == 0);

    /* At rest: the residual bias restarts at zero, the gain stays. */
    CHECK(quatprop_calibration_estimator_get_gain(&est, gain, sd) == QUATPROP_OK);
    float after[9];
    CHECK(quatprop_calibration_estimator_at_rest(&est) == QUATPROP_OK);
    CHECK(quatprop_calibration_estimator_get_gain(&est, after, sd) == QUATPROP_OK && memcmp(after, gain, sizeof gain) == 0);
    CHECK(quatprop_calibration_estimator_get_bias(&est, bias) == QUATPROP_OK);
    CHECK(bias[0] == 0.0f && bias[1] == 0.0f && bias[2] == 0.0f);

    /* The default noise is accepted. */
    static quatprop_calibration_estimator_t d;
    CHECK(quatprop_calibration_estimator_init(&d, 0.01, 0.01, 0.0087, QUATPROP_DEFAULT_MOTION_NOISE) == QUATPROP_OK);
    printf("calibration estimator %u bytes, align %u\n", (unsigned)sizeof est, (unsigned)_Alignof(quatprop_calibration_estimator_t));
    CHECK(sizeof est == QUATPROP_CALIBRATION_ESTIMATOR_SIZE
          && _Alignof(quatprop_calibration_estimator_t) == QUATPROP_CALIBRATION_ESTIMATOR_ALIGN);
}

/* The calibration estimator's refusals: each has its code and leaves the block's bytes as they were. */
static void calibration_estimator_refusals(void) {
    static quatprop_calibration_estimator_t zeroed; /* .bss: never initialized */
    quatprop_calibration_estimator_t e;
    const float ok[3] = {0.1f, 0.2f, 0.3f}, g[3] = {0.0f, 0.0f, 9.81f};
    const float nan3[3] = {0.0f, NAN, 0.0f}, inf3[3] = {INFINITY, 0.0f, 0.0f};
    float out[9] = {7, 7, 7, 7, 7, 7, 7, 7, 7}, out2[9], out3[9];
    REFUSED(&zeroed, quatprop_calibration_estimator_update(&zeroed, ok, g, 0.01), QUATPROP_NOT_INITIALIZED);
    REFUSED(&zeroed, quatprop_calibration_estimator_correct(&zeroed, ok, out), QUATPROP_NOT_INITIALIZED);
    REFUSED(&zeroed, quatprop_calibration_estimator_at_rest(&zeroed), QUATPROP_NOT_INITIALIZED);
    REFUSED(&zeroed, quatprop_calibration_estimator_get_gain(&zeroed, out, out2), QUATPROP_NOT_INITIALIZED);
    REFUSED(&zeroed, quatprop_calibration_estimator_get_bias(&zeroed, out), QUATPROP_NOT_INITIALIZED);
    REFUSED(&zeroed, quatprop_calibration_estimator_get_calibration(&zeroed, out, out2, out3), QUATPROP_NOT_INITIALIZED);
    CHECK(out[0] == 7.0f && out[8] == 7.0f);

    CHECK(quatprop_calibration_estimator_init(NULL, 0.01, 0.01, 0.0087, QUATPROP_DEFAULT_MOTION_NOISE) == QUATPROP_NULL_POINTER);
    CHECK(quatprop_calibration_estimator_init(&e, 0.01, 0.01, 0.0087, QUATPROP_DEFAULT_MOTION_NOISE) == QUATPROP_OK);
    tumble_t t;
    float rate[3], accel[3];
    tumble_init(&t);
    for (int i = 0; i < 400 && tumble_next(&t, rate, accel); i++)
        CHECK(quatprop_calibration_estimator_update(&e, rate, accel, TUMBLE_DT) == QUATPROP_OK);
    /* A bad configuration leaves the block as it was. */
    REFUSED(&e, quatprop_calibration_estimator_init(&e, 0.0, 0.01, 0.0087, 1e-3), QUATPROP_NON_POSITIVE_STEP);
    REFUSED(&e, quatprop_calibration_estimator_init(&e, -0.01, 0.01, 0.0087, 1e-3), QUATPROP_NON_POSITIVE_STEP);
    REFUSED(&e, quatprop_calibration_estimator_init(&e, NAN, 0.01, 0.0087, 1e-3), QUATPROP_NON_FINITE_STEP);
    REFUSED(&e, quatprop_calibration_estimator_init(&e, 0.01, -0.01, 0.0087, 1e-3), QUATPROP_INVALID_ESTIMATOR);
    REFUSED(&e, quatprop_calibration_estimator_init(&e, 0.01, 0.01, 0.06, 1e-3), QUATPROP_INVALID_ESTIMATOR);
    REFUSED(&e, quatprop_calibration_estimator_init(&e, 0.01, NAN, 0.0087, 1e-3), QUATPROP_INVALID_ESTIMATOR);
    REFUSED(&e, quatprop_calibration_estimator_init(&e, 0.01, 0.01, 0.0087, 0.0), QUATPROP_INVALID_ESTIMATOR);
    REFUSED(&e, quatprop_calibration_estimator_init(&e, 0.01, 0.01, 0.0087, INFINITY), QUATPROP_INVALID_ESTIMATOR);
    /* Bad samples: the core's errors; nothing changes. */
    REFUSED(&e, quatprop_calibration_estimator_update(&e, nan3, g, 0.01), QUATPROP_NON_FINITE_RATE);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, inf3, g, 0.01), QUATPROP_NON_FINITE_RATE);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, ok, nan3, 0.01), QUATPROP_NON_FINITE_AUX);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, ok, inf3, 0.01), QUATPROP_NON_FINITE_AUX);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, ok, g, 0.0), QUATPROP_NON_POSITIVE_STEP);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, ok, g, -0.01), QUATPROP_NON_POSITIVE_STEP);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, ok, g, NAN), QUATPROP_NON_FINITE_STEP);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, ok, g, INFINITY), QUATPROP_NON_FINITE_STEP);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, ok, g, 1e300), QUATPROP_NON_FINITE_STEP);
    REFUSED(&e, quatprop_calibration_estimator_correct(&e, nan3, out), QUATPROP_NON_FINITE_RATE);
    CHECK(out[0] == 7.0f);
    /* NULL and misaligned pointers. */
    REFUSED(&e, quatprop_calibration_estimator_update(&e, NULL, g, 0.01), QUATPROP_NULL_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_update(&e, ok, NULL, 0.01), QUATPROP_NULL_POINTER);
    CHECK(quatprop_calibration_estimator_update(NULL, ok, g, 0.01) == QUATPROP_NULL_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_correct(&e, ok, NULL), QUATPROP_NULL_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_correct(&e, NULL, out), QUATPROP_NULL_POINTER);
    CHECK(quatprop_calibration_estimator_correct(NULL, ok, out) == QUATPROP_NULL_POINTER);
    CHECK(quatprop_calibration_estimator_at_rest(NULL) == QUATPROP_NULL_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_get_gain(&e, out, NULL), QUATPROP_NULL_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_get_gain(&e, NULL, out2), QUATPROP_NULL_POINTER);
    CHECK(quatprop_calibration_estimator_get_gain(NULL, out, out2) == QUATPROP_NULL_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_get_bias(&e, NULL), QUATPROP_NULL_POINTER);
    CHECK(quatprop_calibration_estimator_get_bias(NULL, out) == QUATPROP_NULL_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_get_calibration(&e, out, out2, NULL), QUATPROP_NULL_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_get_calibration(&e, NULL, out2, out3), QUATPROP_NULL_POINTER);
    CHECK(quatprop_calibration_estimator_get_calibration(NULL, out, out2, out3) == QUATPROP_NULL_POINTER);
    CHECK(out[0] == 7.0f);
    _Alignas(8) unsigned char raw[16] = {0};
    REFUSED(&e, quatprop_calibration_estimator_update(&e, (const float *)(raw + 2), g, 0.01), QUATPROP_MISALIGNED_POINTER);
    REFUSED(&e, quatprop_calibration_estimator_get_bias(&e, (float *)(raw + 1)), QUATPROP_MISALIGNED_POINTER);
    CHECK(quatprop_calibration_estimator_get_bias((const quatprop_calibration_estimator_t *)(raw + 4), out) == QUATPROP_MISALIGNED_POINTER);
    CHECK(strcmp(quatprop_status_name(QUATPROP_NON_FINITE_AUX), "QUATPROP_NON_FINITE_AUX") == 0);
    CHECK(strcmp(quatprop_status_name(QUATPROP_INVALID_CALIBRATION), "QUATPROP_INVALID_CALIBRATION") == 0);
}

int main(void) {
    quick_start();
    not_initialized_and_null();
    bad_configuration();
    refused_samples();
    delta_angles_and_kahan();
    calibration();
    corrections();
    calibration_estimator();
    calibration_estimator_refusals();
    printf("state %u bytes, align %u\n", (unsigned)sizeof(quatprop_t), (unsigned)_Alignof(quatprop_t));
    CHECK(sizeof(quatprop_t) == QUATPROP_STATE_SIZE && _Alignof(quatprop_t) == QUATPROP_STATE_ALIGN);
    printf("c-api: %u passed, %u failed\n", passed, failed);
    return failed != 0;
}
