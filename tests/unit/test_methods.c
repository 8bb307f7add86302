/* test_methods.c: every row of the method table (src/method.h), its
** gradient against central differences of its value and its Hessian
** against central differences of its gradient, on seeded random elements,
** with polynomial and non-polynomial integrands that read parameters.
** Also closed-form cross-checks between rows that compute the same
** integral two ways (quadrature against geometry). */
#include "helpers.h"

#include "eval.h"
#include "fixq.h"
#include "method.h"
#include "model.h"

/* Central differences with step h have truncation error ~h^2 f''' / 6 and
** rounding error ~eps |f| / h. Values: h = 1e-6 gives both below 1e-9 of
** the gradient scale for corners of order 1 and well-shaped elements
** (area >= 0.05, length >= 0.2); gradients: h = 1e-5 (rounding 1e-11,
** truncation 1e-10 f''''). Measured worst errors over all rows are
** 4e-10 and 1.4e-9 (relative to the largest gradient / Hessian entry);
** tolerances 1e-8 and 1e-7 leave margins of 25 and 70 while any wrong
** term, of the order of the entries themselves, fails by orders of
** magnitude. */
#define FD_HV 1e-6
#define FD_HG 1e-5
#define TOL_G 1e-8
#define TOL_H 1e-7

static void random_element(uint64_t *st, int kind, double x[3][3]) {
  for (;;) {
    memset(x, 0, sizeof(double[3][3]));
    for (int c = 0; c < kind; c++)
      for (int i = 0; i < 3; i++) x[c][i] = h_uniform(st, -1, 1);
    if (kind == TDS_EL_FACET && geom_area(x[0], x[1], x[2], NULL) >= 0.05) return;
    double d[3];
    v3_sub(d, x[1], x[0]);
    if (kind == TDS_EL_EDGE && v3_norm(d) >= 0.2) return;
  }
}

static double maxabs(const double *a, int n) {
  double s = 0;
  for (int i = 0; i < n; i++)
    if (fabs(a[i]) > s) s = fabs(a[i]);
  return s;
}

/* Worst errors of one row at one element: value vs gradient (eg), gradient
** vs Hessian (eh), Hessian asymmetry (es), and whether the value and
** gradient agree between the value-only, gradient and Hessian calls. */
typedef struct fd_err {
  double eg, eh, es;
  int consistent;
} fd_err;

static fd_err fd_row(const tds_method *row, const tds_mlocal *L0) {
  fd_err r = {0, 0, 0, 1};
  tds_mlocal L = *L0;
  double xs[3][3] = {{0}}; /* a copy to perturb */
  for (int c = 0; c < row->kind; c++) {
    memcpy(xs[c], L0->x[c], sizeof xs[c]);
    L.x[c] = xs[c];
  }
  int n = 3 * row->kind;
  double g[3][3], g2[3][3], h[9][9];
  double v0 = row->eval(&L, NULL, NULL);
  double v1 = row->eval(&L, g2, NULL);
  double v2 = row->eval(&L, g, h);
  if (v0 != v1 || v1 != v2 || !isfinite(v0)) r.consistent = 0;
  for (int k = 0; k < n; k++)
    if (fabs(g[k / 3][k % 3] - g2[k / 3][k % 3]) > 1e-15 * (1 + fabs(g2[k / 3][k % 3])))
      r.consistent = 0;
  double gs = maxabs(&g[0][0], n), hs = maxabs(&h[0][0], 81);
  if (gs < 1e-3) gs = 1e-3;
  if (hs < gs) hs = gs;
  for (int k = 0; k < n; k++) {
    int c = k / 3, i = k % 3;
    double keep = xs[c][i];
    xs[c][i] = keep + FD_HV;
    double fp = row->eval(&L, NULL, NULL);
    xs[c][i] = keep - FD_HV;
    double fm = row->eval(&L, NULL, NULL);
    double e = fabs((fp - fm) / (2 * FD_HV) - g[c][i]) / gs;
    if (e > r.eg) r.eg = e;
    double gp[3][3], gm[3][3];
    xs[c][i] = keep + FD_HG;
    row->eval(&L, gp, NULL);
    xs[c][i] = keep - FD_HG;
    row->eval(&L, gm, NULL);
    xs[c][i] = keep;
    for (int j = 0; j < n; j++) {
      double fd = (gp[j / 3][j % 3] - gm[j / 3][j % 3]) / (2 * FD_HG);
      double eh = fabs(fd - h[j][k]) / hs;
      if (eh > r.eh) r.eh = eh;
      double es = fabs(h[j][k] - h[k][j]) / hs;
      if (es > r.es) r.es = es;
    }
  }
  return r;
}

