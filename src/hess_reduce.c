/* hess_reduce.c: the Hessian in the vertices' motion spaces (hess.h,
** tds_hess_reduce). The motion spaces are those of motion.c: boundary
** parameters, or the tangent space of the equality level sets. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "expr.h"
#include "hess.h"
#include "motion.h"
#include "vec3.h"
#include "xattr.h"

void tds_hess_red_free(tds_hess_red *r) {
  tds_alloc a = r->alloc;
  tds_free(&a, r->start);
  tds_free(&a, r->basis);
  tds_free(&a, r->grad);
  tds_spmat_free(&r->H);
  tds_spmat_free(&r->A);
  memset(r, 0, sizeof *r);
}

int tds_hess_vertex_space(const tds_surf *s, tds_id v, const double f[3], double B[3][3],
                        double C[3][3]) {
  const tds_mesh *m = &s->m;
  double vars[TDS_NVARS], g[TDS_NDIFF], H[TDS_NDIFF][TDS_NDIFF];
  memset(B, 0, sizeof(double[3][3]));
  memset(C, 0, sizeof(double[3][3]));
  tds_motion_vars(s, m->x[v], m->vp[v], vars);
  if (m->vbdry[v] != TDS_NONE) {
    const tds_boundary *bd = &s->bdry[m->vbdry[v]];
    int np = bd->nparams;
    for (int i = 0; i < 3; i++) {
      tds_expr_eval_hess(bd->x[i], s->parval, vars, g, H);
      for (int a = 0; a < np; a++) {
        B[i][a] = g[TDS_P1 + a];
        for (int b = 0; b < np; b++) C[a][b] += f[i] * H[TDS_P1 + a][TDS_P1 + b];
      }
    }
    return np;
  }
  /* equality level sets: normals n, Hessians of their formulas (which may
  ** read the vertex's attributes, xattr.h) */
  tds_xattr_fill(s, TDS_VERTEX, v);
  double n[3][3], hs[3][3][3];
  int k = 0;
  for (int c = 0; c < TDS_MAX_CON && k < 3; c++) {
    const tds_constraint *con = &s->con[c];
    if (!(m->vcon[v] & ((tds_cmask)1 << c)) || !con->formula) continue;
    if (con->flags & (TDS_CON_NONNEG | TDS_CON_NONPOS)) continue;
    tds_expr_eval_hess(con->formula, s->parval, vars, g, H);
    for (int i = 0; i < 3; i++) {
      n[k][i] = g[i];
      for (int j = 0; j < 3; j++) hs[k][i][j] = H[i][j];
    }
    k++;
  }
  /* orthonormal basis of span(n) (rank r), then its complement */
  double q[3][3];
  int r = 0;
  for (int j = 0; j < k; j++) {
    double w[3];
    v3_copy(w, n[j]);
    for (int l = 0; l < r; l++) v3_axpy(w, -v3_dot(w, q[l]), q[l]);
    double len = v3_norm(w);
    if (len > 1e-9 * (v3_norm(n[j]) + 1e-300)) {
      for (int i = 0; i < 3; i++) q[r][i] = w[i] / len;
      r++;
    }
  }
  int d = 0;
  for (int e = 0; e < 3 && r + d < 3; e++) {
    double w[3] = {0, 0, 0};
    w[e] = 1;
    for (int l = 0; l < r + d; l++) v3_axpy(w, -v3_dot(w, q[l]), q[l]);
    double len = v3_norm(w);
    if (len > 0.5) { /* one of the three axes always keeps >= 1/sqrt(3) */
      for (int i = 0; i < 3; i++) q[r + d][i] = B[i][d] = w[i] / len;
      d++;
    }
  }
  if (k == 0 || d == 0) return d;
  /* mu: least squares N mu = f (the normal part of f) */
  double G[9], mu[3];
  for (int a = 0; a < k; a++) {
    mu[a] = v3_dot(n[a], f);
    for (int b = 0; b < k; b++) G[a * k + b] = v3_dot(n[a], n[b]);
  }
  if (tds_dense_solve(k, G, mu) != 0) return d; /* dependent normals: no curvature term */
  for (int j = 0; j < k; j++)
    for (int a = 0; a < d; a++)
      for (int b = 0; b < d; b++) {
        double t = 0;
        for (int i = 0; i < 3; i++)
          for (int l = 0; l < 3; l++) t += B[i][a] * hs[j][i][l] * B[l][b];
        C[a][b] -= mu[j] * t;
      }
  return d;
}

