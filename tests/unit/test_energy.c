/* test_energy.c: the geometry kernels (src/geom.h) and the assembled
** energy, gradient and constraint gradients of tds_eval (src/eval.h),
** checked against exact values and central differences. */
#include "helpers.h"

#include "eval.h"
#include "fixq.h"

/* Finite differences. Central differences with step h have truncation
** error h^2/6 f''' and rounding error about eps |f| / h. With h = 1e-6,
** coordinates of order 1 and well-shaped triangles (area >= 0.05, so the
** third derivatives of |N| stay below ~1e3), both are below ~1e-9 times
** the gradient scale; a tolerance of 1e-7 relative to the largest gradient
** component leaves a margin of 100 for rounding while any wrong term (of
** the order of the gradient itself) fails by orders of magnitude. */
#define FD_H 1e-6
#define FD_TOL 1e-7

typedef double (*kernel)(const double *, const double *, const double *,
                         double (*)[3]);

/* Compare the analytic gradient of kernel k at (a, b, c) with central
** differences; returns the worst error relative to the gradient scale. */
static double kernel_fd_error(kernel k, const double p[3][3]) {
  double g[3][3];
  k(p[0], p[1], p[2], g);
  double scale = 0;
  for (int j = 0; j < 3; j++)
    for (int i = 0; i < 3; i++)
      if (fabs(g[j][i]) > scale) scale = fabs(g[j][i]);
  if (scale < 1e-3) scale = 1e-3;
  double worst = 0;
  for (int j = 0; j < 3; j++)
    for (int i = 0; i < 3; i++) {
      double q[3][3];
      memcpy(q, p, sizeof q);
      q[j][i] = p[j][i] + FD_H;
      double fp = k(q[0], q[1], q[2], NULL);
      q[j][i] = p[j][i] - FD_H;
      double fm = k(q[0], q[1], q[2], NULL);
      double err = fabs((fp - fm) / (2 * FD_H) - g[j][i]) / scale;
      if (err > worst) worst = err;
    }
  return worst;
}

/* A random triangle in [-1, 1]^3 with area at least 0.05. */
static void random_triangle(uint64_t *st, double p[3][3]) {
  for (;;) {
    for (int j = 0; j < 3; j++)
      for (int i = 0; i < 3; i++) p[j][i] = h_uniform(st, -1, 1);
    if (geom_area(p[0], p[1], p[2], NULL) >= 0.05) return;
  }
}

static void kernels_fd(void) {
  static const struct {
    const char *name;
    kernel k;
  } ks[] = {{"area", geom_area},
            {"volume_z", geom_volume_z},
            {"volume_sym", geom_volume_sym},
            {"zmoment", geom_zmoment}};
  uint64_t st = 0x9E3779B97F4A7C15ULL;
  for (int n = 0; n < 4; n++) {
    double worst = 0;
    for (int t = 0; t < 200; t++) {
      double p[3][3];
      random_triangle(&st, p);
      double e = kernel_fd_error(ks[n].k, (const double (*)[3])p);
      if (e > worst) worst = e;
    }
    CHECK(worst < FD_TOL);
    if (!(worst < FD_TOL)) printf("  %s: worst relative error %g\n", ks[n].name, worst);
  }
}

/* The kernels' values against independent formulas on random triangles. */
static void kernels_values(void) {
  uint64_t st = 42;
  for (int t = 0; t < 100; t++) {
    double p[3][3];
    random_triangle(&st, p);
    const double *a = p[0], *b = p[1], *c = p[2];
    /* Heron */
    double la = 0, lb = 0, lc = 0;
    for (int i = 0; i < 3; i++) {
      la += (b[i] - c[i]) * (b[i] - c[i]);
      lb += (c[i] - a[i]) * (c[i] - a[i]);
      lc += (a[i] - b[i]) * (a[i] - b[i]);
    }
    la = sqrt(la), lb = sqrt(lb), lc = sqrt(lc);
    double sp = (la + lb + lc) / 2;
    double heron = sqrt(sp * (sp - la) * (sp - lb) * (sp - lc));
    CHECK_NEAR(geom_area(a, b, c, NULL), heron, 1e-12);
    /* the z-content is the signed volume of the prism down to z = 0:
    ** shifting all z by dz adds dz * (projected signed area) */
    double Nz = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    double q[3][3];
    memcpy(q, p, sizeof q);
    for (int j = 0; j < 3; j++) q[j][2] += 0.7;
    CHECK_NEAR(geom_volume_z(q[0], q[1], q[2], NULL) - geom_volume_z(a, b, c, NULL),
               0.7 * Nz / 2, 1e-14);
    /* the symmetric content is the signed volume of the cone to the origin:
    ** det[a b c] / 6 */
    double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0]);
    CHECK_NEAR(geom_volume_sym(a, b, c, NULL), det / 6, 1e-15);
    /* zmoment: the flux of (0, 0, z^2/2), the mean of z^2/2 over the
    ** triangle by the edge-midpoint rule (weights 1/3, exact for
    ** quadratics) times the projected area Nz/2 */
    double mz[3] = {(a[2] + b[2]) / 2, (b[2] + c[2]) / 2, (c[2] + a[2]) / 2};
    double quad = (mz[0] * mz[0] + mz[1] * mz[1] + mz[2] * mz[2]) / 3 / 2;
    CHECK_NEAR(geom_zmoment(a, b, c, NULL), quad * Nz / 2, 1e-14);
  }
}

