/* fixq.c: Lagrange-multiplier constraints (body volumes, fixed quantities). */
#include "fixq.h"

#include "spchol.h"
#include "sparse.h"
#include "string_model.h"
#include "torus.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Conjugate gradient iterations a sparse solve may take with the factors
** of an earlier Gram matrix before it factors the new one: one iteration
** (a solve with the factors) costs about a twentieth of a factorisation
** on a 10,000-cell foam; measured there, 8 is as fast as 5 to 12. */
#define FIXQ_PCG_MAXIT 8

void tds_fixq_free(tds_fixq *fq) {
  tds_alloc a = fq->alloc;
  tds_free(&a, fq->qbody);
  tds_free(&a, fq->qquant);
  tds_free(&a, fq->bq);
  tds_free(&a, fq->value);
  tds_free(&a, fq->target);
  tds_free(&a, fq->mult);
  tds_free(&a, fq->gram);
  tds_free(&a, fq->gpair);
  tds_free(&a, fq->start);
  tds_free(&a, fq->eq);
  tds_free(&a, fq->g);
  tds_free(&a, fq->emap);
  tds_spmat_free(&fq->gm);
  tds_free(&a, fq->gmap);
  tds_free(&a, fq->gold);
  tds_free(&a, fq->gwork);
  tds_free(&a, fq->glam);
  tds_spchol_free(fq->gf);
  memset(fq, 0, sizeof *fq);
}

/* Add q to the entry list of v (during the counting pass, only count). */
static int has_q(const tds_fixq *fq, int32_t lo, int32_t hi, int32_t q) {
  for (int32_t i = lo; i < hi; i++)
    if (fq->eq[i] == q) return 1;
  return 0;
}

/* The entry of quantity q at vertex v, or -1. */
static int32_t entry_of(const tds_fixq *fq, tds_id v, int32_t q) {
  if (q < 0) return -1;
  for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
    if (fq->eq[i] == q) return i;
  return -1;
}

/* fq->emap (fixq.h) for the surface's facets or cell edges; without
** memory there is none (the assembly then searches). */
static void emap_build(const tds_surf *s, tds_fixq *fq) {
  const tds_mesh *m = &s->m;
  if (s->str) {
    const tds_strings *st = s->str;
    if (!st->eb_start || st->idx_ne != m->ne) return;
    int32_t nk = st->eb_start[st->idx_ne];
    fq->emap = tds_malloc(&fq->alloc, 2 * (size_t)(nk > 0 ? nk : 1) * sizeof *fq->emap);
    if (!fq->emap) return;
    for (tds_id e = 0; e < st->idx_ne; e++)
      for (int32_t k = st->eb_start[e]; k < st->eb_start[e + 1]; k++)
        for (int c = 0; c < 2; c++) {
          tds_id v = m->ev[e][c];
          int32_t q = fq->bq[st->eb_body[k]];
          fq->emap[2 * k + c] = v >= 0 && v < fq->nv ? entry_of(fq, v, q) : -1;
        }
    fq->emap_kind = 2;
    fq->emap_gen = st->idx_gen;
    fq->emap_topo = st->idx_topo;
    fq->emap_ne = st->idx_ne;
    return;
  }
  fq->emap = tds_malloc(&fq->alloc, 6 * (size_t)(m->nf > 0 ? m->nf : 1) * sizeof *fq->emap);
  if (!fq->emap) return;
  for (tds_id f = 0; f < m->nf; f++)
    for (int j = 0; j < 2; j++)
      for (int c = 0; c < 3; c++) {
        tds_id b = m->fb[f][j], v = m->fv[f][c];
        int live = tds_alive(m->fflags, f) && b != TDS_NONE && v >= 0 && v < fq->nv;
        fq->emap[6 * f + 3 * j + c] = live ? entry_of(fq, v, fq->bq[b]) : -1;
      }
  fq->emap_kind = 3;
}

