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
#include "attr.h"
#include "check.h"
#include "datafile.h"
#include "eval.h"
#include "helpers.h"
#include "hess.h"
#include "iterate.h"
#include "motion.h"
#include "recalc.h"
#include "topo.h"

#define EX "/usr/share/doc/evolver/examples/"

/* Mean (or, with shortest, least) edge length. */
static double edge_scale(const tds_mesh *m, int shortest) {
  double sum = 0, least = INFINITY;
  int n = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    double d[3];
    v3_sub(d, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
    sum += v3_norm(d);
    if (v3_norm(d) < least) least = v3_norm(d);
    n++;
  }
  return !n ? 1 : shortest ? least : sum / n;
}
static double mean_edge(const tds_mesh *m) { return edge_scale(m, 0); }

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
/* the string model: edge tension, body area, string gravity, content */
static void hess_example_slidestr(void) { example_fd(EX "slidestr.fe", 2, 10); }
/* the string model in a Riemannian metric (METRIC) */
static void hess_example_metric(void) { example_fd(EX "metric.fe", 2, 10); }
static void hess_example_catbody(void) { example_fd(EX "catbody.fe", 2, 10); }
static void hess_example_column(void) { example_fd(EX "column.fe", 2, 10); }
/* the torus model: wrapped facets and the volumes' lattice translations
** (TORUS_FILLED: one body's constraint dropped) */
static void hess_example_twointor(void) { example_fd(EX "twointor.fe", 1, 10); }
static void hess_example_phelanc(void) { example_fd(EX "phelanc.fe", 0, 10); }
/* a symmetry group's wraps (symtest.fe: two Kelvin cells under the group
** "torus", no constraints), refined once */
static void hess_example_symtest(void) { example_fd(EX "symtest.fe", 1, 10); }

/* the string model in the 2-D torus (100grain.fe: 100 cells, wrapped
** edges, AUTOPOP and AUTOCHOP): the energy and the Lagrangian of its 100
** area constraints (each constraint alone as example_fd does would be
** 100 more finite-difference runs; the Lagrangian sums them all). */
static void hess_example_100grain(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, EX "100grain.fe"));
  REQUIRE_OK(&ctx, tds_iterate(&ctx, &s, 5));
  REQUIRE_OK(&ctx, tds_pressures(&ctx, &s));
  CHECK_FD(&ctx, &s, &ENERGY);
  CHECK_FD(&ctx, &s, &LAGR);
  tds_surf_free(&s);
}

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


/* ---- the Hessian in motion space (tds_hess_reduce) ---- */

/* E - sum_q mult_q Q_q at the current positions (mult NULL: E). */
static int lagr_value(tds_ctx *ctx, tds_surf *s, tds_fixq *fq, const double *mult, double *F) {
  tds_eval_out out = {.fq = fq->nq ? fq : NULL};
  int rc = tds_eval(ctx, s, &out);
  *F = out.energy;
  if (mult)
    for (int32_t q = 0; q < fq->nq; q++) *F -= mult[q] * fq->value[q];
  return rc;
}

/* Move every movable vertex by sgn * u (reduced coordinates) through
** tds_motion_apply from saved positions x0, p0. */
static int move_by(tds_surf *s, const tds_hess *h, const tds_hess_red *r, const double *u,
                   double sgn, double (*x0)[3], double (*p0)[2]) {
  int bad = 0;
  for (int32_t k = 0; k < r->nvm; k++) {
    tds_id v = h->vert[k];
    int d = r->start[k + 1] - r->start[k];
    double dx[3] = {0, 0, 0};
    const double *uk = u + r->start[k];
    if (s->m.vbdry[v] != TDS_NONE)
      for (int a = 0; a < d; a++) dx[a] = sgn * uk[a];
    else
      for (int i = 0; i < 3; i++)
        for (int a = 0; a < d; a++) dx[i] += sgn * r->basis[k][i][a] * uk[a];
    if (tds_motion_apply(s, v, x0[v], p0[v], dx) != TDS_OK) bad = 1;
  }
  s->m.coord_gen++;
  return bad;
}

