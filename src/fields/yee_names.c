/* Names of components, waveforms and boundary kinds, and which components a dimension has. */
#include <strings.h>

#include "fields/internal.h"

static const char *const component_names[GM_YEE_N_COMPONENTS] = {"Ex", "Ey", "Ez",
                                                                  "Hx", "Hy", "Hz"};
static const char *const waveform_names[] = {"gaussian", "dgaussian", "ricker", "cw", "custom"};
static const char *const boundary_names[] = {"pec", "pmc", "periodic", "cpml"};

const char *gm_yee_component_name(gm_yee_component c) {
  return (unsigned)c < GM_YEE_N_COMPONENTS ? component_names[c] : NULL;
}

gm_status gm_yee_component_find(const char *name, gm_yee_component *out) {
  for (int c = 0; name != NULL && c < GM_YEE_N_COMPONENTS; ++c)
    if (strcasecmp(name, component_names[c]) == 0) {
      *out = (gm_yee_component)c;
      return GM_OK;
    }
  return GM_ENOTFOUND;
}

const char *gm_waveform_kind_name(gm_waveform_kind kind) {
  return (unsigned)kind < sizeof waveform_names / sizeof *waveform_names ? waveform_names[kind]
                                                                         : NULL;
}

gm_status gm_waveform_kind_find(const char *name, gm_waveform_kind *out) {
  for (size_t k = 0; name != NULL && k < sizeof waveform_names / sizeof *waveform_names; ++k)
    if (strcasecmp(name, waveform_names[k]) == 0) {
      *out = (gm_waveform_kind)k;
      return GM_OK;
    }
  return GM_ENOTFOUND;
}

const char *gm_yee_boundary_kind_name(gm_yee_boundary_kind kind) {
  return (unsigned)kind < sizeof boundary_names / sizeof *boundary_names ? boundary_names[kind]
                                                                         : NULL;
}

gm_status gm_yee_boundary_kind_find(const char *name, gm_yee_boundary_kind *out) {
  for (size_t k = 0; name != NULL && k < sizeof boundary_names / sizeof *boundary_names; ++k)
    if (strcasecmp(name, boundary_names[k]) == 0) {
      *out = (gm_yee_boundary_kind)k;
      return GM_OK;
    }
  return GM_ENOTFOUND;
}

size_t gm_yee_dim_axes(gm_yee_dim dim) {
  switch (dim) {
  case GM_YEE_1D: return 1;
  case GM_YEE_2D_TE:
  case GM_YEE_2D_TM: return 2;
  case GM_YEE_3D: return 3;
  }
  return 0;
}

int gm_yee_dim_has(gm_yee_dim dim, gm_yee_component c) {
  switch (dim) {
  case GM_YEE_1D: return c == GM_EZ || c == GM_HY;
  case GM_YEE_2D_TM: return c == GM_EZ || c == GM_HX || c == GM_HY;
  case GM_YEE_2D_TE: return c == GM_HZ || c == GM_EX || c == GM_EY;
  case GM_YEE_3D: return (unsigned)c < GM_YEE_N_COMPONENTS;
  }
  return 0;
}
