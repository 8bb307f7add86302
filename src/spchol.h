/*
** spchol.h: sparse Cholesky factorisation of symmetric positive
** (semi)definite matrices whose pattern stays fixed while their values
** change: the ordering and symbolic analysis are made once
** (tds_spchol_analyse), then each matrix of that pattern is factored
** numerically (tds_spchol_factor) and solved with (tds_spchol_solve).
** fixq.c uses it for the Gram matrix of the constrained quantities'
** gradients (a 2-D foam's 10,000 body areas), which keeps its pattern
** for as long as the topology does. The library under it is CHOLMOD
** (SuiteSparse), AMD ordering: its solves cost a fraction of MUMPS's
** (la.h) on such matrices, whose fronts are tiny.
**
** A pivot below eps times the largest diagonal entry (eps <= 0: 1e-10)
** counts as zero: the matrix is singular and tds_spchol_factor says so
** (TDS_ENUM). Core code: status codes through ctx, no globals (CHOLMOD's
** own arrays come from the C library, as MUMPS's do).
*/
#ifndef TDS_SPCHOL_H
#define TDS_SPCHOL_H

#include "sparse.h"
#include "tds.h"

typedef struct tds_spchol tds_spchol;

/* Analyse the pattern of A (n x n, upper triangle, CSC; A->upper; its
** values are not read). *out is new (free with tds_spchol_free), NULL on
** failure. TDS_OK, TDS_ENOMEM, TDS_ERANGE (not square / not upper). */
int tds_spchol_analyse(tds_ctx *ctx, const tds_spmat *A, double eps, tds_spchol **out);

/* Factor A, whose pattern must be the analysed one (same colptr and
** rowind; TDS_ERANGE otherwise), replacing f's previous factors. TDS_OK;
** TDS_ENUM when an entry is not finite, or A is not positive definite or
** is singular (a zero pivot); TDS_ENOMEM. On failure f holds no factors
** (tds_spchol_solve refuses it) until a successful factorisation. */
int tds_spchol_factor(tds_ctx *ctx, tds_spchol *f, const tds_spmat *A);

/* Solve A x = b in place (b: n entries) with the last factored A. TDS_OK;
** TDS_ERANGE when f holds no factors; TDS_ENUM when x is not finite;
** TDS_ENOMEM. */
int tds_spchol_solve(tds_ctx *ctx, tds_spchol *f, double *b);

/* Solve A x = b in place by conjugate gradients preconditioned with f's
** factors, for a matrix A (any pattern) near the one factored: x starts
** at x0 (a guess, such as the solution of a system nearby) or, with x0
** NULL, as the factors' solution, and the iteration stops when the
** residual's norm is at most rtol |b| or, with rtol 0, 1e-14 (|b| +
** |A|_F |x|) (a backward error like a direct solve's). work: 4 n doubles.
** *iters is the number of iterations taken, or -1 when they did not get
** there within maxit (then b is unchanged: factor A instead). TDS_OK; as
** tds_spchol_solve otherwise. */
int tds_spchol_solve_near(tds_ctx *ctx, tds_spchol *f, const tds_spmat *A, double *b,
                          const double *x0, double rtol, double *work, int maxit,
                          int *iters);

void tds_spchol_free(tds_spchol *f);

#endif
