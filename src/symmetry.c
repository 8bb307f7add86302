/* symmetry.c: meshes in a symmetry group's quotient (contracts in
** symmetry.h). */
#include "symmetry.h"

#include <math.h>
#include <string.h>

#include "gather.h"
#include "method.h"
#include "symgroup.h"

/* Pull a gathered gradient and Hessian back to the stored vertices. A
** corner c moved by g_c (x_c stored, g_c(x_c) gathered) with Jacobian J_c
** gets g_c <- J_c^T g_c; Hessian blocks (c, d) <- J_c^T H_cd J_d, plus on
** the diagonal sum_i g_c,i d2 g_c,i / dx dx (the gathered gradient: zero for
** affine groups, where J is the rotation R). */
void tds_sym_pullback(const tds_mesh *m, int kind, tds_id el, double g[3][3], double h[9][9]) {
  int32_t w[3] = {0, 0, 0};
  tds_id v[3] = {TDS_NONE, TDS_NONE, TDS_NONE};
  int n = kind == TDS_EL_FACET ? 3 : 2;
  if (kind == TDS_EL_FACET) {
    w[1] = tds_oe_wrap(m, m->fe[el][0]);
    w[2] = tds_corner2_wrap(m, el);
    for (int c = 0; c < 3; c++) v[c] = m->fv[el][c];
  } else {
    w[1] = m->ewrap[el];
    v[0] = m->ev[el][0];
    v[1] = m->ev[el][1];
  }
  double J[3][3][3], T[3][3][3][3], K[3][3][3];
  int moved[3] = {0, 0, 0}, curved = !tds_sym_affine_group(m->sym) && h;
  for (int c = 1; c < n; c++)
    if (w[c]) {
      double out[3];
      tds_sym_jacobian(m->sym, m->symp, (const double(*)[3])m->period, w[c], m->x[v[c]], out,
                       J[c], curved ? T[c] : NULL);
      moved[c] = 1;
    }
  if (!moved[1] && !moved[2]) return;
  if (curved) /* K_c = sum_i g_c,i T_c,i, from the gathered gradient */
    for (int c = 1; c < n; c++)
      if (moved[c])
        for (int j = 0; j < 3; j++)
          for (int k = 0; k < 3; k++)
            K[c][j][k] = g[c][0] * T[c][0][j][k] + g[c][1] * T[c][1][j][k] + g[c][2] * T[c][2][j][k];
  for (int c = 1; c < n; c++) { /* g_c <- J_c^T g_c */
    if (!moved[c]) continue;
    double y[3];
    for (int i = 0; i < 3; i++) y[i] = J[c][0][i] * g[c][0] + J[c][1][i] * g[c][1] + J[c][2][i] * g[c][2];
    memcpy(g[c], y, sizeof y);
  }
  if (!h) return;
  for (int c = 0; c < n; c++) /* rows: block (c, d) <- J_c^T block */
    if (moved[c])
      for (int j = 0; j < 3 * n; j++) {
        double y[3];
        for (int i = 0; i < 3; i++)
          y[i] = J[c][0][i] * h[3 * c][j] + J[c][1][i] * h[3 * c + 1][j] + J[c][2][i] * h[3 * c + 2][j];
        for (int i = 0; i < 3; i++) h[3 * c + i][j] = y[i];
      }
  for (int d = 0; d < n; d++) /* columns: block (c, d) <- block J_d */
    if (moved[d])
      for (int i = 0; i < 3 * n; i++) {
        double y[3];
        for (int j = 0; j < 3; j++)
          y[j] = h[i][3 * d] * J[d][0][j] + h[i][3 * d + 1] * J[d][1][j] + h[i][3 * d + 2] * J[d][2][j];
        for (int j = 0; j < 3; j++) h[i][3 * d + j] = y[j];
      }
  if (curved)
    for (int c = 1; c < n; c++)
      if (moved[c])
        for (int j = 0; j < 3; j++)
          for (int k = 0; k < 3; k++) h[3 * c + j][3 * c + k] += K[c][j][k];
}

int tds_sym_read_params(tds_ctx *ctx, tds_surf *s) {
  int id = s->m.sym;
  double p[2];
  for (int k = 0; k < 2; k++) {
    const char *name = tds_sym_param_name(id, k);
    int slot = name ? tds_surf_param_find(s, name, strlen(name)) : -1;
    p[k] = slot >= 0 ? s->parval[slot] : tds_sym_param_default(id, k);
  }
  const char *bad = tds_sym_param_check(id, p);
  if (bad)
    return tds_seterr(ctx, TDS_ERANGE, "SYMMETRY_GROUP \"%s\": %s", tds_sym_name(id), bad);
  memcpy(s->m.symp, p, sizeof p);
  return TDS_OK;
}

int tds_sym_unsupported(tds_ctx *ctx, const tds_mesh *m, const char *what) {
  if (!tds_mesh_rotates(m)) return TDS_OK;
  return tds_seterr(ctx, TDS_ESYNTAX, "%s is not supported yet with SYMMETRY_GROUP \"%s\"", what,
                    tds_sym_name(m->sym));
}

