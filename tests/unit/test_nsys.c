/* test_nsys.c: the Newton system assembled straight into its unknowns
** (newton_asm.c, the path every hessian, eigenprobe and ritz takes)
** against the general assembly through the xyz Hessian and triplets
** (newton_sys.c, hess.c, hess_reduce.c; checked against finite
** differences in test_hess.c), on states of Evolver's examples with
** every kind of vertex (free, on level sets, on boundaries, on triple
** junctions, fixed), with hessian_normal on and off (and
** hessian_normal_one with hessian_normal_perp), linear_metric, and
** on jittered (badly shaped) copies; in the string model too (2-D
** foams, a 3-D string, the 2-D torus).
**
** Tolerance: the two sum the same products in another order, so they
** agree to rounding: |H x - H' x| <= 1e-12 max|H| |x|_1 for seeded random
** x (a wrong or missing term, a misplaced entry or a lost curvature block
** is of the order of an entry: 1e-3 and more).
*/
#include "check.h"
#include "datafile.h"
#include "helpers.h"
#include "iterate.h"
#include "newton_int.h"
#include "topo.h"

#define EX "/usr/share/doc/evolver/examples/"

static double rnd(uint64_t *st) {
  *st = *st * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(*st >> 11) / 9007199254740992.0 - 0.5;
}

static double maxabs(const tds_spmat *a) {
  double x = 0;
  for (int32_t e = 0; e < (a->ncol ? a->colptr[a->ncol] : 0); e++) x = fmax(x, fabs(a->val[e]));
  return x;
}

/* max |A x - B x| / (max|A| |x|_1) over a few random x (A, B same size). */
static double mat_diff(const tds_spmat *a, const tds_spmat *b, uint64_t seed) {
  if (a->nrow != b->nrow || a->ncol != b->ncol) return INFINITY;
  int32_t n = a->ncol, r = a->nrow;
  double *x = calloc((size_t)n + 1, sizeof *x), *y = calloc((size_t)r + 1, sizeof *y),
         *z = calloc((size_t)r + 1, sizeof *z);
  double worst = 0, scale = maxabs(a) > 0 ? maxabs(a) : 1;
  for (int t = 0; t < 3; t++) {
    double l1 = 0;
    for (int32_t i = 0; i < n; i++) l1 += fabs(x[i] = rnd(&seed));
    tds_spmat_mulv(a, x, y);
    tds_spmat_mulv(b, x, z);
    for (int32_t i = 0; i < r; i++) worst = fmax(worst, fabs(y[i] - z[i]) / (scale * (l1 > 0 ? l1 : 1)));
  }
  free(x);
  free(y);
  free(z);
  return worst;
}

static double vec_diff(const double *a, const double *b, int32_t n) {
  double big = 0, d = 0;
  for (int32_t i = 0; i < n; i++) {
    big = fmax(big, fabs(a[i]));
    d = fmax(d, fabs(a[i] - b[i]));
  }
  return d / (big > 0 ? big : 1);
}

/* Both assemblies of one state and options, compared. */
static void compare(tds_ctx *ctx, tds_surf *s, tds_newton_opts o, const char *what) {
  tds_nsys fast, gen;
  int miss = 1;
  REQUIRE_OK(ctx, tds_nsys_assemble(ctx, s, &o, &fast, &miss));
  CHECK(!miss);
  o.general = 1;
  REQUIRE_OK(ctx, tds_nsys_build(ctx, s, &o, &gen));
  CHECK(fast.m == gen.m && fast.nq == gen.nq);
  if (fast.m != gen.m || fast.nq != gen.nq) {
    fprintf(stderr, "%s: sizes %d %d / %d %d\n", what, (int)fast.m, (int)fast.nq, (int)gen.m,
            (int)gen.nq);
  } else {
    double dh = mat_diff(&gen.H, &fast.H, 7), da = gen.nq ? mat_diff(&gen.A, &fast.A, 8) : 0,
           dm = gen.M.nrow ? mat_diff(&gen.M, &fast.M, 9) : fast.M.nrow ? 1 : 0;
    double dg = vec_diff(gen.grad, fast.grad, gen.m);
    int same = 1;
    for (int32_t j = 0; j < gen.m; j++) {
      same &= gen.vert[j] == fast.vert[j];
      for (int i = 0; i < 3; i++)
        same &= fabs(gen.dx[j][i] - fast.dx[j][i]) <= 1e-12 &&
                fabs(gen.mv[j][i] - fast.mv[j][i]) <= 1e-12;
    }
    for (int32_t q = 0; q < gen.nq; q++)
      same &= gen.mult[q] == fast.mult[q] &&
              fabs(gen.value[q] - fast.value[q]) <= 1e-12 * fabs(gen.value[q]) &&
              gen.target[q] == fast.target[q];
    same &= fabs(gen.energy - fast.energy) <= 1e-12 * fabs(gen.energy);
    if (!(dh <= 1e-12 && da <= 1e-12 && dm <= 1e-12 && dg <= 1e-12 && same))
      fprintf(stderr, "%s: H %g A %g M %g grad %g same %d\n", what, dh, da, dm, dg, same);
    CHECK(dh <= 1e-12);
    CHECK(da <= 1e-12);
    CHECK(dm <= 1e-12);
    CHECK(dg <= 1e-12);
    CHECK(same);
    CHECK(maxabs(&fast.H) > 0);
  }
  tds_nsys_free(&fast);
  tds_nsys_free(&gen);
}

