/* test_hess.c: the sparse Hessian assembly (hess.h) against central
** differences of the assembled gradient (tds_eval), on seeded random
** perturbed small meshes and on states of Evolver's examples, plus an
** exact value.
**
** Tolerances. Central differences of the exact gradient with step
** h = 1e-6 x (mean edge length) have truncation error h^2/6 |d3E| and
** rounding error ~1e-16 |grad| / h. Relative to the largest Hessian entry
** the worst measured is 1e-9 (the catbody state; it scales as h^2, so it
** is truncation), so an entry off by more than 1e-6 x max|H| is a wrong
** term, not noise: scaling the multipliers by 1.01 fails every
** Lagrangian check here at 1e-4 .. 3e-2. Symmetry: the matrix built from the kernels'
** upper halves and the one from their lower halves agree to 1e-12
** relative (rounding of the same sums in another order).
*/
#include "check.h"
#include "datafile.h"
#include "eval.h"
#include "helpers.h"
#include "hess.h"
#include "iterate.h"
#include "topo.h"

#define EX "/usr/share/doc/evolver/examples/"

static double mean_edge(const tds_mesh *m) {
  double sum = 0;
  int n = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    double d[3];
    v3_sub(d, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
    sum += v3_norm(d);
    n++;
  }
  return n ? sum / n : 1;
}

/* ew grad E + sum_q qw[q] grad Q_q at the current positions, in h's
** index map. fq: the pattern (built by the caller). */
static int wgrad(tds_ctx *ctx, tds_surf *s, const tds_hess *h, tds_fixq *fq, double ew,
                 const double *qw, double (*grad)[3], double *gv) {
  tds_eval_out out = {.grad = grad, .fq = fq->nq ? fq : NULL};
  int rc = tds_eval(ctx, s, &out);
  if (rc != TDS_OK) return rc;
  for (int32_t k = 0; k < h->n / 3; k++) {
    tds_id v = h->vert[k];
    for (int i = 0; i < 3; i++) gv[3 * k + i] = ew * grad[v][i];
    for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++)
      for (int i = 0; i < 3; i++) gv[3 * k + i] += qw[fq->eq[e]] * fq->g[e][i];
  }
  return TDS_OK;
}

/* Largest |H - FD(weighted gradient)| over all entries, relative to
** max |H|; opts as for tds_hess_assemble. Also *hmax, and the largest
** upper/lower-half difference in *asym (relative). -1 on failure. */
static double fd_error(tds_ctx *ctx, tds_surf *s, const tds_hess_opts *opts, double *asym) {
  tds_hess h = {0}, hl = {0};
  tds_hess_opts ol = *opts;
  ol.from_lower = 1;
  if (tds_hess_assemble(ctx, s, opts, &h) != TDS_OK) return -1;
  if (tds_hess_assemble(ctx, s, &ol, &hl) != TDS_OK) {
    tds_hess_free(&h);
    return -1;
  }
  tds_fixq fq = {0};
  int32_t n = h.n;
  double (*grad)[3] = calloc((size_t)s->m.nv + 1, sizeof *grad);
  double *gp = calloc((size_t)n + 1, sizeof *gp), *gm = calloc((size_t)n + 1, sizeof *gm);
  double *qw = calloc((size_t)h.nq + 1, sizeof *qw);
  double worst = -1, hmax = 0;
  if (!grad || !gp || !gm || !qw || tds_fixq_build(ctx, s, &fq) != TDS_OK) goto done;
  double ew = opts->quantity >= 0 ? 0 : 1;
  for (int32_t q = 0; q < h.nq; q++)
    qw[q] = opts->quantity >= 0 ? q == opts->quantity : opts->lagrange ? -h.mult[q] : 0;
  for (int32_t j = 0; j < h.H.colptr[n]; j++)
    if (fabs(h.H.val[j]) > hmax) hmax = fabs(h.H.val[j]);
  *asym = 0;
  for (int32_t j = 0; j < n; j++)
    for (int32_t i = 0; i <= j; i++) {
      double d = fabs(tds_spmat_get(&h.H, i, j) - tds_spmat_get(&hl.H, i, j));
      if (d > *asym) *asym = d;
    }
  *asym /= hmax > 0 ? hmax : 1;
  double st = 1e-6 * mean_edge(&s->m);
  worst = 0;
  for (int32_t j = 0; j < n; j++) {
    double *x = &s->m.x[h.vert[j / 3]][j % 3], keep = *x;
    *x = keep + st;
    s->m.coord_gen++;
    int rc = wgrad(ctx, s, &h, &fq, ew, qw, grad, gp);
    *x = keep - st;
    s->m.coord_gen++;
    if (rc == TDS_OK) rc = wgrad(ctx, s, &h, &fq, ew, qw, grad, gm);
    *x = keep;
    s->m.coord_gen++;
    if (rc != TDS_OK) {
      worst = -1;
      break;
    }
    for (int32_t i = 0; i < n; i++) {
      double d = fabs((gp[i] - gm[i]) / (2 * st) - tds_spmat_get(&h.H, i, j));
      if (d > worst) worst = d;
    }
  }
  if (worst >= 0) worst /= hmax > 0 ? hmax : 1;
  if (!(hmax > 0)) worst = -1; /* an all-zero Hessian tests nothing */
done:
  tds_fixq_free(&fq);
  free(grad);
  free(gp);
  free(gm);
  free(qw);
  tds_hess_free(&h);
  tds_hess_free(&hl);
  tds_surf_update(ctx, s);
  return worst;
}

