/* The material library: Lorentz–Drude (LD) fits of the permittivity of metals, as data.
 *
 * Source: A. D. Rakić, A. B. Djurišić, J. M. Elazar, M. L. Majewski, "Optical properties of
 * metallic films for vertical-cavity optoelectronic devices", Appl. Opt. 37 (1998) 5271, the
 * table of LD model parameters (plasma frequency ω_p, oscillator strengths f_j, damping Γ_j and
 * resonances ω_j in eV), model eq.
 *   ε(ω) = 1 − f_0 ω_p² / (ω (ω + iΓ_0)) + Σ_j f_j ω_p² / (ω_j² − ω² − iωΓ_j).
 * The values below were checked against three independent transcriptions of that table (MEEP's
 * materials library, qpms and refractiveindex.info's scripts); where one of them differs
 * (Ag f_3 = 0.011, Al ω_3 = 1.808) the value two agree on is used.
 *
 * In geomint's units (gm_pole, frequencies in cycles per unit time with c = 1 and lengths in
 * units of `unit_um` micrometres) an energy E in eV is the frequency E unit_um / (hc) with
 * hc = 1.23984198 eV µm: the Drude term is the pole f_p = √f_0 ω_p, γ = Γ_0; each Lorentz term
 * the pole f_0 = ω_j, γ = Γ_j, Δε = f_j ω_p² / ω_j². */
#include <math.h>
#include <stddef.h>
#include <strings.h>

#include "fields/internal.h"

#define HC_EV_UM 1.23984198 /* hc in eV·µm (CODATA 2018: 1.239841984 eV·µm) */

typedef struct ld_oscillator {
  double f, gamma, omega; /* strength, Γ_j (eV), ω_j (eV) */
} ld_oscillator;

typedef struct ld_metal {
  const char *name;
  double omega_p, f0, gamma0; /* eV, -, eV */
  size_t n;
  ld_oscillator osc[5];
} ld_metal;

static const ld_metal library[] = {
    {"Ag", 9.01, 0.845, 0.048, 5,
     {{0.065, 3.886, 0.816}, {0.124, 0.452, 4.481}, {0.011, 0.065, 8.185},
      {0.840, 0.916, 9.083}, {5.646, 2.419, 20.29}}},
    {"Au", 9.03, 0.760, 0.053, 5,
     {{0.024, 0.241, 0.415}, {0.010, 0.345, 0.830}, {0.071, 0.870, 2.969},
      {0.601, 2.494, 4.304}, {4.384, 2.214, 13.32}}},
    {"Al", 14.98, 0.523, 0.047, 4,
     {{0.227, 0.333, 0.162}, {0.050, 0.312, 1.544}, {0.166, 1.351, 1.808},
      {0.030, 3.382, 3.473}, {0, 0, 0}}},
};

const char *gm_material_name(size_t k) {
  return k < sizeof library / sizeof library[0] ? library[k].name : NULL;
}

gm_status gm_material_find(const char *name, double unit_um, gm_medium *medium, gm_pole *poles,
                           size_t cap, size_t *n_poles, gm_error *err) {
  if (name == NULL || medium == NULL || poles == NULL || n_poles == NULL)
    return gm_error_set(err, GM_EINVAL, "material: NULL argument");
  if (!(unit_um > 0.0) || !isfinite(unit_um))
    return gm_error_set(err, GM_EINVAL, "material: the length unit must be > 0 um (got %g)",
                        unit_um);
  const ld_metal *m = NULL;
  for (size_t k = 0; k < sizeof library / sizeof library[0]; ++k)
    if (strcasecmp(name, library[k].name) == 0) m = &library[k];
  if (m == NULL)
    return gm_error_set(err, GM_ENOTFOUND, "material: no \"%s\" in the library (Ag, Au, Al)",
                        name);
  if (cap < m->n + 1)
    return gm_error_set(err, GM_EINVAL, "material: %s has %zu poles, room for %zu", m->name,
                        m->n + 1, cap);
  const double scale = unit_um / HC_EV_UM; /* eV → cycles per unit time */
  *medium = gm_medium_vacuum();
  poles[0] = (gm_pole){GM_POLE_DRUDE, sqrt(m->f0) * m->omega_p * scale, m->gamma0 * scale, 0.0};
  for (size_t j = 0; j < m->n; ++j) {
    const ld_oscillator *o = &m->osc[j];
    poles[j + 1] = (gm_pole){GM_POLE_LORENTZ, o->omega * scale, o->gamma * scale,
                             o->f * m->omega_p * m->omega_p / (o->omega * o->omega)};
  }
  *n_poles = m->n + 1;
  return GM_OK;
}
