/* pg.c: the driver of the projected-gradient method (see pg.h, pg_int.h
** and doc/method.md): work arrays, the iteration loop, termination. */
#include "torus.h"
#include "pg.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "gather.h"
#include "motion.h"
#include "progress.h"
#include "pg_int.h"
#include "recalc.h"
#include "snap.h"
#include "vec3.h"

void pg_work_free(pgw *w) {
  tds_free(&w->al, w->kind);
  tds_free(&w->al, w->bnb);
  tds_free(&w->al, w->mov);
  tds_free_aligned(&w->al, w->acc);
  tds_free(&w->al, w->grad);
  tds_free(&w->al, w->fcot);
  tds_free(&w->al, w->d);
  tds_free(&w->al, w->nrm);
  tds_free(&w->al, w->model);
  tds_free(&w->al, w->vel);
  tds_free(&w->al, w->rest);
  tds_free(&w->al, w->tan);
  tds_free(&w->al, w->P);
  tds_free(&w->al, w->Jinv);
  tds_free(&w->al, w->xbest);
  tds_free(&w->al, w->pbest);
  tds_fixq_free(&w->fq);
  tds_free(&w->al, w->an);
  tds_free(&w->al, w->gram);
  tds_free(&w->al, w->rhs);
  tds_free(&w->al, w->mult);
  pg_flip_free(w);
  pg_accel_free(&w->aa);
  pg_plan_free(w);
  memset(w, 0, sizeof *w);
}

/* Classify vertices: fixed, free, on level sets, on a boundary, or on an
** edge of three or more facets (a junction). Needs adjacency. */
static void classify(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  w->nmov = 0;
  w->rigid = 1;
  for (tds_id v = 0; v < m->nv; v++) {
    uint8_t k = VK_FIXED;
    if (tds_vertex_free(s, v) && m->vf_start[v + 1] > m->vf_start[v]) {
      if (m->vbdry[v] != TDS_NONE) k = VK_BDRY;
      else if (m->vcon[v]) k = VK_LEVEL;
      else k = VK_FREE;
      if (k == VK_FREE)
        for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++)
          if (tds_edge_valence(m, TDS_OID(m->ve[i])) > 2) k = VK_JUNCTION;
    }
    w->kind[v] = k;
    if ((k == VK_FIXED && m->vf_start[v + 1] > m->vf_start[v] &&
         !(m->vflags[v] & TDS_DEAD)) || k == VK_BDRY)
      w->rigid = 0;
    w->bnb[v][0] = w->bnb[v][1] = -1;
    if (k == VK_LEVEL || k == VK_BDRY) {
      int nb = 0;
      for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++) {
        tds_id e = TDS_OID(m->ve[i]);
        if (tds_edge_valence(m, e) != 1) continue;
        if (nb < 2) w->bnb[v][nb] = m->ev[e][0] == v ? m->ev[e][1] : m->ev[e][0];
        nb++;
      }
      if (nb != 2) w->bnb[v][0] = w->bnb[v][1] = -1;
    }
    if (k != VK_FIXED) w->mov[w->nmov++] = v;
  }
  /* Only a surface sliding on level sets (a drop on a table) is known to
  ** drift; closed free surfaces converge without the correction. */
  int level = 0;
  for (int32_t j = 0; j < w->nmov; j++) level |= w->kind[w->mov[j]] == VK_LEVEL;
  if (!level) w->rigid = 0;
}