/* Integrands: polynomial (each quadrature rule) and transcendental, all
** reading parameters a and b, so a wrong parameter slot changes them. */
typedef struct integrand_set {
  const char *text[3];
  int npts;
} integrand_set;

static const integrand_set vec_sets[] = {
    {{"a*y", "b*z", "x"}, 1},
    {{"a*x*y", "z^2", "b*x^2 - y*z"}, 3},
    {{"a*x^2*y + z^3", "b*y*z^2", "x*y*z"}, 12},
    {{"a*sin(y)*z", "x^2*exp(b*z)", "cos(a*x*y)"}, 12},
    {{"0", "a/(2 + x*x + y*y)", "sqrt(3 + b*z*z)"}, 2},
};
static const integrand_set sca_sets[] = {
    {{"a + b*x", NULL, NULL}, 1},
    {{"a*x*y + b*z^2", NULL, NULL}, 3},
    {{"a*x^3*y + z^4*b", NULL, NULL}, 12},
    {{"exp(a*x)*cos(b*y*z) + 1/(3 + x^2)", NULL, NULL}, 12},
    {{"sqrt(2 + a*x^2 + y^2)", NULL, NULL}, 2},
};
static const integrand_set formula_sets[] = {
    {{"x^2 + a*y^2 + b*z^2 - 1", NULL, NULL}, 0},
    {{"z - a*sin(x) - b*x*y", NULL, NULL}, 0},
};

typedef struct env {
  tds_ctx ctx;
  tds_surf s;
} env;

static int compile_set(env *E, const integrand_set *is, tds_expr *ig[3]) {
  for (int j = 0; j < 3; j++) {
    ig[j] = NULL;
    if (is->text[j] && tds_model_compile(&E->ctx, &E->s, is->text[j], 0, &ig[j]) != TDS_OK)
      return 0;
  }
  return 1;
}

static void free_set(tds_expr *ig[3]) {
  for (int j = 0; j < 3; j++) tds_expr_free(ig[j]);
}

