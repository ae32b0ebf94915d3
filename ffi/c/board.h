#ifndef BOARD_H
#define BOARD_H
#include <stdint.h>
/* The -icount shift the runner gives QEMU (ffi/ci, ffi/figures.py). */
#define ICOUNT_SHIFT 10u
void board_puts(const char *s);
void board_exit(int ok);
void board_counter_start(void);
uint32_t board_counter_now(void);
uint32_t board_instructions(uint32_t start, uint32_t end);
#endif
