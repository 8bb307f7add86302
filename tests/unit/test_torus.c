/* test_torus.c: the torus model (torus.h, wrap.h) from plain C: wrap
** packing, the gradient of energy and volumes with wraps against central
** differences, the wrap attribute's codes and rules, the cell volume. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "attr.h"
#include "check.h"
#include "datafile.h"
#include "eval.h"
#include "helpers.h"
#include "gather.h"
#include "topo.h"
#include "torus.h"

#define EX "/usr/share/doc/evolver/examples/"

/* pack/unpack/add/neg are exact over the whole range */
static void wrap_packing(void) {
  uint64_t st = 7;
  for (int t = 0; t < 1000; t++) {
    int a[3], b[3], k[3];
    for (int i = 0; i < 3; i++) {
      a[i] = (int)floor(h_uniform(&st, -255, 256));
      b[i] = (int)floor(h_uniform(&st, -255, 256));
    }
    int32_t wa = tds_wrap_pack(a), wb = tds_wrap_pack(b);
    tds_wrap_unpack(wa, k);
    CHECK(k[0] == a[0] && k[1] == a[1] && k[2] == a[2]);
    tds_wrap_unpack(tds_wrap_add(wa, wb), k);
    CHECK(k[0] == a[0] + b[0] && k[1] == a[1] + b[1] && k[2] == a[2] + b[2]);
    CHECK(tds_wrap_add(wa, tds_wrap_neg(wa)) == 0);
  }
  int z[3] = {0, 0, 0};
  CHECK(tds_wrap_pack(z) == 0);
}

/* Evolver's codes: "* - *" 1984, "- + *" 95, "* + -" 127040, "* * +" 4096
** (printed by evolver-nox-d for twointor.fe's edges 6, 14, 19 and 7) */
static void wrap_codes(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, EX "twointor.fe"));
  tds_attr a;
  CHECK(tds_attr_find(&s.m, TDS_EDGE, "wrap", &a));
  const int id[4] = {6, 14, 19, 7};
  const double code[4] = {1984, 95, 127040, 4096};
  for (int i = 0; i < 4; i++) {
    double v[1];
    int n;
    REQUIRE_OK(&ctx, tds_attr_read(&ctx, &s, &a, id[i] - 1, v, &n));
    CHECK(n == 1 && v[0] == code[i]);
    int32_t w;
    CHECK(tds_torus_wrap_from_code(code[i], &w) == TDS_OK && w == s.m.ewrap[id[i] - 1]);
  }
  /* a wrap that opens a facet is refused, the edge unchanged */
  int32_t keep = s.m.ewrap[0];
  double one = 1;
  CHECK(tds_attr_write(&ctx, &s, &a, 0, &one, 1) == TDS_ETOPO);
  CHECK(s.m.ewrap[0] == keep);
  CHECK(strstr(ctx.errmsg, "would not close") != NULL);
  /* not a code: a count of 32 spills into the next field */
  double bad = 32;
  CHECK(tds_attr_write(&ctx, &s, &a, 0, &bad, 1) == TDS_ERANGE);
  CHECK_NEAR(tds_torus_cell_volume(&s.m), 1, 0);
  tds_surf_free(&s);
  /* no torus: refused */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
  CHECK(tds_attr_find(&s.m, TDS_EDGE, "wrap", &a));
  double zero = 0;
  CHECK(tds_attr_write(&ctx, &s, &a, 0, &zero, 1) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "torus") != NULL);
  tds_surf_free(&s);
}

static double energy_at(tds_ctx *ctx, tds_surf *s) {
  tds_eval_out out = {0};
  CHECK(tds_eval(ctx, s, &out) == TDS_OK);
  return out.energy;
}

