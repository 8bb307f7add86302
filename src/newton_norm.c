/* newton_norm.c: the vertices' normal spaces of hessian_normal
** (newton.h, newton_int.h). */
#include <math.h>
#include <string.h>

#include "expr.h"
#include "fixq.h"
#include "gather.h"
#include "motion.h"
#include "newton_int.h"
#include "torus.h"
#include "vec3.h"

/* Area vector (length = area) of live facet f, gathered (wraps applied:
** gather.h). */
static void facet_vec(const tds_mesh *m, tds_id f, double c[3]) {
  tds_corners C;
  tds_gather_facet(m, f, &C);
  double a[3], b[3];
  v3_sub(a, C.x[1], C.x[0]);
  v3_sub(b, C.x[2], C.x[0]);
  v3_cross(c, a, b);
  v3_scale(c, 0.5);
}

const double *tds_norm_seen_from(const tds_mesh *m, tds_id f, tds_id e, int k,
                                 const double c[3], double out[3]) {
  if (!k || !tds_mesh_rotates(m)) return c;
  int32_t w = f != TDS_NONE ? tds_torus_corner_wrap(m, f, k) : m->ewrap[e];
  if (!w) return c;
  double R[3][3], t[3];
  tds_sym_affine(m->sym, m->symp, (const double(*)[3])m->period, w, R, t);
  for (int i = 0; i < 3; i++) out[i] = R[0][i] * c[0] + R[1][i] * c[1] + R[2][i] * c[2];
  return out;
}

void tds_evolver_sum(const tds_mesh *m, tds_fkey *a, int32_t n, double S[3]) {
  for (int32_t i = 1; i < n; i++) { /* a few facets: insertion sort */
    tds_fkey x = a[i];
    int32_t j = i;
    while (j > 0 && (a[j - 1].key > x.key || (a[j - 1].key == x.key && a[j - 1].f > x.f))) {
      a[j] = a[j - 1];
      j--;
    }
    a[j] = x;
  }
  /* the running sum: each facet's area vector added with the sign that
  ** agrees with the sum so far */
  S[0] = S[1] = S[2] = 0;
  for (int32_t i = 0; i < n; i++) {
    double c0[3], ck[3];
    facet_vec(m, a[i].f, c0);
    const double *c = tds_norm_seen_from(m, a[i].f, TDS_NONE, a[i].k, c0, ck);
    v3_axpy(S, v3_dot(S, c) < 0 ? -1 : 1, c);
  }
}

/* TDS_OK or TDS_ENOMEM (then vn is incomplete: an answer that depends on
** memory would make a command's result depend on it). */
int tds_vertex_normals(const tds_alloc *al, const tds_mesh *m, vnorm *vn) {
  memset(vn, 0, (size_t)m->nv * sizeof *vn);
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    double c[3], ck[3];
    facet_vec(m, f, c);
    for (int k = 0; k < 3; k++) {
      vnorm *w = &vn[m->fv[f][k]];
      v3_add(w->an, w->an, tds_norm_seen_from(m, f, TDS_NONE, k, c, ck));
      w->nf++;
    }
  }
  /* Where every facet's normal is within 30 degrees of the plain sum's,
  ** no facet disagrees with a partial sum (any two are within 60
  ** degrees), so the plain sum is Evolver's running sum below; elsewhere
  ** ("bad" vertices) the running sum in Evolver's order. */
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
  int32_t nbad = 0, nfk = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    double c[3], ck[3];
    facet_vec(m, f, c);
    double lim = 0.8660254037844386 * v3_norm(c); /* cos 30 degrees */
    for (int k = 0; k < 3; k++) {
      tds_id v = m->fv[f][k];
      if (!bad[v] && !(v3_dot(tds_norm_seen_from(m, f, TDS_NONE, k, c, ck), ref[v]) >= lim)) bad[v] = 1;
    }
  }
  tds_free(al, ref);
  for (tds_id v = 0; v < m->nv; v++)
    if (bad[v] && vn[v].nf) {
      nbad++;
      nfk += vn[v].nf;
    }
  if (nbad) {
    /* Evolver's order at a vertex (tds_star_key: each edge read is
    ** inserted right after the first in the vertex's edge list) */
    int32_t *emin = tds_malloc(al, ((size_t)m->nv + 1) * sizeof *emin);
    int32_t *at = tds_malloc(al, ((size_t)m->nv + 2) * sizeof *at);
    tds_fkey *fk = tds_malloc(al, ((size_t)nfk + 1) * sizeof *fk);
    if (!emin || !at || !fk) {
      tds_free(al, emin);
      tds_free(al, at);
      tds_free(al, fk);
      tds_free(al, bad);
      return TDS_ENOMEM;
    }
    for (tds_id v = 0; v < m->nv; v++) emin[v] = INT32_MAX;
    for (tds_id e = 0; e < m->ne; e++) {
      if (m->eflags[e] & TDS_DEAD) continue;
      for (int k = 0; k < 2; k++)
        if (e < emin[m->ev[e][k]]) emin[m->ev[e][k]] = e;
    }
    at[0] = 0;
    for (tds_id v = 0; v < m->nv; v++) at[v + 1] = at[v] + (bad[v] ? vn[v].nf : 0);
    for (tds_id f = 0; f < m->nf; f++) {
      if (m->fflags[f] & TDS_DEAD) continue;
      for (int k = 0; k < 3; k++) {
        tds_id v = m->fv[f][k];
        if (!bad[v]) continue;
        tds_fkey x = {tds_star_key(m, f, k, emin[v]), f, k};
        fk[at[v]++] = x;
      }
    }
    for (tds_id v = m->nv; v > 0; v--) at[v] = at[v - 1]; /* back to starts */
    at[0] = 0;
    for (tds_id v = 0; v < m->nv; v++) {
      if (!bad[v] || !vn[v].nf) continue;
      tds_evolver_sum(m, fk + at[v], at[v + 1] - at[v], vn[v].an);
    }
    tds_free(al, emin);
    tds_free(al, at);
    tds_free(al, fk);
  }
  tds_free(al, bad);
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    if (tds_edge_valence(m, e) < 3) continue;
    double d0[3], dk[3];
    tds_corners C;
    tds_gather_edge(m, TDS_OREF(e, 0), &C); /* wraps applied */
    v3_sub(d0, C.x[1], C.x[0]);
    double len = v3_norm(d0);
    if (!(len > 0)) continue;
    v3_scale(d0, 1 / len);
    for (int k = 0; k < 2; k++) {
      const double *d = tds_norm_seen_from(m, TDS_NONE, e, k, d0, dk);
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

void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info);