static void jitter(tds_mesh *m, double amp, uint64_t seed) {
  uint64_t st = seed;
  for (tds_id v = 0; v < m->nv; v++)
    for (int i = 0; i < 3; i++) m->x[v][i] += h_uniform(&st, -amp, amp);
  m->coord_gen++;
}

#define CHECK_FD(ctx, s, opts)                                             \
  do {                                                                     \
    double asym_ = 1, err_ = fd_error((ctx), (s), (opts), &asym_);          \
    CHECK(err_ >= 0);                                                      \
    CHECK(err_ <= 1e-6);                                                   \
    CHECK(asym_ <= 1e-12);                                                 \
    if (!(err_ >= 0 && err_ <= 1e-6 && asym_ <= 1e-12))                    \
      printf("  %s:%d: fd error %g, asymmetry %g\n", __FILE__, __LINE__,   \
             err_, asym_);                                                 \
  } while (0)

static const tds_hess_opts ENERGY = {0, -1, 0}, LAGR = {1, -1, 0};

/* (a) Tetrahedron: tension, prescribed pressure, gravity, random shape. */
static void hess_tetra_fd(void) {
  for (uint64_t seed = 1; seed <= 3; seed++) {
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, h_tetra(&ctx, &s, NULL));
    jitter(&s.m, 0.2, seed);
    uint64_t st = seed * 77;
    for (tds_id f = 0; f < s.m.nf; f++) s.m.ften[f] = h_uniform(&st, 0.5, 2);
    s.m.bflags[0] |= TDS_PRESSURE;
    s.m.bpressure[0] = 1.3;
    s.gravity_on = 1;
    s.gravity = 2.5;
    s.m.bdensity[0] = 0.7;
    CHECK_FD(&ctx, &s, &ENERGY);
    tds_surf_free(&s);
  }
}

/* (a) Triple junction with edge tensions and a fixed vertex, whose
** coordinates must not appear. */
static void hess_triple_fd(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_triple(&ctx, &s, 0.8));
  jitter(&s.m, 0.15, 11);
  uint64_t st = 5;
  for (tds_id e = 0; e < s.m.ne; e++) s.m.eten[e] = h_uniform(&st, 0.1, 1);
  s.m.vflags[2] |= TDS_FIXED;
  tds_hess h = {0};
  REQUIRE_OK(&ctx, tds_hess_assemble(&ctx, &s, &ENERGY, &h));
  CHECK(h.n == 3 * 4);
  CHECK(h.vidx[2] == -1);
  tds_hess_free(&h);
  CHECK_FD(&ctx, &s, &ENERGY);
  tds_surf_free(&s);
}

