/* iterate.c: gradient descent with optimizing scale (the g command). */
#include "iterate.h"
#include "autopop.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval.h"
#include "gather.h"
#include "mobility.h"
#include "motion.h"
#include "progress.h"
#include "recalc.h"
#include "snap.h"
#include "stall.h"
#include "vec3.h"

typedef struct work {
  int32_t nv;
  double (*x0)[3];   /* positions at the start of the step */
  double (*p0)[2];   /* boundary parameters at the start */
  double (*grad)[3]; /* energy gradient */
  double (*vel)[3];  /* motion-space velocity */
  double (*rest)[3]; /* restoring motion of a projection step */
  tds_fixq fq;
  double (*g0)[3];   /* evolver_line_search: fq->g at the start of the step */
  int unconverged;   /* a projection hit its step limit */
  double E0;         /* energy at the start of the step */
  int at_target;     /* quantities were at target at the start */
  double slope;      /* dE/ds along vel at the start (negative) */
  int undone;        /* check_increase took the last step back */
  int keep_vel;      /* autochop: vel is the motion from before the chop */
  int32_t pop_after; /* string autopop: edges removed, pops due after the move */
  double *mob;       /* area normalization: 1/sqrt(a_v) (mobility.h), or NULL */
  /* A trial likely to be the step's last (line_search_tds's second)
  ** evaluates its final positions with the energy's gradient too (spec):
  ** then the next direction() finds grad, fq and their energy (spec_E)
  ** already made at these positions (spec_gen: m.coord_gen then; 0 none) */
  int spec;
  uint64_t spec_gen;
  double spec_E;
  /* why the last trial's projection failed: a status whose message is in
  ** ctx (the Gram matrix singular: a body left without free vertices),
  ** or 0 (a value not finite, or no failure) */
  int trial_why;
  tds_alloc al;      /* the ctx's allocator */
} work;

static void work_free(work *w) {
  tds_free(&w->al, w->x0);
  tds_free(&w->al, w->p0);
  tds_free(&w->al, w->grad);
  tds_free(&w->al, w->vel);
  tds_free(&w->al, w->rest);
  tds_free(&w->al, w->g0);
  tds_free(&w->al, w->mob);
  tds_fixq_free(&w->fq);
}

