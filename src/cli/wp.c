/* geomint wp PROBLEM --methods A,B,C: a work–precision diagram.
 *
 * For each method, a sequence of runs to T with steps dt0, dt0/r, dt0/r², ...: the error of the
 * state at T against a reference, the force evaluations (gm_stats.force_evals) and the wall
 * time of each run. The refinement r = 10^(11 / ((L − 1) p)) depends on the method's order p so
 * that L levels would take an error of 1e-2 down to 1e-13 (a factor 10^(11/(L−1)) per level
 * when the error behaves like C·dtᵖ); dt0 is found by a pilot search (below) unless --dt0 is
 * given. A method's sweep stops early when its error is below 1e-13, when round-off keeps two
 * successive errors below 1e-9 from halving the best one before them, or when the next run would exceed --max-evals force evaluations
 * or (predicted from the last run) --max-time seconds.
 *
 * The error is the max-norm of y − y_ref relative to the max-norm of y_ref. The reference is
 * the problem's exact solution when it has one; else a run of a high-order method (the
 * highest-order explicit method the problem accepts if its order is at least 8, e.g.
 * sofroniou-spaletta-10, else the highest-order method it accepts, e.g. gauss-8) with
 * compensated summation, at a step where its own error estimate (Richardson: the difference
 * of the runs at h and h/2 divided by 2ᵖ − 1, HNW I §II.4) is below 1e-16, and checked against
 * a second run at 1.25 times that step: the difference is printed as the reference's accuracy. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cJSON.h>

#include "cli/cli.h"

static const char usage[] =
    "usage: geomint wp PROBLEM --methods A,B,C [--basic NAME] [--solver NAME] [--t-end T]\n"
    "                  [--dt0 H] [--levels L] [--max-evals N] [--max-time S]\n"
    "                  [--reference NAME] [--compensated] [--set name=value ...] [--json]\n"
    "                  [--plot FILE.png]\n\n"
    "Work-precision diagram: integrate PROBLEM to T with each method at a sequence of steps\n"
    "dt0, dt0/r, dt0/r^2, ... (r = 10^(11/((L-1) p)) for a method of order p, so that the\n"
    "error would fall from about 1e-2 to 1e-13 over L levels) and report the error at T, the\n"
    "force evaluations and the wall time of every run. The error is the max-norm of the state\n"
    "minus the reference, relative to the max-norm of the reference; the reference is the\n"
    "exact solution when the problem has one, else a converged run of a high-order method.\n\n"
    "options:\n"
    "  --methods A,B,C    comma-separated methods to compare (required)\n"
    "  --basic NAME       basic method of the composition methods in the list\n"
    "  --solver NAME      solver of implicit stage equations (see 'geomint run --help')\n"
    "  --t-end T          final time (default 100)\n"
    "  --dt0 H            largest step for every method (default: found per method so that\n"
    "                     its error starts near 1e-2)\n"
    "  --levels L         at most L step sizes per method, 2..64 (default 12)\n"
    "  --max-evals N      skip runs that would make more than N force evaluations\n"
    "                     (default 20000000)\n"
    "  --max-time S       skip runs predicted to take more than S seconds (default 60)\n"
    "  --reference NAME   reference method when there is no exact solution (default: the\n"
    "                     highest-order explicit method of order >= 8 that accepts the\n"
    "                     problem, else the highest-order method that does)\n"
    "  --compensated      compensated summation of the state update in every run (lowers\n"
    "                     the round-off floor of long runs)\n"
    "  --set name=value   change a parameter or an initial value; repeatable\n"
    "  --json             print {\"problem\", \"t_end\", \"reference\", \"rows\": [...],\n"
    "                     \"stopped\": [...]} as JSON (stopped: sweeps cut short by a limit)\n"
    "  --plot FILE.png    draw the error against the force evaluations (log-log) with gnuplot\n";

#define WP_MAX_METHODS 32
#define WP_ERROR_TOP 1e-2      /* the error the sweep starts near */
#define WP_ERROR_BOTTOM 1e-13  /* ... and stops below */
#define WP_PILOT_ACCEPT 1e-3   /* a pilot run this accurate may be asymptotic */
#define WP_ROUNDOFF 1e-9       /* below this, an error that stops falling is round-off */
#define WP_PILOT_DIVISOR 4.0
#define WP_PILOT_TRIES 24
#define WP_REF_TARGET 1e-16    /* estimated truncation error of the reference run */
#define WP_REF_ESTIMATE 1e-6   /* Richardson difference at which the reference is calibrated */

