/*
** quadrature.h: the integration rules of the edge and facet integrals
** (method_integral.c).
*/
#ifndef TDS_QUADRATURE_H
#define TDS_QUADRATURE_H

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

#endif
