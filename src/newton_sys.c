/* newton_sys.c: the Newton system in the vertices' normal spaces
** (newton.h, newton_int.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gather.h"
#include "iterate.h"
#include "motion.h"
#include "newton_int.h"
#include "vec3.h"

void tds_nsys_free(tds_nsys *n) {
  tds_free(&n->alloc, n->vert);
  tds_free(&n->alloc, n->mv);
  tds_free(&n->alloc, n->dx);
  tds_free(&n->alloc, n->grad);
  tds_free(&n->alloc, n->value);
  tds_free(&n->alloc, n->target);
  tds_free(&n->alloc, n->mult);
  tds_spmat_free(&n->H);
  tds_spmat_free(&n->A);
  tds_spmat_free(&n->M);
  memset(n, 0, sizeof *n);
}

/* The multipliers the Hessian of the Lagrangian uses are the pressures
** stored on the surface, as in Evolver (those of the last `g` or Newton
** step: a Newton iteration then converges to what Evolver's does); when
** none was ever computed (all zero with constraints present), they are
** computed at these positions. TDS_OK with *need set, or the status of
** a failure (out of memory: not a reason to recompute them). */
static int need_pressures(tds_ctx *ctx, tds_surf *s, int *needp) {
  tds_fixq fq = {0};
  int rc = tds_fixq_build(ctx, s, &fq);
  if (rc != TDS_OK) return rc;
  int need = 0;
  for (int32_t q = 0; q < fq.nq; q++) {
    double mult = fq.qbody[q] != TDS_NONE ? s->m.bpressure[fq.qbody[q]]
                                          : s->quant[fq.qquant[q]].pressure;
    if (mult != 0) need = -1;
    else if (!need) need = 1;
  }
  tds_fixq_free(&fq);
  *needp = need == 1;
  return TDS_OK;
}

static int nomem(tds_ctx *ctx) { return tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory"); }

/* The string model's metric: each edge's L2 product of the linear
** interpolation of its ends' motions along it, weighted by its length
** times its tension (as Evolver's; its hessian_normal_perp changes
** nothing in the string model, measured). */
static int metric_edges(const tds_mesh *m, double mix, const int32_t *vk,
                        const int32_t *ustart, const tds_nsys *out, tds_sptrip *t) {
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    const tds_id *ev = m->ev[e];
    tds_corners C; /* unwrapped (torus) */
    tds_gather_edge(m, TDS_OREF(e, 0), &C);
    double d[3];
    v3_sub(d, C.x[1], C.x[0]);
    double len = v3_norm(d) * m->eten[e];
    for (int x = 0; x < 2; x++)
      for (int y = 0; y < 2; y++) {
        int32_t kx = vk[ev[x]], ky = vk[ev[y]];
        if (kx < 0 || ky < 0) continue;
        double wgt = len * (x == y ? mix / 3 + (1 - mix) / 2 : mix / 6);
        for (int32_t p = ustart[kx]; p < ustart[kx + 1]; p++)
          for (int32_t q = ustart[ky]; q < ustart[ky + 1]; q++) {
            if (p > q || (x != y && p == q)) continue;
            double v = wgt * v3_dot(out->dx[p], out->dx[q]);
            if (v != 0 && tds_sptrip_add(t, p, q, v)) return TDS_ENOMEM;
          }
      }
  }
  return TDS_OK;
}