typedef struct wp_row {
  const gm_method *method;
  double dt;      /* the step actually taken: (T − t0) / steps */
  size_t steps, force_evals;
  double wall_s, error;
} wp_row;

typedef struct wp_context {
  const char *problem;
  const gm_problem *pb;
  size_t n;           /* state size */
  double t0, t_end;
  const double *y0;
  double *y_ref;      /* reference state at t_end */
  double ref_scale;   /* max-norm of y_ref (1 when it is 0) */
  double *y;          /* work */
  size_t max_evals;
  double max_time;    /* seconds a run may be predicted to take */
  /* the reference when there is no exact solution */
  const gm_method *reference;
  double reference_dt, reference_check;
} wp_context;

/* A sweep cut short by --max-evals or --max-time: said on stderr, and in the JSON ("stopped"). */
typedef struct wp_stop {
  const gm_method *method;
  double dt;        /* the step that was not run */
  double predicted; /* its force evaluations or seconds */
  int by_time;      /* 0: --max-evals, 1: --max-time */
  char message[192];
} wp_stop;

typedef struct wp_rows {
  wp_row *rows;
  size_t n, cap;
  size_t n_stopped_budget; /* sweeps cut short by --max-evals */
  wp_stop *stops;
  size_t n_stops;
} wp_rows;

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double norm_inf(size_t n, const double *x) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) m = fmax(m, fabs(x[i]));
  return m;
}

/* max |a − b| / scale; NaN when a has a non-finite entry. */
static double rel_distance(size_t n, const double *a, const double *b, double scale) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(a[i])) return NAN;
    m = fmax(m, fabs(a[i] - b[i]));
  }
  return m / scale;
}

/* Integrate the scheme from (t0, y0) to t_end with steps of at most h; the state at t_end in
 * y_out. On failure returns the status and writes the reason into why. */
static gm_status integrate(const wp_context *c, const gm_scheme *sc, double h, double *y_out,
                           gm_stats *stats, double *wall_s, char *why, size_t why_cap) {
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  gm_status st = gm_integrator_create_scheme(sc, c->pb, &it, &err);
  if (st != GM_OK) {
    snprintf(why, why_cap, "%s", err.message[0] ? err.message : gm_strerror(st));
    return st;
  }
  if ((st = gm_integrator_set_state(it, c->t0, c->y0)) == GM_OK) {
    double start = now_s();
    st = gm_integrator_integrate(it, c->t_end, h);
    if (wall_s != NULL) *wall_s = now_s() - start;
  }
  if (st != GM_OK) {
    const char *m = gm_integrator_errmsg(it);
    snprintf(why, why_cap, "%s", m[0] ? m : gm_strerror(st));
  } else {
    memcpy(y_out, gm_integrator_state(it), c->n * sizeof *y_out);
  }
  if (stats != NULL) *stats = gm_integrator_stats(it);
  gm_integrator_free(it);
  return st;
}

/* ---- the reference --------------------------------------------------------------------- */

static const gm_method *default_reference(const gm_problem *pb) {
  const gm_method *best_explicit = NULL, *best = NULL;
  for (size_t i = 0, n = gm_method_count(); i < n; ++i) {
    const gm_method *m = gm_method_at(i);
    gm_integrator *it = NULL;
    if (gm_integrator_create(m, pb, &it, NULL) != GM_OK) continue;
    gm_integrator_free(it);
    if (best == NULL || m->order > best->order) best = m;
    if ((m->flags & GM_EXPLICIT) && (best_explicit == NULL || m->order > best_explicit->order))
      best_explicit = m;
  }
  return best_explicit != NULL && best_explicit->order >= 8 ? best_explicit : best;
}