/* Allocate and fill the work arrays; depth > 0 also the Anderson history.
** TDS_OK or TDS_ENOMEM (w freed). */
int pg_work_init(tds_ctx *ctx, tds_surf *s, pgw *w, int depth) {
  tds_mesh *m = &s->m;
  memset(w, 0, sizeof *w);
  w->al = ctx->alloc;
  if (tds_mesh_adjacency(m) != TDS_OK) goto nomem;
  size_t nv = (size_t)(m->nv > 0 ? m->nv : 1), nf = (size_t)(m->nf > 0 ? m->nf : 1);
  w->nv = m->nv;
  w->ne = m->ne;
  w->nf = m->nf;
  w->kind = tds_calloc(&w->al, nv, 1);
  w->bnb = tds_calloc(&w->al, nv, sizeof *w->bnb);
  w->mov = tds_calloc(&w->al, nv, sizeof *w->mov);
  /* one vertex's sums on cache lines of their own: the two halves of
  ** the pass may add into neighbouring slots from two threads */
  size_t accb = (2 * nv * sizeof *w->acc + 63) / 64 * 64;
  w->acc = tds_calloc_aligned(&w->al, accb);
  w->grad = tds_calloc(&w->al, 2 * nv, sizeof *w->grad);
  w->fcot = tds_calloc(&w->al, 3 * nf, sizeof *w->fcot);
  w->d = tds_calloc(&w->al, nv, sizeof *w->d);
  w->nrm = tds_calloc(&w->al, nv, sizeof *w->nrm);
  w->model = tds_calloc(&w->al, nv, sizeof *w->model);
  w->vel = tds_calloc(&w->al, nv, sizeof *w->vel);
  w->rest = tds_calloc(&w->al, nv, sizeof *w->rest);
  w->tan = tds_calloc(&w->al, nv, sizeof *w->tan);
  w->P = tds_calloc(&w->al, nv, sizeof *w->P);
  w->Jinv = tds_calloc(&w->al, nv, sizeof *w->Jinv);
  w->xbest = tds_calloc(&w->al, nv, sizeof *w->xbest);
  w->pbest = tds_calloc(&w->al, nv, sizeof *w->pbest);
  if (!w->kind || !w->bnb || !w->mov || !w->acc || !w->grad || !w->fcot ||
      !w->d || !w->nrm || !w->model || !w->vel || !w->rest || !w->tan ||
      !w->P || !w->Jinv || !w->xbest || !w->pbest)
    goto nomem;
  int rc = tds_fixq_build(ctx, s, &w->fq);
  if (rc != TDS_OK) {
    pg_work_free(w);
    return rc;
  }
  int32_t nq = w->fq.nq;
  if (nq && !w->fq.gram) { /* its Gram matrices are dense (fixq.h) */
    pg_work_free(w);
    return tds_seterr(ctx, TDS_ERANGE,
                      "pg: more than %d constrained volumes and quantities is not supported "
                      "yet (g handles them)", TDS_FIXQ_DENSE_MAX);
  }
  w->an = tds_calloc(&w->al, (size_t)w->fq.nent + 1, sizeof *w->an);
  w->gram = tds_calloc(&w->al, (size_t)nq * (size_t)nq + 1, sizeof *w->gram);
  w->rhs = tds_calloc(&w->al, (size_t)nq + 1, sizeof *w->rhs);
  w->mult = tds_calloc(&w->al, (size_t)nq + 1, sizeof *w->mult);
  if (!w->an || !w->gram || !w->rhs || !w->mult) goto nomem;
  if (pg_flip_init(s, w) != TDS_OK) goto nomem;
  if (pg_plan_init(s, w) != TDS_OK) goto nomem;
  w->threads = 1;
  w->isa = pg_pass_isa(1);
  w->flip_tol = 1e-12;
  classify(s, w);
  pg_gauge_init(s, w);
  if (depth > 0 && pg_accel_init(&w->aa, &w->al, 3 * w->nmov, depth) != TDS_OK) goto nomem;
  w->aa.isa = w->isa;
  return TDS_OK;
nomem:
  pg_work_free(w);
  return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
}

int tds_pg_flip_all(tds_ctx *ctx, tds_surf *s, int32_t *nflips) {
  if (s->m.torus) return tds_torus_unsupported(ctx, "pg's flips");
  pgw w;
  int rc = pg_work_init(ctx, s, &w, 0);
  if (rc != TDS_OK) return rc;
  int32_t n = pg_flip_pass(s, &w);
  pg_work_free(&w);
  if (nflips) *nflips = n;
  return tds_surf_update(ctx, s);
}

int tds_pg_multipliers(tds_ctx *ctx, tds_surf *s, double *mult) {
  pgw w;
  int rc = pg_work_init(ctx, s, &w, 0);
  if (rc != TDS_OK) return rc;
  pg_stepinfo si;
  double energy;
  rc = pg_pass(ctx, s, &w, &energy);
  if (rc == TDS_OK) rc = pg_step(ctx, s, &w, 2, &si);
  for (tds_id b = 0; b < s->m.nb; b++) mult[b] = 0;
  if (rc == TDS_OK)
    for (int32_t q = 0; q < w.fq.nq; q++)
      if (w.fq.qbody[q] != TDS_NONE) mult[w.fq.qbody[q]] = w.mult[q];
  pg_work_free(&w);
  return rc;
}

int tds_pg_probe(tds_ctx *ctx, tds_surf *s, double *energy, double (*grad)[3],
                 double (*dir)[3], double (*model)[3]) {
  pgw w;
  int rc = pg_work_init(ctx, s, &w, 0);
  if (rc != TDS_OK) return rc;
  pg_stepinfo si;
  rc = pg_pass(ctx, s, &w, energy);
  if (rc == TDS_OK) rc = pg_step(ctx, s, &w, 2, &si);
  if (rc == TDS_OK) {
    memset(dir, 0, (size_t)s->m.nv * sizeof *dir);
    memset(model, 0, (size_t)s->m.nv * sizeof *model);
    for (tds_id v = 0; v < s->m.nv; v++) {
      v3_copy(grad[v], w.grad[v]);
      if (!w.kind[v]) continue;
      v3_add(grad[v], grad[v], w.acc[v].ga);
      v3_copy(dir[v], w.d[v]);
      v3_copy(model[v], w.model[v]);
    }
  }
  pg_work_free(&w);
  return rc;
}

