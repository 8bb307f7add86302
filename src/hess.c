/* hess.c: sparse Hessian and KKT assembly (hess.h) through tds_eval's
** loop (eval.c, tds_eval_out.hess). */
#include "hess.h"

#include <stdlib.h>
#include <string.h>

#include "eval.h"
#include "motion.h"

void tds_hess_free(tds_hess *h) {
  tds_alloc a = h->alloc;
  tds_free(&a, h->vidx);
  tds_free(&a, h->vert);
  tds_free(&a, h->grad);
  tds_free(&a, h->fgrad);
  tds_free(&a, h->mult);
  tds_free(&a, h->value);
  tds_free(&a, h->target);
  tds_spmat_free(&h->H);
  tds_spmat_free(&h->A);
  memset(h, 0, sizeof *h);
}

/* Constraint gradients from fq's per-vertex entries into A (n x nq). */
static int fill_A(const tds_fixq *fq, tds_hess *h) {
  tds_sptrip t = {.nrow = h->n, .ncol = h->nq, .alloc = h->alloc};
  for (int32_t v = 0; v < fq->nv && v < h->nv; v++) {
    int32_t r = h->vidx[v];
    if (r < 0) continue;
    for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++)
      for (int i = 0; i < 3; i++)
        if (tds_sptrip_add(&t, r + i, fq->eq[e], fq->g[e][i])) {
          tds_sptrip_free(&t);
          return -1;
        }
  }
  int rc = tds_spmat_from_trip(&t, 0, &h->A);
  tds_sptrip_free(&t);
  return rc;
}

int tds_hess_assemble(tds_ctx *ctx, tds_surf *s, const tds_hess_opts *opts,
                      tds_hess *out) {
  static const tds_hess_opts lagr = {1, -1, 0};
  if (!opts) opts = &lagr;
  TDS_REQUIRE(ctx, s && out);
  tds_mesh *m = &s->m;
  memset(out, 0, sizeof *out);
  out->alloc = ctx->alloc;
  tds_fixq fq = {0};
  tds_sptrip trip = {.alloc = ctx->alloc};
  double (*grad)[3] = NULL, *qw = NULL;
  int rc = tds_fixq_build(ctx, s, &fq);
  if (rc != TDS_OK) return rc;
  out->nv = m->nv;
  out->nq = fq.nq;
  out->vidx = tds_malloc(&out->alloc, ((size_t)m->nv + 1) * sizeof *out->vidx);
  out->vert = tds_malloc(&out->alloc, ((size_t)m->nv + 1) * sizeof *out->vert);
  grad = tds_calloc(&out->alloc, (size_t)m->nv + 1, sizeof *grad);
  qw = tds_calloc(&out->alloc, (size_t)fq.nq + 1, sizeof *qw);
  out->mult = tds_calloc(&out->alloc, (size_t)fq.nq + 1, sizeof *out->mult);
  out->value = tds_calloc(&out->alloc, (size_t)fq.nq + 1, sizeof *out->value);
  out->target = tds_calloc(&out->alloc, (size_t)fq.nq + 1, sizeof *out->target);
  if (!out->vidx || !out->vert || !grad || !qw || !out->mult || !out->value ||
      !out->target)
    goto nomem;
  int32_t k = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    out->vidx[v] = tds_vertex_free(s, v) ? 3 * k : -1;
    if (out->vidx[v] >= 0) out->vert[k++] = v;
  }
  out->n = 3 * k;
  for (int32_t q = 0; q < fq.nq; q++) {
    out->mult[q] = fq.qbody[q] != TDS_NONE ? m->bpressure[fq.qbody[q]]
                                           : s->quant[fq.qquant[q]].pressure;
    if (opts->quantity >= 0) qw[q] = q == opts->quantity;
    else qw[q] = opts->lagrange ? -out->mult[q] : 0;
  }
  trip.nrow = trip.ncol = out->n;
  tds_hess_acc acc = {.vidx = out->vidx, .ew = opts->quantity >= 0 ? 0 : 1,
                      .qw = qw, .trip = &trip, .lower = opts->from_lower};
  tds_eval_out eo = {.grad = grad, .fq = fq.nq ? &fq : NULL, .hess = &acc};
  rc = tds_eval(ctx, s, &eo);
  if (rc == TDS_OK && acc.status != TDS_OK) goto nomem;
  if (rc != TDS_OK) goto fail;
  out->energy = eo.energy;
  out->grad = tds_malloc(&out->alloc, ((size_t)out->n + 1) * sizeof *out->grad);
  if (!out->grad) goto nomem;
  for (int32_t j = 0; j < k; j++)
    for (int i = 0; i < 3; i++) out->grad[3 * j + i] = grad[out->vert[j]][i];
  for (int32_t q = 0; q < fq.nq; q++) {
    out->value[q] = fq.value[q];
    out->target[q] = fq.target[q];
  }
  if (tds_spmat_from_trip(&trip, 1, &out->H) || fill_A(&fq, out)) goto nomem;
  out->fgrad = tds_malloc(&out->alloc, ((size_t)out->n + 1) * sizeof *out->fgrad);
  if (!out->fgrad) goto nomem;
  for (int32_t i = 0; i < out->n; i++) out->fgrad[i] = acc.ew * out->grad[i];
  for (int32_t q = 0; q < fq.nq; q++)
    for (int32_t e = out->A.colptr[q]; e < out->A.colptr[q + 1]; e++)
      out->fgrad[out->A.rowind[e]] += qw[q] * out->A.val[e];
  tds_sptrip_free(&trip);
  tds_fixq_free(&fq);
  tds_free(&out->alloc, grad);
  tds_free(&out->alloc, qw);
  return TDS_OK;
nomem:
  rc = tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
fail:
  tds_sptrip_free(&trip);
  tds_fixq_free(&fq);
  tds_free(&out->alloc, grad);
  tds_free(&out->alloc, qw);
  tds_hess_free(out);
  return rc;
}

int tds_hess_kkt(tds_ctx *ctx, const tds_hess *h, tds_spmat *K) {
  TDS_REQUIRE(ctx, h && K && h->n % 3 == 0);
  int32_t n = h->n;
  tds_sptrip t = {.nrow = n + h->nq, .ncol = n + h->nq, .alloc = ctx->alloc};
  for (int32_t j = 0; j < n; j++)
    for (int32_t e = h->H.colptr[j]; e < h->H.colptr[j + 1]; e++)
      if (tds_sptrip_add(&t, h->H.rowind[e], j, h->H.val[e])) goto nomem;
  for (int32_t q = 0; q < h->nq; q++)
    for (int32_t e = h->A.colptr[q]; e < h->A.colptr[q + 1]; e++)
      if (tds_sptrip_add(&t, h->A.rowind[e], n + q, h->A.val[e])) goto nomem;
  if (tds_spmat_from_trip(&t, 1, K)) goto nomem;
  tds_sptrip_free(&t);
  return TDS_OK;
nomem:
  tds_sptrip_free(&t);
  return tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
}
