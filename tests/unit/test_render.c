/* test_render.c: the picture renderer's contract (errors leave the surface
** untouched, the projection it reports) and the progress history and line
** (src/render.c, src/progress.c). The pictures themselves are checked by
** tests/pictures/pictures.py. */
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "helpers.h"
#include "progress.h"
#include "render.h"

/* Rendering a tetrahedron from the top: the projection is the xy-plane
** (right = x, up = y), the fit puts the bounding sphere in 46% of the
** smaller side, and the file is written. Bad options, an unwritable file
** and an empty surface fail with a message, leaving the surface as it was. */
static void test_render_contract(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_tetra(&ctx, &s, NULL));
  double x0[4][3];
  memcpy(x0, s.m.x, sizeof x0);
  uint64_t gen = s.m.coord_gen;
  tds_render_opts o;
  tds_render_defaults(&o);
  o.azimuth = -90;
  o.elevation = 90;
  o.width = 200;
  o.height = 100;
  o.legend = 0;
  char path[64];
  snprintf(path, sizeof path, "/tmp/tds_test_render_%d.png", (int)getpid());
  tds_render_info in;
  CHECK_OK(&ctx, tds_render_png(&ctx, &s, &o, path, &in));
  struct stat sb;
  CHECK(stat(path, &sb) == 0 && sb.st_size > 100);
  remove(path);
  CHECK(in.drawn == 4);
  CHECK_NEAR(in.right[0], 1, 1e-12);
  CHECK_NEAR(in.up[1], 1, 1e-12);
  CHECK_NEAR(in.toward[2], 1, 1e-12);
  /* bounding box centre (1/2, 1/2, 1/2); farthest corner at sqrt(3)/2 */
  CHECK_NEAR(in.center[0], 0.5, 1e-12);
  CHECK_NEAR(in.radius, sqrt(3) / 2, 1e-12);
  CHECK_NEAR(in.scale, 0.46 * 100 / (sqrt(3) / 2), 1e-12);
  CHECK_NEAR(in.cx, 100, 1e-12);

  o.width = 10;
  CHECK(tds_render_png(&ctx, &s, &o, path, NULL) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "size") != NULL);
  o.width = 200;
  o.distance = 0.5;
  CHECK(tds_render_png(&ctx, &s, &o, path, NULL) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "distance") != NULL);
  o.distance = 0;
  CHECK(tds_render_png(&ctx, &s, &o, "/nonexistent-dir/x.png", NULL) == TDS_EIO);
  CHECK(strstr(ctx.errmsg, "/nonexistent-dir/x.png") != NULL);
  CHECK(access(path, F_OK) != 0);
  s.m.x[2][1] = NAN;
  CHECK(tds_render_png(&ctx, &s, &o, path, NULL) == TDS_ENUM);
  CHECK(strstr(ctx.errmsg, "vertex 3") != NULL);
  CHECK(access(path, F_OK) != 0);
  s.m.x[2][1] = x0[2][1];
  CHECK(memcmp(x0, s.m.x, sizeof x0) == 0 && s.m.coord_gen == gen);
  tds_surf_free(&s);

  tds_surf_init(&s);
  CHECK(tds_render_png(&ctx, &s, &o, path, NULL) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "no facets") != NULL);
  tds_surf_free(&s);
}

/* The colour tables: Evolver's RED is the PC palette's (170, 0, 0), the
** ramp is grey in the middle, and ten bodies get ten clearly different
** colours. */
static void test_colors(void) {
  double c[3], d[3];
  tds_render_evolver_color(4, c);
  CHECK(c[0] == 170 / 255.0 && c[1] == 0 && c[2] == 0);
  tds_render_evolver_color(15, c);
  CHECK(c[0] == 1 && c[1] == 1 && c[2] == 1);
  tds_render_ramp(0.5, c);
  CHECK(c[0] == c[1] && c[1] == c[2]);
  tds_render_ramp(0, c);
  tds_render_ramp(1, d);
  CHECK(c[2] > c[0] && d[0] > d[2]); /* blue low, red high */
  for (int a = 0; a < 10; a++)
    for (int b = 0; b < a; b++) {
      tds_render_body_color(a, c);
      tds_render_body_color(b, d);
      double diff = 0;
      for (int k = 0; k < 3; k++) diff = fmax(diff, fabs(c[k] - d[k]));
      CHECK(diff > 0.1);
    }
}

