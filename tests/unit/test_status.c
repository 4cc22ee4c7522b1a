/* Status codes and the error-reporting helpers shared by all modules. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/core.h"

static const gm_status all_codes[] = {
#define GM_STATUS_ITEM_(name, value, text) name,
    GM_STATUS_LIST(GM_STATUS_ITEM_)
#undef GM_STATUS_ITEM_
};
enum { N_CODES = sizeof all_codes / sizeof all_codes[0] };

Test(status, messages_are_distinct_and_non_empty) {
  cr_assert_eq(N_CODES, 11);
  for (size_t i = 0; i < N_CODES; ++i) {
    const char *m = gm_strerror(all_codes[i]);
    cr_assert_not_null(m);
    cr_assert(strlen(m) > 0, "code %d has an empty message", (int)all_codes[i]);
    cr_assert_str_neq(m, "unknown status", "code %d", (int)all_codes[i]);
    for (size_t j = 0; j < i; ++j)
      cr_assert_str_neq(m, gm_strerror(all_codes[j]), "codes %d and %d share a message",
                        (int)all_codes[i], (int)all_codes[j]);
  }
  cr_assert_str_eq(gm_strerror(GM_OK), "success");
  cr_assert_eq(GM_OK, 0);
  for (size_t i = 1; i < N_CODES; ++i) cr_assert_lt((int)all_codes[i], 0);
}

Test(status, unknown_code) {
  cr_assert_str_eq(gm_strerror((gm_status)-999), "unknown status");
  cr_assert_str_eq(gm_strerror((gm_status)1), "unknown status");
}

Test(status, fail_formats_and_truncates) {
  char buf[16];
  cr_assert_eq(gm_fail(buf, sizeof buf, GM_EINVAL, "step %d of %s", 3, "x"), GM_EINVAL);
  cr_assert_str_eq(buf, "step 3 of x");
  cr_assert_eq(gm_fail(buf, sizeof buf, GM_ENOCONV, "%s", "a message longer than the buffer"),
               GM_ENOCONV);
  cr_assert_eq(strlen(buf), sizeof buf - 1);
  cr_assert_eq(gm_fail(NULL, 0, GM_EIO, "ignored"), GM_EIO);

  gm_error err;
  cr_assert_eq(gm_error_set(&err, GM_ENOTFOUND, "no method '%s'", "rk9"), GM_ENOTFOUND);
  cr_assert_str_eq(err.message, "no method 'rk9'");
  cr_assert_eq(gm_error_set(NULL, GM_ENOMEM, "ignored"), GM_ENOMEM);
}

Test(status, norms_and_finiteness) {
  const double x[4] = {1.0, -3.5, 2.0, 0.0};
  cr_assert(gm_norm_inf(4, x) == 3.5);
  cr_assert(gm_norm_inf(0, x) == 0.0);
  const double y[3] = {1.0, NAN, 5.0};
  cr_assert(isnan(gm_norm_inf(3, y)), "a NaN entry makes the norm NaN");
  cr_assert_eq(gm_first_nonfinite(4, x), 4);
  cr_assert_eq(gm_first_nonfinite(3, y), 1);
  const double z[2] = {0.0, -INFINITY};
  cr_assert_eq(gm_first_nonfinite(2, z), 1);
}
