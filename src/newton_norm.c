/* newton_norm.c: the vertices' normal spaces of hessian_normal
** (newton.h, newton_int.h). */
#include <math.h>
#include <string.h>

#include "expr.h"
#include "fixq.h"
#include "gather.h"
#include "motion.h"
#include "newton_int.h"
#include "vec3.h"

/* Area vector (length = area) of live facet f. */
static void facet_vec(const tds_mesh *m, tds_id f, double c[3]) {
  tds_corners C; /* unwrapped: in the torus a facet may cross the cell */
  tds_gather_facet(m, f, &C);
  double a[3], b[3];
  v3_sub(a, C.x[1], C.x[0]);
  v3_sub(b, C.x[2], C.x[0]);
  v3_cross(c, a, b);
  v3_scale(c, 0.5);
}

/* TDS_OK or TDS_ENOMEM (then vn is incomplete: an answer that depends on
** memory would make a command's result depend on it). */
int tds_vertex_normals(const tds_alloc *al, const tds_mesh *m, vnorm *vn) {
  memset(vn, 0, (size_t)m->nv * sizeof *vn);
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    double c[3];
    facet_vec(m, f, c);
    for (int k = 0; k < 3; k++) {
      vnorm *w = &vn[m->fv[f][k]];
      v3_add(w->an, w->an, c);
      w->nf++;
    }
  }
  /* Where every facet's normal is within 30 degrees of the plain sum's,
  ** each agrees in sign with the dominant direction too (that lies
  ** within 60 degrees of the sum: its Rayleigh quotient is at least the
  ** sum's), so the plain sum is the answer; elsewhere the dominant
  ** direction by power iteration from the plain sum, and the facets
  ** added again with their signs. */
  double (*ref)[3] = tds_malloc(al, ((size_t)m->nv + 1) * sizeof *ref);
  unsigned char *bad = tds_calloc(al, (size_t)m->nv + 1, 1);
  if (!ref || !bad) {
    tds_free(al, ref);
    tds_free(al, bad);
    return TDS_ENOMEM;
  }
  for (tds_id v = 0; v < m->nv; v++) {
    double l = v3_norm(vn[v].an);
    if (l > 0) {
      for (int i = 0; i < 3; i++) ref[v][i] = vn[v].an[i] / l;
    } else {
      bad[v] = 1;
    }
  }
  int nbad = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    double c[3];
    facet_vec(m, f, c);
    double lim = 0.8660254037844386 * v3_norm(c); /* cos 30 degrees */
    for (int k = 0; k < 3; k++) {
      tds_id v = m->fv[f][k];
      if (!bad[v] && !(v3_dot(c, ref[v]) >= lim)) bad[v] = 1;
    }
  }
  for (tds_id v = 0; v < m->nv; v++) nbad += bad[v];
  for (tds_id f = 0; f < m->nf && nbad; f++) { /* sum area n n^T where needed */
    if (m->fflags[f] & TDS_DEAD) continue;
    double c[3];
    facet_vec(m, f, c);
    double A = v3_norm(c);
    for (int k = 0; k < 3; k++) {
      vnorm *w = &vn[m->fv[f][k]];
      if (bad[m->fv[f][k]] && A > 0)
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++) w->P[i][j] += c[i] * c[j] / A;
    }
  }
  for (tds_id v = 0; v < m->nv; v++) {
    if (!bad[v]) continue;
    vnorm *w = &vn[v];
    double r[3];
    v3_copy(r, w->an);
    if (!(v3_norm(r) > 1e-12 * (w->P[0][0] + w->P[1][1] + w->P[2][2]))) {
      int big = 0;
      for (int i = 1; i < 3; i++)
        if (w->P[i][i] > w->P[big][big]) big = i;
      for (int i = 0; i < 3; i++) r[i] = w->P[i][big];
    }
    for (int it = 0; it < 100; it++) {
      double t[3];
      for (int i = 0; i < 3; i++) t[i] = w->P[i][0] * r[0] + w->P[i][1] * r[1] + w->P[i][2] * r[2];
      double l = v3_norm(t);
      if (!(l > 0)) break;
      v3_scale(t, 1 / l);
      double dr[3];
      v3_sub(dr, t, r);
      v3_copy(r, t);
      if (it > 0 && v3_dot(dr, dr) < 1e-30) break; /* converged */
    }
    v3_copy(ref[v], r);
    memset(w->an, 0, sizeof w->an);
  }
  for (tds_id f = 0; f < m->nf && nbad; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    double c[3];
    facet_vec(m, f, c);
    for (int k = 0; k < 3; k++) {
      tds_id v = m->fv[f][k];
      if (bad[v]) v3_axpy(vn[v].an, v3_dot(c, ref[v]) < 0 ? -1 : 1, c);
    }
  }
  tds_free(al, bad);
  tds_free(al, ref);
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    if (tds_edge_valence(m, e) < 3) continue;
    double d[3];
    tds_edge_vec(m, TDS_OREF(e, 0), d); /* unwrapped (torus) */
    double len = v3_norm(d);
    if (!(len > 0)) continue;
    v3_scale(d, 1 / len);
    for (int k = 0; k < 2; k++) {
      vnorm *w = &vn[m->ev[e][k]];
      if (w->nt) {
        double dot = v3_dot(d, w->td) / v3_norm(w->td);
        if (fabs(dot) < 0.5) w->bent = 1;
        v3_axpy(w->td, dot < 0 ? -1 : 1, d);
      } else {
        v3_copy(w->td, d);
      }
      w->nt++;
    }
  }
  return TDS_OK;
}