static void jitter(tds_mesh *m, double amp, uint64_t seed) {
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) m->x[v][i] += amp * rnd(&seed);
  m->coord_gen++;
}

/* An example refined and evolved, then each option set; then jittered
** (vertices on constraints leave them a little: the assembly must not
** care). */
static void example_opt(const char *file, int refine, int steps, int one) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, file));
  for (int r = 0; r < refine; r++) REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  REQUIRE_OK(&ctx, tds_iterate(&ctx, &s, steps));
  REQUIRE_OK(&ctx, tds_pressures(&ctx, &s));
  for (int pass = 0; pass < 2; pass++) {
    compare(&ctx, &s, (tds_newton_opts){.normal = 1, .metric_mix = 0.5}, file);
    compare(&ctx, &s, (tds_newton_opts){.normal = 0, .metric_mix = 0.5}, file);
    compare(&ctx, &s, (tds_newton_opts){.normal = 1, .linear_metric = 1, .metric_mix = 0.3},
            file);
    compare(&ctx, &s, (tds_newton_opts){.normal = 0, .linear_metric = 1, .metric_mix = 1}, file);
    if (one)
      compare(&ctx, &s, (tds_newton_opts){.normal = 1, .normal_one = 1, .linear_metric = 1,
                                          .normal_perp = 1, .metric_mix = 0.5}, file);
    jitter(&s.m, 0.05, 42);
  }
  tds_surf_free(&s);
}

static void example(const char *file, int refine, int steps) { example_opt(file, refine, steps, 1); }

static void nsys_cube(void) { example(EX "cube.fe", 2, 10); }
static void nsys_mound(void) { example(EX "mound.fe", 2, 10); }
static void nsys_catbody(void) { example(EX "catbody.fe", 2, 10); }
static void nsys_column(void) { example(EX "column.fe", 1, 10); }
static void nsys_qmound(void) { example(EX "qmound.fe", 2, 10); }
static void nsys_cat(void) { example(EX "cat.fe", 2, 10); }
static void nsys_twocubes(void) { example("tests/evolver/data/twocubes.fe", 1, 10); }
static void nsys_slidestr(void) { example(EX "slidestr.fe", 2, 10); }
/* the string model: junctions in a 2-D foam, a 3-D string with a
** junction and ends (hessian_normal_one is refused in 3-D space), the
** 2-D torus */
static void nsys_flower(void) { example("tests/evolver/data/flower5.fe", 1, 10); }
static void nsys_string3(void) { example_opt("tests/evolver/data/string3_junction.fe", 1, 10, 0); }
static void nsys_100grain(void) { example(EX "100grain.fe", 0, 3); }

int main(void) {
  RUN(nsys_cube);
  RUN(nsys_mound);
  RUN(nsys_catbody);
  RUN(nsys_column);
  RUN(nsys_qmound);
  RUN(nsys_cat);
  RUN(nsys_twocubes);
  RUN(nsys_slidestr);
  RUN(nsys_flower);
  RUN(nsys_string3);
  RUN(nsys_100grain);
  return check_done();
}