/* Compute y_ref: the exact solution, or a calibrated run of the reference method. */
static int make_reference(wp_context *c, const gm_method *requested) {
  const gm_problem *pb = c->pb;
  if (pb->exact != NULL && requested == NULL) {
    if (pb->exact(pb->ctx, c->t_end, c->y_ref) != 0) {
      cli_error("wp", "%s: the exact solution failed at t = %g", c->problem, c->t_end);
      return CLI_EXIT_FAILURE;
    }
    c->ref_scale = norm_inf(c->n, c->y_ref);
    if (!(c->ref_scale > 0.0)) c->ref_scale = 1.0;
    return CLI_EXIT_OK;
  }
  const gm_method *m = requested != NULL ? requested : default_reference(pb);
  if (m == NULL) {
    cli_error("wp", "%s has no exact solution and no method accepts it as a reference",
              c->problem);
    return CLI_EXIT_USAGE;
  }
  c->reference = m;
  gm_scheme sc = {m, NULL, GM_SOLVER_DEFAULT, 1};
  char why[512];
  double *half = malloc(c->n * sizeof *half);
  if (half == NULL) {
    cli_error("wp", "out of memory");
    return CLI_EXIT_FAILURE;
  }
  /* Calibrate: the largest h = (T − t0)/100/4^k whose Richardson difference is small. */
  double h = (c->t_end - c->t0) / 100.0, h_cal = NAN, estimate = NAN;
  for (int k = 0; k < WP_PILOT_TRIES; ++k, h /= WP_PILOT_DIVISOR) {
    gm_status st = integrate(c, &sc, h, c->y_ref, NULL, NULL, why, sizeof why);
    if (st == GM_EUNSUPPORTED || st == GM_EINVAL) {
      free(half);
      cli_error("wp", "%s with reference %s: %s", c->problem, m->name, why);
      return CLI_EXIT_USAGE;
    }
    if (st != GM_OK) continue; /* too coarse for the solver: refine */
    if (integrate(c, &sc, h / 2, half, NULL, NULL, why, sizeof why) != GM_OK) continue;
    double scale = fmax(norm_inf(c->n, half), 1e-300);
    double d = rel_distance(c->n, c->y_ref, half, scale);
    if (isfinite(d) && d <= WP_REF_ESTIMATE) {
      h_cal = h / 2;
      estimate = d / (pow(2.0, m->order) - 1.0); /* error of the run at h/2 */
      break;
    }
  }
  if (isnan(h_cal)) {
    free(half);
    cli_error("wp", "%s: the reference method %s did not converge", c->problem, m->name);
    return CLI_EXIT_FAILURE;
  }
  double h_ref = estimate > WP_REF_TARGET
                     ? h_cal * pow(WP_REF_TARGET / estimate, 1.0 / m->order)
                     : h_cal;
  gm_status st = integrate(c, &sc, h_ref, c->y_ref, NULL, NULL, why, sizeof why);
  if (st == GM_OK) st = integrate(c, &sc, 1.25 * h_ref, half, NULL, NULL, why, sizeof why);
  if (st != GM_OK) {
    free(half);
    cli_error("wp", "%s: the reference run of %s failed: %s", c->problem, m->name, why);
    return CLI_EXIT_FAILURE;
  }
  c->ref_scale = norm_inf(c->n, c->y_ref);
  if (!(c->ref_scale > 0.0)) c->ref_scale = 1.0;
  c->reference_check = rel_distance(c->n, half, c->y_ref, c->ref_scale);
  c->reference_dt = (c->t_end - c->t0) / ceil((c->t_end - c->t0) / h_ref);
  free(half);
  return CLI_EXIT_OK;
}

/* ---- one method's sweep ---------------------------------------------------------------- */

static int push_row(wp_rows *rows, const wp_row *r) {
  if (rows->n == rows->cap) {
    size_t cap = rows->cap ? 2 * rows->cap : 32;
    wp_row *p = realloc(rows->rows, cap * sizeof *p);
    if (p == NULL) return -1;
    rows->rows = p;
    rows->cap = cap;
  }
  rows->rows[rows->n++] = *r;
  return 0;
}