/* The energy with a prescribed pressure on every body (so -p V, with the
** volumes' lattice translations, is in it) against central differences,
** after a seeded jitter; relative to the largest gradient component. The
** step 1e-6 and tolerance 1e-7: the energy is a polynomial of degree 3
** in the coordinates, so the central difference errs by h^2 times third
** derivatives of order 1, and rounding by 1e-16 / 1e-6. */
static void gradient_fd(const char *file) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, file));
  tds_mesh *m = &s.m;
  uint64_t st = 99;
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) m->x[v][i] += h_uniform(&st, -0.02, 0.02);
  for (tds_id b = 0; b < m->nb; b++) {
    m->bflags[b] = (m->bflags[b] & ~TDS_TARGET) | TDS_PRESSURE;
    m->bpressure[b] = h_uniform(&st, -2, 2);
  }
  m->coord_gen++;
  double (*g)[3] = calloc((size_t)m->nv, sizeof *g);
  tds_eval_out out = {.grad = g};
  REQUIRE_OK(&ctx, tds_eval(&ctx, &s, &out));
  double scale = 0, worst = 0, h = 1e-6;
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) scale = fmax(scale, fabs(g[v][i]));
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) {
      double x0 = m->x[v][i];
      m->x[v][i] = x0 + h;
      m->coord_gen++;
      double ep = energy_at(&ctx, &s);
      m->x[v][i] = x0 - h;
      m->coord_gen++;
      double em = energy_at(&ctx, &s);
      m->x[v][i] = x0;
      m->coord_gen++;
      worst = fmax(worst, fabs((ep - em) / (2 * h) - g[v][i]) / scale);
    }
  if (!(worst < 1e-7)) printf("  %s: worst relative error %g\n", file, worst);
  CHECK(worst < 1e-7);
  CHECK(scale > 0.1);
  free(g);
  tds_surf_free(&s);
}
static void gradient_fd_twointor(void) { gradient_fd(EX "twointor.fe"); }
static void gradient_fd_phelanc(void) { gradient_fd(EX "phelanc.fe"); }

/* A body's volume does not depend on which copy of the cell a vertex is
** stored in: move a vertex by a period and give its edges the opposite
** wraps (what wrap_vertex does); every volume and the energy stay (1e-14:
** the same sums of other numbers). */
static void copy_invariance(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, EX "phelanc.fe"));
  tds_mesh *m = &s.m;
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  double e0 = s.energy, v0[8];
  for (tds_id b = 0; b < 8; b++) v0[b] = m->bvol[b];
  uint64_t st = 5;
  for (int t = 0; t < 20; t++) {
    tds_id v = (tds_id)floor(h_uniform(&st, 0, m->nv));
    int k[3];
    for (int i = 0; i < 3; i++) k[i] = (int)floor(h_uniform(&st, -2, 3));
    REQUIRE_OK(&ctx, tds_torus_wrap_vertex(&ctx, &s, v, tds_wrap_pack(k)));
  }
  CHECK_MESH(&ctx, m);
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK_NEAR(s.energy, e0, 1e-14 * e0);
  for (tds_id b = 0; b < 8; b++) CHECK_NEAR(m->bvol[b], v0[b], 1e-14);
  tds_surf_free(&s);
}

/* detorus: the surface as drawn, no torus: the same area (1e-12), no
** wrap column, a valid mesh, and no edge longer than half the cell (the longest
** edge of twointor after r is 0.36). */
static void detorus_keeps_area(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, EX "twointor.fe"));
  REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  double a0 = s.area;
  REQUIRE_OK(&ctx, tds_torus_detorus(&ctx, &s.m, NULL));
  CHECK(s.m.torus == 0 && s.m.ewrap == NULL); /* no wraps left */
  CHECK_MESH(&ctx, &s.m);
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK_NEAR(s.area, a0, 1e-12 * a0);
  double longest = 0;
  for (tds_id e = 0; e < s.m.ne; e++) {
    if (!tds_alive(s.m.eflags, e)) continue;
    double d[3];
    tds_edge_vec(&s.m, TDS_OREF(e, 0), d);
    longest = fmax(longest, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
  }
  CHECK(longest < 0.5);
  tds_surf_free(&s);
}