/* Every row, 20 random elements per integrand set (or per row when it
** reads none); reports the worst error per row on failure. */
static void rows_fd(void) {
  env E;
  h_setup(&E.ctx, &E.s);
  tds_surf_param_set(&E.s, "a", 0.7);
  tds_surf_param_set(&E.s, "b", -1.3);
  uint64_t st = 12345;
  int tested = 0;
  for (int r = 0; r < TDS_M_NROWS; r++) {
    const tds_method *row = &tds_methods[r];
    if (row->kind == TDS_EL_EPAIR) { /* 4 corners: tests/unit/test_knot.c */
      tested++;
      continue;
    }
    const integrand_set *sets = NULL;
    int nsets = 1;
    if (row->flags & TDS_MF_VECTOR) sets = vec_sets, nsets = 5;
    if (row->flags & TDS_MF_SCALAR) sets = sca_sets, nsets = 5;
    if (row->flags & TDS_MF_FORMULA) sets = formula_sets, nsets = 2;
    double worst_g = 0, worst_h = 0, worst_s = 0;
    int ok = 1, count = 0;
    for (int si = 0; si < nsets; si++) {
      tds_expr *ig[3] = {NULL, NULL, NULL};
      if (sets && !compile_set(&E, &sets[si], ig)) {
        printf("  %s: %s\n", row->name, E.ctx.errmsg);
        ok = 0;
        free_set(ig);
        continue;
      }
      for (int t = 0; t < 20; t++) {
        double xs[3][3];
        /* a metric row gets no tensor: the identity (test_knot.c has one) */
        tds_mlocal L = {.x = {xs[0], xs[1], xs[2]}, .ig = row->flags & TDS_MF_METRIC ? NULL : ig,
                        .npts = sets ? sets[si].npts : 0, .k = 2.5,
                        .param = E.s.parval, .G = 9.8};
        if (row->kind == TDS_EL_EDGE && L.npts > 2) L.npts = 2;
        random_element(&st, row->kind, xs);
        if (r == TDS_M_KLEIN_LENGTH || r == TDS_M_KLEIN_AREA) /* inside the unit ball */
          for (int c = 0; c < row->kind; c++)
            for (int i = 0; i < 3; i++) xs[c][i] *= 0.55;
        fd_err e = fd_row(row, &L);
        ok &= e.consistent;
        if (e.eg > worst_g) worst_g = e.eg;
        if (e.eh > worst_h) worst_h = e.eh;
        if (e.es > worst_s) worst_s = e.es;
        count++;
      }
      free_set(ig);
    }
    /* The gap row's Hessian is itself a central difference of its
    ** gradient (TDS_MF_HESS_FD): the comparison then only checks the
    ** assembly of the differences, with the same tolerance. */
    int pass = ok && worst_g < TOL_G && worst_h < TOL_H && worst_s < 1e-12;
    if (!pass)
      printf("  row %s: value/grad %.2g, grad/hess %.2g, asym %.2g, consistent %d\n",
             row->name, worst_g, worst_h, worst_s, ok);
    CHECK(pass);
    CHECK(count >= 20);
    tested++;
  }
  CHECK(tested == TDS_M_NROWS);
  tds_surf_free(&E.s);
}

/* Rows that compute the same integral two ways agree to rounding: the
** divergence theorem per facet (facet_vector_integral of (0,0,z) is the
** z-volume, of (x,y,z)/3 the symmetric volume, of (0,0,z^2/2) the gravity
** moment), unit scalar integrands give area and length, the edge vector
** integral of a constant field is F . d. Quadrature is exact for these
** polynomial degrees, so only rounding (1e-14) separates them. */
static void rows_agree(void) {
  env E;
  h_setup(&E.ctx, &E.s);
  tds_surf_param_set(&E.s, "a", 2);
  uint64_t st = 777;
  struct {
    int row, ref;
    integrand_set is;
  } pairs[] = {
      {TDS_M_FACET_VECTOR_INTEGRAL, TDS_M_FACET_VOLUME, {{NULL, NULL, "z"}, 1}},
      {TDS_M_FACET_VECTOR_INTEGRAL, TDS_M_FACET_VOLUME_SYM, {{"x/3", "y/3", "z/3"}, 1}},
      {TDS_M_FACET_VECTOR_INTEGRAL, TDS_M_GRAVITY, {{NULL, NULL, "z^2/2"}, 3}},
      {TDS_M_FACET_SCALAR_INTEGRAL, TDS_M_FACET_AREA, {{"1", NULL, NULL}, 1}},
      {TDS_M_EDGE_SCALAR_INTEGRAL, TDS_M_EDGE_LENGTH, {{"1", NULL, NULL}, 1}},
  };
  for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++) {
    tds_expr *ig[3];
    REQUIRE_OK(&E.ctx, compile_set(&E, &pairs[p].is, ig) ? TDS_OK : TDS_ESYNTAX);
    const tds_method *a = &tds_methods[pairs[p].row], *b = &tds_methods[pairs[p].ref];
    for (int t = 0; t < 20; t++) {
      double xs[3][3];
      tds_mlocal L = {.x = {xs[0], xs[1], xs[2]}, .ig = ig, .npts = pairs[p].is.npts,
                      .param = E.s.parval};
      random_element(&st, a->kind, xs);
      double ga[3][3], gb[3][3], ha[9][9], hb[9][9];
      double va = a->eval(&L, ga, ha), vb = b->eval(&L, gb, hb);
      CHECK_NEAR(va, vb, 1e-14);
      for (int k = 0; k < 3 * a->kind; k++) {
        CHECK_NEAR(ga[k / 3][k % 3], gb[k / 3][k % 3], 1e-14);
        for (int j = 0; j < 3 * a->kind; j++) CHECK_NEAR(ha[k][j], hb[k][j], 1e-13);
      }
    }
    free_set(ig);
  }
  /* A constant field along an edge: exactly F . d, and the parameter is
  ** live (changing it needs no recompilation). */
  tds_expr *ig[3];
  integrand_set is = {{"a", "2*a", "-a"}, 1};
  REQUIRE_OK(&E.ctx, compile_set(&E, &is, ig) ? TDS_OK : TDS_ESYNTAX);
  double xs[3][3];
  tds_mlocal L = {.x = {xs[0], xs[1], xs[2]}, .ig = ig, .npts = 1, .param = E.s.parval};
  random_element(&st, TDS_EL_EDGE, xs);
  double d[3];
  v3_sub(d, L.x[1], L.x[0]);
  const tds_method *ev = &tds_methods[TDS_M_EDGE_VECTOR_INTEGRAL];
  CHECK_NEAR(ev->eval(&L, NULL, NULL), 2 * (d[0] + 2 * d[1] - d[2]), 1e-15);
  E.s.parval[tds_surf_param_find(&E.s, "a", 1)] = -0.5;
  CHECK_NEAR(ev->eval(&L, NULL, NULL), -0.5 * (d[0] + 2 * d[1] - d[2]), 1e-15);
  free_set(ig);
  tds_surf_free(&E.s);
}