static int push_stop(wp_rows *rows, const gm_scheme *sc, double h, double predicted, int by_time,
                     const wp_context *c, int quiet) {
  wp_stop *p = realloc(rows->stops, (rows->n_stops + 1) * sizeof *p);
  if (p == NULL) return -1;
  rows->stops = p;
  wp_stop *s = &p[rows->n_stops++];
  *s = (wp_stop){sc->method, h, predicted, by_time, {0}};
  if (by_time)
    snprintf(s->message, sizeof s->message,
             "%s: stopped at dt = %.4g, which would take about %.0f s (over --max-time %g)",
             sc->method->name, h, predicted, c->max_time);
  else
    snprintf(s->message, sizeof s->message,
             "%s: stopped at dt = %.4g, which would exceed --max-evals %zu", sc->method->name, h,
             c->max_evals);
  rows->n_stopped_budget += !by_time;
  if (!quiet) fprintf(stderr, "geomint wp: %s\n", s->message);
  return 0;
}

static size_t steps_for(const wp_context *c, double h) {
  return (size_t)ceil((c->t_end - c->t0) / h);
}

/* One run at step h: a row, or a failure status with its reason in why. */
static gm_status measure(const wp_context *c, const gm_scheme *sc, double h, wp_row *row,
                         char *why, size_t why_cap) {
  gm_stats stats;
  double wall = 0.0;
  gm_status st = integrate(c, sc, h, c->y, &stats, &wall, why, why_cap);
  if (st != GM_OK) return st;
  *row = (wp_row){sc->method, (c->t_end - c->t0) / (double)stats.steps, stats.steps,
                  stats.force_evals, wall, rel_distance(c->n, c->y, c->y_ref, c->ref_scale)};
  return GM_OK;
}

/* The largest step. Pilot runs at h = (T − t0)/100, h/4, h/16, ... until one has an error of
 * at most 1e-3 and the run at half its step confirms the asymptotic regime (an error smaller by
 * at least 2^(p−2)); then dt0 = h·(1e-2 / error)^(1/p), at most 2h, so that the sweep starts
 * near 1e-2 (the error behaving like C·dtᵖ). */
static int find_dt0(const wp_context *c, const gm_scheme *sc, double *dt0) {
  const int p = sc->method->order > 0 ? sc->method->order : 1;
  double h = (c->t_end - c->t0) / 100.0;
  char why[512] = "";
  for (int k = 0; k < WP_PILOT_TRIES; ++k, h /= WP_PILOT_DIVISOR) {
    double evals_per_step = (double)(sc->method->n_stages + 1);
    if (1.5 * (double)steps_for(c, h) * evals_per_step > (double)c->max_evals) break;
    wp_row row, half;
    if (measure(c, sc, h, &row, why, sizeof why) != GM_OK) continue; /* too coarse */
    if (!(isfinite(row.error) && row.error <= WP_PILOT_ACCEPT)) continue;
    if (measure(c, sc, h / 2, &half, why, sizeof why) != GM_OK) continue;
    int asymptotic = half.error <= row.error * pow(2.0, 2 - p) || half.error <= 1e-11;
    if (!asymptotic) continue;
    double grow = row.error > 0.0 ? pow(WP_ERROR_TOP / row.error, 1.0 / p) : 1.0;
    *dt0 = h * fmin(grow, 2.0);
    return CLI_EXIT_OK;
  }
  cli_error("wp", "%s with %s: no step within the --max-evals budget (%zu force evaluations) "
            "gives an error below %g in the asymptotic regime%s%s; try --dt0 or --max-evals",
            c->problem, sc->method->name, c->max_evals, WP_PILOT_ACCEPT, why[0] ? ": " : "",
            why);
  return CLI_EXIT_FAILURE;
}

