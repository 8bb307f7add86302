/* test_knot.c: the knot, string-curvature and Hooke rows (method_knot.c)
** and their assembly (eval_knot.c): each kernel's gradient (and Hessian)
** against central differences on seeded random elements at several
** powers, closed forms, the assembled gradient of every row on a random
** closed polygon against differences of the total energy, and the
** refusals (a Hessian the row does not have, coincident vertices). The
** values themselves are compared with Evolver in tests/evolver/knot.sh.
**
** Tolerances as in test_methods.c: central differences with h = 1e-6
** (values) and 1e-5 (gradients) are accurate to ~1e-9 of the gradient
** scale on these well-separated elements; 1e-8 and 1e-7 leave margins,
** while a wrong term is off by the size of the entries. */
#include "helpers.h"

#include "datafile.h"
#include "eval.h"
#include "hess.h"
#include "method.h"

#define TOL_G 1e-8
#define TOL_H 1e-7

static double maxabs(const double *a, int n) {
  double s = 1e-3;
  for (int i = 0; i < n; i++)
    if (fabs(a[i]) > s) s = fabs(a[i]);
  return s;
}

/* A random point in [-1,1]^3 plus off. */
static void rpoint(uint64_t *st, double *x, double off) {
  for (int i = 0; i < 3; i++) x[i] = h_uniform(st, -1, 1);
  x[0] += off;
}

/* Worst value/gradient and gradient/Hessian errors of a 2- or 3-corner
** row at corners xs (perturbed in place and restored). */
static void fd3(const tds_method *row, tds_mlocal *L, double (*xs)[3], int kind, double *eg,
                double *eh) {
  double g[3][3], h[9][9];
  int n = 3 * kind;
  row->eval(L, g, h);
  double gs = maxabs(&g[0][0], n), hs = maxabs(&h[0][0], 81);
  if (hs < gs) hs = gs;
  for (int k = 0; k < n; k++) {
    double *x = &xs[k / 3][k % 3], keep = *x;
    *x = keep + 1e-6;
    double fp = row->eval(L, NULL, NULL);
    *x = keep - 1e-6;
    double fm = row->eval(L, NULL, NULL);
    double e = fabs((fp - fm) / 2e-6 - g[k / 3][k % 3]) / gs;
    if (e > *eg) *eg = e;
    double gp[3][3], gm[3][3];
    *x = keep + 1e-5;
    row->eval(L, gp, NULL);
    *x = keep - 1e-5;
    row->eval(L, gm, NULL);
    *x = keep;
    for (int j = 0; j < n; j++) {
      double d = fabs((gp[j / 3][j % 3] - gm[j / 3][j % 3]) / 2e-5 - h[j][k]) / hs;
      if (d > *eh) *eh = d;
    }
  }
}

/* knot_energy (powers 1, 2, 3.5), hooke rows (powers 0, 1.5, 2, 3),
** sqcurve_string: 30 random elements each. */
static void knot_kernels_fd(void) {
  uint64_t st = 4242;
  struct {
    int row;
    double pw;
  } cases[] = {{TDS_M_KNOT, 1},  {TDS_M_KNOT, 2},    {TDS_M_KNOT, 3.5}, {TDS_M_HOOKE, 0},
               {TDS_M_HOOKE, 1.5}, {TDS_M_HOOKE, 2}, {TDS_M_HOOKE2, 3}, {TDS_M_SQCURVE_STRING, 2}};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    const tds_method *row = &tds_methods[cases[c].row];
    int kind = row->iter == TDS_IT_VSTAR ? 3 : 2;
    double eg = 0, eh = 0;
    for (int t = 0; t < 30; t++) {
      double xs[3][3];
      double d[3];
      do {
        for (int k = 0; k < kind; k++) rpoint(&st, xs[k], 0);
        v3_sub(d, xs[1], xs[0]);
      } while (v3_norm(d) < 0.3 || (kind == 3 && (v3_sub(d, xs[2], xs[1]), v3_norm(d) < 0.3)));
      tds_mlocal L = {.x = {xs[0], xs[1], xs[2]}, .pw = cases[c].pw, .k = 0.4};
      if (cases[c].pw == 0) L.k = 4; /* -log|L - k|: away from L = k */
      fd3(row, &L, xs, kind, &eg, &eh);
    }
    int ok = eg < TOL_G && eh < (row->flags & TDS_MF_HESS_FD ? 1e-6 : TOL_H);
    if (!ok) printf("  %s pw %g: value/grad %.2g, grad/hess %.2g\n", row->name, cases[c].pw, eg, eh);
    CHECK(ok);
  }
}