int tds_fixq_build(tds_ctx *ctx, tds_surf *s, tds_fixq *fq) {
  tds_mesh *m = &s->m;
  tds_fixq_free(fq);
  fq->alloc = ctx->alloc;
  int32_t nq = 0, nglobal = 0;
  tds_id dropped = tds_torus_dropped_body(m); /* TORUS_FILLED */
  for (tds_id b = 0; b < m->nb; b++)
    if (tds_alive(m->bflags, b) && (m->bflags[b] & TDS_TARGET) && b != dropped) nq++;
  for (int i = 0; i < s->nquant; i++)
    if (s->quant[i].kind == TDS_Q_FIXED) nglobal++;
  nq += nglobal;
  fq->nq = nq;
  fq->nv = m->nv;
  fq->qbody = tds_calloc(&fq->alloc, (size_t)nq, sizeof *fq->qbody);
  fq->qquant = tds_calloc(&fq->alloc, (size_t)nq, sizeof *fq->qquant);
  fq->bq = tds_calloc(&fq->alloc, (size_t)m->nb, sizeof *fq->bq);
  fq->value = tds_calloc(&fq->alloc, (size_t)nq, sizeof *fq->value);
  fq->target = tds_calloc(&fq->alloc, (size_t)nq, sizeof *fq->target);
  fq->mult = tds_calloc(&fq->alloc, (size_t)nq, sizeof *fq->mult);
  int dense = nq <= TDS_FIXQ_DENSE_MAX;
  if (dense) fq->gram = tds_calloc(&fq->alloc, (size_t)nq * (size_t)nq, sizeof *fq->gram);
  fq->start = tds_calloc(&fq->alloc, (size_t)m->nv + 1, sizeof *fq->start);
  if (!fq->qbody || !fq->qquant || !fq->bq || !fq->value || !fq->target ||
      !fq->mult || (dense && !fq->gram) || !fq->start)
    goto nomem;
  int32_t q = 0;
  for (tds_id b = 0; b < m->nb; b++) {
    fq->bq[b] = -1;
    if (tds_alive(m->bflags, b) && (m->bflags[b] & TDS_TARGET) && b != dropped) {
      fq->qbody[q] = b;
      fq->qquant[q] = -1;
      fq->target[q] = m->btarget[b];
      fq->bq[b] = q++;
    }
  }
  int32_t qglobal0 = q;
  for (int i = 0; i < s->nquant; i++)
    if (s->quant[i].kind == TDS_Q_FIXED) {
      fq->qbody[q] = TDS_NONE;
      fq->qquant[q] = i;
      fq->target[q] = s->quant[i].target;
      q++;
    }
  if (nq == 0) return TDS_OK;
  if (tds_mesh_adjacency(m) != TDS_OK) goto nomem;

  /* Entries per vertex: its bodies with targets plus every global quantity.
  ** Upper bound 2 per star facet + nglobal; compacted below. */
  int64_t bound = 0;
  tds_id vb[64]; /* string model: the bodies of a vertex's cells */
  if (s->str && tds_strings_index(ctx, s) != TDS_OK) goto nomem;
  for (tds_id v = 0; v < m->nv; v++)
    bound += (s->str ? (tds_alive(m->vflags, v) ? tds_strings_vertex_bodies(s, v, vb, 64) : 0)
                     : 2 * (int64_t)(m->vf_start[v + 1] - m->vf_start[v])) + nglobal;
  if (bound > INT32_MAX) goto nomem;
  fq->eq = tds_calloc(&fq->alloc, (size_t)bound, sizeof *fq->eq);
  if (!fq->eq) goto nomem;
  int32_t n = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    fq->start[v] = n;
    if (!tds_alive(m->vflags, v)) continue;
    int nvb = s->str ? tds_strings_vertex_bodies(s, v, vb, 64) : 0;
    for (int k = 0; k < nvb; k++)
      if (fq->bq[vb[k]] >= 0 && !has_q(fq, fq->start[v], n, fq->bq[vb[k]]))
        fq->eq[n++] = fq->bq[vb[k]];
    for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++)
      for (int j = 0; j < 2; j++) {
        tds_id b = m->fb[m->vf[i]][j];
        if (b == TDS_NONE || fq->bq[b] < 0) continue;
        if (!has_q(fq, fq->start[v], n, fq->bq[b])) fq->eq[n++] = fq->bq[b];
      }
    for (int32_t k = qglobal0; k < nq; k++) fq->eq[n++] = k;
  }
  fq->start[m->nv] = n;
  fq->nent = n;
  fq->g = tds_calloc(&fq->alloc, (size_t)n, sizeof *fq->g);
  if (!fq->g) goto nomem;
  emap_build(s, fq);
  if (s->str && tds_fixq_dependent(ctx, s, fq, &fq->dep_first, &fq->dep_count) != TDS_OK) {
    tds_fixq_free(fq);
    return TDS_ENOMEM;
  }
  return TDS_OK;