static int sweep(const wp_context *c, const gm_scheme *sc, double dt0_option, size_t levels,
                 wp_rows *rows, int quiet) {
  const int p = sc->method->order > 0 ? sc->method->order : 1;
  double dt0 = dt0_option;
  int status;
  if (!(dt0 > 0.0) && (status = find_dt0(c, sc, &dt0)) != CLI_EXIT_OK) return status;
  const double ratio = pow(10.0, log10(WP_ERROR_TOP / WP_ERROR_BOTTOM) /
                                     ((double)(levels - 1) * p));
  double evals_per_step = 0.0, seconds_per_step = 0.0;
  size_t first = rows->n;
  char why[512];
  for (size_t k = 0; k < levels; ++k) {
    double h = dt0 / pow(ratio, (double)k);
    const double steps = (double)steps_for(c, h);
    const int over_evals = evals_per_step > 0.0 && steps * evals_per_step > (double)c->max_evals;
    if (over_evals || (seconds_per_step > 0.0 && steps * seconds_per_step > c->max_time)) {
      if (push_stop(rows, sc, h, over_evals ? steps * evals_per_step : steps * seconds_per_step,
                    !over_evals, c, quiet) != 0) {
        cli_error("wp", "out of memory");
        return CLI_EXIT_FAILURE;
      }
      return CLI_EXIT_OK;
    }
    wp_row row;
    gm_status st = measure(c, sc, h, &row, why, sizeof why);
    if (st != GM_OK) {
      cli_error("wp", "%s with %s at dt = %g: %s", c->problem, sc->method->name, h, why);
      return st == GM_EINVAL || st == GM_EUNSUPPORTED ? CLI_EXIT_USAGE : CLI_EXIT_FAILURE;
    }
    if (push_row(rows, &row) != 0) {
      cli_error("wp", "out of memory");
      return CLI_EXIT_FAILURE;
    }
    evals_per_step = (double)row.force_evals / (double)row.steps;
    seconds_per_step = row.wall_s / (double)row.steps;
    size_t m = rows->n - first;
    if (!(row.error > WP_ERROR_BOTTOM)) break; /* reached (or NaN: diverged) */
    const wp_row *r = rows->rows + rows->n - 1;
    /* round-off: two levels in a row with small errors that do not halve the best so far */
    if (m >= 3 && r[0].error < WP_ROUNDOFF) {
      double best = r[-2].error;
      for (const wp_row *q = rows->rows + first; q < r - 1; ++q) best = fmin(best, q->error);
      if (r[-1].error > 0.5 * best && r[0].error > 0.5 * best) break;
    }
  }
  return CLI_EXIT_OK;
}

/* ---- the method list --------------------------------------------------------------------- */

/* Split the comma-separated list into schemes; returns an exit status. */
static int parse_methods(const char *list, const char *basic, const char *solver,
                         int compensated, gm_scheme *schemes, size_t *n_schemes) {
  *n_schemes = 0;
  const char *s = list;
  int any_composition = 0;
  while (*s != '\0') {
    size_t len = strcspn(s, ",");
    char name[128];
    if (len > 0) {
      if (len >= sizeof name) {
        cli_error("wp", "--methods: name too long: '%.*s...'", 40, s);
        return CLI_EXIT_USAGE;
      }
      if (*n_schemes == WP_MAX_METHODS) {
        cli_error("wp", "--methods: at most %d methods", WP_MAX_METHODS);
        return CLI_EXIT_USAGE;
      }
      memcpy(name, s, len);
      name[len] = '\0';
      gm_scheme *sc = &schemes[*n_schemes];
      int st = cli_make_scheme("wp", name, NULL, solver, compensated, sc);
      if (st != CLI_EXIT_OK) return st;
      if (basic != NULL && sc->method->family == GM_FAMILY_COMPOSITION) {
        if ((sc->basic = cli_find_method("wp", basic)) == NULL) return CLI_EXIT_USAGE;
        any_composition = 1;
      }
      if (sc->solver != GM_SOLVER_DEFAULT && (sc->method->flags & GM_EXPLICIT) &&
          sc->basic == NULL)
        sc->solver = GM_SOLVER_DEFAULT; /* --solver is for the implicit methods of the list */
      ++*n_schemes;
    }
    s += len;
    if (*s == ',') ++s;
  }
  if (*n_schemes == 0) {
    cli_error("wp", "--methods: the list is empty; give names separated by commas, e.g. "
              "--methods verlet,yoshida-4 (see 'geomint list methods')");
    return CLI_EXIT_USAGE;
  }
  if (basic != NULL && !any_composition) {
    cli_error("wp", "--basic %s: none of the methods is a composition method", basic);
    return CLI_EXIT_USAGE;
  }
  return CLI_EXIT_OK;
}