/* rewrap after a seeded scatter of vertices over neighbouring cells puts
** every vertex in the cell (lattice coordinates in [0, 1)) and keeps the
** energy and volumes (1e-14). */
static void rewrap_into_cell(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, "tests/evolver/torus/kelvin.fe"));
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  double e0 = s.energy, v0 = s.m.bvol[0];
  uint64_t st = 3;
  for (tds_id v = 0; v < s.m.nv; v++) {
    int k[3];
    for (int i = 0; i < 3; i++) k[i] = (int)floor(h_uniform(&st, -1, 2));
    REQUIRE_OK(&ctx, tds_torus_wrap_vertex(&ctx, &s, v, tds_wrap_pack(k)));
  }
  int32_t n = 0;
  REQUIRE_OK(&ctx, tds_torus_rewrap(&ctx, &s, &n));
  CHECK(n > 0);
  CHECK_MESH(&ctx, &s.m);
  for (tds_id v = 0; v < s.m.nv; v++) {
    const double *x = s.m.x[v]; /* bcc: x = sum c_i P_i, c = (y+z, x+z, x+y) */
    double c[3] = {x[1] + x[2], x[0] + x[2], x[0] + x[1]};
    for (int i = 0; i < 3; i++) CHECK(c[i] >= -1e-12 && c[i] < 1 + 1e-12);
  }
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK_NEAR(s.energy, e0, 1e-14 * e0);
  CHECK_NEAR(s.m.bvol[0], v0, 1e-14);
  tds_surf_free(&s);
}

/* V does not depend on which copy of the cell vertices are stored in:
** phelanc refined, V from the stored copies and V after a seeded scatter
** of the vertices over neighbouring cells give the same energy (1e-13:
** the same averages of other numbers) and volumes. */
static void vertex_average_copies(void) {
  double e[2], v[2][8];
  for (int pass = 0; pass < 2; pass++) {
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, EX "phelanc.fe"));
    REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
    uint64_t st = 11;
    for (tds_id x = 0; pass && x < s.m.nv; x++) {
      int k[3];
      for (int i = 0; i < 3; i++) k[i] = (int)floor(h_uniform(&st, -1, 2));
      REQUIRE_OK(&ctx, tds_torus_wrap_vertex(&ctx, &s, x, tds_wrap_pack(k)));
    }
    int32_t n = 0;
    REQUIRE_OK(&ctx, tds_vertex_average(&ctx, &s, NULL, &n));
    CHECK(n > 300);
    CHECK_MESH(&ctx, &s.m);
    e[pass] = s.energy;
    for (tds_id b = 0; b < 8; b++) v[pass][b] = s.m.bvol[b];
    tds_surf_free(&s);
  }
  CHECK_NEAR(e[1], e[0], 1e-13 * e[0]);
  for (tds_id b = 0; b < 8; b++) CHECK_NEAR(v[1][b], v[0][b], 1e-13);
}

/* A Hessian accumulator that takes nothing: with it tds_eval runs the
** general assembly (eval.c) instead of eval_torus.c's facet pass. */
static void hess_none(tds_hess_acc *ha, const tds_id *vs, int kind, double w, double (*h)[9]) {
  (void)ha, (void)vs, (void)kind, (void)w, (void)h;
}