/* The gap row against its closed form on a unit sphere: tail on the
** sphere, head displaced by S; E = k |S| |S . n| / 6 with n = tail. */
static void gap_closed_form(void) {
  env E;
  h_setup(&E.ctx, &E.s);
  tds_expr *f = NULL;
  REQUIRE_OK(&E.ctx, tds_model_compile(&E.ctx, &E.s, "x^2 + y^2 + z^2 - 1", 0, &f));
  tds_expr *ig[3] = {f, NULL, NULL};
  const double tail[3] = {0.6, 0, 0.8}, head[3] = {0.6 + 0.1, 0.2, 0.8 + 0.05};
  tds_mlocal L = {.x = {tail, head}, .ig = ig, .k = 3, .param = E.s.parval};
  double S[3] = {0.1, 0.2, 0.05}, n[3] = {0.6, 0, 0.8};
  double want = 3 * v3_norm(S) * fabs(v3_dot(S, n)) / 6;
  CHECK_NEAR(tds_methods[TDS_M_EDGE_GAP].eval(&L, NULL, NULL), want, 1e-15);
  tds_expr_free(f);
  tds_surf_free(&E.s);
}

/* Degenerate elements (coincident corners, a collinear facet, a zero-length
** edge) have no derivative; every row must still return finite numbers
** (no NaN may reach the assembly), and a vanishing element has value 0. */
static void rows_degenerate(void) {
  env E;
  h_setup(&E.ctx, &E.s);
  tds_surf_param_set(&E.s, "a", 0.7);
  tds_surf_param_set(&E.s, "b", -1.3);
  const double p[3] = {0.3, -0.2, 0.5}, q[3] = {0.6, 0.1, 1.1}, r[3] = {0.9, 0.4, 1.7};
  const double *cases[3][3] = {{p, p, p}, {p, q, r}, {q, q, r}}; /* last: edge q-q */
  for (int rr = 0; rr < TDS_M_NROWS; rr++) {
    const tds_method *row = &tds_methods[rr];
    /* knot energies are infinite where corners meet (test_knot.c) */
    if (row->kind == TDS_EL_EPAIR || (row->flags & TDS_MF_SINGULAR)) continue;
    const integrand_set *is = (row->flags & TDS_MF_VECTOR)   ? &vec_sets[3]
                              : (row->flags & TDS_MF_SCALAR) ? &sca_sets[3]
                              : (row->flags & TDS_MF_FORMULA) ? &formula_sets[1]
                                                              : NULL;
    tds_expr *ig[3] = {NULL, NULL, NULL};
    if (is) REQUIRE_OK(&E.ctx, compile_set(&E, is, ig) ? TDS_OK : TDS_ESYNTAX);
    for (int c = 0; c < 3; c++) {
      double kx[3][3]; /* the Klein row: the points halved, inside the unit ball */
      for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++) kx[k][i] = 0.5 * cases[c][k][i];
      int kl = rr == TDS_M_KLEIN_LENGTH || rr == TDS_M_KLEIN_AREA;
      tds_mlocal L = {.x = {kl ? kx[0] : cases[c][0], kl ? kx[1] : cases[c][1], kl ? kx[2] : cases[c][2]},
                      .ig = row->flags & TDS_MF_METRIC ? NULL : ig,
                      .npts = row->kind == TDS_EL_EDGE ? 2 : 12, .k = 1,
                      .param = E.s.parval, .G = 9.8};
      double g[3][3], h[9][9];
      double v = row->eval(&L, g, h);
      int fin = isfinite(v);
      for (int k = 0; k < 3 * row->kind; k++) {
        fin &= isfinite(g[k / 3][k % 3]);
        for (int j = 0; j < 3 * row->kind; j++) fin &= isfinite(h[k][j]);
      }
      if (!fin) printf("  row %s, case %d: not finite\n", row->name, c);
      CHECK(fin);
      /* a point: no length, area or volume (the vertex rows are the
      ** integrand at a corner, not an integral) */
      if (c == 0 && rr != TDS_M_VERTEX_HEAD && rr != TDS_M_VERTEX_TAIL) CHECK(v == 0);
    }
    free_set(ig);
  }
  tds_surf_free(&E.s);
}

