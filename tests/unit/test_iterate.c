/* test_iterate.c: gradient descent (tds_iterate, src/iterate.h) on the
** cube of volume 1, against Surface Evolver's numbers. */
#include "helpers.h"

#include "eval.h"
#include "iterate.h"
#include "metrics.h"
#include "stall.h"

/* The cube of scripts/cube.tds with volume target 1, unmoved; energy,
** area and volume computed. TDS_OK or the failing status. */
static int cube(tds_ctx *ctx, tds_surf *s) {
  h_setup(ctx, s);
  int rc = h_cube(ctx, s, 1);
  return rc ? rc : tds_surf_update(ctx, s);
}

/* `g 5` on cube.fe: Evolver prints energy 5.11249312772740 after the
** fifth step (tds reproduces the same sequence of scales). Evolver's
** pressure line lags one iteration (3.40832875181479), so the pressure,
** a Lagrange multiplier computed at the start of a step, gets 1e-6. */
static void cube_g5(void) {
  tds_ctx ctx;
  tds_surf s;
  REQUIRE_OK(&ctx, cube(&ctx, &s));
  CHECK_NEAR(s.energy, 6, 1e-15);
  CHECK_OK(&ctx, tds_iterate(&ctx, &s, 5));
  CHECK(s.iterations == 5);
  CHECK_MESH(&ctx, &s.m);
  CHECK(fabs(s.energy - 5.11249312772740) <= 1e-10 * 5.11249312772740);
  CHECK_NEAR(s.m.bvol[0], 1, 1e-12);
  CHECK_NEAR(s.m.bpressure[0], 3.40832875, 1e-6);
  /* s.energy is the energy at the final positions */
  tds_eval_out out = {0};
  CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
  CHECK_NEAR(out.energy, s.energy, 1e-15);
  CHECK_NEAR(out.area, s.area, 1e-15);
  tds_surf_free(&s);
}

/* Ctrl-C: one step completes, then TDS_EINTR with the surface intact. */
static void cube_interrupt(void) {
  tds_ctx ctx, ctx1;
  tds_surf s, s1;
  REQUIRE_OK(&ctx, cube(&ctx, &s));
  ctx.interrupt = 1;
  int rc = tds_iterate(&ctx, &s, 100);
  CHECK(rc == TDS_EINTR);
  CHECK(strstr(ctx.errmsg, "1 of 100") != NULL);
  CHECK(ctx.interrupt == 0); /* consumed */
  CHECK(s.iterations == 1);
  CHECK_MESH(&ctx, &s.m);
  CHECK_NEAR(s.m.bvol[0], 1, 1e-12);

  REQUIRE_OK(&ctx1, cube(&ctx1, &s1));
  CHECK_OK(&ctx1, tds_iterate(&ctx1, &s1, 1));
  CHECK(s1.iterations == 1);
  CHECK(s.energy == s1.energy);
  CHECK(s.scale == s1.scale);
  CHECK(s.m.bpressure[0] == s1.m.bpressure[0]);
  int same = s.m.nv == s1.m.nv;
  for (tds_id v = 0; same && v < s.m.nv; v++)
    for (int i = 0; i < 3; i++) same &= s.m.x[v][i] == s1.m.x[v][i];
  CHECK(same);
  CHECK(s.energy < 6);
  /* and it can go on: the next steps behave like a run of 5 */
  CHECK_OK(&ctx, tds_iterate(&ctx, &s, 4));
  CHECK(fabs(s.energy - 5.11249312772740) <= 1e-10 * 5.11249312772740);
  tds_surf_free(&s);
  tds_surf_free(&s1);
}

