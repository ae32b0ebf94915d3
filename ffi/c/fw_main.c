/* The C quick start on the Cortex-M4F (QEMU mps2-an386): the same raw-count stream as the Rust quick start
 * firmware, the attitude's bits printed in the same line (ffi/ci compares it with
 * firmware/expected/quickstart.txt), then the instructions per sample of on_fifo (SysTick under
 * `-icount shift=10`, as firmware/src/bin/bench.rs). Built twice: with the C API (default) and with
 * -DRUST_BASELINE, the Rust quick start's statically typed Attitude behind the same harness, and with
 * -DRUST_KINDS, the same with the core's run-time SchemeKind and StabilizerKind. The C API's build also
 * times single pushes (quatprop_push_counts, one sample per call: the state's check, decoding and encoding
 * paid every call) and the state's checksum alone (quatprop_bench_checksum, feature bench-hooks), beside ABI 3's
 * word hash it replaced (quatprop_bench_checksum_abi3). */
#include <stdint.h>
#include "board.h"
#include "quickstart.h"
#include "scene.h"

#if defined(RUST_KINDS)
#define NAME "kinds"
#define BASELINE(f) quatprop_baseline_kinds_##f
#elif defined(RUST_BASELINE)
#define NAME "rust"
#define BASELINE(f) quatprop_baseline_##f
#endif

#if defined(BASELINE)
/* One of the Rust quick starts behind ffi/src/baseline.rs's three functions (not in the header). */
uint32_t BASELINE(init)(quatprop_t *s);
void BASELINE(on_fifo)(quatprop_t *s, const int16_t *counts, size_t n);
void BASELINE(attitude)(const quatprop_t *s, quatprop_quat_t *out, uint32_t *refused);
static int start(quatprop_t *s) { return BASELINE(init)(s) == 1; }
static void feed(quatprop_t *s, const int16_t (*f)[3], size_t n, uint32_t *refused) {
    (void)refused;
    BASELINE(on_fifo)(s, &f[0][0], n);
}
static void result(quatprop_t *s, quatprop_quat_t *q, uint32_t *refused) { BASELINE(attitude)(s, q, refused); }
#else
#define NAME "c"
static int start(quatprop_t *s) { return attitude_init(s) == QUATPROP_OK; }
static void feed(quatprop_t *s, const int16_t (*f)[3], size_t n, uint32_t *refused) { attitude_on_fifo(s, f, n, refused); }
static void result(quatprop_t *s, quatprop_quat_t *q, uint32_t *refused) { quatprop_get_attitude(s, q); (void)refused; }
#endif

static char *put_str(char *p, const char *s) {
    while (*s) *p++ = *s++;
    return p;
}
static char *put_hex(char *p, uint32_t v) {
    for (int i = 7; i >= 0; i--) *p++ = "0123456789abcdef"[(v >> (4 * i)) & 15];
    return p;
}
static char *put_dec(char *p, uint32_t v) {
    char t[10];
    int n = 0;
    do { t[n++] = (char)('0' + v % 10); v /= 10; } while (v);
    while (n) *p++ = t[--n];
    return p;
}

static quatprop_t att;
/* Samples per measured run, in FIFO bursts of 32 (as the Rust firmware bench). */
#define QS_SAMPLES 256u
static int16_t fifo[32][3];

static uint32_t timed(uint32_t bursts, uint32_t *refused) {
    if (!start(&att)) return 0;
    uint32_t t0 = board_counter_now();
    for (uint32_t b = 0; b < bursts; b++) feed(&att, (const int16_t(*)[3])fifo, 32, refused);
    return board_instructions(t0, board_counter_now());
}

#if !defined(RUST_BASELINE) && !defined(RUST_KINDS)
uint32_t quatprop_bench_checksum(const quatprop_t *s);
uint32_t quatprop_bench_checksum_abi3(const quatprop_t *s);
/* Single pushes per measured run (the 24-bit SysTick holds about 655 000 instructions). */
#define QS_CALLS 32u
/* Checksums per measured run. */
#define QS_SUMS 64u
static volatile uint32_t sink;

