/*
** eval_int.h: internals shared by the energy passes (eval.c, eval_edge.c,
** eval_quant.c): quadrature rules and integrand evaluation.
*/
#ifndef TDS_EVAL_INT_H
#define TDS_EVAL_INT_H

#include "eval.h"
#include "expr.h"

/* A quadrature rule on an edge (parameter t in [0,1]) or a triangle
** (barycentric points); weights sum to 1. */
typedef struct tds_rule {
  int n;
  const double *t;         /* edges */
  const double (*b)[3];    /* triangles */
  const double *w;
} tds_rule;

/* Edge rules by number of points: 1 (midpoint, exact for linear) and 2
** (Gauss-Legendre, exact for cubics: Evolver's integral_order_1d = 3). */
const tds_rule *tds_edge_rule(int npts);
/* Triangle rules by number of points: 1 (centroid, linear), 3 (quadratic)
** and 12 (degree 6: Evolver's integral_order_2d = 6). */
const tds_rule *tds_facet_rule(int npts);

/* Variables for evaluating expressions at point x. */
void tds_eval_vars(const tds_surf *s, const double x[3], double vars[TDS_NVARS]);

/* Line integral of the vector field F (3 expressions, NULL entries are 0)
** along the straight edge a->b. With ga, gb not NULL, ADDS the gradient
** with respect to a and b. */
double tds_edge_vint(const tds_surf *s, tds_expr *const F[3], int npts,
                     const double a[3], const double b[3], double ga[3],
                     double gb[3]);

/* Energy, content and gap terms of edges on constraints and boundaries. */
void tds_eval_edges(tds_surf *s, tds_eval_out *out);

/* Named quantities: adds energy quantities to out->energy (and gradient),
** stores every quantity's value, and fills the gradients of FIXED ones in
** out->fq (their q indices follow the bodies'). */
void tds_eval_quantities(tds_surf *s, tds_eval_out *out);

#endif