/* (a), (b) Cube with a target volume: energy, each volume alone, and the
** Lagrangian with the pressure tds computes. */
static void hess_cube_fd(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  jitter(&s.m, 0.1, 3);
  REQUIRE_OK(&ctx, tds_pressures(&ctx, &s));
  CHECK(fabs(s.m.bpressure[0]) > 0.1); /* a real multiplier is tested */
  CHECK_FD(&ctx, &s, &ENERGY);
  CHECK_FD(&ctx, &s, &LAGR);
  tds_hess_opts vol = {0, 0, 0};
  CHECK_FD(&ctx, &s, &vol);
  s.symmetric_content = 1;
  CHECK_FD(&ctx, &s, &vol);
  tds_surf_free(&s);
}

/* (a), (b) A named energy quantity and a fixed one on the cube. */
static void hess_quantity_fd(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
  jitter(&s.m, 0.1, 9);
  tds_quantity *Q = calloc(2, sizeof *Q);
  tds_method_inst *mi = calloc(2, sizeof *mi);
  REQUIRE_OK(&ctx, Q && mi ? TDS_OK : TDS_ENOMEM);
  s.quant = Q;
  s.nquant = 2;
  Q[0] = (tds_quantity){.kind = TDS_Q_ENERGY, .modulus = 0.4, .ninst = 1, .inst = &mi[0]};
  mi[0] = (tds_method_inst){.method = TDS_M_FULL_GRAVITY, .modulus = 1};
  s.m.bdensity[0] = 1.5;
  s.gravity_on = 1;
  s.gravity = 2;
  Q[1] = (tds_quantity){.kind = TDS_Q_FIXED, .modulus = 1, .ninst = 1, .inst = &mi[1],
                        .target = 1.1};
  mi[1] = (tds_method_inst){.method = TDS_M_FACET_AREA, .modulus = 1};
  REQUIRE_OK(&ctx, tds_pressures(&ctx, &s));
  CHECK(fabs(Q[1].pressure) > 0.01);
  CHECK_FD(&ctx, &s, &ENERGY);
  CHECK_FD(&ctx, &s, &LAGR);
  tds_hess_opts q0 = {0, 0, 0};
  CHECK_FD(&ctx, &s, &q0);
  s.quant = NULL;
  s.nquant = 0;
  free(Q);
  free(mi);
  tds_surf_free(&s);
}

/* (c) States of Evolver's examples: load, refine, evolve, then the
** Lagrangian (with tds's pressures) and each constrained quantity. */
static void example_fd(const char *file, int refine, int steps) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, file));
  for (int r = 0; r < refine; r++) REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  REQUIRE_OK(&ctx, tds_iterate(&ctx, &s, steps));
  REQUIRE_OK(&ctx, tds_pressures(&ctx, &s));
  CHECK_FD(&ctx, &s, &ENERGY);
  CHECK_FD(&ctx, &s, &LAGR);
  tds_hess h = {0};
  REQUIRE_OK(&ctx, tds_hess_assemble(&ctx, &s, &LAGR, &h));
  for (int32_t q = 0; q < h.nq; q++) {
    tds_hess_opts oq = {0, q, 0};
    CHECK_FD(&ctx, &s, &oq);
    CHECK(fabs(h.mult[q]) > 0); /* the Lagrangian term is really there */
  }
  tds_hess_free(&h);
  tds_surf_free(&s);
}

static void hess_example_cube(void) { example_fd(EX "cube.fe", 2, 10); }
static void hess_example_mound(void) { example_fd(EX "mound.fe", 2, 10); }
static void hess_example_catbody(void) { example_fd(EX "catbody.fe", 2, 10); }
static void hess_example_column(void) { example_fd(EX "column.fe", 2, 10); }