/* The run. ------------------------------------------------------------ */

void tds_pg_defaults(tds_pg_opts *o) {
  memset(o, 0, sizeof *o);
  o->max_iterations = 100000;
  o->nmax = 200;
  o->s = 2;
  o->accel = 1;
  o->depth = 20;
  o->flips = 1;
  o->newton = 1;
  o->probe = 1;
  o->calm = 1;
  o->momentum = 0.6;
  o->momentum_size = 0;
}

static double mean_edge(const tds_mesh *m) {
  double sum = 0;
  int64_t n = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    double d[3];
    tds_edge_vec(m, TDS_OREF(e, 0), d);
    sum += v3_norm(d);
    n++;
  }
  return n ? sum / (double)n : 0;
}

static double cpu_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void save_best(const tds_surf *s, pgw *w) {
  if (!w->nv) return; /* empty surface: no arrays */
  memcpy(w->xbest, s->m.x, (size_t)w->nv * sizeof *w->xbest);
  memcpy(w->pbest, s->m.vp, (size_t)w->nv * sizeof *w->pbest);
}

static void load_best(tds_surf *s, pgw *w) {
  if (!w->nv) return;
  memcpy(s->m.x, w->xbest, (size_t)w->nv * sizeof *w->xbest);
  memcpy(s->m.vp, w->pbest, (size_t)w->nv * sizeof *w->pbest);
  s->m.coord_gen++;
}

/* One evaluation at the current positions, flipping first when the pass
** finds a non-Delaunay edge (then evaluating again). *nflips: flips. */
static int evaluate(tds_ctx *ctx, tds_surf *s, pgw *w, int flips, double sfac,
                    pg_stepinfo *si, int32_t *nflips) {
  *nflips = 0;
  int rc = pg_pass(ctx, s, w, &si->energy);
  if (w->threads > 1) w->threaded++;
  if (rc != TDS_OK) return rc;
  if (flips && pg_flip_needed(s, w)) {
    *nflips = pg_flip_pass(s, w);
    if (*nflips) {
      rc = pg_pass(ctx, s, w, &si->energy);
      if (rc != TDS_OK) return rc;
    }
  }
  return pg_step(ctx, s, w, sfac, si);
}

/* The stability probe (doc/method.md, Termination): move every state
** entry by a pseudo-random amount in [-delta, delta] (a fixed sequence, so
** runs repeat). Nonzero when a vertex could not be projected. */
static int probe_perturb(tds_surf *s, pgw *w, double *X, double delta) {
  pg_get_state(s, w, X);
  uint64_t z = 0x9e3779b97f4a7c15u;
  for (size_t i = 0; i < 3 * (size_t)w->nmov; i++) {
    z ^= z << 13;
    z ^= z >> 7;
    z ^= z << 17;
    X[i] += delta * ((double)(z >> 11) * 0x1p-52 - 1);
  }
  return pg_set_state(s, w, X);
}

/* Momentum of the warm steps (doc/method.md, Acceleration): after the
** plain move from X_k, add beta (X_k - X_{k-1}) (a heavy-ball step), unless
** that would move a vertex by more than cap (measured on the state's
** triples: a boundary vertex's are its parameters) or a facet is a sliver
** (then none, and the next step starts without momentum: *have = 0). mom
** holds X_k - X_{k-1}; G is scratch. 1 when applied, 0 when not, -1 when
** a vertex could not be projected. */
static int warm_momentum(tds_surf *s, pgw *w, const double *mom, double beta,
                         double cap, double *G, int *have) {
  double big = 0;
  for (size_t j = 0; j < (size_t)w->nmov; j++) {
    const double *u = mom + 3 * j;
    double q = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    if (q > big) big = q;
  }
  /* no momentum into a degenerating mesh (a facet angle below 3 degrees
  ** at a movable vertex): on Evolver's collapsing cat.fe momentum 0.8
  ** otherwise carried the film onto a stationary mesh with a zero angle */
  if (beta * beta * big > cap * cap || pg_newton_sliver(s, w)) {
    *have = 0;
    return 0;
  }
  pg_get_state(s, w, G);
  for (size_t i = 0; i < 3 * (size_t)w->nmov; i++) G[i] += beta * mom[i];
  return pg_set_state(s, w, G) ? -1 : 1;
}