/* Names: every user row is found by its name, in any case, and Evolver's
** aliases map to area and length; internal rows are not user methods. */
static void names(void) {
  for (int r = 0; r < TDS_M_NROWS; r++) {
    int user = (tds_methods[r].flags & TDS_MF_USER) != 0;
    CHECK(tds_method_by_name(tds_methods[r].name) == (user ? r : -1));
    CHECK(user == (r < TDS_M_COUNT));
  }
  CHECK(tds_method_by_name("FACET_TENSION") == TDS_M_FACET_AREA);
  CHECK(tds_method_by_name("edge_tension") == TDS_M_EDGE_LENGTH);
  CHECK(tds_method_by_name("Facet_Vector_Integral") == TDS_M_FACET_VECTOR_INTEGRAL);
  CHECK(tds_method_by_name("no_such_method") == -1);
}

/* A quantity with more methods than the old fixed limit of four, through
** the assembly: six facet_area instances with moduli 1..6 and quantity
** modulus 0.5 on the unit cube give 0.5 * 21 * area 6 = 63, and as an
** ENERGY quantity add exactly that to the energy. */
static void quantity_many_methods(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
  double e0 = 0;
  tds_eval_out out = {0};
  CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
  e0 = out.energy;
  int qi;
  REQUIRE_OK(&ctx, tds_model_quantity(&ctx, &s, "many", TDS_Q_ENERGY, 0.5, 0, &qi, NULL));
  for (int k = 1; k <= 6; k++)
    REQUIRE_OK(&ctx, tds_model_method(&ctx, &s, qi, TDS_M_FACET_AREA, k, NULL));
  CHECK(s.quant[qi].ninst == 6);
  CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
  CHECK_NEAR(s.quant[qi].value, 63, 1e-13);
  CHECK_NEAR(out.energy, e0 + 63, 1e-13);
  /* an internal row is not a user method */
  CHECK(tds_model_method(&ctx, &s, qi, TDS_M_FACET_VOLUME_SYM, 1, NULL) == TDS_ESYNTAX);
  CHECK(s.quant[qi].ninst == 6);
  tds_surf_free(&s);
}