static int work_init(tds_ctx *ctx, tds_surf *s, work *w) {
  memset(w, 0, sizeof *w);
  size_t nv = (size_t)s->m.nv;
  w->nv = s->m.nv;
  w->al = ctx->alloc;
  w->x0 = tds_calloc(&w->al, nv, sizeof *w->x0);
  w->p0 = tds_calloc(&w->al, nv, sizeof *w->p0);
  w->grad = tds_calloc(&w->al, nv, sizeof *w->grad);
  w->vel = tds_calloc(&w->al, nv, sizeof *w->vel);
  w->rest = tds_calloc(&w->al, nv, sizeof *w->rest);
  if (s->area_normalization) w->mob = tds_calloc(&w->al, nv ? nv : 1, sizeof *w->mob);
  if (!w->x0 || !w->p0 || !w->grad || !w->vel || !w->rest ||
      (s->area_normalization && !w->mob)) {
    work_free(w);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int rc = tds_fixq_build(ctx, s, &w->fq);
  if (rc == TDS_OK && s->evolver_ls && w->fq.nent &&
      !(w->g0 = tds_calloc(&w->al, (size_t)w->fq.nent, sizeof *w->g0)))
    rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  if (rc != TDS_OK) work_free(w);
  return rc;
}

/* How far a constrained quantity may be from its target: 1e-12 relative
** (absolute for a target of 0). */
static double target_tol(double target) {
  return 1e-12 * (fabs(target) > 0 ? fabs(target) : 1);
}

/* Store multipliers as pressures of their bodies and quantities. */
static void store_pressures(tds_surf *s, const tds_fixq *fq) {
  for (int32_t q = 0; q < fq->nq; q++) {
    if (fq->qbody[q] != TDS_NONE)
      s->m.bpressure[fq->qbody[q]] = fq->mult[q];
    else
      s->quant[fq->qquant[q]].pressure = fq->mult[q];
  }
}

/* Evolver's measure of the distance to the targets: the sum of |error| /
** tolerance, the tolerance 1e-4 (target_tolerance) for a body's volume
** and 1e-4 of the target for a named quantity (NaN if a value is not
** finite). Absolute for bodies, relative for quantities, as Evolver 2.70
** does (measured on cube.fe scaled to volumes 1e-6 and 1e6, as a body and
** as a fixed quantity: tests/evolver/tolerance.sh). */
static double evolver_off(const tds_fixq *fq) {
  double off = 0;
  for (int32_t q = 0; q < fq->nq; q++) {
    double tol = 1e-4;
    if (fq->qbody[q] == TDS_NONE && fq->target[q] != 0) tol *= fabs(fq->target[q]);
    off += fabs(fq->target[q] - fq->value[q]) / tol;
  }
  return off;
}

/* Map the quantities' gradients into each vertex's motion space. */
static void project_qgrad(const tds_surf *s, tds_fixq *fq) {
  for (tds_id v = 0; v < fq->nv; v++) {
    if ((s->m.vflags[v] & TDS_DEAD) || tds_vertex_plain(s, v)) continue;
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
      tds_motion_project(s, v, fq->g[i]);
  }
}

/* With Evolver's search after autochop kept the old motion: the
** quantities' gradients here, for the restoring moves (w->g0). */
static int start_gradients(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_eval_out out = {.fq = &w->fq};
  int rc = tds_eval(ctx, s, &out);
  if (rc != TDS_OK) return rc;
  project_qgrad(s, &w->fq);
  memcpy(w->g0, w->fq.g, (size_t)w->fq.nent * sizeof *w->g0);
  return TDS_OK;
}

/* Evaluate gradient and quantities, then map into motion space and take
** out the constraint directions. Leaves vel, slope, E0 and the pressures
** set. */
static int direction(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_mesh *m = &s->m;
  tds_eval_out out = {.grad = w->grad, .fq = &w->fq};
  int rc = TDS_OK;
  if (w->spec_gen != 0 && w->spec_gen == m->coord_gen) /* made by the last trial */
    out.energy = w->spec_E;
  else
    rc = tds_eval(ctx, s, &out);
  w->spec_gen = 0;
  if (rc != TDS_OK) return rc;
  tds_fixq *fq = &w->fq;
  w->E0 = out.energy;
  w->at_target = 1;
  for (int32_t q = 0; q < fq->nq; q++)
    if (!(fabs(fq->target[q] - fq->value[q]) <= target_tol(fq->target[q])))
      w->at_target = 0;
  for (tds_id v = 0; v < m->nv; v++)
    if (!(m->vflags[v] & TDS_DEAD) && !tds_vertex_plain(s, v))
      tds_motion_project(s, v, w->grad[v]);
  project_qgrad(s, fq);
  /* the projected gradients, for evolver_line_search's restoring moves
  ** (before area normalization weights them) */
  if (w->g0) memcpy(w->g0, fq->g, (size_t)fq->nent * sizeof *fq->g);
  if (w->mob) { /* area normalization: work in the M-weighted metric */
    tds_area_norm_weights(s, w->mob);
    for (tds_id v = 0; v < m->nv; v++) {
      v3_scale(w->grad[v], w->mob[v]);
      for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++) v3_scale(fq->g[i], w->mob[v]);
    }
  }
  rc = tds_fixq_multipliers(ctx, fq, w->grad);
  if (rc != TDS_OK) return rc;
  store_pressures(s, fq);
  w->slope = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    w->vel[v][0] = -w->grad[v][0];
    w->vel[v][1] = -w->grad[v][1];
    w->vel[v][2] = -w->grad[v][2];
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++) {
      double lam = fq->mult[fq->eq[i]];
      w->vel[v][0] += lam * fq->g[i][0];
      w->vel[v][1] += lam * fq->g[i][1];
      w->vel[v][2] += lam * fq->g[i][2];
    }
    w->slope -= v3_dot(w->vel[v], w->vel[v]);
    if (w->mob) v3_scale(w->vel[v], w->mob[v]);
  }
  return TDS_OK;
}

/* One restoring move along fq->g onto the quantity targets (fq->value
** the values here). Returns 0, or -1 if the Gram system is singular. */
static int restore_move(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_mesh *m = &s->m;
  int rc = tds_fixq_restore(ctx, &w->fq, m->nv, w->rest);
  if (rc != TDS_OK) {
    w->trial_why = rc;
    return -1;
  }
  for (tds_id v = 0; v < m->nv; v++) {
    if (tds_vertex_plain(s, v)) {
      v3_add(m->x[v], m->x[v], w->rest[v]);
      continue;
    }
    if (!tds_vertex_free(s, v)) continue;
    double x[3], p[2] = {m->vp[v][0], m->vp[v][1]};
    v3_copy(x, m->x[v]);
    tds_motion_apply(s, v, x, p, w->rest[v]);
  }
  m->coord_gen++;
  return 0;
}