int tds_nsys_build_metric(tds_ctx *ctx, const tds_surf *s, double mix, int perp,
                          const int32_t *vk, const int32_t *ustart, tds_nsys *out) {
  const tds_mesh *m = &s->m;
  int32_t mm = out->m;
  tds_sptrip t = {.nrow = mm, .ncol = mm, .alloc = ctx->alloc};
  if (s->str && metric_edges(m, mix, vk, ustart, out, &t) != TDS_OK) goto nomem;
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    const tds_id *fv = m->fv[f];
    tds_corners C; /* unwrapped (torus) */
    tds_gather_facet(m, f, &C);
    double a[3], b[3], c[3];
    v3_sub(a, C.x[1], C.x[0]);
    v3_sub(b, C.x[2], C.x[0]);
    v3_cross(c, a, b);
    double cl = v3_norm(c);
    double area = 0.5 * cl * m->ften[f]; /* weighted as Evolver's */
    if (perp && cl > 0) v3_scale(c, 1 / cl); /* the unit normal */
    for (int x = 0; x < 3; x++)
      for (int y = 0; y < 3; y++) {
        int32_t kx = vk[fv[x]], ky = vk[fv[y]];
        if (kx < 0 || ky < 0) continue;
        double wgt = area * (x == y ? mix / 6 + (1 - mix) / 3 : mix / 12);
        for (int32_t p = ustart[kx]; p < ustart[kx + 1]; p++)
          for (int32_t q = ustart[ky]; q < ustart[ky + 1]; q++) {
            if (p > q || (x != y && p == q)) continue;
            double v = perp ? wgt * v3_dot(out->dx[p], c) * v3_dot(out->dx[q], c)
                            : wgt * v3_dot(out->dx[p], out->dx[q]);
            if (v != 0 && tds_sptrip_add(&t, p, q, v)) goto nomem;
          }
      }
  }
  if (tds_spmat_from_trip(&t, 1, &out->M)) goto nomem;
  tds_sptrip_free(&t);
  return TDS_OK;
nomem:
  tds_sptrip_free(&t);
  return nomem(ctx);
}