nomem:
  tds_fixq_free(fq);
  return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
}

void tds_fixq_values(const tds_surf *s, tds_fixq *fq) {
  for (int32_t q = 0; q < fq->nq; q++)
    fq->value[q] = fq->qbody[q] != TDS_NONE ? s->m.bvol[fq->qbody[q]]
                                            : s->quant[fq->qquant[q]].value;
}

void tds_fixq_clear(tds_fixq *fq) {
  if (fq->nent) memset(fq->g, 0, (size_t)fq->nent * sizeof *fq->g);
}

int tds_dense_solve(int n, double *A, double *b) {
  for (int k = 0; k < n; k++) {
    int p = k;
    for (int i = k + 1; i < n; i++)
      if (fabs(A[i * n + k]) > fabs(A[p * n + k])) p = i;
    if (!(fabs(A[p * n + k]) > 0)) return -1;
    if (p != k) {
      for (int j = 0; j < n; j++) {
        double t = A[k * n + j];
        A[k * n + j] = A[p * n + j];
        A[p * n + j] = t;
      }
      double t = b[k];
      b[k] = b[p];
      b[p] = t;
    }
    for (int i = k + 1; i < n; i++) {
      double f = A[i * n + k] / A[k * n + k];
      if (f == 0) continue;
      for (int j = k; j < n; j++) A[i * n + j] -= f * A[k * n + j];
      b[i] -= f * b[k];
    }
  }
  for (int k = n - 1; k >= 0; k--) {
    double t = b[k];
    for (int j = k + 1; j < n; j++) t -= A[k * n + j] * b[j];
    b[k] = t / A[k * n + k];
  }
  return 0;
}

/* fq->gpair; 0 without memory. */
static int gram_pairs(tds_fixq *fq) {
  int64_t n = 0;
  for (int32_t v = 0; v < fq->nv; v++)
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
      for (int32_t j = fq->start[v]; j < fq->start[v + 1]; j++) n += fq->eq[i] >= fq->eq[j];
  fq->gpair = tds_malloc(&fq->alloc, (size_t)(n > 0 ? n : 1) * sizeof *fq->gpair);
  if (!fq->gpair) return 0;
  fq->ngpair = n;
  n = 0;
  for (int32_t v = 0; v < fq->nv; v++)
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
      for (int32_t j = fq->start[v]; j < fq->start[v + 1]; j++)
        if (fq->eq[i] >= fq->eq[j]) {
          fq->gpair[n][0] = i;
          fq->gpair[n][1] = j;
          fq->gpair[n++][2] = fq->eq[i] * fq->nq + fq->eq[j];
        }
  return 1;
}