/* Can every scheme integrate the problem? Says which cannot and why. */
static int check_schemes(const char *problem, const gm_problem *pb, const gm_scheme *schemes,
                         size_t n) {
  for (size_t i = 0; i < n; ++i) {
    gm_integrator *it = NULL;
    gm_error err = {{0}};
    gm_status st = gm_integrator_create_scheme(&schemes[i], pb, &it, &err);
    gm_integrator_free(it);
    if (st != GM_OK) {
      char name[128];
      cli_scheme_name(&schemes[i], name, sizeof name);
      cli_error("wp", "%s with %s: %s", problem, name,
                err.message[0] ? err.message : gm_strerror(st));
      return st == GM_ENOMEM ? CLI_EXIT_FAILURE : CLI_EXIT_USAGE;
    }
  }
  return CLI_EXIT_OK;
}

/* ---- output ---------------------------------------------------------------------------- */

static void reference_text(const wp_context *c, char *buf, size_t cap) {
  if (c->reference == NULL)
    snprintf(buf, cap, "exact solution");
  else
    snprintf(buf, cap, "%s, compensated, dt = %.4g (differs by %.1e from a run at 1.25 dt)",
             c->reference->name, c->reference_dt, c->reference_check);
}

static void scheme_label(const gm_scheme *schemes, size_t n_schemes, const gm_method *m,
                         char *buf, size_t cap) {
  for (size_t i = 0; i < n_schemes; ++i)
    if (schemes[i].method == m) {
      cli_scheme_name(&schemes[i], buf, cap);
      return;
    }
  snprintf(buf, cap, "%s", m->name);
}

static int print_json(const wp_context *c, const gm_scheme *schemes, size_t n_schemes,
                      const wp_rows *rows, const char *plot) {
  cJSON *root = cJSON_CreateObject();
  cJSON_AddStringToObject(root, "problem", c->problem);
  cJSON_AddItemToObject(root, "t_end", cli_json_number(c->t_end));
  cJSON_AddStringToObject(root, "reference", c->reference ? c->reference->name : "exact");
  if (c->reference != NULL) {
    cJSON_AddItemToObject(root, "reference_dt", cli_json_number(c->reference_dt));
    cJSON_AddItemToObject(root, "reference_check", cli_json_number(c->reference_check));
  }
  cJSON_AddStringToObject(root, "error", "max-norm of y - y_ref relative to max-norm of y_ref");
  cJSON *a = cJSON_AddArrayToObject(root, "rows");
  for (size_t i = 0; i < rows->n; ++i) {
    const wp_row *r = &rows->rows[i];
    char name[128];
    scheme_label(schemes, n_schemes, r->method, name, sizeof name);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "method", name);
    cJSON_AddNumberToObject(o, "order", r->method->order);
    cJSON_AddItemToObject(o, "dt", cli_json_number(r->dt));
    cJSON_AddNumberToObject(o, "steps", (double)r->steps);
    cJSON_AddNumberToObject(o, "force_evals", (double)r->force_evals);
    cJSON_AddItemToObject(o, "wall_s", cli_json_number(r->wall_s));
    cJSON_AddItemToObject(o, "error", cli_json_number(r->error));
    cJSON_AddItemToArray(a, o);
  }
  cJSON *stopped = cJSON_AddArrayToObject(root, "stopped");
  for (size_t i = 0; i < rows->n_stops; ++i) {
    const wp_stop *s = &rows->stops[i];
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "method", s->method->name);
    cJSON_AddItemToObject(o, "dt", cli_json_number(s->dt));
    cJSON_AddStringToObject(o, "limit", s->by_time ? "max-time" : "max-evals");
    cJSON_AddItemToObject(o, s->by_time ? "predicted_s" : "predicted_force_evals",
                          cli_json_number(s->predicted));
    cJSON_AddStringToObject(o, "message", s->message);
    cJSON_AddItemToArray(stopped, o);
  }
  if (plot != NULL) cJSON_AddStringToObject(root, "plot", plot);
  return cli_json_print(root);
}

