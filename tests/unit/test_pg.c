/* test_pg.c: kernels of the projected-gradient method (src/pg.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "eval.h"
#include "helpers.h"
#include "metrics.h"
#include "pg_int.h"
#include "model.h"
#include "pg.h"
#include "topo.h"
#include "mesh.h"
#include "vec3.h"

static double urand(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return ((*s >> 8) & 0xffffff) / (double)0x1000000;
}

/* Edge between a and b, created if missing (linear search: tiny meshes). */
static int32_t edge_ref(tds_mesh *m, tds_id a, tds_id b) {
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->ev[e][0] == a && m->ev[e][1] == b) return TDS_OREF(e, 0);
    if (m->ev[e][0] == b && m->ev[e][1] == a) return TDS_OREF(e, 1);
  }
  return TDS_OREF(tds_mesh_add_edge(m, a, b), 0);
}

static tds_id add_tri(tds_mesh *m, tds_id a, tds_id b, tds_id c) {
  int32_t oe[3] = {edge_ref(m, a, b), edge_ref(m, b, c), edge_ref(m, c, a)};
  return tds_mesh_add_facet(m, oe);
}

/* A one-ring: centre vertex 0 at c, k ring vertices around it at radius
** about 1 (perturbed by `jit`), heights z_j; ring vertices fixed. */
static void one_ring(tds_surf *s, int k, double jit, unsigned *seed,
                     const double c[3]) {
  tds_surf_init(s);
  tds_mesh *m = &s->m;
  tds_mesh_add_vertex(m, c);
  for (int j = 0; j < k; j++) {
    double a = 2 * TDS_PI * (j + jit * (urand(seed) - 0.5)) / k;
    double r = 1 + jit * (urand(seed) - 0.5);
    double p[3] = {r * cos(a), r * sin(a), -0.3 + jit * (urand(seed) - 0.5)};
    tds_id v = tds_mesh_add_vertex(m, p);
    m->vflags[v] |= TDS_FIXED;
  }
  for (int j = 0; j < k; j++) add_tri(m, 0, 1 + j, 1 + (j + 1) % k);
  tds_mesh_adjacency(m);
}

static void test_normal_independent(void) {
  unsigned seed = 7;
  for (int trial = 0; trial < 20; trial++) {
    tds_surf s;
    double c[3] = {0.1, -0.2, 0.05};
    one_ring(&s, 5 + trial % 4, 0.3, &seed, c);
    double n0[3], n1[3];
    tds_pg_vertex_normal(&s.m, 0, n0);
    for (int i = 0; i < 3; i++) s.m.x[0][i] += 0.5 * (urand(&seed) - 0.5);
    tds_pg_vertex_normal(&s.m, 0, n1);
    for (int i = 0; i < 3; i++) CHECK_NEAR(n1[i], n0[i], 1e-13);
    CHECK(v3_norm(n0) > 0.999999);
    tds_surf_free(&s);
  }
}

/* Newton root of A'(t) = c, with A', A'' from the star model at x + t d. */
static double newton_root(tds_surf *s, const double d[3], double c) {
  double x0[3], t = 0;
  v3_copy(x0, s->m.x[0]);
  for (int it = 0; it < 100; it++) {
    double A0, A1, A2;
    for (int i = 0; i < 3; i++) s->m.x[0][i] = x0[i] + t * d[i];
    tds_pg_star_model(&s->m, 0, d, &A0, &A1, &A2);
    double dt = (A1 - c) / A2;
    t -= dt;
    if (fabs(dt) < 1e-15) break;
  }
  v3_copy(s->m.x[0], x0);
  return t;
}

static void test_normal_root(void) {
  unsigned seed = 11;
  for (int trial = 0; trial < 40; trial++) {
    tds_surf s;
    double c0[3] = {0, 0, 0.2 * (urand(&seed) - 0.5)};
    double jit = trial < 10 ? 0 : 0.05; /* similar, then near-similar */
    one_ring(&s, 6, jit, &seed, c0);
    double n[3], A0, A1, A2;
    tds_pg_vertex_normal(&s.m, 0, n);
    tds_pg_star_model(&s.m, 0, n, &A0, &A1, &A2);
    double b = A1 * A1 + A0 * A2;
    double c = (2 * urand(&seed) - 1) * 0.8 * sqrt(b);
    int clamped;
    double t = tds_pg_normal_root(A0, A1, A2, c, &clamped);
    CHECK(!clamped);
    double tn = newton_root(&s, n, c);
    if (jit == 0)
      CHECK_NEAR(t, tn, 1e-10);
    else
      CHECK(fabs(t - tn) <= 0.05 * fabs(tn) + 1e-3);
    /* at equilibrium the step is zero */
    CHECK_NEAR(tds_pg_normal_root(A0, A1, A2, A1, &clamped), 0, 1e-15);
    /* no root when c^2 >= b */
    tds_pg_normal_root(A0, A1, A2, 1.01 * sqrt(b), &clamped);
    CHECK(clamped);
    tds_surf_free(&s);
  }
}