/* The 4-corner rows, powers 2 and 3, on random pairs of edges some
** distance apart (so that Buck's denominator is positive). */
static void pairs_fd(void) {
  uint64_t st = 99;
  for (int r = 0; r < TDS_M_NROWS; r++) {
    const tds_method *row = &tds_methods[r];
    if (row->kind != TDS_EL_EPAIR) continue;
    double worst = 0;
    int n = 0;
    for (double pw = 2; pw <= 3; pw++)
      for (int t = 0; t < 30; t++) {
        double y[4][3];
        for (int c = 0; c < 4; c++) rpoint(&st, y[c], c < 2 ? 0 : 4);
        const double *yp[4] = {y[0], y[1], y[2], y[3]};
        double g[4][3];
        double v = row->eval4(yp, pw, g);
        if (!isfinite(v)) continue;
        n++;
        double gs = maxabs(&g[0][0], 12);
        for (int k = 0; k < 12; k++) {
          double *x = &y[k / 3][k % 3], keep = *x;
          *x = keep + 1e-6;
          double fp = row->eval4(yp, pw, NULL);
          *x = keep - 1e-6;
          double fm = row->eval4(yp, pw, NULL);
          *x = keep;
          double e = fabs((fp - fm) / 2e-6 - g[k / 3][k % 3]) / gs;
          if (e > worst) worst = e;
        }
        double v2 = row->eval4(yp, pw, NULL);
        CHECK(v2 == v); /* value alone = value with gradient */
      }
    if (!(worst < TOL_G && n >= 40)) printf("  %s: worst %.2g over %d pairs\n", row->name, worst, n);
    CHECK(worst < TOL_G);
    CHECK(n >= 40);
  }
}

/* Closed forms. Two parallel unit edges side by side at distance d (the
** second edge the first moved by d along y): edge_knot = 1/d^2;
** proj = 2/d^2 (r is in the normal plane); circle: the circle through
** one midpoint tangent to the other edge runs backwards there, 1 - cos a
** = 2, so 2/d^2. Buck: 1/(2d + 2 sqrt(1 + d^2) - 4)^2. knot_energy of
** points at distance d: 1/d^p. sqcurve_string at a right angle between
** edges 1 and 2: (4 + 2/3)/3. hooke: (L - k)^2. */
static void closed_forms(void) {
  double d = 1.7;
  double a0[3] = {0, 0, 0}, a1[3] = {1, 0, 0}, b0[3] = {0, d, 0}, b1[3] = {1, d, 0};
  const double *y[4] = {a0, a1, b0, b1};
  CHECK_NEAR(tds_mk_edge_knot(y, 2, NULL), 1 / (d * d), 1e-15);
  CHECK_NEAR(tds_mk_proj_knot(y, 2, NULL), 2 / (d * d), 1e-15);
  CHECK_NEAR(tds_mk_circle_knot(y, 2, NULL), 2 / (d * d), 1e-15);
  double den = 2 * d + 2 * sqrt(1 + d * d) - 4;
  CHECK_NEAR(tds_mk_buck_knot(y, 2, NULL), 1 / (den * den), 1e-14);
  CHECK_NEAR(tds_mk_buck_knot(y, 3, NULL), 1 / (den * den * den), 1e-14);
  tds_mlocal L = {.x = {a0, b0}, .pw = 3};
  CHECK_NEAR(tds_mk_knot(&L, NULL, NULL), 1 / (d * d * d), 1e-15);
  double c0[3] = {-1, 0, 0}, c2[3] = {0, 2, 0};
  tds_mlocal S = {.x = {c0, a0, c2}};
  CHECK_NEAR(tds_mk_sqcurve(&S, NULL, NULL), (4 + 2.0 / 3.0) / 3, 1e-15);
  tds_mlocal H = {.x = {a0, b1}, .pw = 2, .k = 0.5};
  CHECK_NEAR(tds_mk_hooke(&H, NULL, NULL), pow(sqrt(1 + d * d) - 0.5, 2), 1e-14);
  /* where corners meet: infinite energy, zero gradient */
  double g[3][3], h[9][9];
  tds_mlocal P = {.x = {a0, a0}, .pw = 2};
  CHECK(tds_mk_knot(&P, g, h) == HUGE_VAL && g[0][0] == 0 && h[0][0] == 0);
  /* Buck's denominator not positive: edges long for their distance */
  double e1[3] = {10, 0, 0}, f0[3] = {0, 0.1, 0}, f1[3] = {10, 0.1, 0};
  const double *yy[4] = {a0, e1, f0, f1};
  CHECK(tds_mk_buck_knot(yy, 2, NULL) == HUGE_VAL);
}