/* Worst relative error of second (and first) differences of the
** Lagrangian along motions u against u^T Hr u (and grad^T u), over
** ndir seeded random directions. Displacements are 1e-3 x the shortest
** edge: truncation, (|u|/edge)^2 relative, and rounding of the energy
** sums, 1e-16 |F| / |u^T H u|, are both below 1e-6 there (measured
** worst 4e-7 for second differences; they scale as |u|^2, so it is
** truncation; 1e-4 x would be rounding-bound on catbody, whose F carries
** a large volconst). Level sets are held to 1e-14 (constraint_tol) so the
** projection adds nothing. 1e-5 is then a wrong term: leaving out the
** curvature term fails all three at 7e-5 .. 1e-2. First differences
** are relative to sum |grad_i u_i|, small near equilibrium, so their
** third-order error reaches 3e-6: 1e-4. */
static double reduced_error(tds_ctx *ctx, tds_surf *s, int ndir, uint64_t seed,
                            double *gerr) {
  tds_hess h = {0};
  tds_hess_red r = {0};
  tds_fixq fq = {0};
  double worst = -1;
  int32_t nv = s->m.nv;
  double (*x0)[3] = malloc((size_t)nv * sizeof *x0), (*p0)[2] = malloc((size_t)nv * sizeof *p0);
  double *u = NULL, *Hu = NULL;
  if (!x0 || !p0 || tds_hess_assemble(ctx, s, NULL, &h) != TDS_OK ||
      tds_hess_reduce(ctx, s, &h, &r) != TDS_OK || tds_fixq_build(ctx, s, &fq) != TDS_OK)
    goto done;
  u = calloc((size_t)r.m + 1, sizeof *u);
  Hu = calloc((size_t)r.m + 1, sizeof *Hu);
  if (!u || !Hu) goto done;
  memcpy(x0, s->m.x, (size_t)nv * sizeof *x0);
  memcpy(p0, s->m.vp, (size_t)nv * sizeof *p0);
  double L = edge_scale(&s->m, 1), F0;
  if (lagr_value(ctx, s, &fq, h.mult, &F0) != TDS_OK) goto done;
  uint64_t st = seed;
  worst = 0;
  *gerr = 0;
  for (int dir = 0; dir < ndir; dir++) {
    for (int32_t k = 0; k < r.nvm; k++)
      for (int32_t a = r.start[k]; a < r.start[k + 1]; a++) {
        int32_t c = a - r.start[k];
        double bl = sqrt(r.basis[k][0][c] * r.basis[k][0][c] + r.basis[k][1][c] * r.basis[k][1][c] +
                         r.basis[k][2][c] * r.basis[k][2][c]);
        u[a] = h_uniform(&st, -1, 1) * 1e-3 * L / (bl > 0 ? bl : 1);
      }
    double Fp, Fm;
    int bad = move_by(s, &h, &r, u, 1, x0, p0);
    bad |= lagr_value(ctx, s, &fq, h.mult, &Fp) != TDS_OK;
    bad |= move_by(s, &h, &r, u, -1, x0, p0);
    bad |= lagr_value(ctx, s, &fq, h.mult, &Fm) != TDS_OK;
    memcpy(s->m.x, x0, (size_t)nv * sizeof *x0);
    memcpy(s->m.vp, p0, (size_t)nv * sizeof *p0);
    s->m.coord_gen++;
    if (bad) {
      worst = -1;
      break;
    }
    tds_spmat_mulv(&r.H, u, Hu);
    double q = 0, scale = 0, g = 0, gscale = 0;
    for (int32_t i = 0; i < r.m; i++) {
      q += u[i] * Hu[i];
      g += r.grad[i] * u[i];
      gscale += fabs(r.grad[i] * u[i]);
    }
    for (int32_t j = 0; j < r.m; j++)
      for (int32_t e = r.H.colptr[j]; e < r.H.colptr[j + 1]; e++)
        scale += (r.H.rowind[e] == j ? 1 : 2) * fabs(r.H.val[e] * u[r.H.rowind[e]] * u[j]);
    double err = fabs((Fp - 2 * F0 + Fm) - q) / scale;
    if (!(err <= worst)) worst = err;
    double ge = fabs((Fp - Fm) / 2 - g) / gscale;
    if (!(ge <= *gerr)) *gerr = ge;
  }
done:
  free(x0);
  free(p0);
  free(u);
  free(Hu);
  tds_fixq_free(&fq);
  tds_hess_red_free(&r);
  tds_hess_free(&h);
  tds_surf_update(ctx, s);
  return worst;
}