/* gravity_method and full_gravity_method (Evolver: int rho z^2/2 dx dy
** over each facet, rho the density difference of its bodies; the full one
** times G) on the unit cube (z from 0 to 1, int z dV = 1/2) with density
** 0.6: 0.3, and 9.8 * 0.3 with gravity on, 0 with it off; the built-in
** gravity energy is the same 2.94. */
static void quantity_gravity_methods(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
  s.m.bdensity[0] = 0.6;
  s.gravity = 9.8;
  s.gravity_on = 0;
  int qg, qf;
  REQUIRE_OK(&ctx, tds_model_quantity(&ctx, &s, "g", TDS_Q_INFO, 1, 0, &qg, NULL));
  REQUIRE_OK(&ctx, tds_model_method(&ctx, &s, qg, TDS_M_GRAVITY, 1, NULL));
  REQUIRE_OK(&ctx, tds_model_quantity(&ctx, &s, "fg", TDS_Q_INFO, 1, 0, &qf, NULL));
  REQUIRE_OK(&ctx, tds_model_method(&ctx, &s, qf, TDS_M_FULL_GRAVITY, 1, NULL));
  tds_eval_out out = {0};
  CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
  double e_off = out.energy;
  CHECK_NEAR(s.quant[qg].value, 0.3, 1e-15);
  CHECK_NEAR(s.quant[qf].value, 0, 1e-15);
  s.gravity_on = 1;
  CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
  CHECK_NEAR(s.quant[qg].value, 0.3, 1e-15);
  CHECK_NEAR(s.quant[qf].value, 9.8 * 0.3, 1e-14);
  CHECK_NEAR(out.energy - e_off, 9.8 * 0.3, 1e-14);
  tds_surf_free(&s);
}

/* The scatter sends a body's volume gradient to the fixq only when the
** body is constrained: the energy gradient must be the same whether or not
** a fixq is passed, for a body with a prescribed pressure (no target, so
** no fixq entry) and for a body with a target, both under gravity with
** varied tensions on a jittered cube. */
static void assembly_sinks(void) {
  for (int target = 0; target < 2; target++) {
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, h_cube(&ctx, &s, target ? 1 : 0));
    tds_mesh *m = &s.m;
    s.gravity_on = 1;
    s.gravity = 9.8;
    m->bdensity[0] = 0.6;
    if (!target) {
      m->bflags[0] |= TDS_PRESSURE;
      m->bpressure[0] = 0.7;
    }
    uint64_t st = 4242 + (uint64_t)target;
    for (tds_id v = 0; v < m->nv; v++)
      for (int i = 0; i < 3; i++) m->x[v][i] += h_uniform(&st, -0.08, 0.08);
    for (tds_id f = 0; f < m->nf; f++) m->ften[f] = 1 + 0.1 * (f % 3);
    REQUIRE_OK(&ctx, tds_mesh_adjacency(m));
    tds_fixq fq = {0};
    REQUIRE_OK(&ctx, tds_fixq_build(&ctx, &s, &fq));
    CHECK(fq.nq == target);
    double (*g0)[3] = calloc((size_t)m->nv, sizeof *g0);
    double (*g1)[3] = calloc((size_t)m->nv, sizeof *g1);
    tds_eval_out a = {.grad = g0}, b = {.grad = g1, .fq = &fq};
    CHECK_OK(&ctx, tds_eval(&ctx, &s, &a));
    CHECK_OK(&ctx, tds_eval(&ctx, &s, &b));
    CHECK(a.energy == b.energy);
    CHECK(memcmp(g0, g1, (size_t)m->nv * sizeof *g0) == 0);
    free(g0);
    free(g1);
    tds_fixq_free(&fq);
    tds_surf_free(&s);
  }
}

int main(void) {
  RUN(rows_fd);
  RUN(rows_agree);
  RUN(gap_closed_form);
  RUN(rows_degenerate);
  RUN(names);
  RUN(quantity_many_methods);
  RUN(quantity_gravity_methods);
  RUN(assembly_sinks);
  return check_done();
}
