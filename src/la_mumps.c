/* la_mumps.c: la.h on MUMPS (sequential build, libdmumps_seq): symmetric
** general (SYM = 2) LDL^T with 1x1 and 2x2 pivots, QAMD ordering
** (approximate minimum degree that puts dense rows, the constraint
** border of a Newton system, last: SCOTCH, MUMPS's automatic choice,
** orders with fewer operations but its analysis costs twice the
** factorisation on a 50k-vertex surface, and plain AMD/AMF analyse a
** dense row slowly); inertia from INFOG(12) (negative pivots) and INFOG(28)
** (null pivots, ICNTL(24) = 1). Each factorisation owns its MUMPS
** instance, so several may coexist (no globals). A symmetric matrix is
** first offered to la_chol.h (Cholesky, CHOLMOD): when it is positive
** definite that factorisation serves, at about half MUMPS's cost. */
#include "la.h"
#include "la_chol.h"

#include <dmumps_c.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define USE_COMM_WORLD (-987654)

struct tds_la {
  tds_alloc alloc;       /* of this and the arrays (the ctx's) */
  DMUMPS_STRUC_C id;
  int32_t n;
  MUMPS_INT *irn, *jcn;
  double *a;
  tds_inertia in;
  tds_chol *chol;        /* the Cholesky path, when it served */
};

void tds_la_free(tds_la *f) {
  if (!f) return;
  tds_chol_free(f->chol);
  if (f->id.instance_number >= 0) {
    f->id.job = -2;
    dmumps_c(&f->id);
  }
  tds_free(&f->alloc, f->irn);
  tds_free(&f->alloc, f->jcn);
  tds_free(&f->alloc, f->a);
  tds_alloc al = f->alloc;
  tds_free(&al, f);
}

/* MUMPS says nothing on its own output units. */
static void quiet(DMUMPS_STRUC_C *id) {
  id->icntl[0] = -1;
  id->icntl[1] = -1;
  id->icntl[2] = -1;
  id->icntl[3] = 0;
}

