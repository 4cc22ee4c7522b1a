/* --json of the commands of the seeds' experiments (issue 26, "JSON everywhere"): each runs on a
 * small input and prints one JSON object that cJSON parses, with the shared vocabulary
 * (wall_s, steps, max_rel_*), every required key present and every number finite. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "cli/cli_harness.h"
#include "cli/json_vocabulary.h"

TestSuite(cli_json_experiments, .init = make_tmpdir, .fini = remove_tmpdir, .timeout = 120);

Test(cli_json_experiments, pde_rows) {
  static const json_case cases[] = {
      {"pde tent-vi --n 100 --T 2 --json", "steps,wall_s,max_rel_energy_error,max_abs_error"},
      {"pde b10 --no-plot --out b --json", "runs,steps,t,max_rel_energy_error,wall_s"},
      {"pde nls-long --periods 2 --n 32 --no-plot --out n --json",
       "steps,schemes,max_rel_energy_error,max_rel_momentum_error,max_rel_charge_error,wall_s"},
      {"pde nls-long --periods 2 --n 32 --only preissmann --no-plot --out n1 --json",
       "steps,schemes,max_rel_charge_error,wall_s"},
      {"pde spectral-star --n 16 --no-plot --out s --json",
       "steps,dt,modes,max_rel_error_semi_spectral,max_rel_error_semi_diagonal,wall_s"},
      {"pde schrodinger eigen --no-plot --out e --json",
       "against_n,against_dt,order_vi,order_split_step,wall_s"},
      {"pde schrodinger compare --n 32 --T 1 --no-plot --out c --json",
       "steps,rows,vi_max_abs_error,vi_max_rel_charge_error,wall_s"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_json_case(&cases[i]);
}

Test(cli_json_experiments, ode_and_reduction_rows) {
  static const json_case cases[] = {
      {"oscillatory multiscale --no-plot --out m --json",
       "spring_pendulum,steps,msfem,p1_nodal_error,wall_s"},
      {"reduction phases --json", "rows,closed_form,computed,errors,max_abs_phase_error,wall_s"},
      {"reduction phases --out ph --no-plot --json", "rows,max_abs_phase_error,csv,wall_s"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_json_case(&cases[i]);
}

Test(cli_json_experiments, maxwell_rows) {
  static const json_case cases[] = {
      {"maxwell cavity --dim 2 --n 16 --out c --json",
       "steps,dt,modes,found,spurious,max_rel_error_yee,max_rel_error_analytic,wall_s"},
      {"maxwell mesh-cavity --levels 1 --n0 3 --t-end 30 --json",
       "levels,peaks,nearest,farthest,max_rel_error,spurious,wall_s"},
      {"maxwell mesh " GM_SOURCE_DIR "/examples/e5_cavity.msh --e5 --t-end 0.5 --t-compare "
       "0.05 --json",
       "avi,whitney,steps,max_rel_energy_error,max_rel_frequency_error,cost,wall_s"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_json_case(&cases[i]);
}

/* experiments run NAME --json for the quick rows: the row's key numbers by name */
Test(cli_json_experiments, experiments_run) {
  static const json_case cases[] = {
      {"experiments run tent-vi --out x --json", "experiment,steps,max_rel_energy_error,wall_s"},
      {"experiments run b10 --out x --json", "experiment,ms_2_max_rel_energy_error,wall_s"},
      {"experiments run spectral-star --out x --json",
       "experiment,steps,max_rel_frequency_error_semi_spectral,wall_s"},
      {"experiments run phases --out x --json", "experiment,max_abs_phase_error,wall_s"},
      {"experiments run e4 --out x --json", "experiment,steps,leapfrog_max_rel_drift,wall_s"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_json_case(&cases[i]);
}
