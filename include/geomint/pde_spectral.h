/* geomint pde, spectral and variational parts (included by geomint/pde.h):
 *  - the pseudospectral Schrödinger variational integrator of seed 001 §5.8 (with the
 *    coefficient fixes of notes/001 §4) and Strang split-step Fourier, for
 *        i ψ_t = −½ ψ_xx + V(x) ψ      (ħ = m = 1) on a periodic grid;
 *  - the 1-D periodic wave equation u_tt = ⋆d⋆d u with d topological and the diagonal or the
 *    spectral Hodge star of seed 000 §3.3.4;
 *  - the multisymplectic variational integrator of seed 001 §5.1 (bilinear tents) for
 *        u_tt − u_xx + V'(u) = 0.
 * Plan/execute (DESIGN §5a): _create checks, allocates and makes every FFTW plan; _advance never
 * allocates. Pointer parameters are borrowed unless a comment says copied or owned. Complex
 * arrays are interleaved (re, im) pairs. Nothing here prints.
 * Threads: FFTW's planner keeps global state and is not thread-safe, so create and free these
 * solvers from one thread at a time; advancing distinct solvers concurrently is safe. */
#ifndef GEOMINT_PDE_SPECTRAL_H
#define GEOMINT_PDE_SPECTRAL_H

#include <stddef.h>

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Schrödinger ---------------------------------------------------------------------------- */

typedef enum gm_schrodinger_scheme {
  /* Seed 001 §5.8: ψ linear in time on each step, trigonometric interpolation in x, the action
   * integrated exactly in time and by the trapezoid rule in x (exact for the kinetic and time
   * terms of band-limited ψ; V collocated). Its discrete Euler–Lagrange equation is the
   * three-level scheme
   *     i (ψ^{l+1} − ψ^{l−1}) / (2Δt) = H (ψ^{l−1} + 4ψ^l + ψ^{l+1}) / 6,  H = −½∂_x² + V,
   * i.e. Milne–Simpson's rule for ψ_t = −iHψ: order 4 in Δt for this linear equation (the seed
   * says 2; docs/pde.md shows the measurement), stable iff Δt ρ(H) < √3. With `normalize` the
   * multiplier term λ_l ψ^l of the seed keeps ‖ψ^l‖ = ‖ψ⁰‖ exactly. */
  GM_SCHRODINGER_VI = 0,
  /* Strang splitting e^{−iVΔt/2} e^{iΔt∂²/2} e^{−iVΔt/2}, the kinetic flow exact in Fourier
   * space: order 2, unitary, unconditionally stable; 2 FFTs a step. */
  GM_SCHRODINGER_SPLIT_STEP = 1
} gm_schrodinger_scheme;

typedef struct gm_schrodinger_options {
  gm_schrodinger_scheme scheme;
  double dt;          /* Δt > 0 */
  int normalize;      /* VI only: impose ‖ψ^l‖² = ‖ψ⁰‖² with the seed's multiplier (default 0) */
  double solve_tol;   /* VI: stop the inner solve when the update is <= tol·‖ψ‖ (default 1e-15
                         relative, or earlier at the round-off floor) */
  size_t solve_max_iter; /* default 100 */
} gm_schrodinger_options;

gm_schrodinger_options gm_schrodinger_options_defaults(void); /* vi, dt 0 (must be set) */

typedef struct gm_schrodinger gm_schrodinger;

/* Plan a run on x_j = x0 + j·length/n, j = 0..n−1 (n even, >= 4), periodic. V: n values
 * (copied). psi0: n complex values (copied). The VI needs two levels: ψ¹ comes from one
 * classical RK4 step (local error O(Δt⁵), stable since Δt ρ(H) < √3 < 2√2).
 * Errors: GM_EINVAL (NULL, odd or small n, length/Δt not finite and > 0, the VI with
 * Δt ρ(H) >= √3 (the message gives the bound), the VI's inner solve not contracting:
 * Δt·(max V − min V)/3 >= 0.9), GM_EDOMAIN (non-finite V or ψ⁰, ψ⁰ = 0 with normalize),
 * GM_ENOMEM. */
gm_status gm_schrodinger_create(size_t n, double x0, double length, const double *V,
                                const double *psi0, const gm_schrodinger_options *options,
                                gm_schrodinger **out, gm_error *err);
void gm_schrodinger_free(gm_schrodinger *s);

/* Observers as gm_pde's: called every `every` steps (not at step 0) with the solver after the
 * step (ψ, time, norm, energy readable); at most GM_SPECTRAL_MAX_OBSERVERS; a non-zero return
 * stops advance with GM_ECALLBACK. GM_EINVAL for NULL fn, every = 0, too many. */
#define GM_SPECTRAL_MAX_OBSERVERS 8
typedef int (*gm_schrodinger_observer_fn)(gm_schrodinger *s, void *ctx);
gm_status gm_schrodinger_add_observer(gm_schrodinger *s, size_t every,
                                      gm_schrodinger_observer_fn fn, void *ctx, gm_error *err);