/* Exact values and gradients on the unit right triangle. */
static void kernels_exact(void) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  double g[3][3];
  CHECK_NEAR(geom_area(a, b, c, g), 0.5, 1e-16);
  static const double ga[3][3] = {{-0.5, -0.5, 0}, {0.5, 0, 0}, {0, 0.5, 0}};
  for (int j = 0; j < 3; j++)
    for (int i = 0; i < 3; i++) CHECK_NEAR(g[j][i], ga[j][i], 1e-16);
  /* reversed orientation: same area, normal -z */
  CHECK_NEAR(geom_area(a, c, b, NULL), 0.5, 1e-16);

  /* in z = 0 the z-content and z-moment vanish; their z-gradients are the
  ** projected area / 3 and 0 */
  CHECK_NEAR(geom_volume_z(a, b, c, g), 0, 1e-16);
  for (int j = 0; j < 3; j++) {
    CHECK_NEAR(g[j][0], 0, 1e-16);
    CHECK_NEAR(g[j][1], 0, 1e-16);
    CHECK_NEAR(g[j][2], 1.0 / 6, 1e-16);
  }
  CHECK_NEAR(geom_zmoment(a, b, c, g), 0, 1e-16);
  for (int j = 0; j < 3; j++)
    for (int i = 0; i < 3; i++) CHECK_NEAR(g[j][i], 0, 1e-16);

  /* lifted to z = 1: prism volume 1/2, cone volume 1/6, flux of z^2/2
  ** through area 1/2 is 1/4; reversed, all change sign */
  const double A[3] = {0, 0, 1}, B[3] = {1, 0, 1}, C[3] = {0, 1, 1};
  CHECK_NEAR(geom_volume_z(A, B, C, g), 0.5, 1e-16);
  CHECK_NEAR(g[0][0], -0.5, 1e-16); /* dV/dxa = zs/6 (yb - yc) */
  CHECK_NEAR(g[0][1], -0.5, 1e-16);
  CHECK_NEAR(g[1][0], 0.5, 1e-16);
  CHECK_NEAR(g[2][1], 0.5, 1e-16);
  CHECK_NEAR(geom_volume_z(A, C, B, NULL), -0.5, 1e-16);
  CHECK_NEAR(geom_volume_sym(A, B, C, g), 1.0 / 6, 1e-16);
  static const double gs[3][3] = {{-1, -1, 1}, {1, 0, 0}, {0, 1, 0}};
  for (int j = 0; j < 3; j++)
    for (int i = 0; i < 3; i++) CHECK_NEAR(g[j][i], gs[j][i] / 6, 1e-16);
  CHECK_NEAR(geom_volume_sym(A, C, B, NULL), -1.0 / 6, 1e-16);
  CHECK_NEAR(geom_zmoment(A, B, C, g), 0.25, 1e-16);
  for (int j = 0; j < 3; j++) CHECK_NEAR(g[j][2], 1.0 / 6, 1e-16); /* Nz/24 * 4 */
  CHECK_NEAR(geom_zmoment(A, C, B, NULL), -0.25, 1e-16);

  /* degenerate: zero area, zero (not NaN) gradient */
  const double d[3] = {2, 0, 0};
  CHECK(geom_area(a, b, d, g) == 0);
  for (int j = 0; j < 3; j++)
    for (int i = 0; i < 3; i++) CHECK(g[j][i] == 0);
}

/* ---- the assembled energy ---- */

/* Move every vertex of the cube by up to +-amp (deterministic). */
static void jitter(tds_mesh *m, double amp, uint64_t seed) {
  uint64_t st = seed;
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) m->x[v][i] += h_uniform(&st, -amp, amp);
  m->coord_gen++;
}

/* Energy only. */
static double energy_at(tds_ctx *ctx, tds_surf *s) {
  tds_eval_out out = {0};
  int rc = tds_eval(ctx, s, &out);
  CHECK(rc == TDS_OK);
  return out.energy;
}

