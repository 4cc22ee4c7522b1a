/* geomint maxwell run, scene key "dft": the flux planes' spectra after the run. The
 * normalisation file is written (dft.save) before anything is subtracted (dft.subtract), so
 * one run can do both; out/flux_spectra.csv holds per frequency each plane's spectrum (the total
 * field's) and, when a normalisation was subtracted, the spectrum of the scattered field (the
 * transforms minus the saved run's) and the saved run's (incident) spectrum beside it, so that
 * T = plane / plane_incident behind an object and R = −plane_scattered / plane_incident in
 * front of it (as MEEP's load_minus_flux_data); out/flux_spectra.png plots them (gnuplot, when
 * on PATH). */
#include <stdio.h>
#include <stdlib.h>

#include "cli/cli.h"
#include "cli/maxwell.h"
#include "geomint/yee_scene.h"

static const char *const COMMAND = "maxwell run";

int mx_write_spectra(const char *out_dir, const gm_yee_scene *sc) {
  if (sc->dft_n == 0 || sc->dft == NULL) return CLI_EXIT_OK;
  const size_t np = sc->n_fluxes, nf = sc->dft_n;
  gm_error err = {{0}};
  if (sc->dft_save != NULL && gm_yee_dft_flux_save(sc->dft, np, sc->dft_save, &err) != GM_OK) {
    cli_error(COMMAND, "dft.save: %s", err.message);
    return CLI_EXIT_FAILURE;
  }
  double *spec = malloc(np * nf * sizeof *spec), *inc = NULL, *scat = NULL;
  if (spec == NULL) {
    cli_error(COMMAND, "out of memory");
    return CLI_EXIT_FAILURE;
  }
  for (size_t k = 0; k < np; ++k) gm_yee_dft_flux_spectrum(sc->dft[k], spec + k * nf);
  if (sc->dft_subtract != NULL) {
    inc = malloc(np * nf * sizeof *inc);
    scat = malloc(np * nf * sizeof *scat);
    if (inc == NULL || scat == NULL ||
        gm_yee_dft_flux_subtract_file(sc->dft, np, sc->dft_subtract, inc, &err) != GM_OK) {
      cli_error(COMMAND, "dft.subtract: %s", inc == NULL ? "out of memory" : err.message);
      free(spec), free(inc), free(scat);
      return CLI_EXIT_FAILURE;
    }
    for (size_t k = 0; k < np; ++k) gm_yee_dft_flux_spectrum(sc->dft[k], scat + k * nf);
  }
  double *freq = malloc(nf * sizeof *freq);
  char path[4096];
  FILE *f = freq ? fopen(mx_path(path, sizeof path, out_dir, "flux_spectra.csv"), "w") : NULL;
  if (f == NULL) {
    cli_error(COMMAND, "cannot write %s", path);
    free(spec), free(inc), free(scat), free(freq);
    return CLI_EXIT_FAILURE;
  }
  fprintf(f, "frequency");
  for (size_t k = 0; k < np; ++k) {
    fprintf(f, ",%s", sc->fluxes[k].name);
    if (inc) fprintf(f, ",%s_scattered,%s_incident", sc->fluxes[k].name, sc->fluxes[k].name);
  }
  fprintf(f, "\n");
  for (size_t i = 0; i < nf; ++i) {
    freq[i] = nf == 1 ? sc->dft_fmin
                      : sc->dft_fmin + (sc->dft_fmax - sc->dft_fmin) * (double)i / (double)(nf - 1);
    fprintf(f, "%.17g", freq[i]);
    for (size_t k = 0; k < np; ++k) {
      fprintf(f, ",%.17g", spec[k * nf + i]);
      if (inc) fprintf(f, ",%.17g,%.17g", scat[k * nf + i], inc[k * nf + i]);
    }
    fprintf(f, "\n");
  }
  int status = fclose(f) == 0 ? CLI_EXIT_OK : CLI_EXIT_FAILURE;
  if (status != CLI_EXIT_OK) cli_error(COMMAND, "writing %s failed", path);
  if (status == CLI_EXIT_OK && cli_gnuplot_available()) {
    mx_line *lines = calloc(2 * np, sizeof *lines);
    size_t nl = 0;
    for (size_t k = 0; lines != NULL && k < np; ++k) {
      lines[nl++] = (mx_line){sc->fluxes[k].name, nf, freq, spec + k * nf, 0};
      if (inc) lines[nl++] = (mx_line){"incident", nf, freq, inc + k * nf, 1};
    }
    if (lines != NULL)
      status = mx_plot_lines(COMMAND, mx_path(path, sizeof path, out_dir, "flux_spectra.png"),
                             "flux spectra Re(E* x H).n (DFT)", "frequency", "flux", 0, lines,
                             nl);
    free(lines);
  }
  free(spec), free(inc), free(scat), free(freq);
  return status;
}
