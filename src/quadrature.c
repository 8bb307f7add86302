/* quadrature.c: the integration rules of the edge and facet integrals. */
#include "quadrature.h"

#include <stddef.h>

static const double t1[1] = {0.5}, w1[1] = {1};
static const double t2[2] = {0.21132486540518711775, 0.78867513459481288225};
static const double w2[2] = {0.5, 0.5};
static const tds_rule edge1 = {1, t1, NULL, w1}, edge2 = {2, t2, NULL, w2};

const tds_rule *tds_edge_rule(int npts) { return npts == 1 ? &edge1 : &edge2; }

static const double b1[1][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}};
static const double b3[3][3] = {{2.0 / 3, 1.0 / 6, 1.0 / 6},
                                {1.0 / 6, 2.0 / 3, 1.0 / 6},
                                {1.0 / 6, 1.0 / 6, 2.0 / 3}};
static const double w3[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
/* The symmetric 12-point rule of degree 6 (Dunavant's), its constants
** re-derived by Newton's method on the moment equations to 1e-16. */
#define A1 0.5014265096581629
#define A2 0.24928674517091855 /* (1 - A1) / 2 */
#define B1 0.8738219710169999
#define B2 0.063089014491500050 /* (1 - B1) / 2 */
#define C1 0.053145049844823246
#define C2 0.31035245103377757
#define C3 0.63650249912139918 /* 1 - C1 - C2 */
static const double b12[12][3] = {
    {A1, A2, A2}, {A2, A1, A2}, {A2, A2, A1}, {B1, B2, B2}, {B2, B1, B2},
    {B2, B2, B1}, {C1, C2, C3}, {C1, C3, C2}, {C2, C1, C3}, {C2, C3, C1},
    {C3, C1, C2}, {C3, C2, C1},
};
#define WA 0.11678627572636473
#define WB 0.05084490637020388
#define WC 0.08285107561838234
static const double w12[12] = {WA, WA, WA, WB, WB, WB, WC, WC, WC, WC, WC, WC};
static const tds_rule tri1 = {1, NULL, b1, w1}, tri3 = {3, NULL, b3, w3},
                      tri12 = {12, NULL, b12, w12};

const tds_rule *tds_facet_rule(int npts) {
  return npts == 1 ? &tri1 : npts == 3 ? &tri3 : &tri12;
}
