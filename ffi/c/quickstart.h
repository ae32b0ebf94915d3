/* The C quick start (docs/c-api.md shows quickstart.c verbatim): the Rust README quick start's
 * configuration through the C API. */
#ifndef QUICKSTART_H
#define QUICKSTART_H
#include <stdint.h>
#include "quatprop.h"

quatprop_status_t attitude_init(quatprop_t *att);
void attitude_on_fifo(quatprop_t *att, const int16_t (*fifo)[3], size_t n, uint32_t *refused);
#endif