/* Newton steps onto the constrained quantities' targets: x += sum mu_q g_q
** with G mu = target - value, until every value is within 1e-12 of its
** target (relative), or the error stops shrinking below 1e-8 (the
** rounding floor of a sum over many facets), or ten steps are done.
** Leaves s->energy and s->area at the final positions. Returns 0, or -1
** if a value is not finite. */
static int project_quantities(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_fixq *fq = &w->fq;
  double prev = INFINITY;
  for (int it = 0;; it++) {
    /* The quantities' gradients are needed only for another move. After
    ** a move from within 1e5 of the tolerance the values are expected on
    ** target (Newton: 1e-12 relative times the error squared, plus the
    ** sparse solve's 1e-6 times the error): evaluate without them, and
    ** again with them if a move is needed after all (the same values). */
    int grads = fq->nq && !(prev < 1e5);
    int spec = w->spec && !grads; /* expected final: with grad for direction() */
    tds_eval_out out = {.fq = grads || spec ? fq : NULL, .grad = spec ? w->grad : NULL};
    if (tds_eval(ctx, s, &out) != TDS_OK) return -1;
    if (fq->nq && !grads && !spec) tds_fixq_values(s, fq);
    if (spec) {
      w->spec_gen = s->m.coord_gen;
      w->spec_E = out.energy;
      grads = 1;
    }
    s->energy = out.energy;
    s->area = out.area;
    double worst = 0;
    for (int32_t q = 0; q < fq->nq; q++) {
      double err = fabs(fq->target[q] - fq->value[q]) / target_tol(fq->target[q]);
      if (!(err <= worst)) worst = err; /* NaN propagates as failure */
    }
    if (worst <= 1) return 0;
    if (!isfinite(worst)) return -1;
    if (worst < 1e4 && worst > 0.5 * prev) return 0; /* at rounding level */
    prev = worst;
    if (it == 10) {
      w->unconverged = 1;
      return 0;
    }
    if (!grads) {
      out = (tds_eval_out){.fq = fq};
      if (tds_eval(ctx, s, &out) != TDS_OK) return -1;
    }
    project_qgrad(s, fq);
    /* The sparse solve's tolerance (relative residual; tds_fixq_restore):
    ** as loose as leaves the next error where it would be anyway. A move
    ** leaves Newton's remainder, about 1e-12 worst^2 tolerances (measured:
    ** 0.25 to 0.3 times that on the 2-D and 3-D foams), plus the residual,
    ** rtol worst: so 1e-13 worst while another move will follow, and 0.2
    ** / worst for the move that should be the last. Within [1e-6, 1e-3]
    ** (1e-6 everywhere before: on the 10,000-cell foam each move then
    ** took about one iteration of conjugate gradients more). */
    double rq = 1e-13 * worst, rl = 0.2 / worst, rt = rq > rl ? rq : rl;
    fq->restore_rtol = rt < 1e-6 ? 1e-6 : rt > 1e-3 ? 1e-3 : rt;
    int bad = restore_move(ctx, s, w);
    fq->restore_rtol = 0;
    if (bad != 0) return -1;
  }
}

/* Evolver's projection of a trial onto the quantity targets, used with
** evolver_line_search: restoring moves along the quantities' gradients
** at the start of the step (g0), at least one and then while
** evolver_off is above 1, at most ten. Measured against Evolver's
** fixed-scale steps on cube.fe, on cube.fe scaled by 2 (the same energy
** and volume to 1e-15 at scales 1e-4 to 0.25, one to three moves) and on
** knotty.fe, whose length starts 2.7 off its target (three moves, 3e-4
** left, as Evolver, at scales 1e-3 and 1e-2). Where the moves stop
** closing in (knotty.fe's trials from scale 0.1, whose length Evolver
** brings back by means we could not determine) the trial is projected
** exactly instead. Leaves the quantities off target by about the
** tolerance; the next steps restore them. s->energy and s->area are
** those of the final positions. Returns 0, or -1 if a value is not
** finite. */
static int restore_evolver(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_fixq *fq = &w->fq;
  size_t nb = (size_t)fq->nent * sizeof *fq->g;
  double prev = INFINITY;
  memcpy(fq->g, w->g0, nb); /* the moves go along the start's gradients */
  for (int k = 0;; k++) {
    tds_eval_out out = {0}; /* values only: the gradients stay g0 */
    if (tds_eval(ctx, s, &out) != TDS_OK) return -1;
    tds_fixq_values(s, fq);
    s->energy = out.energy;
    s->area = out.area;
    double off = evolver_off(fq);
    if (!isfinite(off) || !isfinite(s->energy)) return -1;
    if (k > 0 && !(off < prev)) { /* the moves diverge (a long trial): project */
      int rc = project_quantities(ctx, s, w);
      memcpy(fq->g, w->g0, nb);
      return rc;
    }
    if (k == 10 || (k > 0 && off <= 1)) return 0;
    prev = off;
    if (restore_move(ctx, s, w) != 0) return -1;
  }
}