int tds_hess_reduce(tds_ctx *ctx, const tds_surf *s, const tds_hess *h, tds_hess_red *out) {
  TDS_REQUIRE(ctx, s && h && out && h->n % 3 == 0);
  memset(out, 0, sizeof *out);
  out->alloc = ctx->alloc;
  int32_t nvm = h->n / 3;
  double (*C)[3][3] = tds_malloc(&out->alloc, ((size_t)nvm + 1) * sizeof *C);
  tds_sptrip t = {.alloc = ctx->alloc}, ta = {.alloc = ctx->alloc};
  out->nvm = nvm;
  out->start = tds_malloc(&out->alloc, ((size_t)nvm + 1) * sizeof *out->start);
  out->basis = tds_malloc(&out->alloc, ((size_t)nvm + 1) * sizeof *out->basis);
  if (!C || !out->start || !out->basis) goto nomem;
  out->start[0] = 0;
  for (int32_t k = 0; k < nvm; k++) {
    int d = tds_hess_vertex_space(s, h->vert[k], h->fgrad + 3 * k, out->basis[k], C[k]);
    out->start[k + 1] = out->start[k] + d;
  }
  int32_t m = out->m = out->start[nvm];
  out->grad = tds_calloc(&out->alloc, (size_t)m + 1, sizeof *out->grad);
  if (!out->grad) goto nomem;
  for (int32_t k = 0; k < nvm; k++)
    for (int32_t a = 0; a < out->start[k + 1] - out->start[k]; a++)
      for (int i = 0; i < 3; i++)
        out->grad[out->start[k] + a] += out->basis[k][i][a] * h->fgrad[3 * k + i];
  /* B^T H B: every entry of the full H (both halves of an off-diagonal
  ** one), kept where the reduced row <= column */
  t.nrow = t.ncol = m;
  for (int32_t j = 0; j < h->n; j++)
    for (int32_t e = h->H.colptr[j]; e < h->H.colptr[j + 1]; e++) {
      int32_t i = h->H.rowind[e];
      for (int half = 0; half < (i == j ? 1 : 2); half++) {
        int32_t r = half ? j : i, c = half ? i : j;
        int32_t kr = r / 3, kc = c / 3;
        for (int32_t a = 0; a < out->start[kr + 1] - out->start[kr]; a++)
          for (int32_t b = 0; b < out->start[kc + 1] - out->start[kc]; b++) {
            int32_t ra = out->start[kr] + a, cb = out->start[kc] + b;
            if (ra > cb) continue;
            double v = out->basis[kr][r % 3][a] * h->H.val[e] * out->basis[kc][c % 3][b];
            if (v != 0 && tds_sptrip_add(&t, ra, cb, v)) goto nomem;
          }
      }
    }
  for (int32_t k = 0; k < nvm; k++)
    for (int32_t a = 0; a < out->start[k + 1] - out->start[k]; a++)
      for (int32_t b = a; b < out->start[k + 1] - out->start[k]; b++)
        if (tds_sptrip_add(&t, out->start[k] + a, out->start[k] + b, C[k][a][b])) goto nomem;
  if (tds_spmat_from_trip(&t, 1, &out->H)) goto nomem;
  ta.nrow = m;
  ta.ncol = h->nq;
  for (int32_t q = 0; q < h->nq; q++)
    for (int32_t e = h->A.colptr[q]; e < h->A.colptr[q + 1]; e++) {
      int32_t i = h->A.rowind[e], k = i / 3;
      for (int32_t a = 0; a < out->start[k + 1] - out->start[k]; a++)
        if (tds_sptrip_add(&ta, out->start[k] + a, q, out->basis[k][i % 3][a] * h->A.val[e]))
          goto nomem;
    }
  if (tds_spmat_from_trip(&ta, 0, &out->A)) goto nomem;
  tds_free(&out->alloc, C);
  tds_sptrip_free(&t);
  tds_sptrip_free(&ta);
  return TDS_OK;
nomem:
  tds_free(&out->alloc, C);
  tds_sptrip_free(&t);
  tds_sptrip_free(&ta);
  tds_hess_red_free(out);
  return tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
}