static void test_convex(void) {
  unsigned seed = 3;
  for (int trial = 0; trial < 20; trial++) {
    tds_surf s;
    double c[3] = {0.2 * (urand(&seed) - 0.5), 0.2 * (urand(&seed) - 0.5), 0.1};
    one_ring(&s, 4 + trial % 5, 0.5, &seed, c);
    double d[3] = {urand(&seed) - 0.5, urand(&seed) - 0.5, urand(&seed) - 0.5};
    v3_scale(d, 1 / v3_norm(d));
    double h = 0.01;
    for (double t = -2; t <= 2; t += 0.05) {
      double am = tds_pg_star_area(&s.m, 0, d, t - h);
      double a0 = tds_pg_star_area(&s.m, 0, d, t);
      double ap = tds_pg_star_area(&s.m, 0, d, t + h);
      CHECK(am + ap - 2 * a0 >= -1e-12);
    }
    /* the model's derivatives match finite differences */
    double A0, A1, A2;
    tds_pg_star_model(&s.m, 0, d, &A0, &A1, &A2);
    double e = 1e-5;
    CHECK_NEAR(A0, tds_pg_star_area(&s.m, 0, d, 0), 1e-12);
    CHECK_NEAR(A1, (tds_pg_star_area(&s.m, 0, d, e) - tds_pg_star_area(&s.m, 0, d, -e)) / (2 * e), 1e-8);
    CHECK_NEAR(A2, (tds_pg_star_area(&s.m, 0, d, e) + tds_pg_star_area(&s.m, 0, d, -e) -
                    2 * A0) / (e * e), 1e-4);
    tds_surf_free(&s);
  }
}

/* Restricted Voronoi cells by numerical integration: the triangle split
** into n^2 small triangles, each given to the corner nearest its centroid. */
static void voronoi_numeric(const double p[3][3], int n, double area[3], double cen[3][3]) {
  for (int k = 0; k < 3; k++) {
    area[k] = 0;
    v3_zero(cen[k]);
  }
  double e1[3], e2[3], N[3];
  v3_sub(e1, p[1], p[0]);
  v3_sub(e2, p[2], p[0]);
  v3_cross(N, e1, e2);
  double da = 0.5 * v3_norm(N) / ((double)n * n);
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n - i; j++)
      for (int up = 0; up < 2; up++) {
        if (up && i + j == n - 1) continue;
        /* centroid of the small triangle in (u, v) units of 1/n */
        double u = up ? (i + 2.0 / 3) : (i + 1.0 / 3);
        double v = up ? (j + 2.0 / 3) : (j + 1.0 / 3);
        u /= n;
        v /= n;
        double q[3];
        for (int c = 0; c < 3; c++) q[c] = p[0][c] + u * e1[c] + v * e2[c];
        int best = 0;
        double bd = INFINITY;
        for (int k = 0; k < 3; k++) {
          double dd[3];
          v3_sub(dd, q, p[k]);
          double l = v3_dot(dd, dd);
          if (l < bd) {
            bd = l;
            best = k;
          }
        }
        area[best] += da;
        v3_axpy(cen[best], da, q);
      }
  for (int k = 0; k < 3; k++)
    if (area[k] > 0) v3_scale(cen[k], 1 / area[k]);
}

static void check_voronoi(const double p[3][3]) {
  double a[3], c[3][3], an[3], cn[3][3];
  tds_pg_voronoi(p, a, c);
  voronoi_numeric(p, 600, an, cn);
  double e1[3], e2[3], N[3];
  v3_sub(e1, p[1], p[0]);
  v3_sub(e2, p[2], p[0]);
  v3_cross(N, e1, e2);
  double A = 0.5 * v3_norm(N);
  CHECK_NEAR(a[0] + a[1] + a[2], A, 1e-12);
  for (int k = 0; k < 3; k++) {
    CHECK_NEAR(a[k] / A, an[k] / A, 3e-3);
    for (int i = 0; i < 3; i++) CHECK_NEAR(c[k][i], cn[k][i], 3e-3);
  }
}

