/* newton_int.h: the Newton system shared by newton.c and newton_eig.c
** (newton.h describes it). */
#ifndef TDS_NEWTON_INT_H
#define TDS_NEWTON_INT_H

#include "hess.h"
#include "newton.h"

typedef struct tds_nsys {
  tds_alloc alloc;      /* of the arrays (the ctx's) */
  int32_t m, nq;
  int32_t *vert;        /* unknown -> vertex slot */
  double (*mv)[3];      /* unknown -> motion-space vector of a unit amount */
  double (*dx)[3];      /* unknown -> displacement in space of a unit amount */
  tds_spmat H;          /* m x m upper */
  tds_spmat A;          /* m x nq */
  tds_spmat M;          /* m x m upper; empty (nrow 0) for the identity */
  double *grad;         /* m: gradient of the Lagrangian */
  double *value, *target; /* nq */
  double *mult;         /* nq: multipliers H was built with */
  double energy;
} tds_nsys;

/* Build at the current positions (multipliers recomputed first). */
int tds_nsys_build(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_nsys *out);
void tds_nsys_free(tds_nsys *n);

/* The bordered K - c [M 0; 0 0] (upper CSC). */
int tds_nsys_kkt(tds_ctx *ctx, const tds_nsys *n, double c, tds_spmat *K);

/* hessian_diff: replace h->H's values by central differences of the
** Lagrangian's gradient (multipliers h->mult), keeping its pattern
** (newton_diff.c). The positions are restored exactly. */
int tds_hess_diff(tds_ctx *ctx, tds_surf *s, tds_hess *h);

/* y = M x (the identity when M is empty). */
void tds_nsys_metric(const tds_nsys *n, const double *x, double *y);

#endif
