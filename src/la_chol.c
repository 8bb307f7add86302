/* la_chol.c: la_chol.h on CHOLMOD (SuiteSparse).
**
** Choices, measured on the hessian benchmark's catenoid (12,096 normal
** unknowns, bench/hessian.sh):
** - AMD ordering only: CHOLMOD's default also tries METIS, whose
**   ordering saves 28% of the operations but costs ten times AMD's
**   analysis (0.038 s against 0.004 s).
** - Supernodes relaxed further than CHOLMOD's defaults (nrelax 8/32/96,
**   zrelax 0.9/0.2/0.1): a surface's supernodes are small, and fewer,
**   larger ones make the dense BLAS calls pay (factorisation 0.0095 s
**   -> 0.008 s, with a few explicit zeros more).
** - OpenMP off during CHOLMOD's calls: Debian's CHOLMOD opens a parallel
**   region of 4 threads (a compile-time constant) to clear each
**   supernode, which on a busy machine costs more than the work (the
**   factorisation 0.017 s -> 0.010 s). omp_set_max_active_levels(0)
**   makes every region run on the calling thread; the previous value is
**   restored before returning.
** Each factorisation owns its cholmod_common, so several may coexist (no
** globals); CHOLMOD's own arrays come from the C library, as MUMPS's do. */
#include "la_chol.h"

#include <math.h>
#include <omp.h>
#include <string.h>
#include <suitesparse/cholmod.h>

#include "cholmod_view.h"

struct tds_chol {
  tds_alloc alloc;
  cholmod_common c;
  cholmod_factor *L;
  int32_t n;
};

void tds_chol_free(tds_chol *f) {
  if (!f) return;
  if (f->L) cholmod_free_factor(&f->L, &f->c);
  cholmod_finish(&f->c);
  tds_alloc al = f->alloc;
  tds_free(&al, f);
}


int tds_chol_factor(tds_ctx *ctx, const tds_spmat *A, double eps, tds_chol **out) {
  *out = NULL;
  int32_t n = A->nrow;
  if (n <= 0 || A->ncol != n || !A->upper) return TDS_ERANGE;
  /* applies: every column ends with its positive diagonal, all finite */
  double amax = 0;
  for (int32_t j = 0; j < n; j++) {
    int32_t e0 = A->colptr[j], e1 = A->colptr[j + 1];
    if (e1 == e0 || A->rowind[e1 - 1] != j || !(A->val[e1 - 1] > 0)) return TDS_ERANGE;
    for (int32_t e = e0; e < e1; e++) {
      double a = fabs(A->val[e]);
      if (!(a <= HUGE_VAL)) return TDS_ERANGE; /* not finite: MUMPS's path reports it */
      if (a > amax) amax = a;
    }
  }
  if (!(amax < HUGE_VAL)) return TDS_ERANGE;
  tds_chol *f = tds_calloc(&ctx->alloc, 1, sizeof *f);
  if (!f) return tds_seterr(ctx, TDS_ENOMEM, "la: out of memory");
  f->alloc = ctx->alloc;
  f->n = n;
  cholmod_start(&f->c);
  f->c.print = 0;
  f->c.error_handler = NULL;
  f->c.nmethods = 1;
  f->c.method[0].ordering = CHOLMOD_AMD;
  f->c.postorder = 1;
  f->c.supernodal = CHOLMOD_SUPERNODAL;
  f->c.nrelax[0] = 8;
  f->c.nrelax[1] = 32;
  f->c.nrelax[2] = 96;
  f->c.zrelax[0] = 0.9;
  f->c.zrelax[1] = 0.2;
  f->c.zrelax[2] = 0.1;
  f->c.quick_return_if_not_posdef = 1;
  cholmod_sparse S = tds_cholmod_view(A);
  int levels = omp_get_max_active_levels();
  omp_set_max_active_levels(0);
  f->L = cholmod_analyze(&S, &f->c);
  if (f->L) cholmod_factorize(&S, f->L, &f->c);
  omp_set_max_active_levels(levels);
  int rc = TDS_OK;
  if (!f->L || f->c.status == CHOLMOD_OUT_OF_MEMORY)
    rc = tds_seterr(ctx, TDS_ENOMEM, "la: out of memory in the factorisation");
  else if (f->c.status != CHOLMOD_OK || f->L->minor < (size_t)n ||
           !(tds_cholmod_min_pivot(f->L) >= eps * amax))
    rc = TDS_ERANGE; /* not definite, or a pivot counts as zero */
  if (rc != TDS_OK) {
    tds_chol_free(f);
    return rc;
  }
  *out = f;
  return TDS_OK;
}

int tds_chol_solve(tds_ctx *ctx, tds_chol *f, double *b) {
  cholmod_dense B = tds_cholmod_column(b, f->n);
  int levels = omp_get_max_active_levels();
  omp_set_max_active_levels(0);
  cholmod_dense *X = cholmod_solve(CHOLMOD_A, f->L, &B, &f->c);
  omp_set_max_active_levels(levels);
  if (!X) return tds_seterr(ctx, TDS_ENOMEM, "la: out of memory in the solve");
  memcpy(b, X->x, (size_t)f->n * sizeof *b);
  cholmod_free_dense(&X, &f->c);
  return TDS_OK;
}
