/* Seed 004's two experiments on invariant schemes (notes/003-004 §2.4, Test 1 and Test 2; the
 * seed's Figs. 24–26): B12, Galilean consistency, and B13, the projection group's viscous
 * shock. Data only: the CLI writes and plots (src/cli/pde_invariant.c). */
#include <math.h>
#include <stdlib.h>

#include "core/internal.h"
#include "pde/invariant_internal.h"

gm_status gm_inv_consistency_order(const gm_inv_scheme *scheme, const gm_inv_group *frame_group,
                                   double *order, double *tau, gm_error *err) {
  if (scheme == NULL || order == NULL)
    return gm_error_set(err, GM_EINVAL, "consistency order: NULL scheme or output");
  const gm_inv_front f = {1.0, 0.0, 0.0, 0.1};
  double lh[4], lt[4];
  for (int i = 0; i < 4; i++) {
    double h = 0.02 / (double)(1 << i);
    gm_inv_run_spec sp = gm_inv_run_spec_defaults();
    sp.scheme = scheme;
    sp.frame_group = frame_group;
    sp.nu = f.nu;
    sp.n = (size_t)(2.0 / h + 0.5) + 1;
    sp.x_left = -1.0;
    sp.h = h;
    sp.t0 = 0.1;
    sp.k = 0.5 * h;
    sp.n_steps = 1;
    sp.exact = gm_inv_burgers_front;
    sp.exact_ctx = &f;
    sp.check_stability = 0;
    double *xu = malloc(2 * sp.n * sizeof *xu), t;
    if (xu == NULL) return gm_error_set(err, GM_ENOMEM, "consistency order: out of memory");
    gm_status st = gm_inv_run(&sp, &t, xu, xu + sp.n, NULL, err);
    double e = 0.0;
    for (size_t j = 0; st == GM_OK && j < sp.n; j++)
      e = fmax(e, fabs(xu[sp.n + j] - gm_inv_burgers_front(t, xu[j], &f)));
    free(xu);
    if (st != GM_OK) return st;
    lh[i] = log(h);
    lt[i] = log(e / sp.k);
    if (tau != NULL) tau[i] = e / sp.k;
  }
  double mh = 0.25 * (lh[0] + lh[1] + lh[2] + lh[3]), mt = 0.25 * (lt[0] + lt[1] + lt[2] + lt[3]);
  double sxy = 0.0, sxx = 0.0;
  for (int i = 0; i < 4; i++) {
    sxy += (lh[i] - mh) * (lt[i] - mt);
    sxx += (lh[i] - mh) * (lh[i] - mh);
  }
  *order = sxy / sxx;
  return GM_OK;
}

const double gm_inv_b12_lambdas[GM_INV_B12_N_LAMBDA] = {0.0, 0.25, 0.5, 1.0};

static const gm_inv_scheme *const b12_schemes[3] = {&gm_inv_ftcs, &gm_inv_lax_wendroff,
                                                    &gm_inv_crank_nicolson};