int tds_pg_run(tds_ctx *ctx, tds_surf *s, const tds_pg_opts *o,
               tds_pg_result *res) {
  if (s->m.torus) return tds_torus_unsupported(ctx, "pg");
  double t0 = now();
  memset(res, 0, sizeof *res);
  if (s->str) /* the string model (struct tds_strings): no triangles */
    return tds_seterr(ctx, TDS_ERANGE, "pg works on soap films; the string model "
                      "is not supported (use g)");
  if (s->klein) /* pg's kernels are Euclidean areas */
    return tds_seterr(ctx, TDS_ERANGE, "pg with KLEIN_METRIC is not supported (use g or "
                      "hessian)");
  pgw w;
  int accel = o->accel && o->depth > 0;
  tds_snap sn; /* all or nothing: a failed run leaves the surface as it was */
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  rc = tds_recalc_if_stale(ctx, s);
  if (rc == TDS_OK) rc = pg_work_init(ctx, s, &w, accel ? o->depth : 0);
  if (rc != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  tds_mesh *m = &s->m;
  w.flip_tol = 1e-3; /* hysteresis: no flipping back and forth */
#ifdef _OPENMP
  w.threads = o->threads == 2 ? 2 : 1;
#endif
  double c0 = cpu_now();
  res->nfree = w.nmov;
  double hbar = mean_edge(m);
  double lim2 = (0.5 * hbar) * (0.5 * hbar);
  double noise = 1e-12 * hbar; /* below this r is at rounding level */
  double fine = 1e-13 * hbar;  /* converged enough to stop an accelerated run */
  int until = o->iterations <= 0;
  int64_t nmaxit = until ? (o->max_iterations > 0 ? o->max_iterations : 100000)
                         : o->iterations;
  int64_t every = o->every;
  if (every == 0) every = until ? 100 : (nmaxit <= 20 ? 1 : (nmaxit + 9) / 10);
  double sfac = o->s;
  double rbest = INFINITY, ebest = 0, lbest = 0;
  int64_t best = 0, progress = 0, since_flip = 0;
  const int warm = 5; /* plain iterations after a flip before mixing */
  const double momentum_cap = 0.2; /* of a mean edge (warm_momentum) */
  const int64_t calm_len = 50; /* flip-free plain steps after a 2-cycle */
  const int64_t calm_max = o->nmax; /* at most this long at a time */
  int64_t calm_until = 0, calm_end = 0, cycles_seen = 0;
  pg_stepinfo si = {0};
  int64_t k;
  /* Non-convergence watch (TDS_PG_CYCLING): windows of 5 N_max
  ** iterations; a window is stuck when it flipped edges and its least r
  ** is not below the least r of every earlier window. Flips restart the
  ** paper's criterion, so without this a run whose flips never stop
  ** (a surface with no stable equilibrium near it) ran to the cap. */
  const int64_t win = 5 * (int64_t)o->nmax;
  int64_t win_start = 0, win_flips = 0, stuck_flips = 0, win_ret0 = 0;
  double win_min = INFINITY, glob_min = INFINITY;
  int stuck = 0, resumes = 0;
  int64_t plain_until = 0; /* > 0: resume the mixing at this iteration */
  /* Stability probe (doc/method.md, Termination): the mixing, Newton's
  ** above all, can converge to a fixed point the plain iteration leaves
  ** (a saddle of the mesh-quality energy). Before an accelerated run
  ** stops as converged, the kept mesh is perturbed by 1e-8 x mean edge
  ** and iterated plainly for probe_len iterations: a flip, or r growing
  ** tenfold from its value after 5 of them, marks the fixed point
  ** unstable and the run goes on from where the plain steps took it
  ** (at most max_probes times); else the kept mesh is restored. */
  const int64_t probe_len = 50;
  const int max_probes = 3;
  int probing = 0, probes = 0, escaping = 0;
  int64_t probe_k0 = 0, probe_flips = 0;
  double probe_r0 = 0;
  double *probe_x = NULL; /* the perturbed state */
  res->hysteresis = w.flip_tol;
  /* Newton preconditioning (pg_newton.c, doc/method.md): once r is below
  ** 1e-3 x mean edge and no edge has flipped for nt_wait iterations, the
  ** map's Jacobian is measured and factored, and the mixing works on the
  ** preconditioned map; measured again when r has not halved for
  ** nt_patience iterations, dropped after a flip (the map changed) or when
  ** r grows a hundredfold. Rigid motions the surface is free to make are
  ** exact null vectors of the Jacobian and a border of the system: the
  ** gauge's (a drop free to slide on a table), or all six on a free
  ** surface (no fixed vertex, boundary or constraint); a surface held only
  ** by level sets without the gauge gets no preconditioning. */
  pg_newton nt;
  memset(&nt, 0, sizeof nt);
  int anchored = 0; /* a fixed vertex with facets, or a boundary vertex */
  for (tds_id v = 0; v < m->nv; v++)
    if ((w.kind[v] == VK_FIXED && m->vf_start[v + 1] > m->vf_start[v] &&
         !(m->vflags[v] & TDS_DEAD)) || w.kind[v] == VK_BDRY)
      anchored = 1;
  int level = 0;
  for (int32_t j = 0; j < w.nmov; j++) level |= w.kind[w.mov[j]] == VK_LEVEL;
  int use_nt = accel && o->newton && w.nmov > 0 && (w.nrig || anchored || !level);
  if (use_nt && pg_newton_init(&nt, &w.al, &w) != TDS_OK) {
    pg_work_free(&w);
    return tds_snap_end(ctx, s, &sn, tds_seterr(ctx, TDS_ENOMEM, "out of memory"));
  }
  nt.free = use_nt && !anchored && !w.nrig;
  /* Momentum of the warm steps after a flip (warm_momentum): the state
  ** of the previous iteration and the last move. */
  double beta = o->momentum;
  /* Heavy-ball momentum's best value is about 1 - 2/sqrt(kappa), kappa
  ** the condition number; the plain iteration's smooth modes contract
  ** like 1 - c/n on n vertices, so kappa grows like n and 1 - beta should
  ** shrink like 1/sqrt(n). On a large mesh flips come every iteration and
  ** nearly every step is a warm step, so this is the run's acceleration
  ** (doc/method.md, Acceleration; doc/paper-results.md, Large inputs). */
  if (beta > 0 && o->momentum_size > 0 && w.nmov > o->momentum_size) {
    double b = 1 - (1 - beta) * sqrt((double)o->momentum_size / (double)w.nmov);
    if (b > 0.95) b = 0.95;
    if (b > beta) beta = b;
  }
  res->momentum = beta;
  double *xprev = NULL, *mom = NULL;
  int have_prev = 0;
  if (accel && beta > 0) {
    xprev = tds_calloc(&w.al, 3 * (size_t)(w.nmov > 0 ? w.nmov : 1), sizeof *xprev);
    mom = tds_calloc(&w.al, 3 * (size_t)(w.nmov > 0 ? w.nmov : 1), sizeof *mom);
    if (!xprev || !mom) {
      tds_free(&w.al, xprev);
      tds_free(&w.al, mom);
      pg_newton_free(&nt);
      pg_work_free(&w);
      return tds_snap_end(ctx, s, &sn, tds_seterr(ctx, TDS_ENOMEM, "out of memory"));
    }
  }
  if (o->probe && accel && until) {
    probe_x = tds_calloc(&w.al, 3 * (size_t)(w.nmov > 0 ? w.nmov : 1), sizeof *probe_x);
    if (!probe_x) {
      tds_free(&w.al, xprev);
      tds_free(&w.al, mom);
      pg_newton_free(&nt);
      pg_work_free(&w);
      return tds_snap_end(ctx, s, &sn, tds_seterr(ctx, TDS_ENOMEM, "out of memory"));
    }
  }
  const int64_t nt_wait = 10, nt_patience = 20, nt_maxb = 50;
  const double nt_start = 1e-3 * hbar;
  int64_t nt_next = 0, nt_since = 0;
  double nt_ref = INFINITY, nt_r0 = INFINITY;
  save_best(s, &w);
  tds_printf(ctx, "pg: %d movable vertices, %s%s\n", w.nmov,
             accel ? "accelerated (Anderson)" : "plain",
             until ? ", until converged" : "");
  tds_progress_begin(ctx, 'p', until ? 0 : nmaxit);
  for (k = 1; k <= nmaxit; k++) {
    int32_t nf;
    rc = evaluate(ctx, s, &w, o->flips, sfac, &si, &nf);
    if (rc != TDS_OK) break;
    /* Flip 2-cycles (doc/method.md, Termination): a quadrilateral flipped
    ** back and forth twice. The mixing (and Newton's steps) carry its
    ** corners across the Delaunay condition each way; plain steps until
    ** no edge has flipped for calm_len iterations, then a fresh history. */
    if (accel && o->calm && w.cycles > cycles_seen) {
      if (!calm_until) {
        res->calms++;
        calm_end = k + calm_max;
      }
      calm_until = k + calm_len;
    } else if (calm_until && nf) {
      calm_until = k + calm_len;
    }
    if (calm_until > calm_end) calm_until = calm_end;
    cycles_seen = w.cycles;
    if (calm_until && k >= calm_until) {
      calm_until = 0;
      pg_accel_reset(&w.aa);
    }
    if (nf) {
      res->flips += nf;
      since_flip = 0;
      if (nt.lu) {
        pg_newton_drop(&nt);
        nt_next = k + nt_wait;
      }
      if (accel) {
        pg_accel_reset(&w.aa);
        res->restarts++;
      }
      rbest = INFINITY; /* the saved mesh has the old topology */
    }
    res->clamps += si.clamps;
    res->r_last = si.r;
    if (!res->reached && si.r < 1e-13 * hbar) res->reached = k;
    if (si.r < rbest) {
      /* Below 1e-13 x mean edge r wanders at rounding level; a new best
      ** there counts as progress (for the patience below) only when it
      ** halves r. */
      if (rbest > fine || si.r < 0.5 * rbest) progress = k;
      rbest = si.r;
      best = k;
      ebest = si.energy;
      lbest = si.lambda0;
      if (until) save_best(s, &w);
      pg_store_pressures(s, &w);
    }
    int live = tds_progress_step(ctx, k, si.energy, si.r);
    if (!live && every > 0 && (k % every == 0 || k == 1))
      tds_printf(ctx, "pg %7lld  r %.3e  lambda % .12g  energy %.15g  flips %lld\n",
                 (long long)k, si.r, si.lambda0, si.energy, (long long)res->flips);
    if (until && probing) {
      probe_flips += nf;
      if (k == probe_k0 + 5) probe_r0 = si.r;
      int grew = k > probe_k0 + 5 && si.r > 10 * probe_r0;
      if (probe_flips || grew) { /* unstable: go on from here */
        probing = 0;
        res->saddles++;
        tds_progress_erase(ctx);
        tds_printf(ctx, "pg %7lld  the fixed point is unstable (%s after %lld plain "
                        "steps from it): continuing\n", (long long)k,
                   probe_flips ? "edges flipped" : "r grew tenfold",
                   (long long)(k - probe_k0));
        /* plain steps until they have left it (a flip, or r ten
        ** thousand times its value after the perturbation), at most N_max
        ** of them; the mixing would return to it from nearby */
        escaping = 1;
        plain_until = k + o->nmax;
        res->reached = 0;
        progress = k;
        rbest = INFINITY;
        nt_next = k + nt_wait;
        win_start = k;
        win_min = glob_min = INFINITY;
        win_flips = 0;
        win_ret0 = w.returns;
        pg_flip_forget(&w);
        stuck = 0;
        stuck_flips = 0;
      } else if (k >= probe_k0 + probe_len) { /* stable: keep the mesh */
        res->converged = 1;
        res->status = TDS_PG_CONVERGED;
        break;
      }
    } else if (until) {
      /* The paper's rule: no new best r for N_max iterations. Above the
      ** rounding level r may rise for a while on a slow mode and fall
      ** again, so there the patience is five times longer; an accelerated
      ** run that stalls there goes on plainly first. */
      int64_t idle = k - progress;
      if (accel && idle >= o->nmax && rbest > fine) {
        /* Stalled: above the rounding level the plain run is judged on
        ** its own; near it (Anderson's least squares amplify rounding,
        ** so its floor can sit a little above the plain iteration's) the
        ** plain steps must beat the kept mesh. */
        accel = 0;
        res->restarts++;
        tds_progress_erase(ctx);
        tds_printf(ctx, "pg %7lld  acceleration stalled at r %.3e: continuing plainly\n",
                   (long long)k, rbest);
        progress = k;
        /* Well above the rounding level the mixing usually stalled on a
        ** saddle of the mesh-quality energy or in a nonlinear stretch:
        ** the plain steps leave it, and after N_max of them the mixing
        ** resumes with a fresh history (at most three times). */
        if (rbest > noise && resumes < 3) plain_until = k + o->nmax;
        if (rbest > noise) rbest = INFINITY;
        idle = 0;
      }
      if (escaping && nf) plain_until = k;
      if (!accel && plain_until && k >= plain_until) {
        escaping = 0;
        accel = 1;
        plain_until = 0;
        resumes++;
        progress = k; /* the mixing gets its own N_max */
        pg_accel_reset(&w.aa);
        res->restarts++;
        tds_progress_erase(ctx);
        tds_printf(ctx, "pg %7lld  resuming acceleration at r %.3e\n", (long long)k, si.r);
      }
      if (rbest == 0 || (o->rtol > 0 && rbest < o->rtol * hbar) ||
          (idle >= o->nmax && rbest <= noise) || idle >= 5 * (int64_t)o->nmax) {
        res->converged = rbest <= 1e-6 * hbar || (o->rtol > 0 && rbest < o->rtol * hbar);
        res->status = res->converged ? TDS_PG_CONVERGED : TDS_PG_STALLED;
        if (res->converged && probe_x && probes < max_probes && rbest <= fine) {
          probes++;
          res->probes++;
          res->converged = 0; /* decided by the probe */
          res->status = TDS_PG_COUNT;
          load_best(s, &w);
          if (nt.lu) pg_newton_drop(&nt);
          accel = 0;
          probing = 1;
          probe_k0 = k;
          probe_flips = 0;
          probe_r0 = INFINITY;
          if (probe_perturb(s, &w, probe_x, 1e-8 * hbar)) {
            rc = tds_seterr(ctx, TDS_ENUM, "projected gradient: a vertex could "
                                           "not be projected onto its constraints");
            break;
          }
          s->iterations++;
          continue; /* this iteration's moves belong to the kept mesh */
        }
        break;
      }
      if (si.r < win_min) win_min = si.r;
      win_flips += nf;
      if (k - win_start >= win) {
        /* A cycle returns to earlier edges: at least half the window's
        ** flips re-create an edge that a flip of this window removed.
        ** Dislocations gliding through a large mesh mostly create new
        ** edges (the 100k hemisphere: 552 flips, no return, in its
        ** second window); those windows are progress, not a cycle, even
        ** when r does not halve (doc/method.md, Termination). */
        int64_t win_ret = w.returns - win_ret0;
        if (win_flips > 0 && !(win_min < 0.5 * glob_min) && 2 * win_ret >= win_flips) {
          /* flips cycling: first widen the flip hysteresis tenfold per
          ** stuck window (1e-3 to 1e-1: a pair of opposite angles may
          ** then exceed pi by up to 0.1 radian before the edge flips),
          ** which ends the cycles of most meshes; give up only when the
          ** widest one does not */
          if (o->flips && w.flip_tol < 0.099) {
            w.flip_tol *= 10;
            res->hysteresis = w.flip_tol;
            stuck = 0;
            stuck_flips = 0;
          } else {
            stuck++;
            stuck_flips += win_flips;
          }
        } else {
          stuck = 0;
          stuck_flips = 0;
        }
        if (win_min < glob_min) glob_min = win_min;
        win_start = k;
        win_min = INFINITY;
        win_flips = 0;
        win_ret0 = w.returns;
        pg_flip_forget(&w);
        if (stuck >= 3) {
          res->status = TDS_PG_CYCLING;
          res->window_flips = stuck_flips;
          break;
        }
      }
    }
    if (accel) pg_get_state(s, &w, w.aa.X);
    if (xprev) { /* the last move, for the warm steps' momentum */
      for (size_t i = 0; i < 3 * (size_t)w.nmov; i++) {
        mom[i] = have_prev ? w.aa.X[i] - xprev[i] : 0;
        xprev[i] = w.aa.X[i];
      }
      have_prev = accel;
    }
    if (pg_apply(s, &w)) {
      rc = tds_seterr(ctx, TDS_ENUM, "projected gradient: a vertex could not "
                                     "be projected onto its constraints");
      break;
    }
    if (xprev && accel && have_prev && !calm_until && !probing && since_flip < warm) {
      int mo = warm_momentum(s, &w, mom, beta, momentum_cap * hbar, w.aa.G, &have_prev);
      if (mo < 0) {
        rc = tds_seterr(ctx, TDS_ENUM, "projected gradient: a vertex could "
                                       "not be projected onto its constraints");
        break;
      }
      res->momentum_steps += mo;
    }
    if (nt.lu) { /* the preconditioner's progress */
      if (si.r < 0.5 * nt_ref) {
        nt_ref = si.r;
        nt_since = k;
      } else if (si.r > 100 * nt_r0 || k - nt_since > nt_patience) {
        pg_newton_drop(&nt);
        nt_next = si.r > 100 * nt_r0 ? k + 5 * nt_wait : k;
      }
      if (nt.lu && pg_newton_sliver(s, &w)) { /* degenerating: not here */
        pg_newton_drop(&nt);
        nt_next = k + 5 * nt_wait;
      }
    }
    if (accel && !calm_until && since_flip >= warm && use_nt && !nt.lu && since_flip >= nt_wait &&
        k >= nt_next && nt.builds < nt_maxb && si.r > noise && si.r < nt_start) {
      pg_get_state(s, &w, w.aa.G);
      rc = pg_newton_build(ctx, s, &w, &nt, w.aa.X, sfac, 1e-7 * hbar);
      if (rc == TDS_ENUM) rc = TDS_OK; /* no usable Jacobian here */
      if (rc != TDS_OK) break;
      if (!nt.lu) nt_next = k + 5 * nt_wait; /* try later */
      if (nt.lu) {
        pg_accel_reset(&w.aa);
        nt_ref = nt_r0 = si.r;
        nt_since = k;
      }
    }
    if (accel && !calm_until && since_flip >= warm) {
      pg_get_state(s, &w, w.aa.G);
      int pre = 0; /* G holds the preconditioned image: set it */
      if (nt.lu) {
        if (pg_newton_apply(ctx, &nt, &w, w.aa.X, w.aa.G) == TDS_OK) {
          pre = 1;
        } else { /* a failed solve: on without it (G is the plain image) */
          pg_newton_drop(&nt);
          nt_next = k + 5 * nt_wait;
          pg_accel_reset(&w.aa);
        }
      }
      int mixed = pg_accel_mix(&w.aa, lim2);
      if ((pre || mixed) && pg_set_state(s, &w, w.aa.X)) {
        rc = tds_seterr(ctx, TDS_ENUM, "projected gradient: a vertex could "
                                       "not be projected onto its constraints");
        break;
      }
    }
    since_flip++;
    s->iterations++;
    if (ctx->step) ctx->step(ctx->step_ud, si.energy);
    if (ctx->interrupt) {
      ctx->interrupt = 0;
      rc = tds_seterr(ctx, TDS_EINTR, "interrupted after %lld iterations",
                      (long long)k);
      break;
    }
  }
  tds_progress_end(ctx);
  if (k > nmaxit) {
    k = nmaxit;
    if (until) res->status = TDS_PG_MAX;
  }
  res->iterations = k;
  if (until && rc == TDS_OK && rbest < (double)INFINITY) load_best(s, &w);
  if (until && rc == TDS_OK) {
    res->r = rbest;
    res->best_iteration = best;
    res->energy = ebest;
    res->lambda = lbest;
  } else {
    res->r = si.r;
    res->best_iteration = k;
    res->energy = si.energy;
    res->lambda = si.lambda0;
  }
  res->restarts += w.aa.restarts;
  res->threaded = w.threaded;
  res->cpu_seconds = cpu_now() - c0;
  res->newton_builds = nt.builds;
  res->cycles = w.cycles;
  res->returns = w.returns;
  tds_free(&w.al, probe_x);
  tds_free(&w.al, xprev);
  tds_free(&w.al, mom);
  pg_newton_free(&nt);
  pg_work_free(&w);
  int rc2 = rc == TDS_OK || rc == TDS_EINTR ? tds_surf_update(ctx, s) : TDS_OK;
  if (rc == TDS_OK) rc = rc2;
  tds_snap_end(ctx, s, &sn, rc);
  res->mean_edge = mean_edge(m);
  res->seconds = now() - t0;
  if (rc == TDS_OK || rc == TDS_EINTR) {
    tds_printf(ctx, "pg: %lld iterations, r %.3e (%.2e x mean edge) at "
                    "iteration %lld, lambda %.15g, energy %.15g, flips %lld, "
                    "clamped %lld, %s\n",
               (long long)res->iterations, res->r,
               res->mean_edge > 0 ? res->r / res->mean_edge : 0,
               (long long)res->best_iteration, res->lambda, s->energy,
               (long long)res->flips, (long long)res->clamps,
               res->converged ? "converged" : "not converged");
    char *msg = res->message;
    size_t ml = sizeof res->message;
    if (rc == TDS_OK && res->status == TDS_PG_CYCLING)
      snprintf(msg, ml, "pg: not converging: %lld edges flipped in the last %lld "
                      "iterations and r never went below %.3e (%.2e x mean edge), "
                      "its best before them; stopped early. The triangulation "
                      "keeps changing: the surface may have no stable "
                      "equilibrium near this shape (a neck pinching off, a "
                      "film collapsing), the mesh is too coarse for it, or "
                      "(a large or irregular mesh) its flips are still "
                      "evening it out and pg() again goes on from here. "
                      "Try g() to see where the surface goes, r() to refine, "
                      "or pg{ flips = false }",
                 (long long)res->window_flips, (long long)(3 * win), glob_min,
                 res->mean_edge > 0 ? glob_min / res->mean_edge : 0);
    else if (rc == TDS_OK && res->status == TDS_PG_STALLED)
    {
      double rel = res->mean_edge > 0 ? res->r / res->mean_edge : 0;
      int far = rel > 1e-2; /* still moving by a good part of an edge */
      snprintf(msg, ml, "pg: not converged: r has not gone below %.3e (%.2e x mean "
                        "edge) for %lld iterations; stopped. %sTry %s",
               res->r, rel, (long long)(5 * (int64_t)o->nmax),
               far ? "The vertices still move by a good part of an edge: the "
                     "surface may have no stable equilibrium near this shape "
                     "(a neck pinching off, a film collapsing). " : "",
               far ? "g() to see where the surface goes, or r() to refine"
               : o->accel && o->depth > 0
                   ? "pg{ plain = true } (without acceleration), a few g() "
                     "first, or a larger nmax"
                   : "a few g() first, or a larger nmax");
    }
    else if (rc == TDS_OK && res->status == TDS_PG_MAX)
      snprintf(msg, ml, "pg: not converged within max = %lld iterations; pg() "
                      "again continues, pg{ max = ... } allows more",
                 (long long)nmaxit);
    if (msg[0]) tds_warnf(ctx, "%s\n", msg);
  }
  return rc;
}
