/* test_export.c: caps and the small tables of export.
** Caps: a cone over a random star-shaped (non-convex) polygon, rotated at
** random, is open at its base; the caps must add n - 2 triangles that all
** face away from the apex, whose areas sum to the polygon's area (1e-12
** relative: a cap that overlaps itself or flips a triangle adds area), and
** leave every edge in two triangles, once each way. */
#include <stdlib.h>

#include <math.h>
#include <stdio.h>
#include <unistd.h>

#include "check.h"
#include "export_int.h"
#include "helpers.h"

static double rnd(unsigned *s) {
  *s = *s * 1103515245u + 12345u;
  return ((*s >> 8) & 0xffffff) / (double)0x1000000;
}

/* Rotate p by the rotation taking e_z to unit axis a (Rodrigues). */
static void rotate(double p[3], const double a[3]) {
  double z[3] = {0, 0, 1}, k[3];
  v3_cross(k, z, a);
  double s = v3_norm(k), c = a[2];
  if (s < 1e-12) return;
  v3_scale(k, 1 / s);
  double kxp[3], r[3];
  v3_cross(kxp, k, p);
  double kp = v3_dot(k, p);
  for (int i = 0; i < 3; i++) r[i] = p[i] * c + kxp[i] * s + k[i] * kp * (1 - c);
  for (int i = 0; i < 3; i++) p[i] = r[i];
}

static void cone_case(unsigned seed, int n) {
  unsigned s = seed;
  xmesh x;
  memset(&x, 0, sizeof x);
  x.nv = n + 1;
  x.nt = n;
  x.x = calloc((size_t)x.nv, sizeof *x.x);
  x.tri = calloc((size_t)(6 * n + 1), sizeof *x.tri);
  double axis[3] = {rnd(&s) - 0.5, rnd(&s) - 0.5, rnd(&s) - 0.5};
  v3_scale(axis, 1 / v3_norm(axis));
  double area2d = 0;
  for (int i = 0; i < n; i++) { /* star: radius 0.3..1 at increasing angles */
    double t = 2 * TDS_PI * (i + 0.4 * rnd(&s)) / n, r = 0.3 + 0.7 * rnd(&s);
    x.x[i][0] = r * cos(t);
    x.x[i][1] = r * sin(t);
  }
  for (int i = 0; i < n; i++) {
    const double *a = x.x[i], *b = x.x[(i + 1) % n];
    area2d += 0.5 * (a[0] * b[1] - a[1] * b[0]);
  }
  x.x[n][2] = 1; /* apex */
  for (int i = 0; i <= n; i++) rotate(x.x[i], axis);
  for (int i = 0; i < n; i++) { /* outward sides: apex, a, b */
    x.tri[i][0] = n;
    x.tri[i][1] = i;
    x.tri[i][2] = (i + 1) % n;
  }
  int32_t ncap = -1;
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  CHECK(tds_export_caps(&ctx, &x, &ncap) == TDS_OK);
  CHECK(ncap == n - 2);
  double sum = 0;
  int flipped = 0;
  for (int32_t t = n; t < x.nt; t++) {
    double nn[3], u[3], v[3];
    v3_sub(u, x.x[x.tri[t][1]], x.x[x.tri[t][0]]);
    v3_sub(v, x.x[x.tri[t][2]], x.x[x.tri[t][0]]);
    v3_cross(nn, u, v);
    sum += 0.5 * v3_norm(nn);
    if (!(v3_dot(nn, axis) < 0)) flipped++; /* must face away from the apex */
  }
  CHECK(flipped == 0);
  CHECK_NEAR(sum, area2d, 1e-12);
  /* every edge twice, once each way */
  int bad = 0;
  for (int32_t t = 0; t < x.nt; t++)
    for (int k = 0; k < 3; k++) {
      int32_t a = x.tri[t][k], b = x.tri[t][(k + 1) % 3], same = 0, opp = 0;
      for (int32_t u = 0; u < x.nt; u++)
        for (int j = 0; j < 3; j++) {
          int32_t c = x.tri[u][j], d = x.tri[u][(j + 1) % 3];
          same += c == a && d == b;
          opp += c == b && d == a;
        }
      bad += same != 1 || opp != 1;
    }
  CHECK(bad == 0);
  free(x.x);
  free(x.tri);
}

