/* symmetry.c: meshes in a symmetry group's quotient (contracts in
** symmetry.h). */
#include "symmetry.h"

#include <math.h>
#include <string.h>

#include "gather.h"
#include "method.h"
#include "symgroup.h"

/* R of the element of corner wrap w (the identity for 0). */
static void rot_of(const tds_mesh *m, int32_t w, double R[3][3]) {
  double t[3];
  tds_sym_affine(m->sym, m->symp, (const double(*)[3])m->period, w, R, t);
}

void tds_sym_pullback(const tds_mesh *m, int kind, tds_id el, double g[3][3], double h[9][9]) {
  int32_t w[3] = {0, 0, 0};
  int n = kind == TDS_EL_FACET ? 3 : 2;
  if (kind == TDS_EL_FACET) {
    w[1] = tds_oe_wrap(m, m->fe[el][0]);
    w[2] = tds_corner2_wrap(m, el);
  } else {
    w[1] = m->ewrap[el];
  }
  double R[3][3][3];
  int moved[3] = {0, 0, 0};
  for (int c = 1; c < n; c++)
    if (w[c]) {
      rot_of(m, w[c], R[c]);
      moved[c] = 1;
    }
  if (!moved[1] && !moved[2]) return;
  for (int c = 1; c < n; c++) { /* g_c <- R_c^T g_c */
    if (!moved[c]) continue;
    double y[3];
    for (int i = 0; i < 3; i++) y[i] = R[c][0][i] * g[c][0] + R[c][1][i] * g[c][1] + R[c][2][i] * g[c][2];
    memcpy(g[c], y, sizeof y);
  }
  if (!h) return;
  for (int c = 0; c < n; c++) /* rows: block (c, d) <- R_c^T block */
    if (moved[c])
      for (int j = 0; j < 3 * n; j++) {
        double y[3];
        for (int i = 0; i < 3; i++)
          y[i] = R[c][0][i] * h[3 * c][j] + R[c][1][i] * h[3 * c + 1][j] + R[c][2][i] * h[3 * c + 2][j];
        for (int i = 0; i < 3; i++) h[3 * c + i][j] = y[i];
      }
  for (int d = 0; d < n; d++) /* columns: block (c, d) <- block R_d */
    if (moved[d])
      for (int i = 0; i < 3 * n; i++) {
        double y[3];
        for (int j = 0; j < 3; j++)
          y[j] = h[i][3 * d] * R[d][0][j] + h[i][3 * d + 1] * R[d][1][j] + h[i][3 * d + 2] * R[d][2][j];
        for (int j = 0; j < 3; j++) h[i][3 * d + j] = y[j];
      }
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

