/* N bodies in 3-D under pairwise Newtonian gravity with optional Plummer softening ε
 * (gravity.c): H = Σ |p_i|²/(2 m_i) − G Σ_{i<j} m_i m_j / sqrt(|q_i − q_j|² + ε²).
 *
 * The bodies come from a file (text parameter `file`) or are drawn (parameters n, cluster,
 * seed) with a deterministic generator, SplitMix64 (Steele, Lea & Flood, "Fast splittable
 * pseudorandom number generators", OOPSLA 2014), so a seed always gives the same cluster:
 *   cluster 0  a cold uniform sphere: positions uniform in the unit ball, at rest (it
 *              collapses: the classic cold-collapse test);
 *   cluster 1  a Plummer sphere in virial equilibrium, sampled as in Aarseth, Hénon & Wielen,
 *              Astron. Astrophys. 37 (1974) 183, appendix: with G = M = 1 and scale radius 1
 *              the radius inverts the cumulative mass M(r) = r³/(1 + r²)^{3/2} at a uniform
 *              X ∈ (0, 0.999] (the last 0.1 % of the mass, beyond r ≈ 39, is left out):
 *              r = (X^{−2/3} − 1)^{−1/2}; the speed is q·v_esc with v_esc = √2 (1 + r²)^{−1/4}
 *              and q from g(q) = q²(1 − q²)^{7/2} by von Neumann rejection (0.1·Y < g(X'),
 *              since max g ≈ 0.092); directions isotropic. The sample is then scaled to the
 *              standard (Hénon) units, where the expected energy is E = −G/4: lengths by
 *              3π/16 (the Plummer scale radius in those units) and velocities by
 *              sqrt(G·16/(3π)) (Heggie & Mathieu, in The Use of Supercomputers in Stellar
 *              Dynamics, LNP 267 (1986) 233). Its virial ratio T/|V| is ½ up to sampling noise.
 * All bodies have mass 1/n; a drawn cluster is moved to its centre-of-mass frame (zero total
 * momentum, centre of mass at the origin).
 *
 * File format: one body per line, "m x y z vx vy vz" (mass > 0, position, velocity),
 * separated by blanks; '#' starts a comment to the end of the line; blank lines are skipped.
 * The file is used as given (no change of frame); p = m v. With a file, n, cluster and seed
 * are not used. Invariants: the energy, and the components of the linear and the angular
 * momentum (gravity.c).
 *
 * central = 1 makes it a "central body + perturbed orbits" problem (gm_problem.celestial) for
 * the near-integrable rows: body 1 (the first line of the file) is the central body and must
 * be heavier than all the others together, and eps must be 0 (the Kepler part is unsoftened). */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/celestial.h"
#include "problems/internal.h"

#define MAX_BODIES 1000000

typedef struct {
  gm_gravity gravity; /* first: the shared gravity callbacks read it */
  size_t n_bodies;
  double *mass;       /* owned, n_bodies */
  double *position;   /* owned, 3 n_bodies */
  double *velocity;   /* owned, 3 n_bodies */
  gm_celestial celestial;
} n_body;

enum { P_N, P_CLUSTER, P_SEED, P_G, P_EPS, P_FILE, P_CENTRAL };

/* ---- SplitMix64 (Steele, Lea & Flood 2014): a Weyl sequence with step 0x9e3779b97f4a7c15
 * (2⁶⁴/φ) passed through a 64-bit finalizer of two xor-shift-multiply rounds. ---- */
typedef struct {
  uint64_t state;
} splitmix64;

