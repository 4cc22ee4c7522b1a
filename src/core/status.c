/* Status codes, their messages, and the small helpers every module uses to report errors. */
#include <math.h>
#include <stdio.h>

#include "core/internal.h"

const char *gm_strerror(gm_status status) {
  switch (status) {
#define GM_STATUS_CASE_(name, value, text) \
  case name:                               \
    return text;
    GM_STATUS_LIST(GM_STATUS_CASE_)
#undef GM_STATUS_CASE_
  }
  return "unknown status";
}

static void format_into(char *buf, size_t cap, const char *fmt, va_list ap) {
  if (buf == NULL || cap == 0) return;
  int n = vsnprintf(buf, cap, fmt, ap);
  if (n < 0) buf[0] = '\0';
}

gm_status gm_fail(char *buf, size_t cap, gm_status status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  format_into(buf, cap, fmt, ap);
  va_end(ap);
  return status;
}

gm_status gm_error_set(gm_error *err, gm_status status, const char *fmt, ...) {
  if (err == NULL) return status;
  va_list ap;
  va_start(ap, fmt);
  format_into(err->message, sizeof err->message, fmt, ap);
  va_end(ap);
  return status;
}

double gm_norm_inf(size_t n, const double *x) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double a = fabs(x[i]);
    if (a > m || isnan(a)) m = a;
  }
  return m;
}