/* Load an example with text replacements (pairs from, to; every
** occurrence), refine, evolve, set pressures. */
static int load_edited(tds_ctx *ctx, tds_surf *s, const char *file, const char *const *rep,
                       int refine, int steps) {
  FILE *fp = fopen(file, "rb");
  if (!fp) return tds_seterr(ctx, TDS_EIO, "%s: cannot open", file);
  static char text[1 << 16], out[1 << 16];
  size_t n = fread(text, 1, sizeof text - 1, fp);
  fclose(fp);
  text[n] = 0;
  for (; rep[0]; rep += 2) {
    size_t o = 0, fl = strlen(rep[0]), tl = strlen(rep[1]);
    for (const char *p = text; *p;) {
      if (!strncmp(p, rep[0], fl) && o + tl < sizeof out) {
        memcpy(out + o, rep[1], tl);
        o += tl;
        p += fl;
      } else if (o + 1 < sizeof out) {
        out[o++] = *p++;
      } else {
        break;
      }
    }
    out[o] = 0;
    memcpy(text, out, o + 1);
  }
  int rc = tds_datafile_load_buffer(ctx, s, file, text, strlen(text));
  if (rc == TDS_OK) rc = tds_recalc(ctx, s);
  for (int i = 0; i < refine && rc == TDS_OK; i++) rc = tds_refine(ctx, s, NULL, NULL);
  if (rc == TDS_OK) rc = tds_iterate(ctx, s, steps);
  if (rc == TDS_OK) rc = tds_pressures(ctx, s);
  s->constraint_tol = 1e-14;
  return rc;
}

#define CHECK_REDUCED(ctx, s)                                               \
  do {                                                                      \
    double gerr_ = 1, err_ = reduced_error((ctx), (s), 6, 99, &gerr_);      \
    CHECK(err_ >= 0 && err_ <= 1e-5);                                       \
    CHECK(gerr_ <= 1e-4);                                                   \
    if (!(err_ >= 0 && err_ <= 1e-5 && gerr_ <= 1e-4))                      \
      printf("  %s:%d: second difference error %g, first %g\n", __FILE__,  \
             __LINE__, err_, gerr_);                                        \
  } while (0)

/* A drop on a curved table (paraboloid level set, contact-angle energy
** integrand, target volume): the tangent basis and the -mu Hess(phi)
** curvature term. */
static void hess_reduced_levelset(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  static const char *const rep[] = {"x3 = 0", "x3 = 0.3*(x1^2 + x2^2)", "angle = 90",
                                    "angle = 60", NULL};
  REQUIRE_OK(&ctx, load_edited(&ctx, &s, EX "mound.fe", rep, 1, 10));
  tds_hess h = {0};
  tds_hess_red r = {0};
  REQUIRE_OK(&ctx, tds_hess_assemble(&ctx, &s, NULL, &h));
  REQUIRE_OK(&ctx, tds_hess_reduce(&ctx, &s, &h, &r));
  int on = 0;
  for (int32_t k = 0; k < r.nvm; k++) on += r.start[k + 1] - r.start[k] == 2;
  CHECK(on >= 8); /* the contact line's vertices have 2 coordinates */
  CHECK(r.m == h.n - on);
  tds_hess_red_free(&r);
  tds_hess_free(&h);
  CHECK_REDUCED(&ctx, &s);
  tds_surf_free(&s);
}

/* Catenoid and column with their boundary vertices free to slide along
** the rings: parameter coordinates and the sum f . d2X/dp2 term; column
** has boundary energy and content integrands and gravity. */
static void reduced_boundary(const char *file) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  static const char *const rep[] = {"boundary 1   fixed", "boundary 1",
                                    "boundary 2   fixed", "boundary 2", NULL};
  REQUIRE_OK(&ctx, load_edited(&ctx, &s, file, rep, 1, 10));
  tds_hess h = {0};
  tds_hess_red r = {0};
  REQUIRE_OK(&ctx, tds_hess_assemble(&ctx, &s, NULL, &h));
  REQUIRE_OK(&ctx, tds_hess_reduce(&ctx, &s, &h, &r));
  int on = 0;
  for (int32_t k = 0; k < r.nvm; k++) on += r.start[k + 1] - r.start[k] == 1;
  CHECK(on >= 12); /* the ring vertices move along their parameter */
  tds_hess_red_free(&r);
  tds_hess_free(&h);
  CHECK_REDUCED(&ctx, &s);
  tds_surf_free(&s);
}
static void hess_reduced_catbody(void) { reduced_boundary(EX "catbody.fe"); }
static void hess_reduced_column(void) { reduced_boundary(EX "column.fe"); }

