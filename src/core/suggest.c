/* "Did you mean" suggestions: names close to a mistyped one by edit distance (restricted
 * Damerau–Levenshtein, case-insensitive; a prefix match counts, so "verlt" is 1 from
 * "verlet-position"). Used by every reader that takes names: methods, problems, scene keys. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "geomint/core.h"

#define MAX_NAME 64
#define MAX_SUGGESTIONS 5

static size_t min3(size_t a, size_t b, size_t c) {
  size_t m = a < b ? a : b;
  return m < c ? m : c;
}

/* Distance table of a against every prefix of b: row m of d. With prefix != 0 the result is
 * the smallest distance from a to any prefix of b ("verlt" is 1 from "verlet-position"). */
static size_t distance(const char *a, const char *b, int prefix) {
  size_t m = strlen(a), n = strlen(b);
  if (m > MAX_NAME) m = MAX_NAME;
  if (n > MAX_NAME) n = MAX_NAME;
  size_t d[MAX_NAME + 1][MAX_NAME + 1];
  for (size_t i = 0; i <= m; ++i) d[i][0] = i;
  for (size_t j = 0; j <= n; ++j) d[0][j] = j;
  for (size_t i = 1; i <= m; ++i) {
    for (size_t j = 1; j <= n; ++j) {
      int ca = tolower((unsigned char)a[i - 1]), cb = tolower((unsigned char)b[j - 1]);
      size_t cost = ca == cb ? 0 : 1;
      d[i][j] = min3(d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost);
      if (i > 1 && j > 1 && ca == tolower((unsigned char)b[j - 2]) &&
          tolower((unsigned char)a[i - 2]) == cb && d[i - 2][j - 2] + 1 < d[i][j])
        d[i][j] = d[i - 2][j - 2] + 1; /* transposition */
    }
  }
  if (!prefix) return d[m][n];
  size_t best = d[m][0];
  for (size_t j = 1; j <= n; ++j)
    if (d[m][j] < best) best = d[m][j];
  return best;
}

size_t gm_edit_distance(const char *a, const char *b) { return distance(a, b, 0); }

/* Largest distance still worth suggesting for a query of this length. */
static size_t tolerance(size_t len) {
  if (len < 3) return 0;
  if (len <= 5) return 1;
  if (len <= 8) return 2;
  return 3;
}

size_t gm_suggest(const char *query, gm_name_at name_at, const void *ctx, char *buf,
                   size_t cap) {
  const char *best[MAX_SUGGESTIONS];
  size_t key[MAX_SUGGESTIONS][2];
  size_t n_best = 0, tol = tolerance(strlen(query));
  for (size_t i = 0;; ++i) {
    const char *name = name_at(ctx, i);
    if (name == NULL) break;
    size_t full = distance(query, name, 0), pre = distance(query, name, 1);
    if (pre > tol && full > tol) continue;
    size_t k0 = pre < full ? pre : full, k1 = full;
    /* insertion into the sorted list of the closest names */
    size_t pos = n_best;
    while (pos > 0 && (key[pos - 1][0] > k0 || (key[pos - 1][0] == k0 && key[pos - 1][1] > k1)))
      --pos;
    if (pos == MAX_SUGGESTIONS) continue;
    size_t last = n_best < MAX_SUGGESTIONS ? n_best : MAX_SUGGESTIONS - 1;
    for (size_t j = last; j > pos; --j) {
      best[j] = best[j - 1];
      key[j][0] = key[j - 1][0];
      key[j][1] = key[j - 1][1];
    }
    best[pos] = name;
    key[pos][0] = k0;
    key[pos][1] = k1;
    if (n_best < MAX_SUGGESTIONS) ++n_best;
  }
  size_t len = 0;
  if (cap > 0) buf[0] = '\0';
  for (size_t j = 0; j < n_best && len < cap; ++j) {
    int w = snprintf(buf + len, cap - len, "%s%s", j > 0 ? ", " : "", best[j]);
    if (w < 0) break;
    len += (size_t)w;
  }
  return n_best;
}