static void print_table(const wp_context *c, const gm_scheme *schemes, size_t n_schemes,
                        const wp_rows *rows, const char *plot) {
  char ref[256];
  reference_text(c, ref, sizeof ref);
  printf("%s, t = %g .. %g\nreference: %s\n", c->problem, c->t0, c->t_end, ref);
  printf("error: max-norm of y - y_ref relative to max-norm of y_ref (%.6g)\n\n", c->ref_scale);
  printf("%-24s %12s %10s %13s %10s %11s\n", "method", "dt", "steps", "force evals", "wall s",
         "error");
  for (size_t i = 0; i < rows->n; ++i) {
    const wp_row *r = &rows->rows[i];
    char name[128];
    scheme_label(schemes, n_schemes, r->method, name, sizeof name);
    if (i > 0 && rows->rows[i - 1].method != r->method) putchar('\n');
    printf("%-24s %12.5g %10zu %13zu %10.4f %11.3e\n", name, r->dt, r->steps, r->force_evals,
           r->wall_s, r->error);
  }
  if (plot != NULL) printf("\nwrote %s\n", plot);
}

static int draw(const wp_context *c, const gm_scheme *schemes, size_t n_schemes,
                const wp_rows *rows, const char *png) {
  cli_xy_series series[WP_MAX_METHODS];
  double *x = malloc((rows->n + 1) * sizeof *x), *y = malloc((rows->n + 1) * sizeof *y);
  char labels[WP_MAX_METHODS][128];
  if (x == NULL || y == NULL) {
    free(x);
    free(y);
    cli_error("wp", "out of memory");
    return CLI_EXIT_FAILURE;
  }
  size_t n_series = 0, at = 0;
  for (size_t s = 0; s < n_schemes; ++s) {
    cli_scheme_name(&schemes[s], labels[s], sizeof labels[s]);
    series[n_series] = (cli_xy_series){labels[s], 0, x + at, y + at};
    for (size_t i = 0; i < rows->n; ++i)
      if (rows->rows[i].method == schemes[s].method) {
        x[at] = (double)rows->rows[i].force_evals;
        y[at] = rows->rows[i].error;
        ++at;
        ++series[n_series].n;
      }
    ++n_series;
  }
  char title[256];
  if (c->reference == NULL)
    snprintf(title, sizeof title, "%s, t_end = %g: error against the exact solution",
             c->problem, c->t_end);
  else
    snprintf(title, sizeof title, "%s, t_end = %g: error against %s at dt = %.3g",
             c->problem, c->t_end, c->reference->name, c->reference_dt);
  int status = cli_plot_loglog("wp", png, title, "force evaluations",
                               "relative error at t_end", series, n_series);
  free(x);
  free(y);
  return status;
}

/* ---- the command ------------------------------------------------------------------------ */

typedef struct wp_options {
  const char *methods, *basic, *solver, *reference, *plot;
  double t_end, dt0, max_time;
  size_t levels, max_evals;
  int json, compensated;
  cli_settings settings;
} wp_options;