/* A non-finite energy is an error with a message, leaves out empty and
** the positions as they were. */
static void hess_bad_input(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  s.m.x[3][1] = NAN;
  tds_hess h = {0};
  CHECK(tds_hess_assemble(&ctx, &s, NULL, &h) == TDS_ENUM);
  CHECK(strstr(ctx.errmsg, "not finite") != NULL);
  CHECK(h.n == 0 && h.H.colptr == NULL && h.vidx == NULL && h.A.colptr == NULL);
  CHECK(isnan(s.m.x[3][1]) && s.m.x[3][0] == h_cube_x[3][0]);
  tds_hess_free(&h); /* safe on an emptied one */
  tds_surf_free(&s);
}

/* (a), (b) Knot energy, string curvature and Hooke springs (the rows with
** Hessians, eval_knot.c) on a seeded random closed polygon in space, with
** its total length held: energy and Lagrangian against differences of the
** assembled gradient. */
static void hess_knot_fd(void) {
  static const char text[] =
      "string\nparameter hooke_length = 0.6\nparameter knot_power = 3\n"
      "quantity k ENERGY modulus 0.5 method knot_energy global\n"
      "quantity c ENERGY modulus 0.3 method sqcurve_string global\n"
      "quantity h ENERGY modulus 2 method hooke_energy global\n"
      "define edge attribute hooke_size real\n"
      "quantity h2 ENERGY modulus 1.5 method hooke2_energy global\n"
      "quantity len FIXED = 7 method edge_tension global\n"
      "vertices\n1 1 0 0\n2 0.6 0.8 0.1\n3 -0.3 0.9 -0.1\n4 -1 0.1 0.2\n"
      "5 -0.6 -0.8 0\n6 0.3 -0.9 -0.2\n7 1.4 0.2 0.3 fixed\n"
      "edges\n1 1 2 hooke_size 0.7\n2 2 3 hooke_size 0.9\n3 3 4 hooke_size 0.5\n"
      "4 4 5 hooke_size 1.1\n5 5 6 hooke_size 0.8\n6 6 1 hooke_size 0.6\n"
      "7 1 7 hooke_size 0.4\n";
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load_buffer(&ctx, &s, "knot.fe", text, strlen(text)));
  for (tds_id e = 0; e < s.m.ne; e++) s.m.eten[e] = 0;
  jitter(&s.m, 0.1, 31);
  REQUIRE_OK(&ctx, tds_pressures(&ctx, &s));
  CHECK(fabs(s.quant[4].pressure) > 0.01);
  CHECK_FD(&ctx, &s, &ENERGY);
  CHECK_FD(&ctx, &s, &LAGR);
  tds_surf_free(&s);
}

/* SYMMETRY_GROUP "genus2" with KLEIN_METRIC (string model): the group's
** maps are projective, so the pullback of a wrapped head's gradient is
** J^T g and its Hessian J^T H J plus the map's curvature weighted by the
** gradient (symmetry.c). A network with single generators and runs,
** refined and jittered (seeded): the gradient against central
** differences of the energy (step 1e-5: measured error 1e-9 relative,
** where rounding of the energy, ~1e-12, gives 1e-7 at step 1e-6;
** tolerance 1e-7 relative to the largest entry) and the Hessian as every
** CHECK_FD;
** the same without KLEIN_METRIC (Euclidean lengths of the same maps). */


