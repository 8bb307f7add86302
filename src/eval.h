/*
** eval.h: total energy, its gradient, and the constrained quantities.
**
** Every term is a row of the method table (method.h); one assembly loop
** (eval.c) gathers each element's corners, calls the row and scatter-adds
** value and gradient. Energy terms:
**   sum_f tension_f area_f                       (surface tension)
**   G sum_b density_b int_b z dV                 (gravity, when on)
**   - sum_b pressure_b V_b                       (bodies with a prescribed pressure)
**   sum_e tension_e length_e                     (edges with a tension)
** plus constraint/boundary edge integrals and named energy quantities.
*/
#ifndef TDS_EVAL_H
#define TDS_EVAL_H

#include "fixq.h"
#include "sparse.h"

/* Hessian collection (hess.h): when tds_eval_out.hess is not NULL, every
** term's element Hessian, times its sink's weight and the weight below,
** is added as triplets (upper half of the global matrix) to trip, or
** (add not NULL) passed to add instead: the element's corners vs, kind
** of them, weight w != 0, h its 3kind x 3kind Hessian (both halves). */
typedef struct tds_hess_acc tds_hess_acc;
struct tds_hess_acc {
  const int32_t *vidx;  /* vertex slot -> global index of its x (y, z
                           follow), or -1 for a vertex that cannot move */
  double ew;            /* weight of the energy's Hessian */
  const double *qw;     /* fixq q -> weight of quantity q's Hessian */
  tds_sptrip *trip;
  int lower;            /* take the kernels' lower halves (a symmetry
                           check; the matrix stored is the same) */
  int status;           /* TDS_ENOMEM when a triplet could not be added */
  void (*add)(tds_hess_acc *ha, const tds_id *vs, int kind, double w, double (*h)[9]);
  void *user;           /* for add */
};

typedef struct tds_eval_out {
  double energy;        /* total energy */
  double area;          /* total facet area (all facets, any tension) */
  double (*grad)[3];    /* if not NULL: dE/dx per vertex slot (overwritten) */
  tds_fixq *fq;         /* if not NULL: values and gradients of the
                           constrained quantities (pattern must be built) */
  tds_hess_acc *hess;   /* if not NULL: collect Hessians (needs grad and,
                           when quantities are weighted, fq) */
} tds_eval_out;

/* Total facet area, or in the string model the total edge length (in the
** metric with METRIC; Evolver's total_area there), computed on demand
** rather than in every evaluation. */
double tds_surf_area(const tds_surf *s);

/* Evaluate at the current positions. Also stores body volumes in m.bvol
** and named quantity values. TDS_OK, or TDS_ENUM when a value is not
** finite (the message names the first bad element). */
int tds_eval(tds_ctx *ctx, tds_surf *s, tds_eval_out *out);

/* The terms alone, ADDED to out (energy, area, grad, fq) and m.bvol, which
** the caller has initialised (tds_eval zeroes them and sets bvol to the
** bodies' volconst). facet_core 0 leaves out facet tension, body volumes,
** pressures and gravity, for a caller that computed them itself (pg's
** fused pass). Also sets the fixq values and the quantity values.
** TDS_OK, TDS_ENUM (energy not finite), TDS_ERANGE. */
int tds_eval_terms(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, int facet_core);

/* The torus model's facet tension and lifted body volumes, without
** Hessians (eval_torus.c), added to out and m.bvol as the general
** assembly (eval.c) adds them, bit for bit; s->tlift must be current.
** 1, or 0 (nothing done: no plan could be made, see there) when the
** general assembly must do it. */
int tds_eval_torus_facets(tds_surf *s, tds_eval_out *out);

/* Add w * h (a kind-corner element Hessian, kind <= 3) at vertices vs to
** the accumulator's triplets (its upper or lower half). */
void tds_eval_scatter_hess(tds_hess_acc *ha, const tds_id *vs, int kind, double w,
                           double (*h)[9]);

/* One instance of a named quantity's method whose row walks something
** other than single elements (TDS_IT_* != ELEMENT: vertex pairs, vertex
** stars, edge pairs, edges with per-edge constants; eval_knot.c): adds
** w times its value to *total and its gradient to the energy (gq -1) or
** fixq quantity gq (>= 0, -2 none), with its Hessian when out->hess.
** TDS_OK, TDS_ENOMEM, TDS_ERANGE (a Hessian the row does not have, a
** power it does not take). */
int tds_eval_global_row(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, int method, double w,
                        int32_t gq, double *total);

#endif