/* `calls` single pushes of the bench's samples at 1 ms. */
static uint32_t timed_single(uint32_t calls) {
    if (!start(&att)) return 0;
    uint32_t bad = 0, t0 = board_counter_now();
    for (uint32_t i = 0; i < calls; i++) bad += quatprop_push_counts(&att, fifo[i % 32], 1.0e-3) != QUATPROP_OK;
    uint32_t n = board_instructions(t0, board_counter_now());
    return bad ? 0 : n;
}

/* `calls` checksums of the state's block (`sum`: the CRC-32C, or ABI 3's word hash). */
static uint32_t timed_sums(uint32_t (*sum)(const quatprop_t *), uint32_t calls) {
    if (!start(&att)) return 0;
    uint32_t t0 = board_counter_now();
    for (uint32_t i = 0; i < calls; i++) sink += sum(&att);
    return board_instructions(t0, board_counter_now());
}

static char *put_fixed2(char *p, uint32_t hundredths) {
    p = put_dec(p, hundredths / 100);
    *p++ = '.';
    *p++ = (char)('0' + hundredths / 10 % 10);
    *p++ = (char)('0' + hundredths % 10);
    return p;
}
#endif

int main(void) {
    char line[160], *p;
    uint32_t refused = 0;
    int16_t burst[QUICKSTART_BURST][3];
    scene_t sc;
    if (!start(&att)) {
        board_puts("quick start refused to start\n");
        return 1;
    }
    scene_init(&sc);
    uint32_t k = 0;
    while (scene_next(&sc, burst)) {
        feed(&att, (const int16_t(*)[3])burst, QUICKSTART_BURST, &refused);
        /* Keep 32 coning samples for the bench (bursts 100 and 101). */
        for (uint32_t i = 0; i < QUICKSTART_BURST; i++) {
            uint32_t j = (k - 100) * QUICKSTART_BURST + i;
            if (k >= 100 && j < 32)
                for (int a = 0; a < 3; a++) fifo[j][a] = burst[i][a];
        }
        k++;
    }
    quatprop_quat_t q;
    result(&att, &q, &refused);
    p = put_str(line, "quickstart samples=");
    p = put_dec(p, QUICKSTART_BURSTS * QUICKSTART_BURST);
    const float c[4] = {q.w, q.x, q.y, q.z};
    for (int i = 0; i < 4; i++) {
        *p++ = ' ';
        p = put_hex(p, scene_bits(c[i]));
    }
    p = put_str(p, " refused=");
    p = put_dec(p, refused);
    p = put_str(p, "\n");
    *p = 0;
    board_puts(line);

    board_counter_start();
    uint32_t r2 = 0;
    uint32_t full = timed(QS_SAMPLES / 32, &r2), empty = timed(0, &r2);
    uint32_t per = (uint32_t)((uint64_t)(full - empty) * 100u / QS_SAMPLES);
    p = put_str(line, "bench " NAME " on_fifo per-sample ");
    p = put_dec(p, per / 100);
    *p++ = '.';
    *p++ = (char)('0' + per / 10 % 10);
    *p++ = (char)('0' + per % 10);
    p = put_str(p, " (samples=256, bursts of 32)\n");
    *p = 0;
    board_puts(line);
#if !defined(RUST_BASELINE) && !defined(RUST_KINDS)
    uint32_t one = timed_single(QS_CALLS), none = timed_single(0);
    uint32_t per_call = (uint32_t)((uint64_t)(one - none) * 100u / QS_CALLS);
    p = put_str(line, "bench c push_counts per-call ");
    p = put_fixed2(p, per_call);
    p = put_str(p, " (calls=32, one sample each)\n");
    *p = 0;
    board_puts(line);
    uint32_t (*const sums[2])(const quatprop_t *) = {quatprop_bench_checksum, quatprop_bench_checksum_abi3};
    const char *const names[2] = {"bench c checksum per-block ", "bench c checksum-abi3 per-block "};
    for (int k = 0; k < 2; k++) {
        uint32_t full_sums = timed_sums(sums[k], QS_SUMS), no_sums = timed_sums(sums[k], 0);
        uint32_t per_sum = (uint32_t)((uint64_t)(full_sums - no_sums) * 100u / QS_SUMS);
        p = put_str(line, names[k]);
        p = put_fixed2(p, per_sum);
        p = put_str(p, " (calls=64)\n");
        *p = 0;
        board_puts(line);
    }
    if (one == 0) refused++;
#endif
    board_puts("quickstart done\n");
    return refused != 0 || r2 != 0;
}