/* Worst error of out.grad against central differences of out.energy,
** relative to the largest gradient component. */
static double grad_fd_error(tds_ctx *ctx, tds_surf *s) {
  tds_mesh *m = &s->m;
  double (*g)[3] = calloc((size_t)m->nv, sizeof *g);
  if (!g) return INFINITY;
  tds_eval_out out = {.grad = g};
  CHECK(tds_eval(ctx, s, &out) == TDS_OK);
  double scale = 0, worst = 0;
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++)
      if (fabs(g[v][i]) > scale) scale = fabs(g[v][i]);
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) {
      double x0 = m->x[v][i];
      m->x[v][i] = x0 + FD_H;
      double ep = energy_at(ctx, s);
      m->x[v][i] = x0 - FD_H;
      double em = energy_at(ctx, s);
      m->x[v][i] = x0;
      double err = fabs((ep - em) / (2 * FD_H) - g[v][i]) / scale;
      if (err > worst) worst = err;
    }
  free(g);
  return worst;
}

/* Cube, body of density 1 under gravity 9.8, a prescribed pressure.
** Returns TDS_OK or the builder's status. */
static int cube_setup(tds_ctx *ctx, tds_surf *s) {
  h_setup(ctx, s);
  int rc = h_cube(ctx, s, 0);
  if (rc != TDS_OK) return rc;
  s->gravity_on = 1;
  s->gravity = 9.8;
  s->m.bdensity[0] = 1;
  s->m.bflags[0] |= TDS_PRESSURE;
  s->m.bpressure[0] = 0.7;
  return TDS_OK;
}

static void eval_cube_exact(void) {
  tds_ctx ctx;
  tds_surf s;
  REQUIRE_OK(&ctx, cube_setup(&ctx, &s));
  double g[14][3];
  tds_eval_out out = {.grad = g};
  CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
  /* area 6, G rho int z dV = 9.8 * 1/2, -p V = -0.7 */
  CHECK_NEAR(out.area, 6, 1e-15);
  CHECK_NEAR(s.m.bvol[0], 1, 1e-15);
  CHECK_NEAR(out.energy, 6 + 4.9 - 0.7, 1e-14);
  /* gravity off: the weight goes */
  s.gravity_on = 0;
  CHECK_NEAR(energy_at(&ctx, &s), 6 - 0.7, 1e-14);
  /* At a face centre (a flat star covering the whole unit face) the area
  ** gradient vanishes; moving it along the outward normal n by t changes
  ** V by t/3 and int z dV by t * int z phi dA = t * zc / 3 (phi the hat
  ** function, symmetric about the centre's height zc). So grad =
  ** n * (-p/3 + G zc/3). Face 1 (y = 0, n = -y, zc = 1/2): vertex 9;
  ** face 5 (z = 1, n = +z): vertex 13; face 6 (z = 0, n = -z): 14. */
  s.gravity_on = 1;
  CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
  const double want[3][3] = {{0, 0.7 / 3 - 9.8 * 0.5 / 3, 0},
                             {0, 0, -0.7 / 3 + 9.8 / 3},
                             {0, 0, 0.7 / 3}};
  const int cv[3] = {8, 12, 13};
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 3; i++) CHECK_NEAR(g[cv[k]][i], want[k][i], 1e-14);
  tds_surf_free(&s);
}

static void eval_cube_gradient(void) {
  for (int sym = 0; sym < 2; sym++) {
    tds_ctx ctx;
    tds_surf s;
    REQUIRE_OK(&ctx, cube_setup(&ctx, &s));
    s.symmetric_content = sym;
    tds_mesh *m = &s.m;
    for (tds_id f = 0; f < m->nf; f++) m->ften[f] = 1 + 0.15 * (f % 5);
    m->eten[0] = 0.3; /* and one edge with a tension */
    jitter(m, 0.08, 7 + sym);
    double err = grad_fd_error(&ctx, &s);
    CHECK(err < FD_TOL);
    if (!(err < FD_TOL)) printf("  sym %d: worst relative error %g\n", sym, err);
    /* each term alone, so one cannot hide another */
    m->bflags[0] &= ~(uint32_t)TDS_PRESSURE;
    err = grad_fd_error(&ctx, &s);
    CHECK(err < FD_TOL);
    s.gravity_on = 0;
    m->bflags[0] |= TDS_PRESSURE;
    for (tds_id f = 0; f < m->nf; f++) m->ften[f] = 0;
    m->eten[0] = 0;
    err = grad_fd_error(&ctx, &s);
    CHECK(err < FD_TOL);
    tds_surf_free(&s);
  }
}

