/* newton_diff.c: hessian_diff, the Hessian of the Lagrangian by central
** differences of its gradient (Evolver's hessian_diff, for checking the
** assembled one): every stored entry of h->H is replaced by the
** symmetrised difference quotient, keeping the assembly's pattern (a
** term the assembly left out shows as a changed value, not as a new
** entry). Step: 1e-6 times the mean edge length, where the difference of
** an exact gradient has truncation ~h^2 and rounding ~1e-16/h, both near
** 1e-10 relative (the unit tests measured 1e-9 at worst). One gradient
** evaluation per coordinate and sign: for checking small surfaces. */
#include <math.h>
#include <string.h>

#include "eval.h"
#include "gather.h"
#include "newton_int.h"
#include "vec3.h"

/* The Lagrangian's gradient grad E - sum_q mult_q grad Q_q per slot. */
static int lgrad(tds_ctx *ctx, tds_surf *s, tds_fixq *fq, const double *mult,
                 double (*g)[3]) {
  tds_eval_out out = {.grad = g, .fq = fq->nq ? fq : NULL};
  int rc = tds_eval(ctx, s, &out);
  if (rc != TDS_OK) return rc;
  for (int32_t v = 0; v < fq->nv && v < s->m.nv; v++)
    for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++)
      v3_axpy(g[v], -mult[fq->eq[e]], fq->g[e]);
  return TDS_OK;
}

int tds_hess_diff(tds_ctx *ctx, tds_surf *s, tds_hess *h) {
  tds_mesh *m = &s->m;
  double len = 0;
  int ne = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    double d[3];
    tds_edge_vec(m, TDS_OREF(e, 0), d); /* unwrapped (torus) */
    len += v3_norm(d);
    ne++;
  }
  double step = 1e-6 * (ne ? len / ne : 1);
  tds_fixq fq = {0};
  int rc = tds_fixq_build(ctx, s, &fq);
  if (rc != TDS_OK) return rc;
  int32_t n = h->n;
  double (*gp)[3] = tds_calloc(&ctx->alloc, (size_t)m->nv + 1, sizeof *gp);
  double (*gm)[3] = tds_calloc(&ctx->alloc, (size_t)m->nv + 1, sizeof *gm);
  double *val = tds_calloc(&ctx->alloc, (size_t)h->H.colptr[n] + 1, sizeof *val);
  /* where row j sits in later columns: the transpose of the pattern */
  int32_t *tptr = tds_calloc(&ctx->alloc, (size_t)n + 2, sizeof *tptr);
  int32_t *tent = tds_calloc(&ctx->alloc, (size_t)h->H.colptr[n] + 1, sizeof *tent);
  int32_t *tfill = tds_calloc(&ctx->alloc, (size_t)n + 1, sizeof *tfill);
  if (!gp || !gm || !val || !tptr || !tent || !tfill) {
    rc = tds_seterr(ctx, TDS_ENOMEM, "hessian_diff: out of memory");
    goto done;
  }
  for (int32_t j = 0; j < n; j++)
    for (int32_t e = h->H.colptr[j]; e < h->H.colptr[j + 1]; e++) tptr[h->H.rowind[e] + 1]++;
  for (int32_t i = 0; i < n; i++) tptr[i + 1] += tptr[i];
  for (int32_t j = 0; j < n; j++)
    for (int32_t e = h->H.colptr[j]; e < h->H.colptr[j + 1]; e++) {
      int32_t i = h->H.rowind[e];
      tent[tptr[i] + tfill[i]++] = e;
    }
  for (int32_t j = 0; j < n && rc == TDS_OK; j++) {
    tds_id v = h->vert[j / 3];
    int c = j % 3;
    double x0 = m->x[v][c];
    m->x[v][c] = x0 + step;
    m->coord_gen++;
    rc = lgrad(ctx, s, &fq, h->mult, gp);
    m->x[v][c] = x0 - step;
    m->coord_gen++;
    if (rc == TDS_OK) rc = lgrad(ctx, s, &fq, h->mult, gm);
    m->x[v][c] = x0;
    m->coord_gen++;
    if (rc != TDS_OK) break;
    /* column j of the difference: half to entries (i, j), i <= j, and
    ** half to entries (j, i) stored in later columns i */
    for (int32_t e = h->H.colptr[j]; e < h->H.colptr[j + 1]; e++) {
      int32_t i = h->H.rowind[e];
      tds_id vi = h->vert[i / 3];
      val[e] += (i == j ? 1.0 : 0.5) * (gp[vi][i % 3] - gm[vi][i % 3]) / (2 * step);
    }
    for (int32_t t = tptr[j]; t < tptr[j + 1]; t++) {
      int32_t e = tent[t], col = 0;
      /* the column of entry e: search colptr (binary) */
      int32_t lo = 0, hi = n;
      while (hi - lo > 1) {
        int32_t mid = (lo + hi) / 2;
        if (h->H.colptr[mid] <= e) lo = mid;
        else hi = mid;
      }
      col = lo;
      if (col == j) continue; /* the diagonal block counted above */
      tds_id vc = h->vert[col / 3];
      val[e] += 0.5 * (gp[vc][col % 3] - gm[vc][col % 3]) / (2 * step);
    }
  }
  if (rc == TDS_OK) {
    /* the gradient at the unperturbed positions again (caches) */
    rc = lgrad(ctx, s, &fq, h->mult, gp);
    memcpy(h->H.val, val, (size_t)h->H.colptr[n] * sizeof *val);
  }
done:
  tds_free(&ctx->alloc, gp);
  tds_free(&ctx->alloc, gm);
  tds_free(&ctx->alloc, val);
  tds_free(&ctx->alloc, tptr);
  tds_free(&ctx->alloc, tent);
  tds_free(&ctx->alloc, tfill);
  tds_fixq_free(&fq);
  return rc;
}