/* A seeded random closed polygon (9 vertices) plus a tail edge, every
** row in a quantity: the assembled gradient against central differences
** of the total energy (1e-7 relative: differences of a sum of ~100
** pair terms). Then: hessian refused while a row without one is on, and
** coincident vertices reported, both as errors naming the row. */
static const char poly_head[] =
    "string\nparameter knot_power = 2.5\nparameter hooke_length = 0.5\n"
    "quantity a ENERGY modulus 0.7 method knot_energy global\n"
    "quantity b ENERGY modulus 0.3 method edge_knot_energy global\n"
    "quantity c ENERGY modulus 0.01 method buck_knot_energy global\n"
    "quantity d ENERGY modulus 0.2 method proj_knot_energy global\n"
    "quantity e ENERGY modulus 0.4 method circle_knot_energy global\n"
    "quantity f ENERGY modulus 1.1 method sqcurve_string global\n"
    "quantity g ENERGY modulus 2 method hooke_energy global\n"
    "define edge attribute hooke_size real\n"
    "quantity h ENERGY modulus 3 method hooke2_energy global\n";

static int load_poly(tds_ctx *ctx, tds_surf *s, uint64_t seed) {
  char text[4096];
  int o = snprintf(text, sizeof text, "%svertices\n", poly_head);
  uint64_t st = seed;
  for (int i = 0; i < 10; i++) {
    double t = 2 * 3.14159265358979323846 * i / 9, r = 2 + h_uniform(&st, -0.3, 0.3);
    if (i == 9) t = 0, r = 3.1; /* the tail's end */
    o += snprintf(text + o, sizeof text - (size_t)o, "%d %.17g %.17g %.17g\n", i + 1,
                  r * cos(t), r * sin(t), h_uniform(&st, -0.4, 0.4));
  }
  o += snprintf(text + o, sizeof text - (size_t)o, "edges\n");
  for (int i = 0; i < 9; i++)
    o += snprintf(text + o, sizeof text - (size_t)o, "%d %d %d hooke_size %.3f\n", i + 1,
                  i + 1, (i + 1) % 9 + 1, 1 + 0.1 * i);
  snprintf(text + o, sizeof text - (size_t)o, "10 1 10 hooke_size 0.9\n");
  return tds_datafile_load_buffer(ctx, s, "poly.fe", text, strlen(text));
}

static void assembly_fd(void) {
  for (uint64_t seed = 1; seed <= 3; seed++) {
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, load_poly(&ctx, &s, seed));
    tds_mesh *m = &s.m;
    double (*grad)[3] = calloc((size_t)m->nv, sizeof *grad);
    tds_eval_out out = {.grad = grad};
    REQUIRE_OK(&ctx, tds_eval(&ctx, &s, &out));
    /* every quantity contributes */
    for (int q = 0; q < s.nquant; q++) CHECK(fabs(s.quant[q].value) > 1e-6);
    double gs = maxabs(&grad[0][0], 3 * m->nv), worst = 0;
    for (tds_id v = 0; v < m->nv; v++)
      for (int i = 0; i < 3; i++) {
        double keep = m->x[v][i], e[2];
        for (int k = 0; k < 2; k++) {
          m->x[v][i] = keep + (k ? -1e-6 : 1e-6);
          tds_eval_out o2 = {0};
          REQUIRE_OK(&ctx, tds_eval(&ctx, &s, &o2));
          e[k] = o2.energy;
        }
        m->x[v][i] = keep;
        double d = fabs((e[0] - e[1]) / 2e-6 - grad[v][i]) / gs;
        if (d > worst) worst = d;
      }
    if (!(worst < 1e-7)) printf("  seed %d: assembled gradient error %.2g\n", (int)seed, worst);
    CHECK(worst < 1e-7);
    /* hessian: edge_knot_energy and the other pair rows have none */
    tds_hess h = {0};
    CHECK(tds_hess_assemble(&ctx, &s, NULL, &h) == TDS_ERANGE);
    CHECK(strstr(ctx.errmsg, "has no Hessian") != NULL);
    tds_hess_free(&h);
    /* coincident vertices: knot_energy is infinite, said so */
    m->x[1][0] = m->x[4][0], m->x[1][1] = m->x[4][1], m->x[1][2] = m->x[4][2];
    m->coord_gen++;
    tds_eval_out o3 = {0};
    CHECK(tds_eval(&ctx, &s, &o3) == TDS_ENUM);
    CHECK(strstr(ctx.errmsg, "vertices 2 and 5 coincide") != NULL);
    free(grad);
    tds_surf_free(&s);
  }
}

int main(void) {
  RUN(knot_kernels_fd);
  RUN(pairs_fd);
  RUN(closed_forms);
  RUN(assembly_fd);
  return check_done();
}