/* Columns W (d x c) of the unknowns of a vertex with motion basis B
** (3 x d, dx = B u): the normal space's directions pulled back into u
** (least squares) and made orthonormal in space (|B w| = 1). c = d (the
** identity) when the vertex keeps its whole motion space. Returns c. */
int tds_normal_columns(const vnorm *vn, const double B[3][3], int d, int full,
                          double W[3][3]) {
  memset(W, 0, sizeof(double[3][3]));
  double nx[3][3];
  int cn = 0;
  if (!full && vn->nf > 0 && vn->nt <= 2 && !vn->bent) {
    if (vn->nt == 0) {
      double len = v3_norm(vn->an);
      if (len > 0) {
        for (int i = 0; i < 3; i++) nx[0][i] = vn->an[i] / len;
        cn = 1;
      }
    } else { /* the plane perpendicular to the triple line */
      double t[3];
      v3_copy(t, vn->td);
      v3_scale(t, 1 / v3_norm(t));
      for (int e = 0; e < 3 && cn < 2; e++) {
        double w[3] = {0, 0, 0};
        w[e] = 1;
        v3_axpy(w, -v3_dot(w, t), t);
        for (int l = 0; l < cn; l++) v3_axpy(w, -v3_dot(w, nx[l]), nx[l]);
        double len = v3_norm(w);
        if (len > 0.5) {
          for (int i = 0; i < 3; i++) nx[cn][i] = w[i] / len;
          cn++;
        }
      }
    }
  }
  if (cn == 0) {
    for (int a = 0; a < d; a++) W[a][a] = 1;
    /* unit length in space for each coordinate direction */
    for (int a = 0; a < d; a++) {
      double l = sqrt(B[0][a] * B[0][a] + B[1][a] * B[1][a] + B[2][a] * B[2][a]);
      if (l > 0) W[a][a] = 1 / l;
    }
    return d;
  }
  /* G = B^T B; w = G^-1 B^T n; Gram-Schmidt with <a, b> = (B a).(B b) */
  double G[3][3];
  for (int a = 0; a < d; a++)
    for (int b = 0; b < d; b++) G[a][b] = B[0][a] * B[0][b] + B[1][a] * B[1][b] + B[2][a] * B[2][b];
  int c = 0;
  for (int j = 0; j < cn && c < d; j++) {
    double g[9], w[3];
    for (int a = 0; a < d; a++) {
      w[a] = B[0][a] * nx[j][0] + B[1][a] * nx[j][1] + B[2][a] * nx[j][2];
      for (int b = 0; b < d; b++) g[a * d + b] = G[a][b];
    }
    if (tds_dense_solve(d, g, w) != 0) continue;
    for (int l = 0; l < c; l++) {
      double dot = 0;
      for (int a = 0; a < d; a++)
        for (int b = 0; b < d; b++) dot += w[a] * G[a][b] * W[b][l];
      for (int a = 0; a < d; a++) w[a] -= dot * W[a][l];
    }
    double nn = 0;
    for (int a = 0; a < d; a++)
      for (int b = 0; b < d; b++) nn += w[a] * G[a][b] * w[b];
    if (!(nn > 1e-12)) continue; /* the normal is across the motion space */
    for (int a = 0; a < d; a++) W[a][c] = w[a] / sqrt(nn);
    c++;
  }
  if (c == 0) return tds_normal_columns(vn, B, d, 1, W);
  return c;
}

int tds_special_normals(tds_ctx *ctx, const tds_surf *s, vnorm *vn) {
  const tds_mesh *m = &s->m;
  if (!s->special_normal[0])
    return tds_seterr(ctx, TDS_ERANGE, "hessian_special_normal is on but the datafile has no "
                      "HESSIAN_SPECIAL_NORMAL_VECTOR");
  for (tds_id v = 0; v < m->nv; v++) {
    if ((m->vflags[v] & TDS_DEAD) || vn[v].nt || !vn[v].nf) continue;
    double vars[TDS_NVARS];
    tds_motion_vars(s, m->x[v], m->vp[v], vars);
    for (int i = 0; i < 3; i++) {
      double c = tds_expr_eval(s->special_normal[i], s->parval, vars);
      if (!isfinite(c))
        return tds_seterr(ctx, TDS_ENUM, "HESSIAN_SPECIAL_NORMAL_VECTOR: c%d is not finite at "
                          "vertex %d", i + 1, (int)v + 1);
      vn[v].an[i] = c;
    }
  }
  return TDS_OK;
}