/* Assemble the Gram matrix of the entry gradients into fq->gram; with
** `lower` only the entries (q, r) with q >= r (the others are then
** undefined; each is the same sum in the same order as its mirror). */
static void gram(tds_fixq *fq, int lower) {
  int32_t nq = fq->nq;
  memset(fq->gram, 0, (size_t)nq * (size_t)nq * sizeof *fq->gram);
  if (lower && (fq->gpair || gram_pairs(fq))) { /* the same sums, without the search */
    const int32_t(*p)[3] = (const int32_t(*)[3])fq->gpair;
    for (int64_t k = 0; k < fq->ngpair; k++) {
      const double *a = fq->g[p[k][0]], *b = fq->g[p[k][1]];
      fq->gram[p[k][2]] += a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    }
    return;
  }
  for (int32_t v = 0; v < fq->nv; v++)
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
      for (int32_t j = fq->start[v]; j < fq->start[v + 1]; j++)
        if (!lower || fq->eq[i] >= fq->eq[j])
          fq->gram[fq->eq[i] * nq + fq->eq[j]] +=
            fq->g[i][0] * fq->g[j][0] + fq->g[i][1] * fq->g[j][1] +
            fq->g[i][2] * fq->g[j][2];
}

/* The sparse Gram matrix's pattern (upper triangle: every pair of
** quantities sharing a vertex, and every diagonal entry, so that a
** constraint without gradient is a zero pivot, not a missing column), the
** map from each vertex's entry pairs (i, j with eq[i] <= eq[j], in the
** order solve_sparse visits them) to their place in fq->gm.val, and the
** analysis of the pattern. */
static int gram_pattern(tds_ctx *ctx, tds_fixq *fq) {
  tds_sptrip t = {.nrow = fq->nq, .ncol = fq->nq, .alloc = fq->alloc};
  int64_t npair = 0;
  int rc = TDS_OK;
  for (int32_t v = 0; v < fq->nv && rc == TDS_OK; v++)
    for (int32_t i = fq->start[v]; i < fq->start[v + 1] && rc == TDS_OK; i++)
      for (int32_t j = fq->start[v]; j < fq->start[v + 1]; j++) {
        if (fq->eq[i] > fq->eq[j]) continue;
        npair++;
        if (tds_sptrip_add(&t, fq->eq[i], fq->eq[j], 0)) {
          rc = TDS_ENOMEM;
          break;
        }
      }
  for (int32_t q = 0; q < fq->nq && rc == TDS_OK; q++)
    if (tds_sptrip_add(&t, q, q, 0)) rc = TDS_ENOMEM;
  if (rc == TDS_OK && tds_spmat_from_trip(&t, 1, &fq->gm)) rc = TDS_ENOMEM;
  tds_sptrip_free(&t);
  if (rc == TDS_OK) {
    int64_t nnz = fq->gm.colptr[fq->nq];
    fq->gmap = tds_malloc(&fq->alloc, (size_t)(npair > 0 ? npair : 1) * sizeof *fq->gmap);
    fq->gold = tds_calloc(&fq->alloc, (size_t)(nnz > 0 ? nnz : 1), sizeof *fq->gold);
    fq->gwork = tds_malloc(&fq->alloc, 4 * (size_t)fq->nq * sizeof *fq->gwork);
    fq->glam = tds_malloc(&fq->alloc, (size_t)fq->nq * sizeof *fq->glam);
    fq->glam_ok = 0;
    if (!fq->gmap || !fq->gold || !fq->gwork || !fq->glam) rc = TDS_ENOMEM;
  }
  if (rc == TDS_OK) {
    int32_t *map = fq->gmap;
    for (int32_t v = 0; v < fq->nv; v++)
      for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
        for (int32_t j = fq->start[v]; j < fq->start[v + 1]; j++) {
          int32_t r = fq->eq[i], c = fq->eq[j];
          if (r > c) continue;
          int32_t lo = fq->gm.colptr[c], hi = fq->gm.colptr[c + 1] - 1;
          while (lo < hi) { /* rows increase within a column */
            int32_t mid = lo + (hi - lo) / 2;
            if (fq->gm.rowind[mid] < r) lo = mid + 1;
            else hi = mid;
          }
          TDS_ASSERT(fq->gm.rowind[lo] == r);
          *map++ = lo;
        }
    rc = tds_spchol_analyse(ctx, &fq->gm, 0, &fq->gf); /* 0: the default zero-pivot size */
  } else {
    rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  if (rc != TDS_OK) { /* made again at the next solve */
    tds_spmat_free(&fq->gm);
    memset(&fq->gm, 0, sizeof fq->gm);
    tds_free(&fq->alloc, fq->gmap);
    tds_free(&fq->alloc, fq->gold);
    tds_free(&fq->alloc, fq->gwork);
    tds_free(&fq->alloc, fq->glam);
    fq->gmap = NULL;
    fq->gold = NULL;
    fq->gwork = NULL;
    fq->glam = NULL;
  }
  return rc;
}

/* The sparse path: the Gram matrix's upper triangle from the per-vertex
** entry lists, factored by spchol.h's sparse Cholesky (G is symmetric
** positive semidefinite; a zero pivot means dependent constraints,
** refused with the dense path's message). The pattern and its analysis
** are made once per fixq (the topology). The factors are kept: a matrix
** equal to the one factored (the multipliers and Evolver's restoring move
** at the same positions) is solved with them directly, and the Gram
** matrices at the next positions (the line search's trial moves and the
** later steps) by conjugate gradients preconditioned with them, until
** that takes more than FIXQ_PCG_MAXIT iterations: then G is factored
** again. rtol: the relative residual the conjugate gradients may leave
** (0: a direct solve's backward error). On a 10,000-cell foam a
** factorisation takes 8 ms, a solve with the factors 0.4 ms, and the
** conjugate gradients 5 to 15 iterations: G is like a graph Laplacian of
** the cells (condition number ~ their number), whose small eigenvalues
** move a lot relative to themselves when the vertices move a little.
** Conjugate gradients without a factorisation were measured 4x slower
** than factoring every time. */
static int solve_sparse(tds_ctx *ctx, tds_fixq *fq, double *rhs, double rtol, int mults) {
  int rc = TDS_OK;
  if (!fq->gf && (rc = gram_pattern(ctx, fq)) != TDS_OK) return rc;
  double *val = fq->gm.val;
  size_t nnz = (size_t)fq->gm.colptr[fq->nq];
  memset(val, 0, nnz * sizeof *val);
  const int32_t *map = fq->gmap;
  for (int32_t v = 0; v < fq->nv; v++)
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
      for (int32_t j = fq->start[v]; j < fq->start[v + 1]; j++) {
        if (fq->eq[i] > fq->eq[j]) continue;
        val[*map++] += fq->g[i][0] * fq->g[j][0] + fq->g[i][1] * fq->g[j][1] +
                       fq->g[i][2] * fq->g[j][2];
      }
  if (fq->gfok && memcmp(val, fq->gold, nnz * sizeof *val) != 0) {
    int its;
    const double *x0 = mults && fq->glam_ok ? fq->glam : NULL;
    rc = tds_spchol_solve_near(ctx, fq->gf, &fq->gm, rhs, x0, rtol, fq->gwork, FIXQ_PCG_MAXIT,
                               &its);
    if (rc != TDS_OK || its >= 0) goto done;
    fq->gfok = 0;
  }
  if (!fq->gfok) {
    rc = tds_spchol_factor(ctx, fq->gf, &fq->gm);
    if (rc == TDS_OK) {
      memcpy(fq->gold, val, nnz * sizeof *val);
      fq->gfok = 1;
    }
  }
  if (rc == TDS_OK) rc = tds_spchol_solve(ctx, fq->gf, rhs);
done:
  if (rc == TDS_OK && mults) {
    memcpy(fq->glam, rhs, (size_t)fq->nq * sizeof *rhs);
    fq->glam_ok = 1;
  }
  if (rc == TDS_ENUM)
    return tds_seterr(ctx, TDS_ENUM,
                      "volume constraints are dependent (singular Gram "
                      "matrix): a body without free vertices, or redundant targets");
  return rc;
}

/* LAPACK: Cholesky factorisation of a dense symmetric positive definite
** matrix, and the solve with its factor. */
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda,
             double *b, const int *ldb, int *info);

