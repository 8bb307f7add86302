/* test_quad.c: quadrature rules and the polynomial degree that picks them.
** A rule of degree d must integrate every monomial of degree <= d exactly
** (to rounding, 1e-15) on the reference triangle / unit interval; the
** integral of x^i y^j over the triangle (0,0),(1,0),(0,1) divided by its
** area is 2 i! j! / (i + j + 2)!. */
#include <math.h>

#include "check.h"
#include "quadrature.h"
#include "model.h"

static double fact(int n) { return n <= 1 ? 1 : n * fact(n - 1); }

static double tri_moment(const tds_rule *R, int i, int j) {
  double s = 0;
  for (int q = 0; q < R->n; q++) /* x = b1, y = b2 on the reference */
    s += R->w[q] * pow(R->b[q][1], i) * pow(R->b[q][2], j);
  return s;
}

static void test_facet_rules(void) {
  int npts[3] = {1, 3, 12}, deg[3] = {1, 2, 6};
  for (int r = 0; r < 3; r++) {
    const tds_rule *R = tds_facet_rule(npts[r]);
    CHECK(R->n == npts[r]);
    for (int i = 0; i <= deg[r]; i++)
      for (int j = 0; i + j <= deg[r]; j++)
        CHECK_NEAR(tri_moment(R, i, j), 2 * fact(i) * fact(j) / fact(i + j + 2), 1e-15);
    /* one degree more is not exact (so the table of degrees is tight) */
    double worst = 0;
    for (int i = 0; i <= deg[r] + 1; i++) {
      int j = deg[r] + 1 - i;
      double err = fabs(tri_moment(R, i, j) - 2 * fact(i) * fact(j) / fact(i + j + 2));
      if (err > worst) worst = err;
    }
    CHECK(worst > 1e-6);
  }
}

static void test_edge_rules(void) {
  int npts[2] = {1, 2}, deg[2] = {1, 3};
  for (int r = 0; r < 2; r++) {
    const tds_rule *R = tds_edge_rule(npts[r]);
    for (int k = 0; k <= deg[r] + 1; k++) {
      double s = 0;
      for (int q = 0; q < R->n; q++) s += R->w[q] * pow(R->t[q], k);
      if (k <= deg[r]) CHECK_NEAR(s, 1.0 / (k + 1), 1e-15);
      else CHECK(fabs(s - 1.0 / (k + 1)) > 1e-3);
    }
  }
}

static int degree_of(tds_surf *s, const char *text) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  tds_expr *e;
  if (tds_model_compile(&ctx, s, text, TDS_EXPR_FORMULA, &e) != TDS_OK) return -99;
  int d = tds_expr_degree(e);
  tds_expr_free(e);
  return d;
}

static void test_degree(void) {
  tds_surf s;
  tds_surf_init(&s);
  tds_surf_param_set(&s, "R", 2);
  CHECK(degree_of(&s, "3") == 0);
  CHECK(degree_of(&s, "R*G") == 0);
  CHECK(degree_of(&s, "z") == 1);
  CHECK(degree_of(&s, "-(R*y)") == 1);
  CHECK(degree_of(&s, "x/2") == 1);
  CHECK(degree_of(&s, "x^2*y") == 3);
  CHECK(degree_of(&s, "(x + y)^3 - z") == 3);
  CHECK(degree_of(&s, "x^2 + y^2 = R^2") == 2);
  CHECK(degree_of(&s, "x**2**2") == 4); /* left-associative: (x^2)^2 */
  CHECK(degree_of(&s, "1/x") == -1);
  CHECK(degree_of(&s, "x^-1") == -1);
  CHECK(degree_of(&s, "x^0.5") == -1);
  CHECK(degree_of(&s, "sin(x)") == -1);
  CHECK(degree_of(&s, "sqrt(x^2)") == -1);
  CHECK(degree_of(&s, "x > 0 ? x : 0") == -1);
  CHECK(degree_of(&s, "cos(R)*x") == 1);
  tds_surf_free(&s);
}

int main(void) {
  RUN(test_facet_rules);
  RUN(test_edge_rules);
  RUN(test_degree);
  return check_done();
}