/* (d) Exact: a flat unit square (two right triangles, diagonal 1-3) in
** z = 0, tension 1. To second order A = 1 + (1/2) int |grad z|^2, so the
** z-block of the Hessian is the P1 stiffness matrix: diagonal 1, -1/2
** along the four sides, 0 across both diagonals; and z does not couple
** to x, y on a flat sheet. Exact in binary, so 1e-15. */
static void hess_flat_square(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, NULL));
  tds_hess h = {0};
  REQUIRE_OK(&ctx, tds_hess_assemble(&ctx, &s, &ENERGY, &h));
  CHECK(h.n == 12);
  static const double K[4][4] = {{1, -0.5, 0, -0.5},
                                 {-0.5, 1, -0.5, 0},
                                 {0, -0.5, 1, -0.5},
                                 {-0.5, 0, -0.5, 1}};
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < 4; b++) {
      CHECK_NEAR(tds_spmat_get(&h.H, h.vidx[a] + 2, h.vidx[b] + 2), K[a][b], 1e-15);
      for (int i = 0; i < 2; i++)
        CHECK_NEAR(tds_spmat_get(&h.H, h.vidx[a] + 2, h.vidx[b] + i), 0, 1e-15);
    }
  CHECK_NEAR(h.energy, 1, 1e-15);
  tds_hess_free(&h);
  tds_surf_free(&s);
}

/* The bordered matrix: H in the top left, the volume gradient in the
** last column, zero in the corner; the volume gradient of the unit cube
** at a corner is the sum of its facets' normal/6 parts, checked against
** tds_eval's. */
static void hess_kkt_layout(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  jitter(&s.m, 0.05, 21);
  REQUIRE_OK(&ctx, tds_pressures(&ctx, &s));
  tds_hess h = {0};
  tds_spmat K = {0};
  REQUIRE_OK(&ctx, tds_hess_assemble(&ctx, &s, &LAGR, &h));
  REQUIRE_OK(&ctx, tds_hess_kkt(&ctx, &h, &K));
  CHECK(K.nrow == h.n + 1 && h.nq == 1);
  tds_fixq fq = {0};
  double (*grad)[3] = calloc((size_t)s.m.nv, sizeof *grad);
  REQUIRE_OK(&ctx, grad ? tds_fixq_build(&ctx, &s, &fq) : TDS_ENOMEM);
  tds_eval_out out = {.grad = grad, .fq = &fq};
  REQUIRE_OK(&ctx, tds_eval(&ctx, &s, &out));
  for (int32_t k = 0; k < h.n / 3; k++) {
    tds_id v = h.vert[k];
    for (int i = 0; i < 3; i++) {
      double gq = 0;
      for (int32_t e = fq.start[v]; e < fq.start[v + 1]; e++) gq += fq.g[e][i];
      CHECK_NEAR(tds_spmat_get(&K, 3 * k + i, h.n), gq, 1e-15);
      CHECK_NEAR(tds_spmat_get(&K, h.n, 3 * k + i), gq, 1e-15);
      CHECK_NEAR(h.grad[3 * k + i], grad[v][i], 1e-15);
      for (int32_t j = 0; j < h.n; j++)
        CHECK(tds_spmat_get(&K, 3 * k + i, j) == tds_spmat_get(&h.H, 3 * k + i, j));
    }
  }
  CHECK(tds_spmat_get(&K, h.n, h.n) == 0);
  /* H x from the upper triangle equals the dense product */
  double x[64], y[64];
  uint64_t st = 4;
  for (int32_t i = 0; i < h.n && i < 64; i++) x[i] = h_uniform(&st, -1, 1);
  if (h.n <= 64) {
    tds_spmat_mulv(&h.H, x, y);
    for (int32_t i = 0; i < h.n; i++) {
      double d = 0;
      for (int32_t j = 0; j < h.n; j++) d += tds_spmat_get(&h.H, i, j) * x[j];
      CHECK_NEAR(y[i], d, 1e-12);
    }
  }
  free(grad);
  tds_fixq_free(&fq);
  tds_spmat_free(&K);
  tds_hess_free(&h);
  tds_surf_free(&s);
}

int main(void) {
  RUN(hess_flat_square);
  RUN(hess_tetra_fd);
  RUN(hess_triple_fd);
  RUN(hess_cube_fd);
  RUN(hess_quantity_fd);
  RUN(hess_kkt_layout);
  RUN(hess_example_cube);
  RUN(hess_example_mound);
  RUN(hess_example_catbody);
  RUN(hess_example_column);
  return check_done();
}