/* Advance n_steps. Errors: GM_ENOCONV (the VI's inner solve; message has step and update),
 * GM_EDOMAIN (non-finite ψ or no real multiplier for the normalisation), GM_ECALLBACK. */
gm_status gm_schrodinger_advance(gm_schrodinger *s, size_t n_steps, gm_error *err);

size_t gm_schrodinger_steps(const gm_schrodinger *s);
double gm_schrodinger_time(const gm_schrodinger *s);
const double *gm_schrodinger_psi(const gm_schrodinger *s); /* n complex, borrowed */
/* h Σ|ψ_j|² at the current level. */
double gm_schrodinger_norm(const gm_schrodinger *s);
/* ⟨ψ, Hψ⟩_h / ⟨ψ, ψ⟩_h at the current level (spectral kinetic part). */
double gm_schrodinger_energy(gm_schrodinger *s); /* uses the solver's FFT scratch */
/* The VI's discrete Noether charge of the phase symmetry ψ → e^{iθ}ψ, conserved exactly:
 *     Q^{l+½} = Re⟨ψ^l, ψ^{l+1}⟩_h − (Δt/3) Im⟨ψ^l, Hψ^{l+1}⟩_h  (→ ‖ψ‖² as Δt → 0),
 * from the pair of the two newest levels (ψ⁰, ψ¹ before the first step).
 * For split-step it is h Σ|ψ_j|² (conserved exactly as well). */
double gm_schrodinger_charge(const gm_schrodinger *s);
/* ⟨a, ψ⟩_h = h Σ conj(a_j) ψ_j (n complex values a), written to out[0] (re), out[1] (im). */
void gm_schrodinger_overlap(const gm_schrodinger *s, const double *a, double *out);
/* Inner-solve iterations so far (VI), FFTs so far (both). */
size_t gm_schrodinger_iterations(const gm_schrodinger *s);
size_t gm_schrodinger_ffts(const gm_schrodinger *s);
/* The VI's dispersion relation inverted: the eigenvalue E of H whose discrete eigenmode turns by
 * the phase ΩΔt per step, E = (3/Δt) sin(ΩΔt) / (2 + cos(ΩΔt)). Split-step: E = Ω. */
double gm_schrodinger_energy_from_frequency(gm_schrodinger_scheme scheme, double omega,
                                            double dt);

/* An eigenvalue by evolution: start from phi (n complex, ideally close to an eigenstate), advance
 * to T (rounded to whole steps), fit the unwrapped phase of c_l = ⟨phi, ψ^l⟩ by least squares,
 * c_l ≈ |c| e^{−iΩ t_l}, and invert the scheme's dispersion relation
 * (gm_schrodinger_energy_from_frequency). E_out: the eigenvalue of the semi-discrete H;
 * omega_out (may be NULL): Ω. Errors as create/advance; GM_EINVAL when T < 2Δt. */
gm_status gm_schrodinger_eigenvalue(size_t n, double x0, double length, const double *V,
                                    const double *phi, const gm_schrodinger_options *options,
                                    double T, double *E_out, double *omega_out, gm_error *err);

/* ---- the 1-D wave equation with a diagonal or a spectral Hodge star ------------------------- */

typedef enum gm_hodge_kind {
  GM_HODGE_DIAGONAL = 0, /* ⋆ = 1/h on primal 1-forms and dual 1-forms (DEC's diagonal star) */
  GM_HODGE_SPECTRAL = 1  /* ⋆̂_k = [h sinc(k/N)]⁻¹, sinc(x) = sin(πx)/(πx) (seed 000 §3.3.4) */
} gm_hodge_kind;

typedef struct gm_wave1d gm_wave1d;

/* u_tt = ⋆d⋆d u on x_j = j·length/n (n even >= 4) periodic, u a primal 0-form, du on edges
 * [x_j, x_{j+1}] by differences (topological), ⋆ to dual 0-forms at x_{j+½}, the dual d, ⋆ back.
 * Leapfrog (kick–drift–kick) in time. u0, v0: n values (copied). Errors: GM_EINVAL (n, length,
 * Δt, the CFL bound Δt <= h (diagonal) or Δt <= 2h/π (spectral)), GM_EDOMAIN, GM_ENOMEM. */
gm_status gm_wave1d_create(size_t n, double length, gm_hodge_kind star, double dt,
                           const double *u0, const double *v0, gm_wave1d **out, gm_error *err);
void gm_wave1d_free(gm_wave1d *w);
/* Observers as gm_schrodinger_add_observer (u, v, time, energy readable after the step). */
typedef int (*gm_wave1d_observer_fn)(gm_wave1d *w, void *ctx);
gm_status gm_wave1d_add_observer(gm_wave1d *w, size_t every, gm_wave1d_observer_fn fn, void *ctx,
                                 gm_error *err);