/* The dense Gram system by LAPACK's Cholesky (G is symmetric, so its
** row-major array is its column-major one; gram(fq, 1)'s triangle is the
** column-major upper one), from this many quantities: a
** third of the operations of tds_dense_solve's elimination, in blocked
** code (on a 128-cell foam 12% of a g step took 1.5%). Below it the
** elimination, as before. Returns 0, or -1 when G is not numerically
** positive definite (then rhs is unchanged and fq->gram destroyed). */
#define FIXQ_CHOL_MIN 32
static int dense_chol(tds_fixq *fq, double *rhs) {
  int n = (int)fq->nq, one = 1, info = 0;
  dpotrf_("U", &n, fq->gram, &n, &info);
  if (info != 0) return -1;
  for (int i = 0; i < n; i++) /* a pivot that counts as zero: dependent */
    if (!(fq->gram[(size_t)i * (size_t)n + (size_t)i] > 0)) return -1;
  dpotrs_("U", &n, &one, fq->gram, &n, rhs, &n, &info);
  return info == 0 ? 0 : -1;
}

/* The combinatorial dependence found at the build (fixq_dep.c). */
static int dependent(tds_ctx *ctx, const tds_fixq *fq) {
  int b = fq->dep_first + 1;
  if (fq->dep_count == 1)
    return tds_seterr(ctx, TDS_ENUM,
                      "volume constraints are dependent: no vertex on the walls of body %d "
                      "can move its area; leave it without a target (body[%d].target = nil)",
                      b, b);
  return tds_seterr(ctx, TDS_ENUM,
                    "volume constraints are dependent: the area targets of the %d bodies "
                    "joined to body %d by movable walls fix the sum of their areas, which the "
                    "foam already fixes (the torus's area, or the area inside fixed edges); "
                    "leave one of them without a target (body[%d].target = nil), or use "
                    "TORUS_FILLED", (int)fq->dep_count, b, b);
}