/* Place every free vertex at x0 + scale*vel, project onto the quantity
** targets (exactly, or as Evolver with evolver_line_search), and return
** the energy there (NAN if not finite). */
static double trial(tds_ctx *ctx, tds_surf *s, work *w, double scale) {
  tds_mesh *m = &s->m;
  int bad = 0;
  w->trial_why = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_vertex_free(s, v)) continue;
    double d[3] = {scale * w->vel[v][0], scale * w->vel[v][1],
                   scale * w->vel[v][2]};
    if (tds_vertex_plain(s, v)) /* tds_motion_apply's sum */
      v3_add(m->x[v], w->x0[v], d);
    else if (tds_motion_apply(s, v, w->x0[v], w->p0[v], d) != TDS_OK)
      bad = 1;
  }
  m->coord_gen++;
  int rc = w->g0 ? restore_evolver(ctx, s, w) : project_quantities(ctx, s, w);
  if (rc != 0 || bad) return NAN;
  return s->energy;
}

/* Vertex of the parabola through (a,Ea), (b,Eb), (c,Ec), a < b < c with
** Eb below both ends; NAN if the three points are collinear. */
static double parabola_min(double a, double Ea, double b, double Eb, double c,
                           double Ec) {
  double d1 = (Eb - Ea) / (b - a), d2 = (Ec - Eb) / (c - b);
  double curv = (d2 - d1) / (c - a); /* half the second derivative */
  if (!(curv > 0)) return NAN;
  return 0.5 * (a + b) - d1 / (2 * curv);
}

/* Evolver's line search (tds.setting("evolver_line_search", true)) along
** vel from the start of the step (energy E0, slope D = dE/ds at 0,
** negative for a descent direction), as Evolver describes its optimizing
** scale and as measured on its steps: starting from the last scale,
** double it while the energy keeps going down (the last trial may pass
** the scale limit; doubling stops once the scale reaches it) or halve it
** until the energy goes below E0, so that a minimum is bracketed; then
** move to the vertex of the parabola through the start and the last two
** scales, capped at the limit. Each trial is a full move with
** projection, so energies are compared on the constraints. Below 1e-12
** of the limit the search gives up and uses scale 0 (which still
** projects). Returns the chosen scale with the positions there and *E
** its energy. */
static double line_search_evolver(tds_ctx *ctx, tds_surf *s, work *w, double E0,
                                  double D, double *E) {
  const double lim = s->scale_limit, tiny = 1e-12 * lim;
  /* After a step whose scale fell to 0 Evolver starts again from 1e-6 of
  ** the limit (measured: cube.fe's g 12; r; g 2 takes Evolver's steps to
  ** 1e-12 from 1e-6 and 2e-6, and parts from 3e-6 and 1e-5; under
  ** scale_limit 0.3, from 3e-7, not 1e-6). */
  double s1 = s->scale > tiny ? s->scale : 1e-6 * lim;
  if (s1 > lim) s1 = lim;
  if (!(D < 0)) { /* no descent direction: stay (still projects) */
    *E = trial(ctx, s, w, 0);
    return 0;
  }
  double sc, Ec;
  double E1 = trial(ctx, s, w, s1);
  if (E1 < E0) { /* double while the energy goes down */
    for (;;) {
      /* the trial may pass the limit (measured: Evolver's second step on
      ** cat.fe brackets with 0.668 and 1.336 under the limit 1, and
      ** tankex.fe's eighth from scale 1 with 1 and 2) */
      sc = 2 * s1;
      Ec = trial(ctx, s, w, sc);
      if (!(Ec < E1)) break;
      s1 = sc, E1 = Ec;
      if (!(s1 < lim)) { /* past the limit and still going down */
        *E = trial(ctx, s, w, lim);
        return lim;
      }
    }
  } else { /* halve until below E0 */
    do {
      sc = s1, Ec = E1;
      s1 = 0.5 * s1;
      if (s1 < tiny) {
        *E = trial(ctx, s, w, 0);
        return 0;
      }
      E1 = trial(ctx, s, w, s1);
    } while (!(E1 < E0));
  }
  /* 0 < s1 < sc with E1 below both ends. As measured on cat.fe (r; u;
  ** g 120), Evolver's scale is the vertex of the parabola through the
  ** start (not the previous trial), s1 and sc, taken even when it lies
  ** close to s1 or its energy is above E1 (its first step's scale is the
  ** vertex through 0, 0.4 and 0.8 to 1e-13). */
  double t = parabola_min(0, E0, s1, E1, sc, Ec);
  if (!(t > 0 && t < sc)) t = s1;
  if (t > lim) t = lim;
  *E = trial(ctx, s, w, t);
  if (t != s1 && !isfinite(*E)) { /* the vertex failed to project */
    *E = trial(ctx, s, w, s1);
    return s1;
  }
  return t;
}