/* Every edge of x in exactly two triangles, once each way. */
static int watertight(const xmesh *x) {
  int bad = 0;
  for (int32_t t = 0; t < x->nt; t++)
    for (int k = 0; k < 3; k++) {
      int32_t a = x->tri[t][k], b = x->tri[t][(k + 1) % 3], same = 0, opp = 0;
      for (int32_t u = 0; u < x->nt; u++)
        for (int j = 0; j < 3; j++) {
          int32_t c = x->tri[u][j], d = x->tri[u][(j + 1) % 3];
          same += c == a && d == b;
          opp += c == b && d == a;
        }
      bad += same != 1 || opp != 1;
    }
  return bad == 0;
}

/* Append triangle abc oriented so that its normal has a positive
** component along dir. */
static void tri_out(xmesh *x, int32_t a, int32_t b, int32_t c, const double dir[3]) {
  double u[3], v[3], n[3];
  v3_sub(u, x->x[b], x->x[a]);
  v3_sub(v, x->x[c], x->x[a]);
  v3_cross(n, u, v);
  int flip = v3_dot(n, dir) < 0;
  x->tri[x->nt][0] = a;
  x->tri[x->nt][1] = flip ? c : b;
  x->tri[x->nt][2] = flip ? b : c;
  x->nt++;
}

/* A ring-shaped solid (star-shaped outer and inner rims at random radii,
** walls, a flat top) open at the bottom: the two bottom loops lie in one
** plane with opposite orientations, so the cap is one ring: n_outer +
** n_inner triangles (one polygon joined by a bridge), area = outer area
** - inner area (1e-12; two separate discs would add the inner area), the
** result closed with Euler characteristic 0 (a torus). */
static void ring_case(unsigned seed) {
  unsigned s = seed;
  int n = 5 + (int)(seed % 17);
  xmesh x;
  memset(&x, 0, sizeof x);
  x.nv = 4 * n;
  x.x = calloc((size_t)x.nv, sizeof *x.x);
  x.tri = calloc((size_t)(6 * 8 * n + 1), sizeof *x.tri);
  double axis[3] = {rnd(&s) - 0.5, rnd(&s) - 0.5, rnd(&s) - 0.5};
  v3_scale(axis, 1 / v3_norm(axis));
  /* vertices: outer bottom 0..n-1, outer top n.., inner bottom 2n.., inner top 3n.. */
  for (int i = 0; i < n; i++) {
    double t = 2 * TDS_PI * (i + 0.4 * rnd(&s)) / n;
    double ro = 2 + rnd(&s), ri = 0.5 + 0.5 * rnd(&s);
    double P[4][3] = {{ro * cos(t), ro * sin(t), 0}, {ro * cos(t), ro * sin(t), 1},
                      {ri * cos(t), ri * sin(t), 0}, {ri * cos(t), ri * sin(t), 1}};
    for (int k = 0; k < 4; k++) memcpy(x.x[k * n + i], P[k], sizeof P[k]);
  }
  double area = 0;
  for (int i = 0; i < n; i++) {
    int j = (i + 1) % n;
    area += 0.5 * (x.x[i][0] * x.x[j][1] - x.x[i][1] * x.x[j][0]);
    area -= 0.5 * (x.x[2 * n + i][0] * x.x[2 * n + j][1] - x.x[2 * n + i][1] * x.x[2 * n + j][0]);
  }
  for (int i = 0; i < n; i++) {
    int j = (i + 1) % n;
    double mid[3], in[3], up[3] = {0, 0, 1};
    for (int c = 0; c < 3; c++) mid[c] = 0.5 * (x.x[i][c] + x.x[j][c]);
    mid[2] = 0;
    for (int c = 0; c < 3; c++) in[c] = -mid[c];
    tri_out(&x, i, j, n + j, mid); /* outer wall, facing out */
    tri_out(&x, i, n + j, n + i, mid);
    tri_out(&x, 2 * n + i, 2 * n + j, 3 * n + j, in); /* inner wall, facing the axis */
    tri_out(&x, 2 * n + i, 3 * n + j, 3 * n + i, in);
    tri_out(&x, n + i, n + j, 3 * n + j, up); /* top */
    tri_out(&x, n + i, 3 * n + j, 3 * n + i, up);
  }
  int32_t nt0 = x.nt, ncap = -1;
  for (int i = 0; i < x.nv; i++) rotate(x.x[i], axis);
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  CHECK(tds_export_caps(&ctx, &x, &ncap) == TDS_OK);
  CHECK(ncap == 2 * n);
  double sum = 0;
  int flipped = 0;
  for (int32_t t = nt0; t < x.nt; t++) {
    double nn[3], u[3], v[3];
    v3_sub(u, x.x[x.tri[t][1]], x.x[x.tri[t][0]]);
    v3_sub(v, x.x[x.tri[t][2]], x.x[x.tri[t][0]]);
    v3_cross(nn, u, v);
    sum += 0.5 * v3_norm(nn);
    if (!(v3_dot(nn, axis) < 0)) flipped++; /* facing down, out of the solid */
  }
  CHECK(flipped == 0);
  CHECK_NEAR(sum, area, 1e-12);
  CHECK(watertight(&x));
  /* V - E + F = 0; every edge is in two triangles, so E = 3F/2 */
  CHECK(x.nv - 3 * x.nt / 2 + x.nt == 0);
  free(x.x);
  free(x.tri);
}