int tds_nsys_build(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_nsys *out) {
  memset(out, 0, sizeof *out);
  out->alloc = ctx->alloc;
  const tds_mesh *m = &s->m;
  tds_hess h = {0};
  tds_hess_red r = {0};
  tds_sptrip t = {.alloc = ctx->alloc};
  vnorm *vn = NULL;
  int32_t *rk = NULL, *ustart = NULL;
  double (*W)[3][3] = NULL;
  int need = 0, rc = need_pressures(ctx, s, &need);
  if (rc == TDS_OK && need) rc = tds_pressures(ctx, s);
  if (rc == TDS_OK && !o->diff && !o->general) { /* the fast way (newton_asm.c) */
    int miss = 0;
    rc = tds_nsys_assemble(ctx, s, o, out, &miss);
    if (rc != TDS_OK || !miss) return rc;
    out->alloc = ctx->alloc;
  }
  if (rc == TDS_OK) rc = tds_hess_assemble(ctx, s, NULL, &h);
  if (rc == TDS_OK && o->diff) rc = tds_hess_diff(ctx, s, &h);
  if (rc == TDS_OK) rc = tds_hess_reduce(ctx, s, &h, &r);
  if (rc == TDS_OK) { /* the xyz matrices are not needed any more: less peak memory */
    tds_spmat_free(&h.H);
    tds_spmat_free(&h.A);
  }
  if (rc != TDS_OK) goto fail;
  int32_t nvm = r.nvm;
  vn = tds_malloc(&ctx->alloc, ((size_t)m->nv + 1) * sizeof *vn);
  W = tds_malloc(&ctx->alloc, ((size_t)nvm + 1) * sizeof *W);
  ustart = tds_malloc(&ctx->alloc, ((size_t)nvm + 1) * sizeof *ustart);
  rk = tds_malloc(&ctx->alloc, ((size_t)r.m + 1) * sizeof *rk);
  if (!vn || !W || !ustart || !rk) goto nomem;
  if ((rc = tds_hess_normals(ctx, s, o, vn)) != TDS_OK) goto fail;
  ustart[0] = 0;
  for (int32_t k = 0; k < nvm; k++) {
    int d = r.start[k + 1] - r.start[k];
    for (int32_t a = r.start[k]; a < r.start[k + 1]; a++) rk[a] = k;
    int c = d == 0 ? 0 : tds_normal_columns(&vn[h.vert[k]], r.basis[k], d, !o->normal, W[k]);
    ustart[k + 1] = ustart[k] + c;
  }
  int32_t mm = out->m = ustart[nvm];
  out->nq = h.nq;
  out->energy = h.energy;
  out->vert = tds_malloc(&ctx->alloc, ((size_t)mm + 1) * sizeof *out->vert);
  out->mv = tds_calloc(&ctx->alloc, (size_t)mm + 1, sizeof *out->mv);
  out->dx = tds_calloc(&ctx->alloc, (size_t)mm + 1, sizeof *out->dx);
  out->grad = tds_calloc(&ctx->alloc, (size_t)mm + 1, sizeof *out->grad);
  out->value = tds_calloc(&ctx->alloc, (size_t)h.nq + 1, sizeof *out->value);
  out->target = tds_calloc(&ctx->alloc, (size_t)h.nq + 1, sizeof *out->target);
  if (!out->vert || !out->mv || !out->dx || !out->grad || !out->value || !out->target)
    goto nomem;
  out->mult = tds_calloc(&ctx->alloc, (size_t)h.nq + 1, sizeof *out->mult);
  if (!out->mult) goto nomem;
  for (int32_t q = 0; q < h.nq; q++) {
    out->value[q] = h.value[q];
    out->target[q] = h.target[q];
    out->mult[q] = h.mult[q];
  }
  for (int32_t k = 0; k < nvm; k++) {
    int d = r.start[k + 1] - r.start[k];
    tds_id v = h.vert[k];
    int bdry = m->vbdry[v] != TDS_NONE;
    for (int32_t j = ustart[k]; j < ustart[k + 1]; j++) {
      int c = j - ustart[k];
      out->vert[j] = v;
      for (int a = 0; a < d; a++) {
        double wa = W[k][a][c];
        out->grad[j] += wa * r.grad[r.start[k] + a];
        for (int i = 0; i < 3; i++) out->dx[j][i] += r.basis[k][i][a] * wa;
        if (bdry) out->mv[j][a] = wa;
      }
      if (!bdry) v3_copy(out->mv[j], out->dx[j]);
    }
  }
  /* H = W^T Hr W over both halves of each stored entry */
  t.nrow = t.ncol = mm;
  for (int32_t j = 0; j < r.m; j++)
    for (int32_t e = r.H.colptr[j]; e < r.H.colptr[j + 1]; e++) {
      int32_t i = r.H.rowind[e];
      for (int half = 0; half < (i == j ? 1 : 2); half++) {
        int32_t ri = half ? j : i, ci = half ? i : j;
        int32_t kr = rk[ri], kc = rk[ci];
        int ar = ri - r.start[kr], ac = ci - r.start[kc];
        for (int32_t p = ustart[kr]; p < ustart[kr + 1]; p++)
          for (int32_t q = ustart[kc]; q < ustart[kc + 1]; q++) {
            if (p > q) continue;
            double v = W[kr][ar][p - ustart[kr]] * r.H.val[e] * W[kc][ac][q - ustart[kc]];
            if (v != 0 && tds_sptrip_add(&t, p, q, v)) goto nomem;
          }
      }
    }
  for (int32_t j = 0; j < mm; j++) /* every diagonal entry exists */
    if (tds_sptrip_add(&t, j, j, 0)) goto nomem;
  if (tds_spmat_from_trip(&t, 1, &out->H)) goto nomem;
  tds_spmat_free(&r.H);
  tds_sptrip_free(&t);
  t = (tds_sptrip){.nrow = mm, .ncol = h.nq, .alloc = ctx->alloc};
  for (int32_t q = 0; q < h.nq; q++)
    for (int32_t e = r.A.colptr[q]; e < r.A.colptr[q + 1]; e++) {
      int32_t i = r.A.rowind[e], k = rk[i];
      for (int32_t p = ustart[k]; p < ustart[k + 1]; p++) {
        double v = W[k][i - r.start[k]][p - ustart[k]] * r.A.val[e];
        if (v != 0 && tds_sptrip_add(&t, p, q, v)) goto nomem;
      }
    }
  if (tds_spmat_from_trip(&t, 0, &out->A)) goto nomem;
  tds_sptrip_free(&t);
  if (o->linear_metric) {
    int32_t *vk = tds_malloc(&ctx->alloc, ((size_t)m->nv + 1) * sizeof *vk);
    if (!vk) goto nomem;
    for (tds_id v = 0; v < m->nv; v++) vk[v] = h.vidx[v] < 0 ? -1 : h.vidx[v] / 3;
    rc = tds_nsys_build_metric(ctx, s, o->metric_mix, o->normal_perp, vk, ustart, out);
    tds_free(&ctx->alloc, vk);
    if (rc != TDS_OK) goto fail;
  }
  tds_free(&ctx->alloc, vn);
  tds_free(&ctx->alloc, W);
  tds_free(&ctx->alloc, ustart);
  tds_free(&ctx->alloc, rk);
  tds_hess_red_free(&r);
  tds_hess_free(&h);
  return TDS_OK;
nomem:
  rc = nomem(ctx);
fail:
  tds_sptrip_free(&t);
  tds_free(&ctx->alloc, vn);
  tds_free(&ctx->alloc, W);
  tds_free(&ctx->alloc, ustart);
  tds_free(&ctx->alloc, rk);
  tds_hess_red_free(&r);
  tds_hess_free(&h);
  tds_nsys_free(out);
  return rc;
}

