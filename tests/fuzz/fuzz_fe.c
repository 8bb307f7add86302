/*
** fuzz_fe.c: libFuzzer harness of the .fe datafile loader.
**
** Each input is a datafile; it is also given to the content sniffer
** (tds_datafile_detect) as a file without extension. When it loads, the
** harness runs a bounded round of commands on it -- a dump that must
** reload to the same counts and energy, one `g` step, one `r` (small
** surfaces only), another `g` -- checks the mesh invariants after each,
** and dumps and reloads again. A failing command is fine if it leaves the
** surface exactly as before; a crash, sanitizer report, broken mesh,
** non-finite value after a load or a successful command, or a dump that
** does not reload is a bug.
*/
#include <math.h>
#include <stdint.h>

#include "datafile.h"
#include "fuzz_util.h"
#include "iterate.h"
#include "mesh.h"
#include "snap.h"
#include "surf.h"
#include "topo.h"

/* Bounded work per input: commands run only below these sizes. */
enum { MAX_ITER_FACETS = 400, MAX_REFINE_FACETS = 100 };

static void init_ctx(tds_ctx *ctx) {
  tds_ctx_init(ctx);
  ctx->quiet = 1;
  ctx->out = fuzz_no_output;
  ctx->warn = fuzz_no_output;
}

static int same_energy(double a, double b) {
  return fabs(a - b) <= 1e-7 * fmax(1.0, fmax(fabs(a), fabs(b)));
}

/* Dump s, reload it and compare counts (and the energy when finite). */
static void dump_reload(tds_surf *s) {
  tds_ctx ctx;
  init_ctx(&ctx);
  const char *path = fuzz_scratch(".fe");
  int rc = tds_datafile_dump(&ctx, s, path);
  FUZZ_CHECK(rc == TDS_OK, "dump failed: %s", ctx.errmsg);
  tds_surf t;
  tds_surf_init(&t);
  rc = tds_datafile_load(&ctx, &t, path);
  FUZZ_CHECK(rc == TDS_OK, "dump does not reload: %s", ctx.errmsg);
  for (int k = 0; k < TDS_NKINDS; k++)
    FUZZ_CHECK(tds_mesh_count(&s->m, k) == tds_mesh_count(&t.m, k),
               "kind %d: %d elements, %d after reload", k,
               (int)tds_mesh_count(&s->m, k), (int)tds_mesh_count(&t.m, k));
  tds_ctx c1, c2;
  init_ctx(&c1);
  init_ctx(&c2);
  if (tds_surf_update(&c1, s) == TDS_OK) {
    FUZZ_CHECK(tds_surf_update(&c2, &t) == TDS_OK, "reloaded energy fails: %s", c2.errmsg);
    FUZZ_CHECK(same_energy(s->energy, t.energy), "energy %.17g, %.17g after reload",
               s->energy, t.energy);
  }
  tds_surf_free(&t);
  unlink(path);
}

static void check_mesh(tds_surf *s, const char *after) {
  tds_ctx ctx;
  init_ctx(&ctx);
  FUZZ_CHECK(tds_mesh_check(&ctx, &s->m) == TDS_OK, "mesh broken after %s: %s", after,
             ctx.errmsg);
}

/* Run one command (g or r) with the all-or-nothing rule checked: after a
** success everything is finite, after a failure the surface is bit for bit
** what it was. */
static void command(tds_surf *s, const char *name) {
  tds_ctx ctx;
  init_ctx(&ctx);
  tds_snap before;
  if (tds_snap_take(&ctx, s, &before) != TDS_OK) return;
  int rc = name[0] == 'r' ? tds_refine(&ctx, s, NULL, NULL) : tds_iterate(&ctx, s, 1);
  check_mesh(s, name);
  tds_ctx c2;
  init_ctx(&c2);
  if (rc == TDS_OK)
    FUZZ_CHECK(tds_surf_all_finite(&c2, s, 1) == TDS_OK, "after %s: %s", name, c2.errmsg);
  else
    FUZZ_CHECK(tds_snap_same(&c2, s, &before) == TDS_OK, "%s failed (%s) and changed: %s", name,
               ctx.errmsg, c2.errmsg);
  tds_snap_free(&before);
}

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  setenv("OMP_NUM_THREADS", "1", 1);
  return 0;
}

/* Content sniffing (a file named without .fe/.tds) reads the same bytes. */
static void detect(const uint8_t *data, size_t size) {
  const char *path = fuzz_scratch("");
  FILE *f = fopen(path, "wb");
  if (!f) return;
  size_t n = fwrite(data, 1, size, f);
  if (fclose(f) == 0 && n == size) {
    int r = tds_datafile_detect(path);
    FUZZ_CHECK(r == 0 || r == 1, "detect returned %d", r);
  }
  unlink(path);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  detect(data, size);
  tds_ctx ctx;
  init_ctx(&ctx);
  tds_surf s;
  tds_surf_init(&s);
  if (tds_datafile_load_buffer(&ctx, &s, "fuzz.fe", (const char *)data, size) != TDS_OK) {
    FUZZ_CHECK(ctx.errmsg[0] != 0, "load failed without a message");
    tds_surf_free(&s);
    return 0;
  }
  check_mesh(&s, "load");
  FUZZ_CHECK(tds_surf_all_finite(&ctx, &s, 0) == TDS_OK, "after load: %s", ctx.errmsg);
  dump_reload(&s);
  if (tds_mesh_count(&s.m, TDS_FACET) <= MAX_ITER_FACETS &&
      tds_mesh_count(&s.m, TDS_VERTEX) <= 3 * MAX_ITER_FACETS) {
    command(&s, "g");
    if (tds_mesh_count(&s.m, TDS_FACET) <= MAX_REFINE_FACETS &&
        tds_mesh_count(&s.m, TDS_EDGE) <= 3 * MAX_REFINE_FACETS) {
      command(&s, "r");
      command(&s, "g after r");
    }
    dump_reload(&s);
  }
  tds_surf_free(&s);
  return 0;
}