static int check_options(const wp_options *o, const cli_option *dt0_option) {
  if (cli_check_positive("wp", "--t-end", o->t_end) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  if (dt0_option->seen && cli_check_positive("wp", "--dt0", o->dt0) != CLI_EXIT_OK)
    return CLI_EXIT_USAGE;
  if (o->levels < 2 || o->levels > 64) {
    cli_error("wp", "--levels must be between 2 and 64, got %zu", o->levels);
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive("wp", "--max-time", o->max_time) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  if (o->max_evals == 0) {
    cli_error("wp", "--max-evals must be at least 1");
    return CLI_EXIT_USAGE;
  }
  return CLI_EXIT_OK;
}

static int run_wp(const char *problem, const gm_model *model, const wp_options *o,
                  const gm_scheme *schemes, size_t n_schemes, const gm_method *reference) {
  const gm_problem *pb = gm_model_problem(model);
  int status = check_schemes(problem, pb, schemes, n_schemes);
  if (status != CLI_EXIT_OK) return status;
  wp_context c = {problem, pb, gm_model_state_size(model), 0.0, o->t_end, NULL, NULL, 1.0,
                  NULL, o->max_evals, o->max_time, NULL, NAN, NAN};
  double *y0 = calloc(c.n, sizeof *y0);
  c.y_ref = calloc(c.n, sizeof *c.y_ref);
  c.y = calloc(c.n, sizeof *c.y);
  wp_rows rows = {NULL, 0, 0, 0, NULL, 0};
  if (y0 == NULL || c.y_ref == NULL || c.y == NULL) {
    cli_error("wp", "out of memory");
    status = CLI_EXIT_FAILURE;
  } else {
    gm_model_initial_state(model, &c.t0, y0);
    c.y0 = y0;
    if (!(o->t_end > c.t0)) {
      cli_error("wp", "--t-end %g is not after the initial time %g", o->t_end, c.t0);
      status = CLI_EXIT_USAGE;
    }
  }
  if (status == CLI_EXIT_OK) status = make_reference(&c, reference);
  for (size_t i = 0; i < n_schemes && status == CLI_EXIT_OK; ++i)
    status = sweep(&c, &schemes[i], o->dt0, o->levels, &rows, o->json);
  if (status == CLI_EXIT_OK && o->plot != NULL)
    status = draw(&c, schemes, n_schemes, &rows, o->plot);
  if (status == CLI_EXIT_OK) {
    if (o->json)
      status = print_json(&c, schemes, n_schemes, &rows, o->plot);
    else
      print_table(&c, schemes, n_schemes, &rows, o->plot);
  }
  free(rows.rows);
  free(rows.stops);
  free(y0);
  free(c.y_ref);
  free(c.y);
  return status;
}

static int wp_main(int argc, char **argv) {
  wp_options o = {NULL, NULL, NULL, NULL, NULL, 100.0, 0.0, 60.0, 12, 20000000, 0, 0, {0, {0}}};
  cli_option options[] = {{"--methods", CLI_ARG_STRING, &o.methods, 0},
                          {"--dt0", CLI_ARG_DOUBLE, &o.dt0, 0},
                          {"--t-end", CLI_ARG_DOUBLE, &o.t_end, 0},
                          {"--levels", CLI_ARG_COUNT, &o.levels, 0},
                          {"--max-evals", CLI_ARG_COUNT, &o.max_evals, 0},
                          {"--max-time", CLI_ARG_DOUBLE, &o.max_time, 0},
                          {"--basic", CLI_ARG_STRING, &o.basic, 0},
                          {"--solver", CLI_ARG_STRING, &o.solver, 0},
                          {"--reference", CLI_ARG_STRING, &o.reference, 0},
                          {"--set", CLI_ARG_SETTING, &o.settings, 0},
                          {"--plot", CLI_ARG_STRING, &o.plot, 0},
                          {"--compensated", CLI_ARG_FLAG, &o.compensated, 0},
                          {"--json", CLI_ARG_FLAG, &o.json, 0}};
  const char *problem[1];
  size_t n_problem = 0;
  int status = cli_parse("wp", argc, argv, options, sizeof options / sizeof options[0], problem,
                         1, &n_problem);
  if (status == CLI_HELP) {
    fputs(usage, stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (n_problem == 0 || o.methods == NULL) {
    cli_error("wp", "usage: geomint wp PROBLEM --methods A,B,C (see 'geomint wp --help')");
    return CLI_EXIT_USAGE;
  }
  if ((status = check_options(&o, &options[1])) != CLI_EXIT_OK) return status;
  gm_scheme schemes[WP_MAX_METHODS];
  size_t n_schemes = 0;
  if ((status = parse_methods(o.methods, o.basic, o.solver, o.compensated, schemes,
                              &n_schemes)) != CLI_EXIT_OK)
    return status;
  const gm_method *reference = NULL;
  if (o.reference != NULL && (reference = cli_find_method("wp", o.reference)) == NULL)
    return CLI_EXIT_USAGE;
  if (o.plot != NULL) {
    if (!cli_gnuplot_available()) {
      cli_error("wp", "--plot: gnuplot is not installed (or not on PATH)");
      return CLI_EXIT_FAILURE;
    }
    if ((status = cli_plot_check_output("wp", o.plot)) != CLI_EXIT_OK) return status;
  }
  gm_model *model = NULL;
  if ((status = cli_open_model("wp", problem[0], &o.settings, &model)) != CLI_EXIT_OK)
    return status;
  status = run_wp(problem[0], model, &o, schemes, n_schemes, reference);
  gm_model_free(model);
  return status;
}

const cli_command cli_wp_command = {"wp", "work-precision diagram: error against force evaluations",
                                    usage, wp_main};