/* sym: MUMPS's SYM (2: symmetric upper, 0: general, unsymmetric LU);
** eps: the relative zero-pivot size (la.h). */
static int factor(tds_ctx *ctx, const tds_spmat *A, int sym, double eps, tds_la **out) {
  *out = NULL;
  int32_t n = A->nrow;
  int64_t nnz = A->colptr[n];
  tds_la *f = tds_calloc(&ctx->alloc, 1, sizeof *f);
  if (!f) return tds_seterr(ctx, TDS_ENOMEM, "la: out of memory");
  f->alloc = ctx->alloc;
  f->id.instance_number = -1;
  f->n = n;
  if (n == 0) {
    *out = f;
    return TDS_OK;
  }
  if (sym == 2) { /* positive definite: Cholesky (la_chol.h) */
    int rc = tds_chol_factor(ctx, A, eps > 0 ? eps : 1e-10, &f->chol);
    if (rc == TDS_OK) {
      f->in.pos = n;
      *out = f;
      return TDS_OK;
    }
    if (rc != TDS_ERANGE) {
      tds_la_free(f);
      return rc;
    }
  }
  f->irn = tds_malloc(&ctx->alloc, (size_t)(nnz + 1) * sizeof *f->irn);
  f->jcn = tds_malloc(&ctx->alloc, (size_t)(nnz + 1) * sizeof *f->jcn);
  f->a = tds_malloc(&ctx->alloc, (size_t)(nnz + 1) * sizeof *f->a);
  if (!f->irn || !f->jcn || !f->a) {
    tds_la_free(f);
    return tds_seterr(ctx, TDS_ENOMEM, "la: out of memory");
  }
  double amax = 0;
  for (int32_t j = 0; j < n; j++)
    for (int32_t e = A->colptr[j]; e < A->colptr[j + 1]; e++) {
      if (!isfinite(A->val[e])) {
        tds_la_free(f);
        return tds_seterr(ctx, TDS_ENUM, "la: matrix entry (%d, %d) is not finite",
                          (int)A->rowind[e] + 1, (int)j + 1);
      }
      f->irn[e] = A->rowind[e] + 1;
      f->jcn[e] = j + 1;
      f->a[e] = A->val[e];
      if (fabs(A->val[e]) > amax) amax = fabs(A->val[e]);
    }
  DMUMPS_STRUC_C *id = &f->id;
  id->comm_fortran = USE_COMM_WORLD;
  id->par = 1;
  id->sym = sym;
  id->job = -1;
  dmumps_c(id);
  if (id->infog[0] < 0) {
    int e = id->infog[0];
    f->id.instance_number = -1;
    tds_la_free(f);
    return tds_seterr(ctx, TDS_ENOMEM, "la: the solver could not start (MUMPS error %d)", e);
  }
  quiet(id);
  id->n = n;
  id->nnz = nnz;
  id->irn = f->irn;
  id->jcn = f->jcn;
  id->a = f->a;
  id->icntl[6] = 6;    /* ICNTL(7): QAMD */
  id->icntl[12] = 1;   /* ICNTL(13): no ScaLAPACK root (keeps inertia) */
  if (sym == 0) {
    id->icntl[6] = 0;  /* ICNTL(7): AMD ordering, the same on every run
                          (the automatic choice made the pg runs that use
                          it differ from run to run in the last bits) */
    id->icntl[47] = 0; /* ICNTL(48): no tree parallelism (fixed order) */
  }
  id->icntl[23] = 1;   /* ICNTL(24): detect null pivots */
  if (!(eps > 0)) eps = 1e-10;
  id->cntl[2] = -eps * (amax > 0 ? amax : 1); /* CNTL(3) < 0: absolute threshold */
  for (int tries = 0;; tries++) {
    id->job = 4; /* analyse and factor */
    dmumps_c(id);
    int e = id->infog[0];
    if (e >= 0) break;
    if ((e == -8 || e == -9 || e == -14 || e == -15 || e == -17 || e == -20) && tries < 6) {
      id->icntl[13] = (id->icntl[13] > 0 ? id->icntl[13] : 20) * 2; /* ICNTL(14): more room */
      continue;
    }
    tds_la_free(f);
    if (e == -13) return tds_seterr(ctx, TDS_ENOMEM, "la: out of memory in the factorisation");
    return tds_seterr(ctx, TDS_ENUM, "la: the factorisation failed (MUMPS error %d, %d)", e,
                      (int)id->infog[1]);
  }
  f->in.zero = id->infog[27];
  f->in.neg = id->infog[11];
  f->in.pos = n - f->in.neg - f->in.zero;
  *out = f;
  return TDS_OK;
}

int tds_la_factor(tds_ctx *ctx, const tds_spmat *A, double eps, tds_la **out) {
  *out = NULL;
  if (A->nrow != A->ncol || !A->upper)
    return tds_seterr(ctx, TDS_ERANGE, "la: the matrix must be square and symmetric (upper)");
  return factor(ctx, A, 2, eps, out);
}

int tds_la_factor_lu(tds_ctx *ctx, const tds_spmat *A, tds_la **out) {
  *out = NULL;
  if (A->nrow != A->ncol || A->upper)
    return tds_seterr(ctx, TDS_ERANGE, "la: the matrix must be square and general (not upper)");
  return factor(ctx, A, 0, 0, out);
}

tds_inertia tds_la_inertia(const tds_la *f) { return f->in; }

int tds_la_solve(tds_ctx *ctx, tds_la *f, double *b, int allow_singular) {
  if (f->n == 0) return TDS_OK;
  if (f->in.zero && !allow_singular)
    return tds_seterr(ctx, TDS_ENUM, "la: the matrix is singular (%d zero pivots)",
                      (int)f->in.zero);
  if (f->chol) {
    int rc = tds_chol_solve(ctx, f->chol, b);
    if (rc != TDS_OK) return rc;
    goto check;
  }
  DMUMPS_STRUC_C *id = &f->id;
  id->rhs = b;
  id->nrhs = 1;
  id->lrhs = f->n;
  id->icntl[19] = 0; /* dense right-hand side */
  id->icntl[20] = 0; /* centralised solution, in rhs */
  id->job = 3;
  dmumps_c(id);
  if (id->infog[0] < 0)
    return tds_seterr(ctx, TDS_ENUM, "la: the solve failed (MUMPS error %d)", (int)id->infog[0]);
check:
  for (int32_t i = 0; i < f->n; i++)
    if (!isfinite(b[i])) return tds_seterr(ctx, TDS_ENUM, "la: the solution is not finite");
  return TDS_OK;
}
