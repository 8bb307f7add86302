/*
** la_chol.h: the positive definite fast path of la.h (la_chol.c, on
** CHOLMOD): a supernodal Cholesky factorisation L L^T with AMD ordering,
** which la_mumps.c tries first on a symmetric matrix. It applies only to
** a matrix whose diagonal is positive and whose entries are finite, and
** succeeds only when the matrix is positive definite with every pivot
** (L_ii^2) at least eps times the largest |entry|: then MUMPS's LDL^T
** would report the inertia (0 negative, 0 zero, n positive) too, and
** that inertia is exact. Otherwise the caller factors with MUMPS
** (pivoting, inertia of any matrix, null pivots).
** Core code: status codes through ctx, no globals.
*/
#ifndef TDS_LA_CHOL_H
#define TDS_LA_CHOL_H

#include "sparse.h"
#include "tds.h"

typedef struct tds_chol tds_chol;

/* Factor the n x n symmetric A (upper CSC, rows sorted in each column),
** eps > 0 the relative zero-pivot size. TDS_OK with *out set (free with
** tds_chol_free); TDS_ERANGE with *out NULL when the path does not
** apply (a diagonal entry missing or not positive, an entry not finite)
** or A is not positive definite, or has a pivot below eps times its
** largest |entry| (nothing is set in ctx: the caller falls back);
** TDS_ENOMEM. */
int tds_chol_factor(tds_ctx *ctx, const tds_spmat *A, double eps, tds_chol **out);

/* Solve A x = b in place (b: n entries). TDS_OK or TDS_ENOMEM. */
int tds_chol_solve(tds_ctx *ctx, tds_chol *f, double *b);

void tds_chol_free(tds_chol *f);

#endif
