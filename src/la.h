/*
** la.h: sparse symmetric linear algebra behind one small interface: an
** LDL^T factorisation with pivoting of a symmetric, possibly indefinite
** or singular matrix, its inertia, and solves. The Newton step, the
** eigenvalue probes and ritz (newton.h) use only this, so the library
** under it (la_mumps.c: MUMPS, sequential) can be changed.
**
** Inertia: the numbers of negative, zero and positive eigenvalues, read
** from the factorisation's pivots (Sylvester's law). A pivot counts as
** zero when its size is below eps times the largest entry of the matrix
** (null pivot detection; eps <= 0: 1e-10); a matrix with zero pivots is singular,
** and tds_la_solve refuses it (TDS_ENUM) unless allow_singular was
** asked for (then the null directions get 0 in the solution).
** Core code: status codes through ctx, no globals.
*/
#ifndef TDS_LA_H
#define TDS_LA_H

#include "sparse.h"
#include "tds.h"

typedef struct tds_la tds_la;

typedef struct tds_inertia {
  int32_t neg, zero, pos;
} tds_inertia;

/* Factor the n x n symmetric matrix A (upper triangle, CSC; A->upper),
** eps the relative zero-pivot size above.
** *out is a new factorisation (free with tds_la_free), NULL on failure.
** TDS_OK, TDS_ENOMEM, TDS_ERANGE (not square / not upper), TDS_ENUM
** (an entry not finite, or the factorisation failed). */
int tds_la_factor(tds_ctx *ctx, const tds_spmat *A, double eps, tds_la **out);

/* Factor the n x n general (unsymmetric) matrix A (CSC, not upper): LU
** with pivoting. Solves as above; its inertia means nothing but `zero`
** (null pivots). Same status codes. */
int tds_la_factor_lu(tds_ctx *ctx, const tds_spmat *A, tds_la **out);

/* Inertia of the factored matrix. */
tds_inertia tds_la_inertia(const tds_la *f);

/* Solve A x = b in place (b: n entries). TDS_OK; TDS_ENUM when A is
** singular and allow_singular is 0, or the solution is not finite. */
int tds_la_solve(tds_ctx *ctx, tds_la *f, double *b, int allow_singular);

void tds_la_free(tds_la *f);

#endif
