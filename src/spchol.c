/* spchol.c: spchol.h on CHOLMOD (SuiteSparse). */
#include "spchol.h"

#include <math.h>
#include <string.h>
#include <suitesparse/cholmod.h>

#include "cholmod_view.h"

struct tds_spchol {
  tds_alloc alloc;   /* of this and the pattern copy (the ctx's) */
  cholmod_common c;  /* one per factorisation: several may coexist */
  cholmod_factor *L; /* symbolic after the analysis, numeric once factored */
  cholmod_dense *X, *Y, *E; /* cholmod_solve2's workspace, kept */
  int32_t n;
  int factored;
  double eps;
  int32_t *colptr, *rowind; /* the analysed pattern */
};

void tds_spchol_free(tds_spchol *f) {
  if (!f) return;
  if (f->L) cholmod_free_factor(&f->L, &f->c);
  if (f->X) cholmod_free_dense(&f->X, &f->c);
  if (f->Y) cholmod_free_dense(&f->Y, &f->c);
  if (f->E) cholmod_free_dense(&f->E, &f->c);
  cholmod_finish(&f->c);
  tds_alloc a = f->alloc;
  tds_free(&a, f->colptr);
  tds_free(&a, f->rowind);
  tds_free(&a, f);
}

static int cholmod_rc(tds_ctx *ctx, const cholmod_common *c, const char *what) {
  if (c->status == CHOLMOD_OUT_OF_MEMORY)
    return tds_seterr(ctx, TDS_ENOMEM, "spchol: out of memory in the %s", what);
  return tds_seterr(ctx, TDS_ENUM, "spchol: the %s failed (CHOLMOD status %d)", what,
                    c->status);
}