/* The history keeps every iteration up to 2^20 entries, then every other
** one: after 2^20 + 10 iterations it holds the odd iterations, with their
** energies, and a run off a terminal never claims the line. */
static void test_history(void) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  tds_progress p;
  tds_progress_init(&p);
  ctx.progress = &p;
  int64_t N = (1 << 20) + 10;
  tds_progress_begin(&ctx, 'g', N);
  int claimed = 0;
  for (int64_t k = 1; k <= N; k++) claimed |= tds_progress_step(&ctx, k, (double)k, 0.5);
  CHECK(tds_progress_end(&ctx) == 0 && !claimed);
  CHECK(p.count == N && p.stride == 2);
  CHECK(p.n == (1 << 19) + 5);
  int ok = 1;
  for (int32_t i = 0; i < p.n; i++)
    ok &= p.iter[i] == 2 * i + 1 && p.energy[i] == p.iter[i] && p.kinds[i] == 'g';
  CHECK(ok);
  tds_progress_clear(&p);
  CHECK(p.n == 0 && p.count == 0);
  tds_progress_free(&p);
}

static char outbuf[4096];
static void capture(void *ud, const char *text) {
  (void)ud;
  strncat(outbuf, text, sizeof outbuf - strlen(outbuf) - 1);
}

/* On a terminal the line is drawn only after a quarter second, redrawn in
** place with '\r', and erased at the end, which reports the lines it
** replaced; quiet turns it off. */
static void test_live_line(void) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  ctx.out = capture;
  tds_progress p;
  tds_progress_init(&p);
  p.tty = 1;
  ctx.progress = &p;
  outbuf[0] = 0;
  tds_progress_begin(&ctx, 'g', 10);
  CHECK(tds_progress_step(&ctx, 1, 2.5, 0.125) == 1);
  CHECK(outbuf[0] == 0); /* too soon to draw */
  struct timespec ts = {0, 300000000};
  nanosleep(&ts, NULL);
  CHECK(tds_progress_step(&ctx, 2, 2.25, 0.25) == 1);
  CHECK(strncmp(outbuf, "\rg 2/10  energy 2.25  scale 0.25  ", 34) == 0);
  CHECK(strstr(outbuf, " it/s  ") != NULL && strstr(outbuf, "s left") != NULL);
  CHECK(strchr(outbuf, '\n') == NULL);
  size_t len = strlen(outbuf);
  CHECK(tds_progress_end(&ctx) == 2);
  CHECK(outbuf[len] == '\r' && outbuf[strlen(outbuf) - 1] == '\r');
  ctx.quiet = 1;
  tds_progress_begin(&ctx, 'p', 0);
  CHECK(tds_progress_step(&ctx, 1, 1, 1e-3) == 0);
  CHECK(tds_progress_end(&ctx) == 0);
  char line[256];
  tds_progress_format(line, sizeof line, 'p', 50, 100, 4.5, 1e-6, 2);
  CHECK(strcmp(line, "pg 50/100  energy 4.5  r 1e-06  25 it/s  2s left") == 0);
  tds_progress_format(line, sizeof line, 'p', 7, 0, 4.5, 1e-6, 0);
  CHECK(strcmp(line, "pg 7  energy 4.5  r 1e-06  0 it/s") == 0);
  tds_progress_free(&p);
}

int main(void) {
  RUN(test_render_contract);
  RUN(test_colors);
  RUN(test_history);
  RUN(test_live_line);
  return check_done();
}
