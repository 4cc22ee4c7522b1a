/* What a Yee grid, its materials and its probe buffers would occupy, estimated before anything
 * is allocated, so that an absurd size ("cells": [1e5, 1e5, 1e5], a probe buffer of 10^15
 * samples) is refused with its size in bytes instead of failing inside malloc or swapping the
 * machine to a halt. The budget is the machine's physical memory. */
#include <stdio.h>
#include <unistd.h>

#include "fields/internal.h"

double yee_memory_budget(void) {
  long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) return (double)pages * (double)page;
  return 64.0 * (1u << 30); /* unknown: assume a 64 GiB machine */
}

const char *yee_bytes_text(double bytes, char *out, size_t cap) {
  static const char *const unit[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  size_t u = 0;
  while (bytes >= 1000.0 && u + 1 < sizeof unit / sizeof *unit) bytes /= 1000.0, ++u;
  if (bytes >= 1000.0) /* beyond exabytes: keep the exponent */
    snprintf(out, cap, "%.3g %s", bytes, unit[u]);
  else
    snprintf(out, cap, u == 0 ? "%.0f %s" : "%.1f %s", bytes, unit[u]);
  return out;
}

/* Field, coefficient and material arrays of gm_yee_create for grid (the worst case: every
 * component, Bloch's complex fields, per-edge coefficients of a lossy non-uniform medium), plus
 * the three per-cell material arrays of gm_yee_materials_create. In doubles, so that it cannot
 * overflow. */
double yee_grid_bytes(const gm_yee_grid *grid, int complex_fields) {
  const size_t axes = gm_yee_dim_axes(grid->dim);
  double cells = 1.0, padded = 1.0;
  for (size_t a = 0; a < axes; ++a) {
    cells *= (double)grid->n[a];
    padded *= (double)grid->n[a] + 2.0;
  }
  /* 6 components × parts + zeros + 6 cb + 3 ca arrays on the padded layout; ε, μ copies and
   * ε, μ, σ of the materials per cell */
  const double arrays = 6.0 * (complex_fields ? 2.0 : 1.0) + 1.0 + 6.0 + 3.0;
  return 8.0 * (arrays * padded + 5.0 * cells);
}

gm_status yee_memory_check(double bytes, const char *what, gm_error *err) {
  const double budget = yee_memory_budget();
  if (bytes <= budget) return GM_OK;
  char need[32], have[32];
  return gm_error_set(err, GM_EINVAL, "%s need %s, more than this machine's %s of memory", what,
                      yee_bytes_text(bytes, need, sizeof need),
                      yee_bytes_text(budget, have, sizeof have));
}