static void test_caps_ring(void) {
  for (unsigned seed = 1; seed <= 30; seed++) ring_case(seed);
}

static void test_caps_star(void) {
  for (unsigned seed = 1; seed <= 40; seed++) cone_case(seed, 5 + (int)(seed % 23));
}

static void test_caps_closed(void) { /* a closed tetrahedron needs no cap */
  xmesh x;
  memset(&x, 0, sizeof x);
  double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  int32_t t[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  x.nv = 4;
  x.nt = 4;
  x.x = p;
  x.tri = calloc(25, sizeof *x.tri);
  memcpy(x.tri, t, sizeof t);
  int32_t ncap = -1;
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  CHECK(tds_export_caps(&ctx, &x, &ncap) == TDS_OK);
  CHECK(ncap == 0 && x.nt == 4);
  free(x.tri);
}

static void test_tables(void) {
  unsigned char c[4];
  tds_export_rgba(-1, c);
  CHECK(c[3] == 0);
  tds_export_rgba(4, c); /* RED */
  CHECK(c[0] == 170 && c[1] == 0 && c[2] == 0 && c[3] == 255);
  tds_export_rgba(15, c); /* WHITE */
  CHECK(c[0] == 255 && c[1] == 255 && c[2] == 255);
  tds_export_rgba(16 + 14, c); /* wraps to YELLOW */
  CHECK(c[0] == 255 && c[1] == 255 && c[2] == 85);
  CHECK(tds_export_format_of("a/b.PLY") == TDS_FMT_PLY);
  CHECK(tds_export_format_of("x.msh") == TDS_FMT_MSH);
  CHECK(tds_export_format_of("dir.stl/file") == -1);
  CHECK(tds_export_format_of("file.stlx") == -1);
  CHECK(tds_export_format_of("noext") == -1);
}

/* A coordinate that is not finite (the Lua setters refuse one, so only the
** core can make it) is refused with TDS_ENUM naming the vertex, and no file
** or temporary is left. */
static void test_nonfinite_refused(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  CHECK(h_triangle(&ctx, &s) == TDS_OK);
  s.m.x[1][0] = NAN;
  char dir[] = "/tmp/tds_export_XXXXXX";
  CHECK(mkdtemp(dir) != NULL);
  char path[64];
  snprintf(path, sizeof path, "%s/t.obj", dir);
  tds_export_opts o;
  memset(&o, 0, sizeof o);
  o.format = TDS_FMT_OBJ;
  CHECK(tds_export(&ctx, &s, path, &o) == TDS_ENUM);
  CHECK(strstr(ctx.errmsg, "vertex 2") != NULL);
  CHECK(access(path, F_OK) != 0);
  CHECK(rmdir(dir) == 0); /* empty: no temporary left behind */
  tds_surf_free(&s);
}

int main(void) {
  RUN(test_nonfinite_refused);
  RUN(test_caps_star);
  RUN(test_caps_ring);
  RUN(test_caps_closed);
  RUN(test_tables);
  return check_done();
}