/* tds's line search (the default) along vel from the start of the step
** (energy E0, slope D = dE/ds at 0, negative for a descent direction).
** Usually two trials a step where Evolver's takes three or more, and on
** the bench cube a lower energy after 20 steps. Each trial is a full
** move with projection, so energies are compared on the constraints. The
** next scale minimises the parabola through E0, D and the last trial;
** a trial that does not lower the energy is retried at a smaller scale.
** Returns the chosen scale with the positions there and *E its energy. */
static double line_search_tds(tds_ctx *ctx, tds_surf *s, work *w, double E0,
                          double D, double *E) {
  const double lim = s->scale_limit, tiny = 1e-12 * lim;
  double s1 = s->scale > tiny ? s->scale : 0.1 * lim;
  if (s1 > lim) s1 = lim;
  if (!(D < 0)) { /* no descent direction: stay (still projects) */
    *E = trial(ctx, s, w, 0);
    return 0;
  }
  double E1 = trial(ctx, s, w, s1);
  while (!(E1 < E0)) { /* shrink until the energy goes down */
    double a = (E1 - E0 - D * s1) / (s1 * s1);
    double t = a > 0 ? -D / (2 * a) : s1 / 2;
    if (!(t < 0.5 * s1)) t = 0.5 * s1;
    if (!(t > 0.1 * s1)) t = 0.1 * s1;
    s1 = t;
    if (s1 < tiny) {
      *E = trial(ctx, s, w, 0);
      return 0;
    }
    E1 = trial(ctx, s, w, s1);
  }
  /* s1 lowers the energy: one interpolated (or extrapolated) try. */
  double a = (E1 - E0 - D * s1) / (s1 * s1);
  double t = a > 0 ? -D / (2 * a) : 4 * s1;
  if (t > 4 * s1) t = 4 * s1;
  if (t > lim) t = lim;
  if (!(fabs(t - s1) > 0.05 * s1)) { /* close enough: keep s1 */
    *E = E1;
    return s1;
  }
  w->spec = 1; /* usually the step's last trial */
  double Et = trial(ctx, s, w, t);
  w->spec = 0;
  if (Et < E1) {
    *E = Et;
    return t;
  }
  *E = trial(ctx, s, w, s1);
  return s1;
}

/* Conjugate gradient (Polak-Ribiere, restarted when beta < 0): replace
** vel by vel + beta * previous direction. The history lives in the surface
** and is dropped when the topology changes (Evolver resets it after any
** surface modification). Returns TDS_ENOMEM if the history cannot grow. */
static int conjugate(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_mesh *m = &s->m;
  if (s->cg_nv != m->nv || s->cg_topo != m->topo_gen || !s->cg_dir) {
    size_t n = (size_t)(m->nv > 0 ? m->nv : 1);
    /* New arrays first, so that a failure leaves the history as it was. */
    double (*d)[3] = tds_calloc(&m->alloc, n, sizeof *d);
    double (*p)[3] = d ? tds_calloc(&m->alloc, n, sizeof *p) : NULL;
    if (!p) {
      tds_free(&m->alloc, d);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    }
    tds_free(&m->alloc, s->cg_dir);
    tds_free(&m->alloc, s->cg_prev);
    s->cg_dir = d;
    s->cg_prev = p;
    s->cg_nv = m->nv;
    s->cg_topo = m->topo_gen;
    s->cg_norm2 = 0;
  }
  double g2 = 0, gdg = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    g2 += v3_dot(w->vel[v], w->vel[v]);
    if (s->cg_norm2 > 0)
      gdg += v3_dot(w->vel[v], w->vel[v]) - v3_dot(w->vel[v], s->cg_prev[v]);
  }
  double beta = s->cg_norm2 > 0 ? gdg / s->cg_norm2 : 0;
  if (!(beta > 0)) beta = 0;
  w->slope = 0; /* -<steepest descent, new direction> */
  for (tds_id v = 0; v < m->nv; v++) {
    v3_copy(s->cg_prev[v], w->vel[v]);
    for (int k = 0; k < 3; k++) {
      s->cg_dir[v][k] = w->vel[v][k] + beta * (s->cg_norm2 > 0 ? s->cg_dir[v][k] : 0);
      w->slope -= w->vel[v][k] * s->cg_dir[v][k];
      w->vel[v][k] = s->cg_dir[v][k];
    }
  }
  s->cg_norm2 = g2;
  return TDS_OK;
}

