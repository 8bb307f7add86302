/* method_torus.c: the torus model's row (torus.h): facet_flux, the flux
** (N . e_d) / 2 of the constant unit field e_d through a facet, d = the
** row constant k (0, 1 or 2), N = (x1 - x0) x (x2 - x0). The volume of a
** facet translated by a lattice vector t differs from the untranslated
** one by t_z N_z / 2 (int z dx dy) or t . N / 6 (symmetric content): the
** assembly weights this row by those components per body. */
#include "method.h"

static const int eps[3][3][3] = {
    {{0, 0, 0}, {0, 0, 1}, {0, -1, 0}},
    {{0, 0, -1}, {0, 0, 0}, {1, 0, 0}},
    {{0, 1, 0}, {-1, 0, 0}, {0, 0, 0}}};

double tds_mk_facet_flux(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  int d = (int)L->k;
  if (d < 0) d = 0;
  if (d > 2) d = 2;
  const double *const *x = L->x;
  double a[3], b[3];
  for (int i = 0; i < 3; i++) {
    a[i] = x[1][i] - x[0][i];
    b[i] = x[2][i] - x[0][i];
  }
  int p = (d + 1) % 3, q = (d + 2) % 3;
  double v = 0.5 * (a[p] * b[q] - a[q] * b[p]);
  if (g) {
    /* dN_d/dx[c][i] = (E_i x e_c)_d with e_c = x[c+1] - x[c+2]: e_c[q]
    ** for i = p, -e_c[p] for i = q, 0 for i = d (the values of
    ** tds_mk_normal_derivs' crosses with the unit vectors, without them) */
    for (int c = 0; c < 3; c++) {
      const double *y = x[(c + 1) % 3], *z = x[(c + 2) % 3];
      g[c][d] = 0;
      g[c][p] = 0.5 * (y[q] - z[q]);
      g[c][q] = -0.5 * (y[p] - z[p]);
    }
  }
  if (h) {
    /* N = x0 x x1 + x1 x x2 + x2 x x0: bilinear, so the second derivative
    ** of N_d in x_c[i], x_{c+1}[j] is eps(d, i, j), zero elsewhere. */
    for (int r = 0; r < 9; r++)
      for (int c = 0; c < 9; c++) h[r][c] = 0;
    for (int c = 0; c < 3; c++) {
      int c1 = (c + 1) % 3;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          double e = 0.5 * eps[d][i][j];
          h[3 * c + i][3 * c1 + j] += e;
          h[3 * c1 + j][3 * c + i] += e;
        }
    }
  }
  return v;
}