static void test_voronoi(void) {
  double acute[3][3] = {{0, 0, 0}, {1, 0.1, 0.2}, {0.4, 0.9, -0.1}};
  double right[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 0.7, 0}};
  double obtuse[3][3] = {{0, 0, 0}, {1, 0, 0.1}, {-0.4, 0.3, 0.2}};
  double obtuse2[3][3] = {{0.3, 0.1, 0}, {-0.5, 0.05, 0}, {1.2, 0.0, 0.05}};
  check_voronoi(acute);
  check_voronoi(right);
  check_voronoi(obtuse);
  check_voronoi(obtuse2);
}

/* A strip of two triangles per test whose shared edge is not Delaunay. */
static void quad(tds_surf *s) {
  tds_surf_init(s);
  tds_mesh *m = &s->m;
  double p[4][3] = {{0, 0, 0}, {2, 0, 0}, {1, 0.2, 0}, {1, -0.2, 0}};
  for (int i = 0; i < 4; i++) tds_mesh_add_vertex(m, p[i]);
  add_tri(m, 0, 1, 2); /* edge 0-1 has opposite angles near pi each */
  add_tri(m, 1, 0, 3);
  tds_mesh_adjacency(m);
}

static tds_id edge_between(const tds_mesh *m, tds_id a, tds_id b) {
  for (tds_id e = 0; e < m->ne; e++)
    if ((m->ev[e][0] == a && m->ev[e][1] == b) || (m->ev[e][0] == b && m->ev[e][1] == a))
      return e;
  return TDS_NONE;
}

static void test_flip_rules(void) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  tds_surf s;
  int32_t n;
  /* plain: flips */
  quad(&s);
  CHECK(tds_pg_flip_all(&ctx, &s, &n) == TDS_OK);
  CHECK(n == 1);
  CHECK(edge_between(&s.m, 2, 3) != TDS_NONE);
  CHECK(tds_mesh_check(&ctx, &s.m) == TDS_OK);
  tds_surf_free(&s);
  /* fixed edge: no flip */
  quad(&s);
  s.m.eflags[edge_between(&s.m, 0, 1)] |= TDS_FIXED;
  CHECK(tds_pg_flip_all(&ctx, &s, &n) == TDS_OK);
  CHECK(n == 0);
  tds_surf_free(&s);
  /* edge on a constraint: no flip */
  quad(&s);
  tds_expr *f = NULL;
  CHECK(tds_model_compile(&ctx, &s, "z = 0", TDS_EXPR_FORMULA, &f) == TDS_OK);
  CHECK(tds_model_constraint(&ctx, &s, 1, 0, f, NULL, NULL) == TDS_OK);
  s.m.econ[edge_between(&s.m, 0, 1)] = 1;
  CHECK(tds_pg_flip_all(&ctx, &s, &n) == TDS_OK);
  CHECK(n == 0);
  tds_surf_free(&s);
  /* non-manifold edge (three facets): no flip */
  quad(&s);
  double p5[3] = {1, 0, 1};
  tds_mesh_add_vertex(&s.m, p5);
  add_tri(&s.m, 0, 1, 4);
  tds_mesh_adjacency(&s.m);
  CHECK(tds_pg_flip_all(&ctx, &s, &n) == TDS_OK);
  CHECK(n == 0);
  CHECK(edge_between(&s.m, 0, 1) != TDS_NONE);
  tds_surf_free(&s);
}

/* The octahedron's vertices all have k1 + k2 of the same value by
** symmetry, and a regular ring gives the cotangent formula's value. */
static void test_quality_metric(void) {
  tds_surf s;
  unsigned seed = 1;
  double c[3] = {0, 0, 0};
  one_ring(&s, 6, 0, &seed, c);
  tds_quality_out q;
  tds_quality(&s, &q);
  CHECK(q.n == 6);
  /* ring radius 1, centre 0.3 above: isosceles with apex angle 60 deg */
  double side = sqrt(1 + 0.09);
  double apex = 2 * asin(0.5 / side) * 180 / TDS_PI;
  CHECK_NEAR(q.min, apex, 1e-9);
  CHECK_NEAR(q.std, 0, 1e-6);
  tds_surf_free(&s);
}