/* autopop and autochop (autopop.h) before the step, each from the motion
** as it is, and the work arrays made again for the surface they leave.
** The step then moves with that motion: after a chop the new vertices
** take the mean of their ends' motions. On soap films autopop runs first
** and the step, too, keeps the motion found before it (measured on
** cat.fe's pinched neck with immediate_autopop: 6e-8 from Evolver's
** energy after the step, where finding the motion again left 1e-4). The
** string model follows
** Evolver (measured on 100grain.fe): autochop runs first, autopop keeps
** the motion found before both (a junction merged at a midpoint takes the
** mean of its ends'), chop_follow, and autopop's pops wait for the move
** (after_move). */
/* The string model, after autopop: a chopped edge's new vertex v whose
** neighbours are no longer the split edge's ends, or one of which autopop
** moved to a midpoint, goes to the midpoint of its neighbours and moves
** with the mean of their motions, so that it ends at the midpoint of the
** moved ends (Evolver's result, measured on 100grain.fe at step 819).
** ends[2 i], ends[2 i + 1]: the split edge of new vertex v0 + i; moved:
** the vertices autopop placed at midpoints (NULL: none). */
static void chop_follow(tds_mesh *m, double (*keep)[3], tds_id v0, tds_id v1,
                        const int32_t *ends, const uint8_t *moved) {
  for (tds_id v = v0; v < v1; v++) {
    if (!tds_alive(m->vflags, v) || m->ve_start[v + 1] - m->ve_start[v] != 2) continue;
    int32_t o0 = m->ve[m->ve_start[v]], o1 = m->ve[m->ve_start[v] + 1];
    tds_id a = tds_oe_head(m, o0), b = tds_oe_head(m, o1);
    tds_id ea = ends[2 * (v - v0)], eb = ends[2 * (v - v0) + 1];
    if (((a == ea && b == eb) || (a == eb && b == ea)) && !(moved && (moved[a] || moved[b])))
      continue;
    double da[3], db[3];
    tds_edge_vec(m, o0, da);
    tds_edge_vec(m, o1, db);
    for (int k = 0; k < 3; k++) {
      m->x[v][k] += 0.5 * (da[k] + db[k]);
      keep[v][k] = 0.5 * (keep[a][k] + keep[b][k]);
    }
    m->coord_gen++;
  }
}

static int maintain(tds_ctx *ctx, tds_surf *s, work *w) {
  double (*keep)[3] = NULL; /* the step's motion once the mesh changed */
  int32_t nkeep = 0, pop_after = 0;
  int32_t *cends = NULL, chop0 = 0, chop1 = 0; /* strings: the chop's new vertices */
  uint8_t *moved = NULL;                        /* strings: autopop's midpoints */
  int rc = TDS_OK;
  for (int order = 0; order < 2 && rc == TDS_OK; order++) {
    int pass = s->str ? !order : order; /* 0 autopop, 1 autochop: strings chop first */
    if (!(pass ? s->autochop : s->autopop)) continue;
    int changed = 0;
    if (keep) memcpy(w->vel, keep, (size_t)nkeep * sizeof *keep);
    else rc = direction(ctx, s, w);
    if (rc != TDS_OK) break;
    if (!keep) {
      nkeep = w->nv;
      keep = tds_malloc(&w->al, (size_t)(nkeep > 0 ? nkeep : 1) * sizeof *keep);
      if (!keep) {
        rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
        break;
      }
      memcpy(keep, w->vel, (size_t)nkeep * sizeof *keep);
    }
    const double(*vel)[3] = (const double(*)[3])w->vel;
    int32_t *ends = NULL, *mix = NULL, nmix = 0, deferred = 0, nv0 = s->m.nv;
    rc = pass ? tds_autochop(ctx, s, vel, w->nv, 2 * s->scale, s->autochop_length, &ends, &changed)
              : tds_autopop(ctx, s, vel, w->nv, s->scale, &mix, &nmix, &deferred, &changed);
    if (rc != TDS_OK || !changed) {
      tds_free(&s->m.alloc, ends);
      tds_free(&s->m.alloc, mix);
      continue;
    }
    pop_after = deferred;
    /* a chop's new vertices: the mean of their ends' motions; a pop's
    ** none; autopop's rules (a merged junction) */
    double (*k2)[3] = tds_realloc(&w->al, keep, (size_t)(s->m.nv > 0 ? s->m.nv : 1) * sizeof *k2);
    if (!k2) {
      tds_free(&s->m.alloc, ends);
      tds_free(&s->m.alloc, mix);
      rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      break;
    }
    keep = k2;
    for (tds_id v = nv0; v < s->m.nv; v++)
      for (int k = 0; k < 3; k++)
        keep[v][k] = ends ? 0.5 * (keep[ends[2 * (v - nv0)]][k] + keep[ends[2 * (v - nv0) + 1]][k])
                          : 0;
    for (int32_t i = 0; i < nmix; i++)
      for (int k = 0; k < 3; k++)
        keep[mix[3 * i]][k] = 0.5 * (keep[mix[3 * i + 1]][k] + keep[mix[3 * i + 2]][k]);
    nkeep = s->m.nv;
    if (s->str && pass) { /* kept for chop_follow */
      cends = ends, ends = NULL;
      chop0 = nv0, chop1 = s->m.nv;
    }
    if (s->str && nmix && !moved) {
      moved = tds_calloc(&w->al, (size_t)s->m.nv, 1);
      if (!moved) rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      for (int32_t i = 0; moved && i < nmix; i++) moved[mix[3 * i]] = 1;
    }
    tds_free(&s->m.alloc, ends);
    tds_free(&s->m.alloc, mix);
    if (rc != TDS_OK) break;
    tds_alloc al = w->al;
    work_free(w);
    rc = work_init(ctx, s, w);
    if (rc != TDS_OK) {
      memset(w, 0, sizeof *w);
      w->al = al;
      break;
    }
    w->keep_vel = keep != NULL;
  }
  if (rc == TDS_OK && cends && pop_after) {
    if ((rc = tds_mesh_adjacency(&s->m)) != TDS_OK)
      rc = tds_seterr(ctx, rc, "out of memory");
    else
      chop_follow(&s->m, keep, chop0, chop1, cends, moved);
  }
  tds_free(&s->m.alloc, cends);
  tds_free(&w->al, moved);
  w->pop_after = pop_after;
  if (rc == TDS_OK && w->keep_vel) {
    memcpy(w->vel, keep, (size_t)nkeep * sizeof *keep);
    w->slope = 0; /* the line search's slope along the kept motion */
    for (tds_id v = 0; v < s->m.nv; v++) w->slope -= v3_dot(w->vel[v], w->vel[v]);
  }
  tds_free(&w->al, keep);
  return rc;
}