static uint64_t splitmix64_next(splitmix64 *rng) {
  uint64_t z = (rng->state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/* Uniform on [0, 1) with 53 random bits. */
static double uniform(splitmix64 *rng) {
  return (double)(splitmix64_next(rng) >> 11) * 0x1.0p-53;
}

/* A uniformly distributed unit vector scaled by length: z uniform in [−1, 1], azimuth uniform
 * (Archimedes: the area of a spherical zone is proportional to its height). */
static void isotropic(splitmix64 *rng, double length, double *out) {
  double z = 2.0 * uniform(rng) - 1.0, phi = 2.0 * GM_PI * uniform(rng);
  double rho = sqrt(fmax(0.0, 1.0 - z * z));
  out[0] = length * rho * cos(phi);
  out[1] = length * rho * sin(phi);
  out[2] = length * z;
}

static gm_status allocate(n_body *nb, size_t n, char *errmsg, size_t cap) {
  nb->n_bodies = n;
  nb->mass = malloc(n * sizeof *nb->mass);
  nb->position = malloc(3 * n * sizeof *nb->position);
  nb->velocity = malloc(3 * n * sizeof *nb->velocity);
  if (nb->mass == NULL || nb->position == NULL || nb->velocity == NULL)
    return gm_fail(errmsg, cap, GM_ENOMEM, "n-body: out of memory for %zu bodies", n);
  return GM_OK;
}

/* Subtract the centre of mass from the positions and its velocity from the velocities. */
static void centre_of_mass_frame(n_body *nb) {
  double total = 0.0, cq[3] = {0, 0, 0}, cv[3] = {0, 0, 0};
  for (size_t i = 0; i < nb->n_bodies; ++i) {
    total += nb->mass[i];
    for (size_t k = 0; k < 3; ++k) {
      cq[k] += nb->mass[i] * nb->position[3 * i + k];
      cv[k] += nb->mass[i] * nb->velocity[3 * i + k];
    }
  }
  for (size_t i = 0; i < nb->n_bodies; ++i)
    for (size_t k = 0; k < 3; ++k) {
      nb->position[3 * i + k] -= cq[k] / total;
      nb->velocity[3 * i + k] -= cv[k] / total;
    }
}

static void cold_sphere(n_body *nb, splitmix64 *rng) {
  for (size_t i = 0; i < nb->n_bodies; ++i) {
    double *x = nb->position + 3 * i, r2;
    do { /* rejection from the cube [−1, 1)³ */
      for (size_t k = 0; k < 3; ++k) x[k] = 2.0 * uniform(rng) - 1.0;
      r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    } while (r2 > 1.0);
    for (size_t k = 0; k < 3; ++k) nb->velocity[3 * i + k] = 0.0;
  }
}

static void plummer_sphere(n_body *nb, splitmix64 *rng, double G) {
  const double length = 3.0 * GM_PI / 16.0, speed = sqrt(G / length);
  for (size_t i = 0; i < nb->n_bodies; ++i) {
    double x = 0.999 * (1.0 - uniform(rng)); /* (0, 0.999] */
    double r = 1.0 / sqrt(pow(x, -2.0 / 3.0) - 1.0);
    isotropic(rng, r * length, nb->position + 3 * i);
    double q, g;
    do {
      q = uniform(rng);
      g = q * q * pow(1.0 - q * q, 3.5);
    } while (0.1 * uniform(rng) >= g);
    double v = q * sqrt(2.0) * pow(1.0 + r * r, -0.25);
    isotropic(rng, v * speed, nb->velocity + 3 * i);
  }
}

/* Is x an integer in [lo, hi]? */
static int is_integer_in(double x, double lo, double hi) {
  return x >= lo && x <= hi && x == floor(x);
}

static gm_status generate(n_body *nb, const double *params, char *errmsg, size_t cap) {
  const double n = params[P_N], cluster = params[P_CLUSTER], seed = params[P_SEED];
  if (!is_integer_in(n, 2.0, MAX_BODIES))
    return gm_fail(errmsg, cap, GM_EINVAL, "n-body: n must be an integer from 2 to %d, got %g",
                   MAX_BODIES, n);
  if (!is_integer_in(cluster, 0.0, 1.0))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "n-body: cluster must be 0 (cold uniform sphere) or 1 (Plummer sphere), got %g",
                   cluster);
  if (!is_integer_in(seed, 0.0, 9007199254740992.0))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "n-body: seed must be an integer from 0 to 2^53, got %g", seed);
  gm_status st = allocate(nb, (size_t)n, errmsg, cap);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < nb->n_bodies; ++i) nb->mass[i] = 1.0 / n;
  splitmix64 rng = {(uint64_t)seed};
  if (cluster == 0.0)
    cold_sphere(nb, &rng);
  else
    plummer_sphere(nb, &rng, params[P_G]);
  centre_of_mass_frame(nb);
  return GM_OK;
}