/* The fused pass against the reference code: energy and gradient against
** tds_eval, the star model against tds_pg_star_model along the same
** direction, on a jittered cube body (face centres movable) with varied
** tensions, an edge tension, gravity, and a volume target or a pressure. */
static void check_probe(tds_ctx *ctx, tds_surf *s) {
  tds_mesh *m = &s->m;
  double (*g)[3] = calloc((size_t)m->nv, sizeof *g);
  double (*gp)[3] = calloc((size_t)m->nv, sizeof *gp);
  double (*dir)[3] = calloc((size_t)m->nv, sizeof *dir);
  double (*model)[3] = calloc((size_t)m->nv, sizeof *model);
  tds_eval_out out = {.grad = g};
  CHECK_OK(ctx, tds_eval(ctx, s, &out));
  double e;
  CHECK_OK(ctx, tds_pg_probe(ctx, s, &e, gp, dir, model));
  CHECK_NEAR(e, out.energy, 1e-13 * fabs(out.energy));
  int nmov = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (m->vflags[v] & TDS_FIXED) continue;
    nmov++;
    for (int i = 0; i < 3; i++) CHECK_NEAR(gp[v][i], g[v][i], 1e-13);
    CHECK_NEAR(v3_norm(dir[v]), 1, 1e-14);
    double A0, A1, A2;
    tds_pg_star_model(m, v, dir[v], &A0, &A1, &A2);
    CHECK_NEAR(model[v][0], A0, 1e-13);
    CHECK_NEAR(model[v][1], A1, 1e-13);
    CHECK_NEAR(model[v][2], A2, 1e-12 * (1 + fabs(A2)));
  }
  CHECK(nmov == 6);
  free(g);
  free(gp);
  free(dir);
  free(model);
}

static void test_fused_pass(void) {
  for (int variant = 0; variant < 3; variant++) {
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, h_cube(&ctx, &s, variant == 2 ? 0 : 1.1));
    tds_mesh *m = &s.m;
    for (tds_id v = 0; v < 8; v++) m->vflags[v] |= TDS_FIXED; /* corners */
    unsigned seed = 17 + variant;
    for (tds_id v = 0; v < m->nv; v++)
      for (int i = 0; i < 3; i++) m->x[v][i] += 0.1 * (urand(&seed) - 0.5);
    for (tds_id f = 0; f < m->nf; f++) m->ften[f] = 1 + 0.2 * (f % 4);
    m->eten[0] = 0.4;
    s.gravity_on = 1;
    s.gravity = 9.8;
    m->bdensity[0] = 0.7;
    s.symmetric_content = variant == 1;
    if (variant == 2) {
      m->bflags[0] |= TDS_PRESSURE;
      m->bpressure[0] = 0.3;
    }
    check_probe(&ctx, &s);
    tds_surf_free(&s);
  }
}

/* One pass of the method with the given threads and vector unit: energy,
** body volumes, per-vertex sums, gradients and constraint gradients, as
** one flat array (for bitwise comparison). */
static double *pass_snapshot(tds_ctx *ctx, tds_surf *s, int threads, int isa,
                             size_t *n) {
  pgw w;
  if (pg_work_init(ctx, s, &w, 0) != TDS_OK) return NULL;
  w.threads = threads;
  w.isa = pg_pass_isa(isa);
  double e;
  CHECK_OK(ctx, pg_pass(ctx, s, &w, &e));
  const tds_mesh *m = &s->m;
  size_t k = (size_t)m->nv * (sizeof(pg_acc) / sizeof(double) + 3) +
             3 * (size_t)w.fq.nent + (size_t)m->nb + 3 * (size_t)m->nf + 1;
  double *out = calloc(k, sizeof *out), *o = out;
  *o++ = e;
  for (tds_id b = 0; b < m->nb; b++) *o++ = m->bvol[b];
  for (tds_id v = 0; v < m->nv; v++) {
    memcpy(o, &w.acc[v], sizeof(pg_acc));
    o += sizeof(pg_acc) / sizeof(double);
    memcpy(o, w.grad[v], 3 * sizeof(double));
    o += 3;
  }
  for (int32_t i = 0; i < w.fq.nent; i++) {
    memcpy(o, w.fq.g[i], 3 * sizeof(double));
    o += 3;
  }
  memcpy(o, w.fcot, 3 * (size_t)m->nf * sizeof(double));
  o += 3 * (size_t)m->nf;
  *n = (size_t)(o - out);
  CHECK(w.nshared > 0 && w.half[1].i1 > w.half[1].i0); /* both halves used */
  pg_work_free(&w);
  return out;
}