/* The string model after the move: autopop's pops, in the moved
** positions as Evolver's (measured on 100grain.fe at step 246); the work
** arrays made again if vertices were added. E: the energy, updated. */
static int after_move(tds_ctx *ctx, tds_surf *s, work *w, double *E) {
  tds_mesh *m = &s->m;
  int32_t nv = m->nv, cnt = w->pop_after;
  w->pop_after = 0;
  int rc = tds_autopop_pop(ctx, s, cnt);
  if (rc != TDS_OK) return rc;
  *E = s->energy;
  if (m->nv != nv) {
    tds_alloc al = w->al;
    work_free(w);
    if ((rc = work_init(ctx, s, w)) != TDS_OK) {
      memset(w, 0, sizeof *w);
      w->al = al;
    }
  }
  return rc;
}

static int step(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_mesh *m = &s->m;
  if (s->autopop || s->autochop) {
    int rc = maintain(ctx, s, w);
    if (rc != TDS_OK) return rc;
  }
  if (m->nv) { /* an empty surface has no arrays (memcpy from NULL is UB) */
    memcpy(w->x0, m->x, (size_t)m->nv * sizeof *w->x0);
    memcpy(w->p0, m->vp, (size_t)m->nv * sizeof *w->p0);
  }
  int rc = TDS_OK;
  if (w->keep_vel) {
    w->keep_vel = 0;
    if (w->g0) rc = start_gradients(ctx, s, w);
  } else {
    rc = direction(ctx, s, w);
    if (rc == TDS_OK && s->conj_grad) rc = conjugate(ctx, s, w);
  }
  if (rc != TDS_OK) return rc;
  double E, scale;
  if (s->fixed_scale) {
    scale = s->scale;
    E = trial(ctx, s, w, scale);
  } else {
    double E0 = w->at_target ? w->E0 : trial(ctx, s, w, 0);
    scale = s->evolver_ls ? line_search_evolver(ctx, s, w, E0, w->slope, &E)
                          : line_search_tds(ctx, s, w, E0, w->slope, &E);
    s->scale = scale;
  }
  /* tds_iterate puts the surface back; a projection that failed says why */
  if (!isfinite(E) && w->trial_why) return w->trial_why;
  if (!isfinite(E)) return tds_seterr(ctx, TDS_ENUM, "iteration produced a non-finite energy");
  if (s->check_increase && E > w->E0) { /* Evolver's check_increase */
    if (m->nv) {
      memcpy(m->x, w->x0, (size_t)m->nv * sizeof *w->x0);
      memcpy(m->vp, w->p0, (size_t)m->nv * sizeof *w->p0);
    }
    m->coord_gen++;
    w->spec_gen = 0;
    w->undone = 1;
    if (w->pop_after && (rc = after_move(ctx, s, w, &E)) != TDS_OK) return rc;
    return tds_surf_update(ctx, s);
  }
  if (w->pop_after && (rc = after_move(ctx, s, w, &E)) != TDS_OK) return rc;
  /* Changed parameters: as Evolver, the step is taken from the positions
  ** as they were, then the surface follows the parameters. */
  if (s->placed_gen != s->param_gen) {
    w->spec_gen = 0; /* other parameters: other values */
    if ((rc = tds_recalc(ctx, s)) != TDS_OK) return rc;
    E = s->energy;
  }
  s->energy = E;
  s->iterations++;
  return TDS_OK;
}