#define FDH 1e-5 /* the energy's rounding (~1e-12) over 1e-5: 1e-7 */
/* The gradient's first dims coordinates against central differences of
** the energy, to 1e-7 of its largest entry (which must be above 0.1). */
static void grad_fd(tds_ctx *ctx, tds_surf *s, int dims, const char *what) {
  double (*grad)[3] = calloc((size_t)s->m.nv, sizeof *grad);
  tds_eval_out out = {.grad = grad};
  REQUIRE_OK(ctx, tds_eval(ctx, s, &out));
  double worst = 0, big = 0;
  for (tds_id v = 0; v < s->m.nv; v++)
    for (int i = 0; i < dims; i++) {
      double keep = s->m.x[v][i], e[2];
      for (int k = 0; k < 2; k++) {
        s->m.x[v][i] = keep + (k ? -FDH : FDH);
        s->m.coord_gen++;
        tds_eval_out o = {0};
        REQUIRE_OK(ctx, tds_eval(ctx, s, &o));
        e[k] = o.energy;
      }
      s->m.x[v][i] = keep;
      s->m.coord_gen++;
      worst = fmax(worst, fabs((e[0] - e[1]) / (2 * FDH) - grad[v][i]));
      big = fmax(big, fabs(grad[v][i]));
    }
  if (!(worst <= 1e-7 * big)) printf("  %s gradient: fd error %g of %g\n", what, worst, big);
  CHECK(big > 0.1 && worst <= 1e-7 * big);
  free(grad);
}
static void genus2_fd(int klein) {
  char text[1024];
  snprintf(text, sizeof text,
           "STRING\nSPACE_DIMENSION 2\n%sSYMMETRY_GROUP \"genus2\"\n"
           "vertices\n1 0.1 0.05\n2 -0.2 0.3\n3 0.3 -0.4\n4 -0.35 -0.25 fixed\n"
           "edges\n1 1 3 wrap 0x10\n2 3 1 wrap 0x21\n3 1 2 wrap 0x32\n4 2 1 wrap 0x43\n"
           "5 1 2\n6 2 3 wrap 0x30\n7 4 1 wrap 0x75 tension 1.5\n8 3 4 wrap 0x01\n",
           klein ? "KLEIN_METRIC\n" : "");
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load_buffer(&ctx, &s, "g2.fe", text, strlen(text)));
  REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  jitter(&s.m, 0.02, klein ? 41 : 43);
  for (tds_id v = 0; v < s.m.nv; v++) s.m.x[v][2] = 0;
  s.m.coord_gen++;
  CHECK_FD(&ctx, &s, &ENERGY);
  /* the gradient against differences of the energy */
  grad_fd(&ctx, &s, 2, "genus2");
  tds_surf_free(&s);
}
static void hess_genus2_klein(void) { genus2_fd(1); }
static void hess_genus2_euclid(void) { genus2_fd(0); }

/* KLEIN_METRIC on a film (hyperbolic facet areas, method_klein.c), with
** and without genus2 wraps on its edges (three facets whose wraps
** multiply to the identity, G_0 carrying corners near the ball's edge),
** refined and jittered (seeded):
** the gradient against central differences of the energy (as genus2_fd)
** and the Hessian as every CHECK_FD. */
static void klein_film_fd(int g2) {
  char text[1024];
  snprintf(text, sizeof text,
           "KLEIN_METRIC\n%s"
           "vertices\n1 0.1 0.2 0.3\n2 -0.5 -0.1 0.2\n3 -0.4 0.3 -0.3\n4 -0.6 0.1 0.0\n"
           "5 0.2 -0.3 0.1 fixed\n"
           "edges\n1 1 2%s\n2 2 3\n3 3 1%s\n4 2 4\n5 4 1%s\n6 1 5\n7 5 3%s\n"
           "faces\n1 1 2 3\n2 1 4 5\n3 -3 -7 -6\n",
           g2 ? "SYMMETRY_GROUP \"genus2\"\n" : "", g2 ? " wrap 0x10" : "",
           g2 ? " wrap 0x54" : "", g2 ? " wrap 0x54" : "", g2 ? " wrap 0x10" : "");
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load_buffer(&ctx, &s, "kf.fe", text, strlen(text)));
  REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  jitter(&s.m, 0.01, g2 ? 51 : 53);
  CHECK_FD(&ctx, &s, &ENERGY);
  grad_fd(&ctx, &s, 3, "klein film");
  tds_surf_free(&s);
}
static void hess_klein_film(void) { klein_film_fd(0); }
static void hess_klein_film_genus2(void) { klein_film_fd(1); }

