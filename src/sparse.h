/*
** sparse.h: a small sparse matrix type for Hessians and constraint
** gradients: entries are collected as triplets (row, column, value) in
** any order, with repeats, then compressed to CSC (compressed sparse
** column: column j holds rows rowind[colptr[j] .. colptr[j+1]-1], strictly
** increasing, with values val[...]; repeated triplets are summed).
**
** A symmetric matrix is stored as its UPPER triangle (upper = 1: only
** entries with row <= column exist; the lower half is implied). Core
** code: status codes, no globals.
*/
#ifndef TDS_SPARSE_H
#define TDS_SPARSE_H

#include <stdint.h>

#include "tds.h"

/* Both types allocate through `alloc` (zero: the C library): set a
** triplet list's before its first add; a matrix takes its triplets'. */
typedef struct tds_sptrip {
  int32_t nrow, ncol;
  int64_t n, cap;
  int32_t *i, *j;
  double *v;
  tds_alloc alloc;      /* kept by tds_sptrip_free */
} tds_sptrip;

typedef struct tds_spmat {
  int32_t nrow, ncol;
  int upper;            /* 1: symmetric, upper triangle stored */
  int32_t *colptr;      /* ncol + 1 */
  int32_t *rowind;      /* colptr[ncol] */
  double *val;
  tds_alloc alloc;
} tds_spmat;

/* Append (i, j, v); 0, or -1 when out of memory (t is unchanged). */
int tds_sptrip_add(tds_sptrip *t, int32_t i, int32_t j, double v);
void tds_sptrip_free(tds_sptrip *t);

/* Compress t into out (sizes t's). With upper, triplets with i > j are
** stored as (j, i): the caller gives each symmetric pair once, or only
** the upper half. Explicit zeros after summing are kept (the pattern is
** the structure of the assembly). 0, or -1 when out of memory. */
int tds_spmat_from_trip(const tds_sptrip *t, int upper, tds_spmat *out);
void tds_spmat_free(tds_spmat *a);

/* Entry (i, j), 0 if not stored; for an upper matrix, (j, i) when i > j. */
double tds_spmat_get(const tds_spmat *a, int32_t i, int32_t j);

/* y = A x (y has nrow entries; the implied lower half counts for upper). */
void tds_spmat_mulv(const tds_spmat *a, const double *x, double *y);

#endif