/* The bordered matrix copied column by column from H (whose diagonal is
** all stored) and A: no triplets, when the metric is the identity. */
static int kkt_direct(tds_ctx *ctx, const tds_nsys *n, double c, tds_spmat *K) {
  int32_t mm = n->m, N = mm + n->nq;
  int64_t nnz = (int64_t)n->H.colptr[mm] + n->A.colptr[n->nq];
  memset(K, 0, sizeof *K);
  K->alloc = ctx->alloc;
  K->nrow = K->ncol = N;
  K->upper = 1;
  K->colptr = tds_malloc(&ctx->alloc, ((size_t)N + 1) * sizeof *K->colptr);
  K->rowind = tds_malloc(&ctx->alloc, ((size_t)nnz + 1) * sizeof *K->rowind);
  K->val = tds_malloc(&ctx->alloc, ((size_t)nnz + 1) * sizeof *K->val);
  if (!K->colptr || !K->rowind || !K->val) {
    tds_spmat_free(K);
    return nomem(ctx);
  }
  int64_t k = 0;
  K->colptr[0] = 0;
  for (int32_t j = 0; j < mm; j++) {
    for (int32_t e = n->H.colptr[j]; e < n->H.colptr[j + 1]; e++) {
      K->rowind[k] = n->H.rowind[e];
      K->val[k++] = n->H.val[e] - (n->H.rowind[e] == j ? c : 0);
    }
    K->colptr[j + 1] = (int32_t)k;
  }
  for (int32_t q = 0; q < n->nq; q++) {
    for (int32_t e = n->A.colptr[q]; e < n->A.colptr[q + 1]; e++) {
      K->rowind[k] = n->A.rowind[e];
      K->val[k++] = n->A.val[e];
    }
    K->colptr[mm + q + 1] = (int32_t)k;
  }
  return TDS_OK;
}

int tds_nsys_kkt(tds_ctx *ctx, const tds_nsys *n, double c, tds_spmat *K) {
  int32_t mm = n->m;
  if (!n->M.nrow) return kkt_direct(ctx, n, c, K);
  tds_sptrip t = {.nrow = mm + n->nq, .ncol = mm + n->nq, .alloc = ctx->alloc};
  for (int32_t j = 0; j < mm; j++)
    for (int32_t e = n->H.colptr[j]; e < n->H.colptr[j + 1]; e++)
      if (tds_sptrip_add(&t, n->H.rowind[e], j, n->H.val[e])) goto nomem;
  if (c != 0) {
    if (n->M.nrow) {
      for (int32_t j = 0; j < mm; j++)
        for (int32_t e = n->M.colptr[j]; e < n->M.colptr[j + 1]; e++)
          if (tds_sptrip_add(&t, n->M.rowind[e], j, -c * n->M.val[e])) goto nomem;
    } else {
      for (int32_t j = 0; j < mm; j++)
        if (tds_sptrip_add(&t, j, j, -c)) goto nomem;
    }
  }
  for (int32_t q = 0; q < n->nq; q++)
    for (int32_t e = n->A.colptr[q]; e < n->A.colptr[q + 1]; e++)
      if (tds_sptrip_add(&t, n->A.rowind[e], mm + q, n->A.val[e])) goto nomem;
  if (tds_spmat_from_trip(&t, 1, K)) goto nomem;
  tds_sptrip_free(&t);
  return TDS_OK;
nomem:
  tds_sptrip_free(&t);
  return nomem(ctx);
}

void tds_nsys_metric(const tds_nsys *n, const double *x, double *y) {
  if (n->M.nrow) tds_spmat_mulv(&n->M, x, y);
  else memcpy(y, x, (size_t)n->m * sizeof *y);
}
