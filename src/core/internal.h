/* Private helpers of the core module; never installed. */
#ifndef GM_CORE_INTERNAL_H
#define GM_CORE_INTERNAL_H

#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "geomint/core.h"

/* Write a formatted message into buf (capacity cap, always NUL-terminated) and return status,
 * so that error paths read `return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "...")`. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
gm_status gm_fail(char *buf, size_t cap, gm_status status, const char *fmt, ...);

/* Same, for the optional gm_error of creators (err may be NULL). */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
gm_status gm_error_set(gm_error *err, gm_status status, const char *fmt, ...);

#define GM_PI 3.14159265358979323846

/* input_file.c: open a file the user named for reading; NULL with a message in why (capacity
 * cap) when it cannot be opened or is a directory, block device or socket. Never blocks on a
 * FIFO without a writer (it reads as empty). */
#include <stdio.h>
FILE *gm_input_open(const char *path, char *why, size_t cap);

/* json_strict.c: the offset of the first place where text breaks the JSON grammar in a way
 * cJSON accepts (a number like 050 or 1., bytes that are not UTF-8 or raw control characters in
 * a string), with *why saying what; strlen(text) with *why = NULL when there is none. */
size_t gm_json_check_text(const char *text, const char **why);
/* Copy in to out (capacity cap, NUL-terminated) with control bytes written as \xNN, so that a
 * message never sends a raw ESC sequence to a terminal; returns the length written. */
size_t gm_escape_controls(const char *in, char *out, size_t cap);

/* Index of the first non-finite entry of x[0..n), or n when all are finite. The driver checks
 * every new state, so the common case is one pass of integer operations with one-cycle
 * latency: a double is NaN or ±inf exactly when its exponent bits are all ones (IEEE 754). */
static inline size_t gm_first_nonfinite(size_t n, const double *x) {
  const uint64_t exponent = 0x7ff0000000000000ull;
  uint64_t largest = 0;
  for (size_t i = 0; i < n; ++i) {
    uint64_t bits;
    memcpy(&bits, &x[i], sizeof bits);
    bits &= exponent;
    largest = bits > largest ? bits : largest;
  }
  if (largest != exponent) return n;
  for (size_t i = 0; i < n; ++i)
    if (!isfinite(x[i])) return i;
  return n;
}

/* max_i |x_i| */
double gm_norm_inf(size_t n, const double *x);

#endif