static int solve(tds_ctx *ctx, tds_fixq *fq, double *rhs, double rtol, int mults) {
  if (fq->dep_count > 0) return dependent(ctx, fq);
  if (!fq->gram) return solve_sparse(ctx, fq, rhs, rtol, mults);
  int chol = fq->nq >= FIXQ_CHOL_MIN;
  gram(fq, chol);
  if (chol && dense_chol(fq, rhs) == 0) return TDS_OK;
  if (chol) gram(fq, 0); /* not definite: the elimination says */
  if (tds_dense_solve(fq->nq, fq->gram, rhs) != 0)
    return tds_seterr(ctx, TDS_ENUM,
                      "volume constraints are dependent (singular Gram "
                      "matrix): a body without free vertices, or redundant targets");
  return TDS_OK;
}

int tds_fixq_multipliers(tds_ctx *ctx, tds_fixq *fq, double (*gradE)[3]) {
  if (fq->nq == 0) return TDS_OK;
  double *b = fq->mult;
  memset(b, 0, (size_t)fq->nq * sizeof *b);
  for (int32_t v = 0; v < fq->nv; v++)
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
      b[fq->eq[i]] += fq->g[i][0] * gradE[v][0] + fq->g[i][1] * gradE[v][1] +
                      fq->g[i][2] * gradE[v][2];
  return solve(ctx, fq, b, 0, 1);
}

int tds_fixq_restore(tds_ctx *ctx, tds_fixq *fq, int32_t nv, double (*dx)[3]) {
  TDS_REQUIRE(ctx, dx && nv >= fq->nv);
  memset(dx, 0, (size_t)nv * sizeof *dx);
  if (fq->nq == 0) return TDS_OK;
  double *mu = fq->mult;
  for (int32_t q = 0; q < fq->nq; q++) mu[q] = fq->target[q] - fq->value[q];
  int rc = solve(ctx, fq, mu, fq->restore_rtol, 0);
  if (rc != TDS_OK) return rc;
  for (int32_t v = 0; v < fq->nv; v++)
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++) {
      double c = mu[fq->eq[i]];
      dx[v][0] += c * fq->g[i][0];
      dx[v][1] += c * fq->g[i][1];
      dx[v][2] += c * fq->g[i][2];
    }
  return TDS_OK;
}