/* ---- reading a file of bodies ---------------------------------------------------------- */

/* Parse the numbers of one line (comment stripped) into v; returns how many (at most 8 are
 * looked at), or −1 with the offending word in bad (capacity cap) when one is not a number. */
static int parse_numbers(char *line, double v[8], char *bad, size_t cap) {
  char *hash = strchr(line, '#');
  if (hash != NULL) *hash = '\0';
  int count = 0;
  char *s = line;
  for (;;) {
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n' || *s == '\v' || *s == '\f') ++s;
    if (*s == '\0') return count;
    char *end = NULL;
    double x = strtod(s, &end);
    int separated = end != s && (*end == '\0' || *end == ' ' || *end == '\t' || *end == '\r' ||
                                 *end == '\n' || *end == '\v' || *end == '\f');
    if (!separated) {
      /* the word as the message shows it: at most 24 bytes, anything but printable ASCII as
       * \xNN so a file cannot write escape sequences to the terminal */
      size_t len = strcspn(s, " \t\r\n\v\f"), w = 0;
      for (size_t i = 0; i < len && i < 24 && w + 5 < cap; ++i) {
        unsigned char c = (unsigned char)s[i];
        if (c >= 0x20 && c < 0x7f && c != '\\') bad[w++] = (char)c;
        else w += (size_t)snprintf(bad + w, cap - w, "\\x%02x", c);
      }
      bad[w] = '\0';
      return -1;
    }
    if (count < 8) v[count] = x;
    ++count;
    s = end;
    if (count > 8) return count;
  }
}

/* Limits of a file of bodies: a line holds 7 numbers and a comment, so 4096 bytes is plenty; the
 * file is at most MAX_BODY_FILE_BYTES (256 MiB, over 10^6 bodies at %.17g), so an endless
 * stream (/dev/zero, a pipe that never closes) is an error, not an endless read. */
#define MAX_BODY_LINE 4096
#define MAX_BODY_FILE_BYTES ((size_t)256 << 20)

/* One line (without its '\n') into line[MAX_BODY_LINE + 1]: 1 read, 0 end of file, -1 too
 * long, -2 a NUL byte. *total counts the bytes read so far. */
static int read_body_line(FILE *f, char *line, size_t *total) {
  size_t n = 0;
  int c;
  while ((c = getc(f)) != EOF) {
    ++*total;
    if (c == '\n') break;
    if (c == '\0') return -2;
    if (n == MAX_BODY_LINE) return -1;
    line[n++] = (char)c;
  }
  line[n] = '\0';
  return c == EOF && n == 0 ? 0 : 1;
}

