/* Minimal Cortex-M4F startup for QEMU's mps2-an386: vector table, .data/.bss, FPU on, main, semihosting
 * exit. No C library. */
#include <stdint.h>
#include "board.h"

extern uint32_t __data_load, __data_start, __data_end, __bss_start, __bss_end, __stack_top;
int main(void);

static int semihost(int op, const void *arg) {
    register int r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void board_puts(const char *s) { semihost(0x04, s); } /* SYS_WRITE0 */

void board_exit(int ok) {
    /* SYS_EXIT: ADP_Stopped_ApplicationExit is exit status 0 in QEMU, any other reason 1. */
    semihost(0x18, (const void *)(uintptr_t)(ok ? 0x20026 : 0x20023));
    for (;;) {
    }
}

void Reset_Handler(void) {
    uint32_t *src = &__data_load, *dst = &__data_start;
    while (dst < &__data_end) *dst++ = *src++;
    for (dst = &__bss_start; dst < &__bss_end;) *dst++ = 0;
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20; /* CPACR: CP10, CP11 full access (FPU on) */
    __asm__ volatile("dsb\n isb" ::: "memory");
    board_exit(main() == 0);
}

static void fault(void) {
    board_puts("fault\n");
    board_exit(0);
}

__attribute__((section(".vectors"), used)) static const void *const vectors[16] = {
    &__stack_top, (const void *)Reset_Handler, (const void *)fault, (const void *)fault,
    (const void *)fault, (const void *)fault, (const void *)fault, 0, 0, 0, 0,
    (const void *)fault, (const void *)fault, 0, (const void *)fault, (const void *)fault,
};

/* SysTick on the 25 MHz core clock; under `-icount shift=10` one instruction is 2^10 ns = 25.6 ticks. */
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
void board_counter_start(void) {
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0;
    SYST_CSR = 5; /* enable, core clock, no interrupt */
}
uint32_t board_counter_now(void) { return SYST_CVR; }
uint32_t board_instructions(uint32_t start, uint32_t end) {
    uint64_t ticks = (start - end) & 0x00FFFFFFu;
    return (uint32_t)((ticks * 40u + (1u << (ICOUNT_SHIFT - 1))) >> ICOUNT_SHIFT);
}