int tds_iterate(tds_ctx *ctx, tds_surf *s, int n) {
  /* The line search shrinks from the limit to 1e-12 of it: a limit that is
  ** not a positive normal number would never end it. */
  if (s->fixed_scale ? !(isfinite(s->scale) && s->scale >= 0)
                     : !(s->scale_limit > 0 && isnormal(s->scale_limit)))
    return tds_seterr(ctx, TDS_ERANGE, "%s %g is not usable: give a positive finite value",
                      s->fixed_scale ? "the fixed scale" : "the scale limit",
                      s->fixed_scale ? s->scale : s->scale_limit);
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  if (n == 0) return tds_snap_end(ctx, s, &sn, tds_recalc_if_stale(ctx, s));
  work w;
  rc = work_init(ctx, s, &w);
  if (rc != TDS_OK) {
    tds_snap_free(&sn);
    return rc;
  }
  tds_progress_begin(ctx, 'g', n);
  int last = 0; /* countdown number of the last step done */
  int warned = 0; /* the stall warning is given once per command */
  for (int i = n; i > 0; i--) {
    rc = step(ctx, s, &w);
    if (rc != TDS_OK && n > 1) { /* say which step failed */
      char msg[sizeof ctx->errmsg];
      snprintf(msg, sizeof msg, "%s", ctx->errmsg);
      tds_seterr(ctx, rc, "step %d of %d: %s", n - i + 1, n, msg);
    }
    if (rc != TDS_OK) break;
    if (w.undone) { /* no line for a step taken back; g stops */
      tds_progress_erase(ctx);
      tds_warnf(ctx, "warning: motion would have increased the energy: "
                "coordinates restored, g stopped after %d of %d steps "
                "(check_increase)\n", n - i, n);
      break;
    }
    last = i;
    if (!tds_progress_step(ctx, n - i + 1, s->energy, s->scale))
      tds_printf(ctx, "%3d. %s: %#17.15g energy: %#17.15g  scale: %#g\n", i,
                 s->str ? "length" : "area", tds_surf_area(s), s->energy, s->scale);
    if (ctx->step) ctx->step(ctx->step_ud, s->energy);
    if (w.unconverged) {
      tds_progress_erase(ctx);
      tds_warnf(ctx, "warning: volume or quantity constraints did not converge "
                "in 10 projections\n");
      w.unconverged = 0;
    }
    /* once per command, and not again for the same facet; the scan only
    ** when the quick pass cannot rule a degenerate facet out */
    int collapsed = tds_stall_collapsed(s, w.slope, s->energy);
    if (!warned && (collapsed || !tds_stall_clear(s))) {
      tds_stall_out so;
      tds_stall_scan(s, &so);
      if (so.degenerate || collapsed) {
        warned = 1;
        if (s->stall_facet != tds_stall_facet(&so) + 1) {
          tds_progress_erase(ctx);
          tds_stall_warn(ctx, s, &so, collapsed);
          s->stall_facet = tds_stall_facet(&so) + 1;
        }
      }
    }
    if (ctx->interrupt) {
      ctx->interrupt = 0;
      rc = tds_seterr(ctx, TDS_EINTR, "interrupted: %d of %d iterations done",
                      n - i + 1, n);
      break;
    }
  }
  if (!warned && rc == TDS_OK) s->stall_facet = 0; /* healthy again */
  if (tds_progress_end(ctx) > 0) /* the live line replaced them: the last */
    tds_printf(ctx, "%3d. %s: %#17.15g energy: %#17.15g  scale: %#g\n", last,
               s->str ? "length" : "area", tds_surf_area(s), s->energy, s->scale);
  work_free(&w);
  /* After a step, energy, area and volumes are those of its last trial,
  ** which is where the vertices are; after an interruption compute them.
  ** A failed command (not an interruption) puts the surface back. */
  if (rc == TDS_EINTR) tds_surf_update(ctx, s);
  return tds_snap_end(ctx, s, &sn, rc);
}

int tds_pressures(tds_ctx *ctx, tds_surf *s) {
  work w;
  int rc = work_init(ctx, s, &w);
  if (rc == TDS_OK) rc = direction(ctx, s, &w);
  work_free(&w);
  return rc;
}