/* With a fixed scale (Evolver's `m 0.01`) every step lowers the energy,
** keeps the volume and moves by the given scale. */
static void cube_fixed_scale(void) {
  tds_ctx ctx;
  tds_surf s;
  REQUIRE_OK(&ctx, cube(&ctx, &s));
  s.fixed_scale = 1;
  s.scale = 0.01;
  double prev = s.energy;
  int down = 1;
  for (int i = 0; i < 10; i++) {
    CHECK_OK(&ctx, tds_iterate(&ctx, &s, 1));
    if (!(s.energy < prev)) {
      down = 0;
      printf("  step %d: energy %.17g after %.17g\n", i + 1, s.energy, prev);
    }
    prev = s.energy;
    CHECK_NEAR(s.m.bvol[0], 1, 1e-12);
  }
  CHECK(down);
  CHECK(s.scale == 0.01);
  CHECK(s.iterations == 10);
  /* small steps: still well above the optimizing run's 5 steps */
  CHECK(s.energy > 5.11249312772740 && s.energy < 6);
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);
}

/* Fixed vertices stay where they are. */
static void cube_fixed_vertex(void) {
  tds_ctx ctx;
  tds_surf s;
  REQUIRE_OK(&ctx, cube(&ctx, &s));
  s.m.vflags[0] |= TDS_FIXED;
  s.m.vflags[8] |= TDS_FIXED; /* a face centre */
  double x0[3], x8[3];
  v3_copy(x0, s.m.x[0]);
  v3_copy(x8, s.m.x[8]);
  CHECK_OK(&ctx, tds_iterate(&ctx, &s, 5));
  for (int i = 0; i < 3; i++) {
    CHECK(s.m.x[0][i] == x0[i]);
    CHECK(s.m.x[8][i] == x8[i]);
  }
  CHECK(s.m.x[6][0] != 1); /* the opposite corner did move */
  CHECK_NEAR(s.m.bvol[0], 1, 1e-12);
  tds_surf_free(&s);
}

/* Pressures without moving: the multiplier that makes grad E - p grad V
** orthogonal to grad V, the same the first step computes. */
static void cube_pressures(void) {
  tds_ctx ctx;
  tds_surf s;
  REQUIRE_OK(&ctx, cube(&ctx, &s));
  tds_mesh *m = &s.m;
  /* off the symmetric shape, so that every gradient is nonzero */
  uint64_t st = 11;
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) m->x[v][i] += h_uniform(&st, -0.05, 0.05);
  double x[14][3];
  memcpy(x, m->x, sizeof x);
  CHECK_OK(&ctx, tds_pressures(&ctx, &s));
  CHECK(memcmp(x, m->x, sizeof x) == 0);
  double p = m->bpressure[0];
  /* of the order of dA/dV = 4 for a uniformly scaled cube (A = 6 V^(2/3)) */
  CHECK(p > 2 && p < 4);
  double gA[14][3];
  tds_fixq fq = {0};
  CHECK_OK(&ctx, tds_mesh_adjacency(m));
  CHECK_OK(&ctx, tds_fixq_build(&ctx, &s, &fq));
  tds_eval_out out = {.grad = gA, .fq = &fq};
  CHECK_OK(&ctx, tds_eval(&ctx, &s, &out));
  double dot = 0, norm = 0;
  for (tds_id v = 0; v < m->nv; v++)
    for (int32_t i = fq.start[v]; i < fq.start[v + 1]; i++)
      for (int k = 0; k < 3; k++) {
        dot += (gA[v][k] - p * fq.g[i][k]) * fq.g[i][k];
        norm += gA[v][k] * fq.g[i][k];
      }
  CHECK(norm > 0.1);
  CHECK(fabs(dot) <= 1e-13 * norm);
  tds_fixq_free(&fq);
  /* the first step stores the pressure it computed before moving */
  CHECK_OK(&ctx, tds_iterate(&ctx, &s, 1));
  CHECK_NEAR(m->bpressure[0], p, 1e-14);
  tds_surf_free(&s);
}