/* Energy, area, volumes, the energy's gradient and the quantities'
** gradients of eval_torus.c's facet pass and of the general assembly;
** 1 when they are the same bits. */
static int same_as_general(tds_ctx *ctx, tds_surf *s, tds_fixq *fq) {
  tds_mesh *m = &s->m;
  double e0[2]; /* without gradients: the general loop with an empty Hessian */
  tds_hess_acc h0 = {.ew = 1, .add = hess_none};
  double (*g0)[3] = calloc((size_t)m->nv, sizeof *g0);
  for (int k = 0; k < 2; k++) {
    tds_eval_out out = {.grad = k ? g0 : NULL, .hess = k ? &h0 : NULL};
    CHECK(tds_eval(ctx, s, &out) == TDS_OK);
    e0[k] = out.energy;
  }
  free(g0);
  if (e0[0] != e0[1]) return 0;
  size_t nv = (size_t)m->nv, nb = (size_t)m->nb, ne = (size_t)fq->nent;
  double (*g[2])[3], *vol[2], (*qg[2])[3], e[2], a[2];
  tds_hess_acc ha = {.ew = 1, .add = hess_none};
  for (int k = 0; k < 2; k++) {
    g[k] = calloc(nv, sizeof *g[k]);
    tds_eval_out out = {.grad = g[k], .fq = fq, .hess = k ? &ha : NULL};
    CHECK(tds_eval(ctx, s, &out) == TDS_OK);
    e[k] = out.energy;
    a[k] = out.area;
    vol[k] = malloc(nb * sizeof *vol[k]);
    memcpy(vol[k], m->bvol, nb * sizeof *vol[k]);
    qg[k] = malloc(ne * sizeof *qg[k]);
    memcpy(qg[k], fq->g, ne * sizeof *qg[k]);
  }
  int same = e[0] == e[1] && a[0] == a[1] && !memcmp(vol[0], vol[1], nb * sizeof *vol[0]) &&
             !memcmp(g[0], g[1], nv * sizeof *g[0]) && !memcmp(qg[0], qg[1], ne * sizeof *qg[0]);
  for (int k = 0; k < 2; k++) free(g[k]), free(vol[k]), free(qg[k]);
  return same;
}

/* eval_torus.c's facet pass gives the general assembly's numbers bit for
** bit (it computes the same expressions in the same order): on phelanc
** refined and jittered (seeded), with bodies holding volumes and bodies
** with prescribed pressures, a facet left out of the volumes, a facet
** with one body, without the entry map (the entries searched), and
** after the vertices were scattered over so many cells that the pass's
** table of wraps (255) overflows and the general assembly takes over. */
static void facet_pass_exact(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, EX "phelanc.fe"));
  REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  tds_mesh *m = &s.m;
  uint64_t st = 17;
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) m->x[v][i] += h_uniform(&st, -0.01, 0.01);
  for (tds_id b = 0; b < m->nb; b += 2) {
    m->bflags[b] = (m->bflags[b] & ~TDS_TARGET) | TDS_PRESSURE;
    m->bpressure[b] = h_uniform(&st, -2, 2);
  }
  m->fflags[5] |= TDS_NONCONTENT;
  m->fb[9][1] = TDS_NONE;
  m->topo_gen++;
  m->coord_gen++;
  REQUIRE_OK(&ctx, tds_mesh_adjacency(m));
  tds_fixq fq = {0};
  REQUIRE_OK(&ctx, tds_fixq_build(&ctx, &s, &fq));
  CHECK(fq.nq > 0 && fq.emap_kind == TDS_EL_FACET);
  CHECK(same_as_general(&ctx, &s, &fq));
  int kind = fq.emap_kind;
  fq.emap_kind = 0;
  CHECK(same_as_general(&ctx, &s, &fq));
  fq.emap_kind = kind;
  tds_fixq_free(&fq);
  for (tds_id v = 0; v < m->nv; v++) {
    int k[3];
    for (int i = 0; i < 3; i++) k[i] = (int)floor(h_uniform(&st, -6, 7));
    REQUIRE_OK(&ctx, tds_torus_wrap_vertex(&ctx, &s, v, tds_wrap_pack(k)));
  }
  REQUIRE_OK(&ctx, tds_mesh_adjacency(m));
  fq = (tds_fixq){0};
  REQUIRE_OK(&ctx, tds_fixq_build(&ctx, &s, &fq));
  CHECK(same_as_general(&ctx, &s, &fq));
  tds_fixq_free(&fq);
  tds_surf_free(&s);
}

int main(void) {
  RUN(wrap_packing);
  RUN(wrap_codes);
  RUN(gradient_fd_twointor);
  RUN(gradient_fd_phelanc);
  RUN(copy_invariance);
  RUN(detorus_keeps_area);
  RUN(rewrap_into_cell);
  RUN(vertex_average_copies);
  RUN(facet_pass_exact);
  return check_done();
}