/* Advance n_steps; GM_EDOMAIN (non-finite value), GM_ECALLBACK (an observer stopped it). */
gm_status gm_wave1d_advance(gm_wave1d *w, size_t n_steps, gm_error *err);
double gm_wave1d_time(const gm_wave1d *w);
const double *gm_wave1d_u(const gm_wave1d *w); /* n values, borrowed */
const double *gm_wave1d_v(const gm_wave1d *w);
/* ½ h Σ v² + ½ ⟨du, ⋆du⟩ at the current step. */
double gm_wave1d_energy(const gm_wave1d *w);
/* out = ⋆d⋆d in (n values each; in != out). Does not allocate. */
void gm_wave1d_laplacian(gm_wave1d *w, const double *in, double *out);
/* The star on primal 1-forms: edge values f (n) → dual 0-form at x_{j+½} (n). */
void gm_wave1d_star1(gm_wave1d *w, const double *edges, double *dual);
/* The symbol of ⋆d⋆d for the integer wavenumber m (−n/2 < m <= n/2): −(2/h)² sin²(πm/n)
 * (diagonal) or, by construction, −κ² with κ = 2πm/length (spectral). */
double gm_wave1d_symbol(gm_hodge_kind star, size_t n, double length, long m);

/* ---- the multisymplectic variational integrator with bilinear tents (seed 001 §5.1) -------- */

/* u_tt − u_xx + V'(u) = 0 on x_i = x0 + i h, i = 0..n−1, periodic with u_{i+n} = u_i + twist.
 * L_d on each rectangle: the kinetic and gradient terms integrated exactly over the bilinear
 * interpolant, V by the trapezoid rule at the four corners; the four-term DEL is
 *   (1/6)(δ_t²u_{i−1} + 4δ_t²u_i + δ_t²u_{i+1})^j − (1/6)(δ_x²u^{j−1} + 4δ_x²u^j + δ_x²u^{j+1})_i
 *     + V'(u_i^j) = 0,
 * linear in the new level (a constant circulant tridiagonal solve, factored at create).
 * Stable for Δt <= Δx (linear analysis; create refuses Δt > Δx). */
typedef double (*gm_tentvi_potential_fn)(double u, const void *ctx);
typedef struct gm_tentvi gm_tentvi;
/* u0, u1: the first two levels (n values each, copied). V and dV required; d2V (V'') only for
 * the tangent variations, NULL: central differences of dV. Errors: GM_EINVAL (NULL, n < 4,
 * h, Δt not finite > 0, Δt > h), GM_EDOMAIN (non-finite data), GM_ENOMEM. */
gm_status gm_tentvi_create(size_t n, double x0, double h, double twist, double dt,
                           gm_tentvi_potential_fn V, gm_tentvi_potential_fn dV,
                           gm_tentvi_potential_fn d2V, const void *ctx, const double *u0,
                           const double *u1, gm_tentvi **out, gm_error *err);
void gm_tentvi_free(gm_tentvi *m);
gm_status gm_tentvi_advance(gm_tentvi *m, size_t n_steps, gm_error *err);
double gm_tentvi_time(const gm_tentvi *m);          /* time of the newest level */
const double *gm_tentvi_u(const gm_tentvi *m);      /* newest level, n values, borrowed */
const double *gm_tentvi_u_prev(const gm_tentvi *m); /* the level before */
/* The energy of the strip between the two newest levels j, j+1 (bounded, not exact):
 *   E = Σ_i [Δx(a_i² + a_i a_{i+1} + a_{i+1}²)/(6Δt²) + (c_i² + c_i d_i + d_i²)/(6Δx)
 *            + Δx(V(u_i^j) + V(u_i^{j+1}))/2],
 * a_i = u_i^{j+1} − u_i^j, c_i = u_{i+1}^j − u_i^j, d_i = u_{i+1}^{j+1} − u_i^{j+1}: the
 * rectangles' exact ∫∫(½u_t² + ½u_x²)/Δt plus the trapezoid V. */
double gm_tentvi_energy(const gm_tentvi *m);
/* Tangent variations: set two first variations (U0, U1), (W0, W1) of the first two levels
 * (n values each, copied); they are then advanced with the linearised DEL and
 * gm_tentvi_symplectic_form returns the discrete symplectic form of the time strip,
 *   ω = Σ_i [U^j M W^{j+1} − W^j M U^{j+1}]_i,  M = D₁D₂ of the strip's L_d
 *   = −(Δx/(6Δt))(z_{i−1} + 4z_i + z_{i+1}) + (Δt/(6Δx))(z_{i+1} − 2z_i + z_{i−1}),
 * which the multisymplectic form formula keeps constant; scale (may be NULL) receives the sum of
 * the |terms| (for a relative residual). NAN before variations are set. */
gm_status gm_tentvi_set_variations(gm_tentvi *m, const double *U0, const double *U1,
                                   const double *W0, const double *W1, gm_error *err);
double gm_tentvi_symplectic_form(const gm_tentvi *m, double *scale);

#ifdef __cplusplus
}
#endif

#endif