int tds_spchol_analyse(tds_ctx *ctx, const tds_spmat *A, double eps, tds_spchol **out) {
  *out = NULL;
  if (A->nrow != A->ncol || !A->upper)
    return tds_seterr(ctx, TDS_ERANGE, "spchol: the matrix must be square and symmetric (upper)");
  int32_t n = A->nrow;
  size_t nnz = (size_t)A->colptr[n];
  tds_spchol *f = tds_calloc(&ctx->alloc, 1, sizeof *f);
  if (!f) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  f->alloc = ctx->alloc;
  f->n = n;
  f->eps = eps > 0 ? eps : 1e-10;
  cholmod_start(&f->c);
  f->c.print = 0;
  f->c.error_handler = NULL;
  /* nested dissection (CHOLMOD's, on METIS's partitions): on a
  ** 10,000-cell foam's Gram matrix it has half the operations of AMD's
  ** ordering (1.7e7 against 3.1e7) and factors in 60% of the time */
  f->c.nmethods = 1;
  f->c.method[0].ordering = CHOLMOD_NESDIS;
  /* parts under 1,000 nodes ordered by CAMD, not dissected further: on
  ** that Gram matrix the analysis (once per g command) took 17 ms
  ** instead of 25, for 1% more entries in the factor */
  f->c.method[0].nd_small = 1000;
  f->c.postorder = 1;
  f->c.quick_return_if_not_posdef = 1;
  /* simplicial: the supernodal factorisation's dense blocks are too
  ** small to pay for its BLAS calls and OpenMP threads (it took 1.3-1.9x
  ** the time on a 10,000-cell foam's Gram matrix) */
  f->c.supernodal = CHOLMOD_SIMPLICIAL;
  f->colptr = tds_malloc(&ctx->alloc, (size_t)(n + 1) * sizeof *f->colptr);
  f->rowind = tds_malloc(&ctx->alloc, (nnz + 1) * sizeof *f->rowind);
  if (!f->colptr || !f->rowind) {
    tds_spchol_free(f);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  memcpy(f->colptr, A->colptr, (size_t)(n + 1) * sizeof *f->colptr);
  if (nnz) memcpy(f->rowind, A->rowind, nnz * sizeof *f->rowind);
  if (n > 0) {
    cholmod_sparse S = tds_cholmod_view(A);
    f->L = cholmod_analyze(&S, &f->c);
    if (!f->L) {
      int rc = cholmod_rc(ctx, &f->c, "analysis");
      tds_spchol_free(f);
      return rc;
    }
  }
  *out = f;
  return TDS_OK;
}


int tds_spchol_factor(tds_ctx *ctx, tds_spchol *f, const tds_spmat *A) {
  f->factored = 0;
  int32_t n = f->n;
  if (A->nrow != n || A->ncol != n || !A->upper ||
      memcmp(A->colptr, f->colptr, (size_t)(n + 1) * sizeof *f->colptr) != 0 ||
      (f->colptr[n] &&
       memcmp(A->rowind, f->rowind, (size_t)f->colptr[n] * sizeof *f->rowind) != 0))
    return tds_seterr(ctx, TDS_ERANGE, "spchol: the matrix's pattern is not the analysed one");
  double dmax = 0;
  for (int32_t j = 0; j < n; j++)
    for (int32_t e = A->colptr[j]; e < A->colptr[j + 1]; e++) {
      double a = A->val[e];
      if (!isfinite(a))
        return tds_seterr(ctx, TDS_ENUM, "spchol: matrix entry (%d, %d) is not finite",
                          (int)A->rowind[e] + 1, (int)j + 1);
      if (A->rowind[e] == j && fabs(a) > dmax) dmax = fabs(a);
    }
  if (n == 0) {
    f->factored = 1;
    return TDS_OK;
  }
  cholmod_sparse S = tds_cholmod_view(A);
  if (!cholmod_factorize(&S, f->L, &f->c) && f->c.status != CHOLMOD_NOT_POSDEF)
    return cholmod_rc(ctx, &f->c, "factorisation");
  if (f->c.status == CHOLMOD_OUT_OF_MEMORY) return cholmod_rc(ctx, &f->c, "factorisation");
  if (f->c.status == CHOLMOD_NOT_POSDEF || f->L->minor < f->L->n ||
      !(tds_cholmod_min_pivot(f->L) > f->eps * (dmax > 0 ? dmax : 1)))
    return tds_seterr(ctx, TDS_ENUM, "spchol: the matrix is singular or not positive definite");
  f->factored = 1;
  return TDS_OK;
}

int tds_spchol_solve(tds_ctx *ctx, tds_spchol *f, double *b) {
  if (!f->factored) return tds_seterr(ctx, TDS_ERANGE, "spchol: solve before a factorisation");
  if (f->n == 0) return TDS_OK;
  cholmod_dense B = tds_cholmod_column(b, f->n);
  if (!cholmod_solve2(CHOLMOD_A, f->L, &B, NULL, &f->X, NULL, &f->Y, &f->E, &f->c))
    return cholmod_rc(ctx, &f->c, "solve");
  const double *x = f->X->x;
  for (int32_t i = 0; i < f->n; i++) {
    if (!isfinite(x[i])) return tds_seterr(ctx, TDS_ENUM, "spchol: the solution is not finite");
    b[i] = x[i];
  }
  return TDS_OK;
}

static double dot(int32_t n, const double *a, const double *b) {
  double t = 0;
  for (int32_t i = 0; i < n; i++) t += a[i] * b[i];
  return t;
}

int tds_spchol_solve_near(tds_ctx *ctx, tds_spchol *f, const tds_spmat *A, double *b,
                          const double *x0, double rtol, double *work, int maxit,
                          int *iters) {
  int32_t n = f->n;
  *iters = 0;
  if (A->nrow != n || A->ncol != n || !A->upper)
    return tds_seterr(ctx, TDS_ERANGE, "spchol: the matrix is not n x n symmetric (upper)");
  if (n == 0) return TDS_OK;
  double *x = work, *r = x + n, *z = r + n, *p = z + n;
  double anorm = 0; /* |A|_F from the upper triangle, for rtol 0 */
  if (!(rtol > 0))
    for (int32_t j = 0; j < n; j++)
      for (int32_t k = A->colptr[j]; k < A->colptr[j + 1]; k++)
        anorm += (A->rowind[k] == j ? 1 : 2) * A->val[k] * A->val[k];
  anorm = sqrt(anorm);
  double bnorm = sqrt(dot(n, b, b));
  if (!isfinite(anorm) || !isfinite(bnorm))
    return tds_seterr(ctx, TDS_ENUM, "spchol: the matrix or right-hand side is not finite");
  int rc;
  if (x0) {
    memcpy(x, x0, (size_t)n * sizeof *x);
  } else {
    memcpy(x, b, (size_t)n * sizeof *x);
    if ((rc = tds_spchol_solve(ctx, f, x)) != TDS_OK) return rc;
  }
  tds_spmat_mulv(A, x, r);
  for (int32_t i = 0; i < n; i++) r[i] = b[i] - r[i];
  double rz = 0;
  for (int it = 0;; it++) {
    *iters = it;
    double rn = sqrt(dot(n, r, r));
    if (rtol > 0 ? rn <= rtol * bnorm : rn <= 1e-14 * (bnorm + anorm * sqrt(dot(n, x, x)))) {
      memcpy(b, x, (size_t)n * sizeof *x);
      return TDS_OK;
    }
    if (it == maxit || !isfinite(rn)) {
      *iters = -1;
      return TDS_OK;
    }
    memcpy(z, r, (size_t)n * sizeof *z);
    if ((rc = tds_spchol_solve(ctx, f, z)) != TDS_OK) return rc;
    double rz1 = dot(n, r, z);
    /* the first direction is z itself (p is not yet set) */
    if (it) {
      double beta = rz1 / rz;
      for (int32_t i = 0; i < n; i++) p[i] = z[i] + beta * p[i];
    } else {
      memcpy(p, z, (size_t)n * sizeof *p);
    }
    rz = rz1;
    double *Ap = z; /* z is free until the next iteration */
    tds_spmat_mulv(A, p, Ap);
    double pAp = dot(n, p, Ap);
    if (!(pAp > 0)) { /* A is not positive definite along p */
      *iters = -1;
      return TDS_OK;
    }
    double alpha = rz / pAp;
    for (int32_t i = 0; i < n; i++) {
      x[i] += alpha * p[i];
      r[i] -= alpha * Ap[i];
    }
  }
}