/* The stall scan (stall.h) on a jittered grid: its smallest angle, found
** from sines, is the quality metric's (acos of normalised dot products) to
** 1e-9 degrees and names the same facet; nothing is degenerate. A vertex
** moved onto the line of a facet's other two corners makes that facet the
** worst, degenerate (angle below 1e-3 degrees). The collapse test: never
** with a fixed scale, not with a small force, yes with a tiny scale and a
** large force. */
static void stall_scan(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_grid(&ctx, &s, 6, 0.3, 7));
  tds_mesh *m = &s.m;
  tds_stall_out o;
  tds_stall_scan(&s, &o);
  double mn = INFINITY;
  tds_id worst = TDS_NONE;
  for (tds_id f = 0; f < m->nf; f++) {
    double a = tds_facet_min_angle(m, f);
    if (a < mn) mn = a, worst = f;
  }
  CHECK(o.worst == worst);
  CHECK_NEAR(o.angle, mn, 1e-9);
  CHECK(!o.degenerate);
  CHECK_NEAR(o.mean_area, 1.0 / 2, 1e-12); /* 72 facets tile the 6 x 6 square */
  /* facet 0 is (0,0) (1,0) v; v = vertex (1,1) onto the x axis */
  tds_id v = 1 + 7 * 1;
  m->x[v][0] = 0.5, m->x[v][1] = 1e-13;
  m->coord_gen++;
  tds_stall_scan(&s, &o);
  CHECK(o.worst == 0);
  CHECK(o.degenerate);
  CHECK(o.angle < 1e-3);
  CHECK(tds_stall_facet(&o) == 0);
  s.scale_limit = 1;
  s.fixed_scale = 1, s.scale = 0;
  CHECK(!tds_stall_collapsed(&s, -1, 1));
  s.fixed_scale = 0, s.scale = 1e-9;
  CHECK(tds_stall_collapsed(&s, -1e-3, 1));
  CHECK(!tds_stall_collapsed(&s, -1e-12, 1));
  s.scale = 0.1;
  CHECK(!tds_stall_collapsed(&s, -1e-3, 1));
  tds_surf_free(&s);
}

/* tds_stall_clear, the quick pass before the scan, never clears a
** surface the scan finds degenerate, and clears one whose smallest angle
** and area are clear of the tolerances (by 1e-5 and a factor 2: its
** margin is 1e-6, and its area test uses the mean of the squared areas):
** the jittered grid, then 300 seeded placements of vertex (1,1) on the
** line through (0.5, 0) at angles of 1e-4 to 1e-2 degrees from the x
** axis, which gives facet 0 that smallest angle. */
static void stall_clear(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_grid(&ctx, &s, 6, 0.3, 7));
  tds_mesh *m = &s.m;
  CHECK(tds_stall_clear(&s));
  uint64_t st = 21;
  int n[2] = {0, 0};
  tds_id v = 1 + 7 * 1;
  for (int t = 0; t < 300; t++) {
    double deg = pow(10, h_uniform(&st, -4, -2)), r = h_uniform(&st, 0.1, 0.45);
    m->x[v][0] = 0.5 + r * cos(deg * TDS_PI / 180);
    m->x[v][1] = r * sin(deg * TDS_PI / 180);
    m->coord_gen++;
    tds_stall_out o;
    tds_stall_scan(&s, &o);
    int clear = tds_stall_clear(&s);
    n[clear]++;
    CHECK(!clear || !o.degenerate);
    if (o.angle > 1e-3 * (1 + 1e-5) && o.tiny_area > 2e-9 * o.mean_area) CHECK(clear);
  }
  CHECK(n[0] > 50 && n[1] > 50);
  tds_surf_free(&s);
}

int main(void) {
  RUN(stall_scan);
  RUN(stall_clear);
  RUN(cube_g5);
  RUN(cube_interrupt);
  RUN(cube_fixed_scale);
  RUN(cube_fixed_vertex);
  RUN(cube_pressures);
  return check_done();
}