static gm_status read_bodies(n_body *nb, const char *path, double softening, char *errmsg,
                             size_t cap) {
  FILE *f = fopen(path, "r");
  if (f == NULL)
    return gm_fail(errmsg, cap, GM_EIO, "n-body: cannot open '%s': %s", path, strerror(errno));
  char *line = malloc(MAX_BODY_LINE + 1);
  size_t n = 0, n_alloc = 0, line_no = 0, total = 0;
  size_t *body_line = NULL;
  gm_status st = line != NULL ? GM_OK : gm_fail(errmsg, cap, GM_ENOMEM, "n-body: out of memory");
  int got;
  while (st == GM_OK && (got = read_body_line(f, line, &total)) != 0) {
    ++line_no;
    if (got == -2) {
      st = gm_fail(errmsg, cap, GM_EINVAL, "n-body: %s:%zu: a NUL byte: not a text file", path,
                   line_no);
      break;
    }
    if (got == -1) {
      st = gm_fail(errmsg, cap, GM_EINVAL,
                   "n-body: %s:%zu: a line longer than %d bytes (one body per line: m x y z vx "
                   "vy vz)",
                   path, line_no, MAX_BODY_LINE);
      break;
    }
    if (total > MAX_BODY_FILE_BYTES) {
      st = gm_fail(errmsg, cap, GM_EINVAL,
                   "n-body: %s: more than %zu bytes, the limit for a file of bodies", path,
                   MAX_BODY_FILE_BYTES);
      break;
    }
    double v[8];
    char bad[4 * 24 + 8];
    int count = parse_numbers(line, v, bad, sizeof bad);
    if (count == 0) continue;
    if (count < 0) {
      st = gm_fail(errmsg, cap, GM_EINVAL, "n-body: %s:%zu: '%s' is not a number", path, line_no,
                   bad);
      break;
    }
    if (count != 7) {
      st = gm_fail(errmsg, cap, GM_EINVAL,
                   "n-body: %s:%zu: expected 7 numbers (m x y z vx vy vz), found %s%d", path,
                   line_no, count > 7 ? "more than " : "", count > 7 ? 7 : count);
      break;
    }
    for (size_t k = 0; k < 7 && st == GM_OK; ++k)
      if (!isfinite(v[k]))
        st = gm_fail(errmsg, cap, GM_EINVAL, "n-body: %s:%zu: number %zu is %g, not finite",
                     path, line_no, k + 1, v[k]);
    if (st == GM_OK && !(v[0] > 0.0))
      st = gm_fail(errmsg, cap, GM_EINVAL, "n-body: %s:%zu: the mass must be positive, got %g",
                   path, line_no, v[0]);
    if (st == GM_OK && n == MAX_BODIES)
      st = gm_fail(errmsg, cap, GM_EINVAL, "n-body: %s:%zu: more than %d bodies", path, line_no,
                   MAX_BODIES);
    if (st != GM_OK) break;
    if (n == n_alloc) {
      size_t grow = n_alloc ? 2 * n_alloc : 64;
      double *m = realloc(nb->mass, grow * sizeof *m);
      if (m != NULL) nb->mass = m;
      double *x = realloc(nb->position, 3 * grow * sizeof *x);
      if (x != NULL) nb->position = x;
      double *u = realloc(nb->velocity, 3 * grow * sizeof *u);
      if (u != NULL) nb->velocity = u;
      size_t *l = realloc(body_line, grow * sizeof *l);
      if (l != NULL) body_line = l;
      if (m == NULL || x == NULL || u == NULL || l == NULL) {
        st = gm_fail(errmsg, cap, GM_ENOMEM, "n-body: out of memory reading '%s'", path);
        break;
      }
      n_alloc = grow;
    }
    nb->mass[n] = v[0];
    for (size_t k = 0; k < 3; ++k) {
      nb->position[3 * n + k] = v[1 + k];
      nb->velocity[3 * n + k] = v[4 + k];
    }
    body_line[n++] = line_no;
  }
  if (st == GM_OK && ferror(f))
    st = gm_fail(errmsg, cap, GM_EIO, "n-body: error reading '%s'", path);
  free(line);
  fclose(f);
  nb->n_bodies = n;
  if (st == GM_OK && n == 0)
    st = gm_fail(errmsg, cap, GM_EINVAL,
                 "n-body: %s: no bodies (one per line: m x y z vx vy vz; '#' comments)", path);
  /* Without softening two bodies in one place make the energy infinite: say which. */
  for (size_t i = 0; st == GM_OK && softening == 0.0 && i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const double *a = nb->position + 3 * i, *b = nb->position + 3 * j;
      if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) {
        st = gm_fail(errmsg, cap, GM_EINVAL,
                     "n-body: %s: the bodies on lines %zu and %zu are at the same place (a "
                     "collision; set eps > 0 to soften it)",
                     path, body_line[i], body_line[j]);
        break;
      }
    }
  free(body_line);
  return st;
}