/* The pass's results do not depend on the number of threads nor on the
** vector unit, to the last bit (two halves with their own sums at shared
** vertices; the same operations in the same order on every unit). A
** refined, jittered cube body with fixed corners, gravity, varied
** tensions; variants with a pressure (the scalar body path) and with
** symmetric content. */
static void test_pass_deterministic(void) {
  for (int variant = 0; variant < 3; variant++) {
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, h_cube(&ctx, &s, variant == 1 ? 0 : 1.1));
    tds_mesh *m = &s.m;
    for (tds_id v = 0; v < 8; v++) m->vflags[v] |= TDS_FIXED;
    REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
    REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
    REQUIRE_OK(&ctx, tds_mesh_adjacency(m));
    unsigned seed = 31 + variant;
    for (tds_id v = 0; v < m->nv; v++)
      for (int i = 0; i < 3; i++) m->x[v][i] += 0.05 * (urand(&seed) - 0.5);
    for (tds_id f = 0; f < m->nf; f++) m->ften[f] = 1 + 0.1 * (f % 3);
    m->ften[5] = 0; /* a tensionless facet */
    s.gravity_on = 1;
    s.gravity = 9.8;
    m->bdensity[0] = 0.7;
    s.symmetric_content = variant == 2;
    if (variant == 1) {
      m->bflags[0] |= TDS_PRESSURE;
      m->bpressure[0] = 0.3;
    }
    CHECK(m->nf >= 96);
    size_t n0 = 0, n;
    double *ref = pass_snapshot(&ctx, &s, 1, 0, &n0);
    for (int cfg = 1; cfg < 4; cfg++) {
      double *o = pass_snapshot(&ctx, &s, 1 + (cfg & 1), cfg >> 1, &n);
      CHECK(ref && o && n == n0 && memcmp(ref, o, n * sizeof *o) == 0);
      free(o);
    }
    free(ref);
    tds_surf_free(&s);
  }
}

/* Anderson mixing on a linear contraction X -> A X + b with eigenvalues
** up to 0.999: plain iteration needs tens of thousands of steps; the
** accelerated one reaches the fixed point to 1e-12 in far fewer. */
static void test_anderson_linear(void) {
  enum { N = 60 };
  double A[N][N], b[N], x[N], y[N];
  unsigned seed = 5;
  /* A = Q diag(l) Q^T with Q a product of random Householder reflections */
  double Q[N][N];
  for (int i = 0; i < N; i++)
    for (int j = 0; j < N; j++) Q[i][j] = i == j;
  for (int h = 0; h < 3; h++) {
    double u[N], un = 0;
    for (int i = 0; i < N; i++) {
      u[i] = urand(&seed) - 0.5;
      un += u[i] * u[i];
    }
    for (int i = 0; i < N; i++) u[i] /= sqrt(un);
    for (int i = 0; i < N; i++) {
      double d = 0;
      for (int k = 0; k < N; k++) d += Q[i][k] * u[k];
      for (int k = 0; k < N; k++) Q[i][k] -= 2 * d * u[k];
    }
  }
  for (int i = 0; i < N; i++)
    for (int j = 0; j < N; j++) {
      double t = 0;
      for (int k = 0; k < N; k++) t += Q[i][k] * (0.999 * k / (N - 1)) * Q[j][k];
      A[i][j] = t;
    }
  for (int i = 0; i < N; i++) b[i] = urand(&seed) - 0.5;
  pg_accel a;
  if (pg_accel_init(&a, NULL, N, 20) != TDS_OK) {
    CHECK(0);
    return;
  }
  for (int i = 0; i < N; i++) x[i] = 0;
  int it, mixed = 0;
  double res = 1;
  for (it = 0; it < 2000 && res > 1e-12; it++) {
    for (int i = 0; i < N; i++) {
      double t = b[i];
      for (int k = 0; k < N; k++) t += A[i][k] * x[k];
      y[i] = t;
    }
    res = 0;
    for (int i = 0; i < N; i++) res = fmax(res, fabs(y[i] - x[i]));
    memcpy(a.X, x, sizeof x);
    memcpy(a.G, y, sizeof y);
    mixed += pg_accel_mix(&a, 1e300);
    memcpy(x, a.X, sizeof x);
  }
  CHECK(res <= 1e-12);
  CHECK(it < 400);
  CHECK(mixed > 0);
  pg_accel_free(&a);
}

int main(void) {
  RUN(test_normal_independent);
  RUN(test_normal_root);
  RUN(test_convex);
  RUN(test_voronoi);
  RUN(test_flip_rules);
  RUN(test_quality_metric);
  RUN(test_fused_pass);
  RUN(test_anderson_linear);
  RUN(test_pass_deterministic);
  return check_done();
}
