/*
** eval_int.h: internals shared by the energy passes (eval.c, eval_edge.c,
** eval_quant.c): quadrature rules and integrand evaluation.
*/
#ifndef TDS_EVAL_INT_H
#define TDS_EVAL_INT_H

#include "eval.h"
#include "expr.h"

/* Gauss-Legendre on [0,1] with 2 points: exact for cubics, Evolver's
** default integral_order_1d = 3. */
#define TDS_GAUSS1_N 2
extern const double tds_gauss1_t[TDS_GAUSS1_N], tds_gauss1_w[TDS_GAUSS1_N];

/* Symmetric 12-point triangle rule exact for degree 6 (Evolver's default
** integral_order_2d = 6): barycentric points and weights summing to 1. */
#define TDS_GAUSS2_N 12
extern const double tds_gauss2_b[TDS_GAUSS2_N][3], tds_gauss2_w[TDS_GAUSS2_N];

/* Variables for evaluating expressions at point x. */
void tds_eval_vars(const tds_surf *s, const double x[3], double vars[TDS_NVARS]);

/* Line integral of the vector field F (3 expressions, NULL entries are 0)
** along the straight edge a->b. With ga, gb not NULL, ADDS the gradient
** with respect to a and b. */
double tds_edge_vint(const tds_surf *s, tds_expr *const F[3], const double a[3],
                     const double b[3], double ga[3], double gb[3]);

/* Energy, content and gap terms of edges on constraints and boundaries. */
void tds_eval_edges(tds_surf *s, tds_eval_out *out);

/* Named quantities: adds energy quantities to out->energy (and gradient),
** stores every quantity's value, and fills the gradients of FIXED ones in
** out->fq (their q indices follow the bodies'). */
void tds_eval_quantities(tds_surf *s, tds_eval_out *out);

#endif
