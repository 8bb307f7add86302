/*
** hess.h: the sparse Hessian of the whole energy, and of the Lagrangian
** of the constrained problem (Evolver's `hessian` matrix), for Newton
** steps and eigenvalues.
**
** Index map: the unknowns are the xyz coordinates of the vertices that
** can move (tds_vertex_free: not FIXED, not dead), in slot order: the
** k-th such vertex v has global indices 3k, 3k+1, 3k+2 (vidx[v] = 3k,
** vert[k] = v); fixed and dead vertices have vidx -1 and no rows.
** Vertices on level-set constraints and parametric boundaries are
** included with all three coordinates: H is the Hessian in full xyz
** coordinates; tds_hess_reduce (below) restricts it to each vertex's
** motion space (the level sets' tangent plane, or the boundary's
** parameters) with the curvature term that restriction brings.
**
** The assembly is tds_eval's own loop (eval.c) with every row's kernel
** asked for its Hessian, so exactly the terms of the energy are in it:
** facet tension, prescribed pressures, gravity, edge tension, constraint
** and boundary energy integrands, the gap energy, named ENERGY quantities.
** With the Lagrangian, each constrained quantity q (body volumes with a
** target, then FIXED named quantities, in tds_fixq's order) adds
** -lambda_q Hess Q_q, lambda_q its multiplier as tds computes it: the
** body's pressure (m.bpressure) or the quantity's pressure; call
** tds_pressures (iterate.h) first for multipliers at these positions.
** At a constrained equilibrium grad E = sum_q lambda_q grad Q_q.
*/
#ifndef TDS_HESS_H
#define TDS_HESS_H

#include "fixq.h"
#include "sparse.h"

typedef struct tds_hess_opts {
  int lagrange;          /* add -sum_q lambda_q Hess Q_q */
  int32_t quantity;      /* >= 0: instead, the Hessian of constrained
                            quantity q alone (no energy); -1 otherwise */
  int from_lower;        /* build H from the kernels' lower halves
                            instead of their upper ones (the same matrix
                            when every kernel is symmetric: a test) */
} tds_hess_opts;

typedef struct tds_hess {
  int32_t nv;            /* vertex slots vidx covers */
  int32_t *vidx;         /* slot -> 3k, or -1 (cannot move) */
  int32_t *vert;         /* k -> slot, n/3 entries */
  int32_t n;             /* unknowns: 3 x movable vertices */
  tds_spmat H;           /* n x n symmetric, upper triangle, CSC */
  double *grad;          /* n: gradient of the energy (same index map) */
  double *fgrad;         /* n: gradient of the function H is the Hessian
                            of: grad E - sum_q lambda_q grad Q_q for the
                            Lagrangian, grad E, or grad Q_q alone */
  double energy;
  int32_t nq;            /* constrained quantities */
  tds_spmat A;           /* n x nq: column q = grad Q_q (xyz, unprojected) */
  double *mult;          /* nq: lambda_q used (read from the surface) */
  double *value;         /* nq: Q_q now */
  double *target;        /* nq */
  tds_alloc alloc;        /* of the arrays (the ctx's at assembly) */
} tds_hess;

/* Assemble at the current positions (opts NULL: the Lagrangian,
** {1, -1, 0}).
** out is overwritten (free it with tds_hess_free; safe on a zeroed one).
** TDS_OK, TDS_ENOMEM, TDS_ENUM (energy not finite), TDS_ERANGE; on
** failure out is empty. The surface is not changed except that body
** volumes and quantity values are recomputed (as tds_eval does). */
int tds_hess_assemble(tds_ctx *ctx, tds_surf *s, const tds_hess_opts *opts,
                      tds_hess *out);
void tds_hess_free(tds_hess *h);

/* The bordered (KKT) matrix [H A; A^T 0], (n + nq) square, upper
** triangle, CSC: the quantities' rows and columns follow the coordinates.
** TDS_OK or TDS_ENOMEM. */
int tds_hess_kkt(tds_ctx *ctx, const tds_hess *h, tds_spmat *K);

/* The Hessian restricted to the vertices' motion spaces (motion.h), as
** second derivatives of the function along the motion tds's steps make:
** per movable vertex k, reduced coordinates u (start[k] .. start[k+1]-1)
** with dx = B u to first order, where B (columns basis[k][.][a]) is
**   a free vertex:     the identity (3 coordinates);
**   on level sets:     an orthonormal basis of the tangent space of its
**                      equality constraints (3 - their rank coordinates;
**                      one-sided constraints are not held, as in
**                      tds_motion_project);
**   on a boundary:     dX/dp, the coordinates being the parameters.
** Hr = B^T H B + the curvature term of the motion: on level sets phi_j
** with normal components (N^T N) mu = N^T f (f = h->fgrad at the vertex),
** -sum_j mu_j B^T Hess(phi_j) B; on a boundary sum_i f_i d2X_i/dp dp.
** grad = B^T fgrad, A = B^T A. TDS_OK, TDS_ENOMEM. */
typedef struct tds_hess_red {
  int32_t nvm;           /* movable vertices (h->n / 3) */
  int32_t *start;        /* nvm + 1 */
  double (*basis)[3][3]; /* nvm: basis[k][i][a] = dx_i/du_a */
  int32_t m;             /* reduced unknowns */
  tds_spmat H;           /* m x m, upper triangle */
  double *grad;          /* m */
  tds_spmat A;           /* m x nq */
  tds_alloc alloc;        /* of the arrays (the ctx's) */
} tds_hess_red;

/* One vertex's motion basis B (columns B[.][a], a < d) and curvature
** block C (d x d) as above, f its fgrad; returns d. */
int tds_hess_vertex_space(const tds_surf *s, tds_id v, const double f[3], double B[3][3],
                          double C[3][3]);

int tds_hess_reduce(tds_ctx *ctx, const tds_surf *s, const tds_hess *h, tds_hess_red *out);
void tds_hess_red_free(tds_hess_red *r);

#endif