int tds_lead_eig(const double P[6], const double ref[3], double e[3]) {
  double a[9] = {P[0], P[1], P[2], P[1], P[3], P[4], P[2], P[4], P[5]};
  double w[3], work[16];
  int n = 3, lwork = 16, info = 0;
  dsyev_("V", "U", &n, a, &n, w, work, &lwork, &info);
  if (info != 0 || !(w[2] > 0)) return 0;
  double sg = v3_dot(a + 6, ref) < 0 ? -1 : 1; /* a + 6: the largest's vector */
  for (int i = 0; i < 3; i++) e[i] = sg * a[6 + i];
  return 1;
}

void tds_unit_nnt(const double c[3], double P[6]) {
  double l2 = v3_dot(c, c);
  if (!(l2 > 0)) return;
  P[0] += c[0] * c[0] / l2;
  P[1] += c[0] * c[1] / l2;
  P[2] += c[0] * c[2] / l2;
  P[3] += c[1] * c[1] / l2;
  P[4] += c[1] * c[2] / l2;
  P[5] += c[2] * c[2] / l2;
}

int tds_normals_one(const tds_alloc *al, const tds_mesh *m, vnorm *vn) {
  double (*P)[6] = tds_calloc(al, (size_t)m->nv + 1, sizeof *P); /* upper xx xy xz yy yz zz */
  if (!P) return TDS_ENOMEM;
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    double c[3];
    facet_vec(m, f, c);
    for (int k = 0; k < 3; k++) tds_unit_nnt(c, P[m->fv[f][k]]);
  }
  for (tds_id v = 0; v < m->nv; v++) {
    if ((m->vflags[v] & TDS_DEAD) || !vn[v].nf) continue;
    double e[3];
    if (!tds_lead_eig(P[v], vn[v].an, e)) continue; /* no facet with an area */
    v3_copy(vn[v].an, e);
    vn[v].nt = 0;
    vn[v].bent = 0;
  }
  tds_free(al, P);
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
  if (!full && !vn->full && vn->nf > 0 && vn->nt <= 2 && !vn->bent) {
    if (vn->nt == 0) {
      double a[3];
      v3_copy(a, vn->an);
      if (vn->flat) a[2] = 0;
      double len = v3_norm(a);
      if (len > 0) {
        for (int i = 0; i < 3; i++) nx[0][i] = a[i] / len;
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
  int whole = cn == 0;
  if (whole && vn->flat) { /* the xy plane's part of the motion space */
    memset(nx, 0, sizeof nx);
    nx[0][0] = nx[1][1] = 1;
    cn = 2;
  } else if (whole) {
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
  if (c == 0 && !whole) return tds_normal_columns(vn, B, d, 1, W);
  return c;
}

int tds_special_normals(tds_ctx *ctx, const tds_surf *s, vnorm *vn) {
  const tds_mesh *m = &s->m;
  if (!s->special_normal[0])
    return tds_seterr(ctx, TDS_ERANGE, "hessian_special_normal is on but the datafile has no "
                      "HESSIAN_SPECIAL_NORMAL_VECTOR");
  for (tds_id v = 0; v < m->nv; v++) {
    if ((m->vflags[v] & TDS_DEAD) || vn[v].nt || !vn[v].nf) continue;
    int rc = tds_special_at(ctx, s, v, vn[v].an);
    if (rc != TDS_OK) return rc;
  }
  return TDS_OK;
}

int tds_special_at(tds_ctx *ctx, const tds_surf *s, tds_id v, double an[3]) {
  const tds_mesh *m = &s->m;
  double vars[TDS_NVARS];
  tds_motion_vars(s, m->x[v], m->vp[v], vars);
  for (int i = 0; i < 3; i++) {
    if (!s->special_normal[i]) { /* C3 in 2-D space */
      an[i] = 0;
      continue;
    }
    double c = tds_expr_eval(s->special_normal[i], s->parval, vars);
    if (!isfinite(c))
      return tds_seterr(ctx, TDS_ENUM, "HESSIAN_SPECIAL_NORMAL_VECTOR: c%d is not finite at "
                        "vertex %d", i + 1, (int)v + 1);
    an[i] = c;
  }
  return TDS_OK;
}
