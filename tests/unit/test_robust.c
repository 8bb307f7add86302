/* test_robust.c: snapshots (all-or-nothing commands), the finiteness
** check, refused scale limits and the all-or-nothing file writer. */
#define _XOPEN_SOURCE 700 /* mkdtemp */
#include <dirent.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "helpers.h"
#include "iterate.h"
#include "snap.h"
#include "wfile.h"

/* A snapshot taken, then coordinates, topology and pressures changed:
** restoring gives back the surface bit for bit, and its energy. */
static void snap_restore_exact(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  CHECK(h_cube(&ctx, &s, 1) == TDS_OK);
  CHECK(tds_iterate(&ctx, &s, 3) == TDS_OK);
  CHECK(tds_surf_update(&ctx, &s) == TDS_OK);
  double e0 = s.energy, p0 = s.m.bpressure[0];
  tds_snap sn;
  CHECK(tds_snap_take(&ctx, &s, &sn) == TDS_OK);
  CHECK(tds_snap_same(&ctx, &s, &sn) == TDS_OK);
  CHECK(tds_refine(&ctx, &s, NULL, NULL) == TDS_OK);
  s.m.x[0][0] += 0.25;
  s.m.bpressure[0] = 42;
  s.iterations += 7;
  CHECK(tds_snap_same(&ctx, &s, &sn) != TDS_OK); /* counts differ */
  tds_snap_restore(&s, &sn);
  CHECK(tds_snap_take(&ctx, &s, &sn) == TDS_OK);
  CHECK(h_check(&ctx, &s.m) == TDS_OK);
  CHECK(tds_mesh_count(&s.m, TDS_VERTEX) == 14 && tds_mesh_count(&s.m, TDS_FACET) == 24);
  CHECK(s.m.bpressure[0] == p0 && s.iterations == 3);
  CHECK(tds_surf_update(&ctx, &s) == TDS_OK);
  CHECK(s.energy == e0); /* the same positions give the same bits */
  /* a coordinate change alone is named */
  s.m.x[4][2] = nextafter(s.m.x[4][2], 2);
  CHECK(tds_snap_same(&ctx, &s, &sn) == TDS_ENUM && strstr(ctx.errmsg, "vertex 5 changed"));
  tds_snap_free(&sn);
  tds_surf_free(&s);
}

/* g(3) at a fixed scale of 1e300 fails at its first step: all of it is
** undone, the surface equals a snapshot taken before. */
static void iterate_failure_restores(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  CHECK(h_cube(&ctx, &s, 1) == TDS_OK);
  CHECK(tds_iterate(&ctx, &s, 2) == TDS_OK);
  tds_snap before;
  CHECK(tds_snap_take(&ctx, &s, &before) == TDS_OK);
  s.fixed_scale = 1;
  s.scale = 1e300;
  CHECK(tds_iterate(&ctx, &s, 3) == TDS_ENUM);
  CHECK(strstr(ctx.errmsg, "step 1 of 3") && strstr(ctx.errmsg, "as before the command"));
  s.scale = before.scale; /* the fixed scale was the test's own change */
  CHECK(tds_snap_same(&ctx, &s, &before) == TDS_OK);
  CHECK(tds_surf_all_finite(&ctx, &s, 0) == TDS_OK);
  tds_snap_free(&before);
  tds_surf_free(&s);
}

/* Limits that would make the line search loop forever are refused before
** anything moves; an empty surface iterates to energy exactly 0. */
static void scale_limits_refused(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  CHECK(tds_iterate(&ctx, &s, 2) == TDS_OK && s.energy == 0); /* empty */
  CHECK(s.iterations == 2);
  CHECK(h_cube(&ctx, &s, 1) == TDS_OK);
  const double bad[] = {INFINITY, NAN, 0, 1e-320, -1};
  for (int i = 0; i < 5; i++) {
    s.scale_limit = bad[i];
    CHECK(tds_iterate(&ctx, &s, 1) == TDS_ERANGE);
    CHECK(s.iterations == 2 && strstr(ctx.errmsg, "scale limit"));
  }
  s.scale_limit = 1;
  CHECK(tds_iterate(&ctx, &s, 1) == TDS_OK && s.iterations == 3);
  tds_surf_free(&s);
}