static gm_status prepare(void *ctx, const double *params, const char *const *texts, size_t *dim,
                         char *errmsg, size_t cap) {
  n_body *nb = ctx;
  const double G = params[P_G], eps = params[P_EPS];
  if (!(G > 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "n-body: G must be positive, got %g", G);
  if (!(eps >= 0.0))
    return gm_fail(errmsg, cap, GM_EINVAL, "n-body: the softening eps must be >= 0, got %g",
                   eps);
  const double central = params[P_CENTRAL];
  if (!(central == 0.0 || central == 1.0))
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "n-body: central must be 0 or 1 (body 1 is a dominant central body), got %g",
                   central);
  if (central == 1.0 && eps != 0.0)
    return gm_fail(errmsg, cap, GM_EINVAL,
                   "n-body: central = 1 needs eps = 0 (the Kepler orbits are unsoftened)");
  gm_status st = texts[P_FILE] != NULL ? read_bodies(nb, texts[P_FILE], eps, errmsg, cap)
                                       : generate(nb, params, errmsg, cap);
  if (st != GM_OK) return st;
  if (central == 1.0) {
    double others = 0.0;
    for (size_t i = 1; i < nb->n_bodies; ++i) others += nb->mass[i];
    if (nb->n_bodies < 2 || !(nb->mass[0] > others))
      return gm_fail(errmsg, cap, GM_EINVAL,
                     "n-body: central = 1 needs body 1 heavier than all the others together "
                     "(mass %g against %g)",
                     nb->mass[0], others);
  }
  *dim = 3 * nb->n_bodies;
  return GM_OK;
}

static gm_status setup(void *ctx, const double *params, gm_problem *pb, double *t0, double *y0,
                       char *errmsg, size_t cap) {
  (void)t0;
  (void)errmsg;
  (void)cap;
  n_body *nb = ctx;
  const size_t n = nb->n_bodies;
  nb->gravity = (gm_gravity){3 * n, n, params[P_G], params[P_EPS] * params[P_EPS], nb->mass};
  gm_gravity_setup(pb);
  if (params[P_CENTRAL] == 1.0) {
    nb->celestial = (gm_celestial){n, nb->mass, params[P_G], params[P_EPS] == 0.0};
    pb->celestial = &nb->celestial;
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < 3; ++k) {
      y0[3 * i + k] = nb->position[3 * i + k];
      y0[3 * n + 3 * i + k] = nb->mass[i] * nb->velocity[3 * i + k];
    }
  return GM_OK;
}

static void release(void *ctx) {
  n_body *nb = ctx;
  free(nb->mass);
  free(nb->position);
  free(nb->velocity);
}

static const gm_param_info params[] = {
    {"n", 100.0, "number of bodies of a drawn cluster", GM_PARAM_NUMBER},
    {"cluster", 1.0, "0 cold uniform sphere, 1 Plummer sphere (Aarseth-Henon-Wielen)",
     GM_PARAM_NUMBER},
    {"seed", 1.0, "seed of the cluster's random numbers (SplitMix64)", GM_PARAM_NUMBER},
    {"G", 1.0, "gravitational constant", GM_PARAM_NUMBER},
    {"eps", 0.0, "softening length (Plummer softening), >= 0", GM_PARAM_NUMBER},
    {"file", 0.0, "file of bodies, one per line: m x y z vx vy vz", GM_PARAM_TEXT},
    {"central", 0.0, "1: body 1 is a dominant central body (near-integrable rows)",
     GM_PARAM_NUMBER}};

const gm_model_def gm_model_n_body = {
    {"n-body",
     "N bodies with pairwise gravity, optional softening; a Plummer or cold cluster drawn "
     "from a seed, or a file",
     GM_PROBLEM_SEPARABLE, 300, 7, params, GM_GRAVITY_N_INVARIANTS, gm_gravity_invariant_names,
     0},
    sizeof(n_body), prepare, setup, NULL, release};
