/* Body-centred cubic tetrahedra: the well-centred tetrahedral mesh of a cube grid. For every
 * interior face of the nx×ny×nz cube grid, the octahedron spanned by the face's four corners and
 * the centres of its two cubes is cut into four tetrahedra around the centre–centre segment.
 * With cubic cells every tetrahedron is congruent, with two edges of length h (centre–centre,
 * corner–corner) and four of length √3 h/2; its circumcentre is its centroid, so the
 * circumcentric Hodge stars of all dimensions are positive (the mesh is well-centred in the sense
 * of VanderZee, Hirani, Guoy, Ramos, SIAM J. Sci. Comput. 31 (2010); the centroid property is
 * checked by the test bcc_mesh_is_well_centred through the positive stars).
 * Without `fill` the domain is the box minus the square pyramids (cube centre + boundary face) on
 * its boundary, and the 8 box corners belong to no tetrahedron and are left out; with `fill` each
 * pyramid is cut in four around the segment from its cube centre to the centre of its boundary
 * square (a new vertex): the halves of the octahedra that the wall would cut, whose circumcentre
 * lies on the wall. Along the box's edges and at its corners two walls meet and the summed stars
 * of some interior edges and faces are negative or zero (about 4 per boundary square): the
 * filled mesh is not well-centred, use it with the Whitney star. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "core/internal.h"
#include "geomint/mesh.h"

gm_status gm_mesh_bcc(const double lo[3], const double hi[3], size_t nx, size_t ny, size_t nz,
                      int fill, gm_mesh **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (lo == NULL || hi == NULL) return gm_error_set(err, GM_EINVAL, "box corners are NULL");
  for (int d = 0; d < 3; ++d)
    if (!(isfinite(lo[d]) && isfinite(hi[d]) && hi[d] > lo[d]))
      return gm_error_set(err, GM_EINVAL, "empty or non-finite box along axis %d", d);
  if (nx < 2 || ny < 2 || nz < 2 || nx > 2048 || ny > 2048 || nz > 2048)
    return gm_error_set(err, GM_EINVAL,
                        "bcc: cell counts %zu x %zu x %zu out of range (2..2048 each)", nx, ny, nz);
  const size_t n[3] = {nx, ny, nz};
  const size_t sx = nx + 1, sxy = (nx + 1) * (ny + 1), n_corner = sxy * (nz + 1);
  const size_t n_centre = nx * ny * nz;
  /* interior faces normal to axis a: (n[a] − 1) × the other two counts */
  const size_t n_faces = (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1);
  const size_t n_bnd = fill ? 2 * (nx * ny + ny * nz + nz * nx) : 0; /* boundary squares */
  size_t *renum = malloc((n_corner + n_centre) * sizeof(size_t));
  gm_mesh *m = NULL;
  gm_status st = renum ? gm_mesh_create(3, n_corner + n_centre + n_bnd - (fill ? 0 : 8), 3, 4 * (n_faces + n_bnd), &m) : GM_ENOMEM;
  if (st != GM_OK) {
    free(renum);
    return gm_error_set(err, st, "bcc: cannot allocate %zu tetrahedra", 4 * n_faces);
  }
  double h[3];
  for (int d = 0; d < 3; ++d) h[d] = (hi[d] - lo[d]) / (double)n[d];
  size_t nv = 0;
  for (size_t k = 0; k <= nz; ++k)
    for (size_t j = 0; j <= ny; ++j)
      for (size_t i = 0; i <= nx; ++i) {
        const size_t idx[3] = {i, j, k}, v = k * sxy + j * sx + i;
        const int corner =
            !fill && (i == 0 || i == nx) && (j == 0 || j == ny) && (k == 0 || k == nz);
        renum[v] = corner ? SIZE_MAX : nv;
        if (corner) continue;
        for (int d = 0; d < 3; ++d)
          m->x[3 * nv + (size_t)d] = idx[d] == n[d] ? hi[d] : lo[d] + (double)idx[d] * h[d];
        ++nv;
      }
  for (size_t k = 0; k < nz; ++k)
    for (size_t j = 0; j < ny; ++j)
      for (size_t i = 0; i < nx; ++i) {
        const size_t idx[3] = {i, j, k};
        renum[n_corner + (k * ny + j) * nx + i] = nv;
        for (int d = 0; d < 3; ++d) m->x[3 * nv + (size_t)d] = lo[d] + ((double)idx[d] + 0.5) * h[d];
        ++nv;
      }
  size_t *c = m->cells;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, q = (a + 2) % 3;
    size_t lim[3] = {nx, ny, nz};
    lim[a] -= 1; /* the face between cube idx and idx + e_a */
    for (size_t k = 0; k < lim[2]; ++k)
      for (size_t j = 0; j < lim[1]; ++j)
        for (size_t i = 0; i < lim[0]; ++i) {
          size_t lo_c[3] = {i, j, k}, hi_c[3] = {i, j, k};
          hi_c[a] += 1;
          const size_t c1 = renum[n_corner + (lo_c[2] * ny + lo_c[1]) * nx + lo_c[0]];
          const size_t c2 = renum[n_corner + (hi_c[2] * ny + hi_c[1]) * nx + hi_c[0]];
          size_t sq[4]; /* the face's corners in cyclic order */
          static const int cyc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
          for (int r = 0; r < 4; ++r) {
            size_t p[3] = {hi_c[0], hi_c[1], hi_c[2]};
            p[b] += (size_t)cyc[r][0];
            p[q] += (size_t)cyc[r][1];
            sq[r] = renum[p[2] * sxy + p[1] * sx + p[0]];
          }
          for (int r = 0; r < 4; ++r) {
            c[0] = c1, c[1] = c2, c[2] = sq[r], c[3] = sq[(r + 1) % 4];
            c += 4;
          }
        }
  }
  /* fill: the pyramid on each boundary square, cut in four around centre – square centre */
  for (int a = 0; fill && a < 3; ++a) {
    const int b = (a + 1) % 3, q = (a + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      size_t lim[3] = {nx, ny, nz};
      lim[a] = 1;
      for (size_t k = 0; k < lim[2]; ++k)
        for (size_t j = 0; j < lim[1]; ++j)
          for (size_t i = 0; i < lim[0]; ++i) {
            size_t cell[3] = {i, j, k};
            cell[a] = side ? n[a] - 1 : 0;
            const size_t cc = renum[n_corner + (cell[2] * ny + cell[1]) * nx + cell[0]];
            double *xm = m->x + 3 * nv; /* the square's centre */
            for (int d = 0; d < 3; ++d)
              xm[d] = d == a ? (side ? hi[d] : lo[d]) : lo[d] + ((double)cell[d] + 0.5) * h[d];
            const size_t mid = nv++;
            size_t sq[4];
            static const int cyc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int r = 0; r < 4; ++r) {
              size_t p[3] = {cell[0], cell[1], cell[2]};
              p[a] += (size_t)side;
              p[b] += (size_t)cyc[r][0];
              p[q] += (size_t)cyc[r][1];
              sq[r] = renum[p[2] * sxy + p[1] * sx + p[0]];
            }
            for (int r = 0; r < 4; ++r) {
              c[0] = cc, c[1] = mid, c[2] = sq[r], c[3] = sq[(r + 1) % 4];
              c += 4;
            }
          }
    }
  }
  free(renum);
  *out = m;
  return GM_OK;
}