/* The finiteness check names the first non-finite value; derived values
** (energy) are checked only when asked. */
static void finiteness_check(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  CHECK(h_cube(&ctx, &s, 1) == TDS_OK);
  CHECK(tds_surf_update(&ctx, &s) == TDS_OK);
  CHECK(tds_surf_all_finite(&ctx, &s, 1) == TDS_OK);
  s.energy = NAN;
  CHECK(tds_surf_all_finite(&ctx, &s, 0) == TDS_OK);
  CHECK(tds_surf_all_finite(&ctx, &s, 1) == TDS_ENUM && strstr(ctx.errmsg, "energy"));
  s.m.x[2][1] = INFINITY;
  CHECK(tds_surf_all_finite(&ctx, &s, 0) == TDS_ENUM &&
        strstr(ctx.errmsg, "vertex 3: coordinate is inf"));
  tds_surf_free(&s);
}

static int count_entries(const char *dir) {
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d));)
    n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
  if (d) closedir(d);
  return n;
}

static int file_is(const char *path, const char *text) {
  char buf[256] = {0};
  FILE *f = fopen(path, "r");
  if (!f) return 0;
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  return n == strlen(text) && !memcmp(buf, text, n);
}

static int write_all(tds_ctx *ctx, const char *path, const char *text, size_t n) {
  tds_wfile w;
  int rc = tds_wfile_open(ctx, &w, path);
  if (rc) return rc;
  for (size_t i = 0; i < n; i++) fputs(text, w.f);
  return tds_wfile_commit(ctx, &w);
}

/* The writer: a new file, a replaced one keeping its mode, a read-only one
** refused, and a write cut by a file-size limit leaving the old file and
** no temporary file behind. */
static void writer_all_or_nothing(void) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  char dir[] = "/tmp/tds-unit-XXXXXX", path[64], ro[64];
  CHECK(mkdtemp(dir) != NULL);
  snprintf(path, sizeof path, "%s/a.fe", dir);
  snprintf(ro, sizeof ro, "%s/ro.fe", dir);
  CHECK(write_all(&ctx, path, "first\n", 1) == TDS_OK && file_is(path, "first\n"));
  CHECK(chmod(path, 0640) == 0);
  CHECK(write_all(&ctx, path, "second\n", 1) == TDS_OK && file_is(path, "second\n"));
  struct stat st;
  CHECK(stat(path, &st) == 0 && (st.st_mode & 07777) == 0640);
  CHECK(write_all(&ctx, ro, "old\n", 1) == TDS_OK && chmod(ro, 0444) == 0);
  CHECK(write_all(&ctx, ro, "new\n", 1) == TDS_EIO && strstr(ctx.errmsg, "read-only"));
  CHECK(file_is(ro, "old\n"));
  CHECK(write_all(&ctx, dir, "x", 1) == TDS_EIO && strstr(ctx.errmsg, "directory"));
  /* 1 MB against a 64 KiB limit */
  struct rlimit old, lim = {64 << 10, 64 << 10};
  void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
  CHECK(getrlimit(RLIMIT_FSIZE, &old) == 0);
  lim.rlim_max = old.rlim_max;
  CHECK(setrlimit(RLIMIT_FSIZE, &lim) == 0);
  CHECK(write_all(&ctx, path, "0123456789abcdef", 1 << 16) == TDS_EIO);
  CHECK(strstr(ctx.errmsg, "File too large") != NULL);
  CHECK(setrlimit(RLIMIT_FSIZE, &old) == 0);
  signal(SIGXFSZ, prev);
  CHECK(file_is(path, "second\n"));
  CHECK(count_entries(dir) == 2); /* a.fe and ro.fe: no temporary file */
  unlink(path);
  chmod(ro, 0644);
  unlink(ro);
  rmdir(dir);
}

int main(void) {
  RUN(snap_restore_exact);
  RUN(iterate_failure_restores);
  RUN(scale_limits_refused);
  RUN(finiteness_check);
  RUN(writer_all_or_nothing);
  return check_done();
}
