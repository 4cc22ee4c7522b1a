/* Runs are bitwise reproducible only if the compiler does not fuse a*b + c into an FMA:
 * every library source must be compiled with -ffp-contract=off (DESIGN §6). */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

Test(build_flags, library_compiled_without_contraction) {
  FILE *f = fopen(GM_BUILD_DIR "/compile_commands.json", "r");
  cr_assert_not_null(f, "compile_commands.json missing in %s", GM_BUILD_DIR);
  static char line[1 << 16];
  size_t commands = 0, with_flag = 0;
  while (fgets(line, sizeof line, f)) {
    if (strstr(line, "\"command\"") == NULL || strstr(line, "/src/") == NULL) continue;
    ++commands;
    if (strstr(line, "-ffp-contract=off") != NULL) ++with_flag;
  }
  fclose(f);
  cr_expect_gt(commands, 10);
  cr_expect_eq(with_flag, commands, "%zu of %zu compile commands lack -ffp-contract=off",
               commands - with_flag, commands);
}

/* With contraction, x*y − p would be computed exactly (the FMA's error term), not 0. */
Test(build_flags, no_fused_multiply_add_in_this_unit) {
  volatile double vx = 1.0 + 0x1p-30, vy = 1.0 - 0x1p-30;
  double x = vx, y = vy;
  double p = x * y;
  double r = x * y - p;
  cr_expect_eq(r, 0.0, "a*b - c was contracted: %.3g", r);
}