/* Volume gradients in the fixed-quantity store against differences of
** m.bvol, in both contents. */
static void eval_cube_volume_gradient(void) {
  for (int sym = 0; sym < 2; sym++) {
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
    s.symmetric_content = sym;
    tds_mesh *m = &s.m;
    jitter(m, 0.08, 99 + sym);
    CHECK_OK(&ctx, tds_mesh_adjacency(m));
    tds_fixq fq = {0};
    CHECK_OK(&ctx, tds_fixq_build(&ctx, &s, &fq));
    CHECK(fq.nq == 1 && fq.qbody[0] == 0 && fq.bq[0] == 0);
    CHECK_NEAR(fq.target[0], 1, 0);
    tds_eval_out out = {.fq = &fq};
    CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
    CHECK(fq.value[0] == m->bvol[0]);
    double V0 = m->bvol[0];
    CHECK(fabs(V0 - 1) > 1e-4); /* the jitter changed it */
    double scale = 0, worst = 0;
    for (int32_t i = 0; i < fq.nent; i++)
      for (int k = 0; k < 3; k++)
        if (fabs(fq.g[i][k]) > scale) scale = fabs(fq.g[i][k]);
    CHECK(scale > 0.1);
    for (tds_id v = 0; v < m->nv; v++) {
      double gv[3] = {0, 0, 0};
      int nent = 0;
      for (int32_t i = fq.start[v]; i < fq.start[v + 1]; i++) {
        CHECK(fq.eq[i] == 0);
        v3_add(gv, gv, fq.g[i]);
        nent++;
      }
      CHECK(nent == 1); /* every vertex touches the body */
      for (int i = 0; i < 3; i++) {
        double x0 = m->x[v][i];
        m->x[v][i] = x0 + FD_H;
        energy_at(&ctx, &s);
        double vp = m->bvol[0];
        m->x[v][i] = x0 - FD_H;
        energy_at(&ctx, &s);
        double vm = m->bvol[0];
        m->x[v][i] = x0;
        double err = fabs((vp - vm) / (2 * FD_H) - gv[i]) / scale;
        if (err > worst) worst = err;
      }
    }
    CHECK(worst < FD_TOL);
    if (!(worst < FD_TOL)) printf("  sym %d: worst relative error %g\n", sym, worst);
    tds_fixq_free(&fq);
    tds_surf_free(&s);
  }
}

/* Closed surfaces: the z-content and the symmetric content agree. */
static void closed_contents_agree(void) {
  static const double shift[3] = {0.3, -0.2, 0.7};
  for (int shape = 0; shape < 2; shape++)
    for (int jit = 0; jit < 2; jit++) {
      tds_ctx ctx;
      tds_surf s;
      h_setup(&ctx, &s);
      if (shape == 0)
        REQUIRE_OK(&ctx, h_tetra(&ctx, &s, NULL));
      else
        REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
      for (tds_id v = 0; v < s.m.nv; v++) v3_add(s.m.x[v], s.m.x[v], shift);
      if (jit) jitter(&s.m, 0.05, 3);
      CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
      double vz = s.m.bvol[0];
      s.symmetric_content = 1;
      CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
      double vs = s.m.bvol[0];
      CHECK_NEAR(vz, vs, 1e-14);
      if (!jit) CHECK_NEAR(vz, shape ? 1.0 : 1.0 / 6, 1e-14);
      tds_surf_free(&s);
    }
}

/* A face listed negatively in a body (facet's back body) counts with a
** minus sign: a tetrahedron declared with reversed faces has volume 1/6
** as the back body. */
static void back_body_sign(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  static const double t[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  static const int ev[6][2] = {{1, 2}, {2, 3}, {3, 1}, {1, 4}, {2, 4}, {3, 4}};
  /* the faces of h_tetra, each loop reversed: normals point inwards */
  static const int loops[] = {1, 2, 3, 0, 4, -5, -1, 0, -3, 6, -4, 0, 5, -6, -2, 0};
  REQUIRE_OK(&ctx, h_mesh(&ctx, &s, 4, t, 6, ev, 4, loops));
  int32_t faces[4] = {-1, -2, -3, -4};
  CHECK_OK(&ctx, tds_decl_body(&ctx, &s, 0, 4, faces));
  CHECK_MESH(&ctx, &s.m);
  for (tds_id f = 0; f < 4; f++) CHECK(s.m.fb[f][0] == TDS_NONE && s.m.fb[f][1] == 0);
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK_NEAR(s.m.bvol[0], 1.0 / 6, 1e-15);
  /* and the gradient with a pressure on the back body */
  s.m.bflags[0] |= TDS_PRESSURE;
  s.m.bpressure[0] = 1.3;
  jitter(&s.m, 0.05, 5);
  double err = grad_fd_error(&ctx, &s);
  CHECK(err < FD_TOL);
  tds_surf_free(&s);
}

int main(void) {
  RUN(kernels_fd);
  RUN(kernels_values);
  RUN(kernels_exact);
  RUN(eval_cube_exact);
  RUN(eval_cube_gradient);
  RUN(eval_cube_volume_gradient);
  RUN(closed_contents_agree);
  RUN(back_body_sign);
  return check_done();
}