/* Element attributes in integrands and formulas (xattr.h): a drop on a
** curved table whose curvature is a vertex attribute (the formula), with
** a contact angle per edge (the constraint's energy integrand), a weight
** per facet (an energy and a fixed quantity) and per edge (an edge
** quantity), seeded random values. An attribute is a constant of its
** element, so the checks are the usual ones: the Hessian against
** differences of the gradient, and the reduced gradient and Hessian
** against differences of the Lagrangian along real motions (the curved
** formula's per-vertex Hessian enters through -mu Hess(phi)). */
static void hess_attr(void) {
  static const char text[] =
      "define edge attribute ang real\n"
      "define vertex attribute cv real\n"
      "define facet attribute fw real\n"
      "define edge attribute ew real\n"
      "constraint 1 formula: x3 = cv*(x^2 + y^2)\n"
      "energy: e1: cos(ang*pi/180)*y e2: 0 e3: 0\n"
      "quantity fq energy method facet_scalar_integral global\n"
      "scalar_integrand: fw*z^2\n"
      "quantity eq energy method edge_vector_integral global\n"
      "vector_integrand: q1: ew*y*z q2: 0 q3: ew*x\n"
      "quantity vq fixed = 0 method facet_vector_integral global\n"
      "vector_integrand: q1: 0 q2: 0 q3: (1 + fw)*z\n"
      "vertices\n"
      "1 0 0 0 constraint 1\n2 1 0 0 constraint 1\n3 1 1 0 constraint 1\n"
      "4 0 1 0 constraint 1\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n"
      "edges\n1 1 2 constraint 1\n2 2 3 constraint 1\n3 3 4 constraint 1\n"
      "4 4 1 constraint 1\n5 5 6\n6 6 7\n7 7 8\n8 8 5\n9 1 5\n10 2 6\n11 3 7\n12 4 8\n"
      "faces\n1 1 10 -5 -9\n2 2 11 -6 -10\n3 3 12 -7 -11\n4 4 9 -8 -12\n5 5 6 7 8\n"
      "bodies\n1 1 2 3 4 5 volume 1\n";
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load_buffer(&ctx, &s, "attr.fe", text, sizeof text - 1));
  REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  uint64_t st = 2024;
  static const struct { int kind; const char *name; double lo, hi; } set[] = {
      {TDS_EDGE, "ang", 60, 120}, {TDS_VERTEX, "cv", 0, 0.3},
      {TDS_FACET, "fw", 0, 0.5}, {TDS_EDGE, "ew", 0, 0.2}};
  for (int k = 0; k < 4; k++) {
    tds_attr a;
    if (!tds_attr_find(&s.m, set[k].kind, set[k].name, &a)) {
      CHECK(0);
      tds_surf_free(&s);
      return;
    }
    int32_t n = set[k].kind == TDS_VERTEX ? s.m.nv : set[k].kind == TDS_EDGE ? s.m.ne : s.m.nf;
    for (tds_id i = 0; i < n; i++) {
      double v = h_uniform(&st, set[k].lo, set[k].hi);
      CHECK_OK(&ctx, tds_attr_write(&ctx, &s, &a, i, &v, 1));
    }
  }
  REQUIRE_OK(&ctx, tds_recalc(&ctx, &s)); /* onto the new curved tables */
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  s.quant[2].target = s.quant[2].value; /* vq held where it is */
  REQUIRE_OK(&ctx, tds_iterate(&ctx, &s, 5));
  REQUIRE_OK(&ctx, tds_pressures(&ctx, &s));
  s.constraint_tol = 1e-14;
  CHECK_FD(&ctx, &s, &ENERGY);
  CHECK_FD(&ctx, &s, &LAGR);
  CHECK_REDUCED(&ctx, &s);
  /* the attributes are really read: other values, another energy */
  double e0 = s.energy;
  tds_attr a;
  double v = 2;
  CHECK(tds_attr_find(&s.m, TDS_FACET, "fw", &a));
  CHECK_OK(&ctx, tds_attr_write(&ctx, &s, &a, 0, &v, 1));
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK(fabs(s.energy - e0) > 1e-6);
  tds_surf_free(&s);
}

int main(void) {
  RUN(hess_flat_square);
  RUN(hess_tetra_fd);
  RUN(hess_triple_fd);
  RUN(hess_cube_fd);
  RUN(hess_quantity_fd);
  RUN(hess_knot_fd);
  RUN(hess_genus2_klein);
  RUN(hess_genus2_euclid);
  RUN(hess_klein_film);
  RUN(hess_klein_film_genus2);
  RUN(hess_kkt_layout);
  RUN(hess_example_cube);
  RUN(hess_example_mound);
  RUN(hess_example_slidestr);
  RUN(hess_example_metric);
  RUN(hess_example_catbody);
  RUN(hess_example_column);
  RUN(hess_example_twointor);
  RUN(hess_example_phelanc);
  RUN(hess_example_symtest);
  RUN(hess_example_100grain);
  RUN(hess_reduced_levelset);
  RUN(hess_reduced_catbody);
  RUN(hess_reduced_column);
  RUN(hess_attr);
  RUN(hess_bad_input);
  return check_done();
}