gm_status gm_inv_b12_run(gm_inv_b12 *out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "B12: NULL output");
  const gm_inv_front front = {0.5, -0.5, 0.0, 5e-3};
  const size_t n = 201;
  const double h = 2e-2, k = 0.5 * h; /* the seed's CFL ½ read as k/h */
  out->n = n;
  for (size_t j = 0; j < n; j++) {
    out->x[j] = -2.0 + (double)j * h;
    out->exact[j] = gm_inv_burgers_front(1.0, out->x[j], &front);
  }
  for (size_t s = 0; s < GM_INV_B12_N_SCHEMES; s++)
    for (size_t l = 0; l < GM_INV_B12_N_LAMBDA; l++) {
      size_t r = s * GM_INV_B12_N_LAMBDA + l;
      gm_inv_b12_row *row = &out->rows[r];
      double a[4] = {0.0, 0.0, 0.0, gm_inv_b12_lambdas[l]}; /* the boost g₅(λ) */
      gm_inv_run_spec sp = gm_inv_run_spec_defaults();
      sp.scheme = b12_schemes[s / 2];
      sp.frame_group = s % 2 ? &gm_inv_burgers_g0 : NULL;
      sp.nu = front.nu;
      sp.n = n;
      sp.x_left = -2.0;
      sp.h = h;
      sp.t0 = 0.0;
      sp.k = k;
      sp.n_steps = 100;
      sp.exact = gm_inv_burgers_front;
      sp.exact_ctx = &front;
      sp.transform_group = &gm_inv_burgers_g0;
      sp.transform_a = a;
      sp.check_stability = 0; /* the seed shows what the unstable runs do */
      double t, x[201], u[201];
      gm_inv_run_stats st;
      gm_error e = {{0}};
      *row = (gm_inv_b12_row){sp.scheme->name, (int)(s % 2), a[3], GM_OK, 0, NAN, NAN, NAN, NAN};
      row->status = gm_inv_run(&sp, &t, x, u, &st, &e);
      if (row->status == GM_ENOMEM || row->status == GM_EINVAL)
        return gm_error_set(err, row->status, "B12 %s: %s", sp.scheme->name, e.message);
      row->steps_done = st.steps;
      row->step_bound = st.step_bound;
      double emax = 0.0, umax = -INFINITY, umin = INFINITY;
      for (size_t j = 0; j < n; j++) {
        gm_inv_point p;
        out->u[r][j] = NAN;
        if (row->status != GM_OK) continue;
        gm_inv_burgers_g0.act_inverse(a, (gm_inv_point){t, x[j], u[j]}, &p, NULL);
        out->u[r][j] = p.u;
        emax = fmax(emax, fabs(p.u - gm_inv_burgers_front(p.t, p.x, &front)));
        umax = fmax(umax, p.u);
        umin = fmin(umin, p.u);
      }
      if (row->status != GM_OK) continue;
      row->max_error = emax;
      row->overshoot = fmax(umax - front.u_left, front.u_right - umin);
      double dmax = 0.0;
      const double *u0 = out->u[s * GM_INV_B12_N_LAMBDA];
      for (size_t j = 0; j < n; j++) dmax = fmax(dmax, fabs(out->u[r][j] - u0[j]));
      row->max_diff_lambda0 = dmax;
    }
  return GM_OK;
}

gm_status gm_inv_b13_run(gm_inv_b13 *out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "B13: NULL output");
  const gm_inv_shock shock = {0.5, 1.0, 1e-2};
  const size_t n = 41;
  const double h = 5e-2;
  out->n = n;
  for (int form = 0; form < 2; form++) {
    gm_inv_run_spec sp = gm_inv_run_spec_defaults();
    sp.scheme = &gm_inv_ftcs;
    sp.frame_group = form ? &gm_inv_burgers_g0 : NULL;
    sp.nu = shock.nu;
    sp.n = n;
    sp.x_left = -1.0;
    sp.h = h;
    sp.k = 5e-2;
    sp.n_steps = 40; /* t = 2 */
    sp.exact = gm_inv_burgers_shock;
    sp.exact_ctx = &shock;
    double t;
    gm_status st = gm_inv_run(&sp, &t, out->x, form ? out->invariant : out->standard, NULL, err);
    if (st != GM_OK) return st;
  }
  out->err_standard = out->err_invariant = out->err_shock_standard = out->err_shock_invariant = 0;
  for (size_t j = 0; j < n; j++) {
    out->exact[j] = gm_inv_burgers_shock(2.0, out->x[j], &shock);
    double es = fabs(out->standard[j] - out->exact[j]);
    double ei = fabs(out->invariant[j] - out->exact[j]);
    out->err_standard = fmax(out->err_standard, es);
    out->err_invariant = fmax(out->err_invariant, ei);
    if (fabs(out->x[j]) <= 0.2 + 1e-12) {
      out->err_shock_standard = fmax(out->err_shock_standard, es);
      out->err_shock_invariant = fmax(out->err_shock_invariant, ei);
    }
  }
  return GM_OK;
}
