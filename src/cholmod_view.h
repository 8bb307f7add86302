/*
** cholmod_view.h: what la_chol.c and spchol.c share about CHOLMOD: tds's
** matrices and vectors seen as CHOLMOD's (on tds's arrays, nothing
** copied) and the smallest pivot of a factor. Internal to those two files.
*/
#ifndef TDS_CHOLMOD_VIEW_H
#define TDS_CHOLMOD_VIEW_H

#include <math.h>
#include <string.h>
#include <suitesparse/cholmod.h>

#include "sparse.h"

/* A (square, upper CSC, rows sorted) as CHOLMOD's upper symmetric
** matrix on A's arrays (only read). */
static inline cholmod_sparse tds_cholmod_view(const tds_spmat *A) {
  cholmod_sparse S;
  memset(&S, 0, sizeof S);
  S.nrow = S.ncol = (size_t)A->nrow;
  S.nzmax = (size_t)A->colptr[A->ncol];
  S.p = A->colptr;
  S.i = A->rowind;
  S.x = A->val;
  S.stype = 1;
  S.itype = CHOLMOD_INT;
  S.xtype = CHOLMOD_REAL;
  S.dtype = CHOLMOD_DOUBLE;
  S.sorted = 1;
  S.packed = 1;
  return S;
}

/* The n-vector b as a CHOLMOD dense column. */
static inline cholmod_dense tds_cholmod_column(double *b, int32_t n) {
  cholmod_dense B;
  memset(&B, 0, sizeof B);
  B.nrow = B.d = B.nzmax = (size_t)n;
  B.ncol = 1;
  B.x = b;
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  return B;
}

/* The smallest pivot of the factor (D_jj of LDL^T, L_jj^2 of LL^T), or
** -1 when one is not positive. */
static inline double tds_cholmod_min_pivot(const cholmod_factor *L) {
  double mn = HUGE_VAL;
  const double *x = L->x;
  if (L->is_super) {
    const int *super = L->super, *pi = L->pi, *px = L->px;
    for (size_t k = 0; k < L->nsuper; k++) {
      int ncol = super[k + 1] - super[k], nrow = pi[k + 1] - pi[k];
      for (int j = 0; j < ncol; j++) {
        double d = x[px[k] + (size_t)j * (size_t)nrow + (size_t)j];
        if (!(d > 0)) return -1;
        if (d * d < mn) mn = d * d;
      }
    }
    return mn;
  }
  const int *p = L->p;
  for (size_t j = 0; j < L->n; j++) {
    double d = x[p[j]];
    if (!(d > 0)) return -1;
    double piv = L->is_ll ? d * d : d;
    if (piv < mn) mn = piv;
  }
  return mn;
}

#endif
