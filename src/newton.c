/* newton.c: Newton steps, inertia probes, moves and saddle (newton.h);
** ritz is in newton_eig.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "eval.h"
#include "fixq.h"
#include "motion.h"
#include "newton_int.h"
#include "recalc.h"
#include "snap.h"
#include "vec3.h"

/* How far the quantities are off their targets for Evolver's restoring
** after a Newton step: the sum of |target - value| / (1e-4 |target|)
** (1e-4 for a target 0), relative for bodies too: on perturbed polygons
** of areas 3.31 and 3.37, errors of 3.96e-4 and 1.35e-4 after the first
** move, Evolver moves again after the first and not after the second.
** (iterate.c's evolver_off for g takes 1e-4 for a body, which the unit
** cube it was measured on does not tell apart.) */
static double evolver_off(const tds_fixq *fq) {
  double off = 0;
  for (int32_t q = 0; q < fq->nq; q++) {
    double tol = 1e-4;
    if (fq->target[q] != 0) tol *= fabs(fq->target[q]);
    off += fabs(fq->target[q] - fq->value[q]) / tol;
  }
  return off;
}

/* The constrained quantities' gradients (*fq) and a zeroed restoring
** motion per vertex slot (*rest, the caller frees both), for the
** restoring loops below. */
static int restore_begin(tds_ctx *ctx, tds_surf *s, tds_fixq *fq, double (**rest)[3]) {
  int rc = tds_fixq_build(ctx, s, fq);
  if (rc != TDS_OK) return rc;
  *rest = tds_calloc(&ctx->alloc, (size_t)s->m.nv + 1, sizeof **rest);
  if (!*rest) {
    tds_fixq_free(fq);
    return tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
  }
  return TDS_OK;
}

/* Move every free vertex by its restoring motion (onto its constraints). */
static void apply_rest(tds_surf *s, const double (*rest)[3]) {
  tds_mesh *m = &s->m;
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_vertex_free(s, v)) continue;
    double x[3], p[2] = {m->vp[v][0], m->vp[v][1]};
    v3_copy(x, m->x[v]);
    tds_motion_apply(s, v, x, p, rest[v]);
  }
  m->coord_gen++;
}

/* The restoring after a Newton step, as Evolver's (measured on a
** perturbed 15-gon whose step moves its vertices by up to 0.2: the area
** after it and every position to 5e-13): moves along the quantities'
** gradients at the moved positions, those gradients kept while only the
** values are recomputed, at least one, then while Evolver's off (above)
** is over 1, at most eleven (a 14-gon whose step leaves its area 3.3
** times its target: Evolver's eleven moves, to 5e-11 in position);
** where the moves stop closing in, the exact
** projection (project_quantities) instead. After a small step the first
** move leaves the values at rounding level, so one is made. Leaves
** s->energy and s->area at the final positions. TDS_OK or TDS_ENUM. */
static int project_quantities(tds_ctx *ctx, tds_surf *s, int maxit);
static int restore_evolver(tds_ctx *ctx, tds_surf *s) {
  tds_mesh *m = &s->m;
  tds_fixq fq = {0};
  double (*rest)[3] = NULL;
  int rc = restore_begin(ctx, s, &fq, &rest);
  if (rc != TDS_OK) return rc;
  tds_eval_out out = {.fq = fq.nq ? &fq : NULL}; /* the gradients, kept */
  if ((rc = tds_eval(ctx, s, &out)) == TDS_OK) {
    s->energy = out.energy;
    s->area = out.area;
    for (tds_id v = 0; v < m->nv && v < fq.nv; v++)
      for (int32_t i = fq.start[v]; i < fq.start[v + 1]; i++) tds_motion_project(s, v, fq.g[i]);
  }
  double prev = INFINITY;
  for (int k = 0; rc == TDS_OK && fq.nq; k++) {
    double off = evolver_off(&fq);
    if (!isfinite(off)) {
      rc = tds_seterr(ctx, TDS_ENUM, "a constrained quantity is not finite after the step");
      break;
    }
    if (k > 0 && !(off < prev)) { /* the moves diverge: project exactly */
      rc = project_quantities(ctx, s, 10);
      break;
    }
    if (k == 11 || (k > 0 && off <= 1)) break;
    prev = off;
    if ((rc = tds_fixq_restore(ctx, &fq, m->nv, rest)) != TDS_OK) break;
    apply_rest(s, (const double(*)[3])rest);
    tds_eval_out o2 = {.fq = NULL}; /* the values only */
    if ((rc = tds_eval(ctx, s, &o2)) != TDS_OK) break;
    tds_fixq_values(s, &fq);
    s->energy = o2.energy;
    s->area = o2.area;
  }
  tds_free(&ctx->alloc, rest);
  tds_fixq_free(&fq);
  return rc;
}

/* Bring the constrained quantities to their targets by Newton steps along
** their gradients (the restoring motion of `g`): until within 1e-12
** relative, or the error stops shrinking (rounding), or maxit steps.
** Leaves s->energy and s->area at the final positions. TDS_OK or
** TDS_ENUM. */
static int project_quantities(tds_ctx *ctx, tds_surf *s, int maxit) {
  tds_mesh *m = &s->m;
  tds_fixq fq = {0};
  double (*rest)[3] = NULL;
  int rc = restore_begin(ctx, s, &fq, &rest);
  if (rc != TDS_OK) return rc;
  double prev = INFINITY;
  for (int it = 0;; it++) {
    tds_eval_out out = {.fq = fq.nq ? &fq : NULL};
    if ((rc = tds_eval(ctx, s, &out)) != TDS_OK) break;
    s->energy = out.energy;
    s->area = out.area;
    double worst = 0;
    for (int32_t q = 0; q < fq.nq; q++) {
      double tol = 1e-12 * (fabs(fq.target[q]) > 0 ? fabs(fq.target[q]) : 1);
      double err = fabs(fq.target[q] - fq.value[q]) / tol;
      if (!(err <= worst)) worst = err;
    }
    if (!isfinite(worst)) {
      rc = tds_seterr(ctx, TDS_ENUM, "a constrained quantity is not finite after the step");
      break;
    }
    if (worst <= 1 || (worst < 1e4 && worst > 0.5 * prev) || it == maxit) break;
    prev = worst;
    for (tds_id v = 0; v < m->nv; v++)
      for (int32_t i = fq.start[v]; i < fq.start[v + 1]; i++) tds_motion_project(s, v, fq.g[i]);
    if ((rc = tds_fixq_restore(ctx, &fq, m->nv, rest)) != TDS_OK) break;
    apply_rest(s, (const double(*)[3])rest);
    if (it + 1 == maxit) { /* the energy where it stops */
      tds_eval_out o2 = {.fq = NULL};
      if ((rc = tds_eval(ctx, s, &o2)) != TDS_OK) break;
      s->energy = o2.energy;
      s->area = o2.area;
      break;
    }
  }
  tds_free(&ctx->alloc, rest);
  tds_fixq_free(&fq);
  return rc;
}

/* Store the multiplier of the q-th constrained quantity (fixq order). */
static void set_mult(tds_surf *s, int32_t q, double v) {
  tds_ctx c;
  tds_ctx_init(&c);
  tds_fixq fq = {0};
  if (tds_fixq_build(&c, s, &fq) != TDS_OK) return;
  if (q < fq.nq) {
    if (fq.qbody[q] != TDS_NONE) s->m.bpressure[fq.qbody[q]] = v;
    else s->quant[fq.qquant[q]].pressure = v;
  }
  tds_fixq_free(&fq);
}

/* Positions at the start of a command. */
typedef struct start {
  tds_alloc alloc;
  double (*x0)[3], (*p0)[2];
  int nomem;  /* a placement ran out of memory: the command fails with
                 TDS_ENOMEM (a line search on NaN samples would give
                 another result than with memory) */
} start;

static int start_take(tds_ctx *ctx, const tds_surf *s, start *st) {
  st->alloc = ctx->alloc;
  size_t nv = (size_t)s->m.nv + 1;
  st->x0 = tds_malloc(&ctx->alloc, nv * sizeof *st->x0);
  st->p0 = tds_malloc(&ctx->alloc, nv * sizeof *st->p0);
  if (!st->x0 || !st->p0) { /* st holds nothing (start_free may follow) */
    tds_free(&ctx->alloc, st->x0);
    tds_free(&ctx->alloc, st->p0);
    st->x0 = NULL;
    st->p0 = NULL;
    return tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
  }
  if (s->m.nv) {
    memcpy(st->x0, s->m.x, (size_t)s->m.nv * sizeof *st->x0);
    memcpy(st->p0, s->m.vp, (size_t)s->m.nv * sizeof *st->p0);
  }
  return TDS_OK;
}

static void start_free(start *st) {
  tds_free(&st->alloc, st->x0);
  tds_free(&st->alloc, st->p0);
}

/* Place every vertex at its start moved by t * (sum of w_j mv_j) (onto
** its level sets), then restore the quantities as Evolver's hessian
** does (restore_evolver). The energy (NAN if it failed) is returned. */
static double place(tds_ctx *ctx, tds_surf *s, start *st, const tds_nsys *n,
                    const double *w, double t) {
  tds_mesh *m = &s->m;
  int bad = 0;
  int32_t j = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_vertex_free(s, v)) continue;
    double d[3] = {0, 0, 0};
    for (; j < n->m && n->vert[j] == v; j++) v3_axpy(d, t * w[j], n->mv[j]);
    if (tds_motion_apply(s, v, st->x0[v], st->p0[v], d) != TDS_OK) bad = 1;
  }
  m->coord_gen++;
  if (bad) return NAN;
  int rc = restore_evolver(ctx, s);
  if (rc == TDS_ENOMEM) st->nomem = 1;
  if (rc != TDS_OK) return NAN;
  return isfinite(s->energy) ? s->energy : (double)NAN;
}

/* Least energy along t in (0, tmax]: the energy at tmax, then halving
** (down to 1e-6 tmax, as Evolver) while that lowers it (or the energy is
** not below the start), then the
** parabola through the best sample and its neighbours (t = 0 among them)
** when its vertex is inside and lower. Leaves the surface at the t
** returned, *E its energy. */
static double seek(tds_ctx *ctx, tds_surf *s, start *st, const tds_nsys *n,
                   const double *w, double E0, double tmax, double *E) {
  double ts[48], es[48];
  int k = 0;
  ts[k] = 0;
  es[k++] = E0;
  double t = tmax, e = place(ctx, s, st, n, w, t);
  ts[k] = t;
  es[k++] = e;
  while (k < 44 && t > 1e-6 * tmax) { /* Evolver gives up at 1e-6 of it */
    double t2 = t / 2, e2 = place(ctx, s, st, n, w, t2);
    ts[k] = t2;
    es[k++] = e2;
    if (isfinite(e) && e < E0 && !(e2 < e)) break;
    t = t2;
    e = e2;
  }
  /* sort by t (insertion: few points) */
  for (int a = 1; a < k; a++)
    for (int b = a; b > 0 && ts[b] < ts[b - 1]; b--) {
      double x = ts[b], y = es[b];
      ts[b] = ts[b - 1], es[b] = es[b - 1];
      ts[b - 1] = x, es[b - 1] = y;
    }
  int best = 0;
  for (int i = 1; i < k; i++)
    if (es[i] < es[best]) best = i;
  double tb = ts[best], eb = es[best];
  int c = best == 0 ? 1 : best == k - 1 ? k - 2 : best; /* middle of three */
  if (k >= 3 && isfinite(es[c - 1]) && isfinite(es[c]) && isfinite(es[c + 1])) {
    double t0 = ts[c - 1], t1 = ts[c], t2 = ts[c + 1];
    double e0 = es[c - 1], e1 = es[c], e2 = es[c + 1];
    double num = (t1 - t0) * (t1 - t0) * (e1 - e2) - (t1 - t2) * (t1 - t2) * (e1 - e0);
    double den = (t1 - t0) * (e1 - e2) - (t1 - t2) * (e1 - e0);
    double d1 = (e1 - e0) / (t1 - t0), d2 = (e2 - e1) / (t2 - t1);
    if (den != 0 && d2 > d1) { /* convex: a minimum */
      double tp = t1 - 0.5 * num / den;
      if (tp > 0 && tp <= tmax && tp != tb) {
        double ep = place(ctx, s, st, n, w, tp);
        if (ep < eb) {
          *E = ep;
          return tp;
        }
      }
    }
  }
  *E = tb > 0 ? place(ctx, s, st, n, w, tb) : place(ctx, s, st, n, w, 0);
  return tb;
}

/* Factor the bordered system at shift c; *index: negative eigenvalues of
** H - c M on the constraints. */
static int factor(tds_ctx *ctx, const tds_nsys *n, double eps, double c, tds_la **f,
                  tds_inertia *in) {
  tds_spmat K = {0};
  int rc = tds_nsys_kkt(ctx, n, c, &K);
  if (rc == TDS_OK) rc = tds_la_factor(ctx, &K, eps, f);
  tds_spmat_free(&K);
  if (rc != TDS_OK) return rc;
  *in = tds_la_inertia(*f);
  in->neg -= n->nq;
  in->pos -= n->nq;
  if (in->neg < 0 || in->pos < 0) { /* dependent constraint gradients */
    tds_la_free(*f);
    *f = NULL;
    return tds_seterr(ctx, TDS_ENUM, "hessian: the constraints' gradients are dependent "
                      "(a volume or quantity cannot be held, or hessian_epsilon is so "
                      "large that its pivot counts as zero)");
  }
  return TDS_OK;
}

/* A singular system (motions that do not change the energy to second
** order, as translations with hessian_normal off) is solved with its
** null directions left out, when it is consistent: the residual of the
** solution below 1e-6 of |b| + |K| |x| (the second term is rounding,
** which dominates when the step is tiny, amplified by the nearly null
** directions: 1.2e-8 measured on knotty.fe's free knot, whose six rigid
** motions are null; an inconsistent system leaves a residual of the
** order of |b|), or when |b| is itself at the rounding floor (1e-11 |K|:
** converged), so the step is the Newton step up to those directions.
** Otherwise it is refused. */
static int singular_solve(tds_ctx *ctx, const tds_nsys *n, tds_la *f, double *b, int32_t zero) {
  int32_t N = n->m + n->nq;
  double *b0 = tds_malloc(&ctx->alloc, ((size_t)N + 1) * sizeof *b0), *r = tds_malloc(&ctx->alloc, ((size_t)N + 1) * sizeof *r);
  tds_spmat K = {0};
  int rc = b0 && r ? TDS_OK : tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
  if (rc == TDS_OK) {
    memcpy(b0, b, (size_t)N * sizeof *b0);
    rc = tds_nsys_kkt(ctx, n, 0, &K);
  }
  if (rc == TDS_OK) rc = tds_la_solve(ctx, f, b, 1);
  if (rc == TDS_OK) {
    tds_spmat_mulv(&K, b, r);
    double res = 0, nb = 0, nx = 0, nk = 0;
    for (int32_t i = 0; i < N; i++) {
      res = fmax(res, fabs(r[i] - b0[i]));
      nb = fmax(nb, fabs(b0[i]));
      nx = fmax(nx, fabs(b[i]));
    }
    for (int64_t e = 0; e < K.colptr[N]; e++) nk = fmax(nk, fabs(K.val[e]));
    /* rounding in K x is a few ulps of |K| |x| per entry; a right-hand
    ** side at the rounding floor of the gradient (converged) is consistent */
    if (!(res <= 1e-6 * (nb + nk * nx) || nb <= 1e-11 * nk))
      rc = tds_seterr(ctx, TDS_ENUM, "hessian: the Hessian is singular (%d zero eigenvalues) and "
                      "the step has no solution; try hessian_normal on, or fix the free "
                      "directions", (int)zero);
  }
  tds_spmat_free(&K);
  tds_free(&ctx->alloc, b0);
  tds_free(&ctx->alloc, r);
  return rc;
}

int tds_newton_probe(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double c,
                     tds_inertia *in) {
  if (!isfinite(c)) return tds_seterr(ctx, TDS_ERANGE, "eigenprobe: the probe value is not finite");
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  tds_nsys n;
  rc = tds_nsys_build(ctx, s, o, &n);
  if (rc == TDS_OK) {
    tds_la *f = NULL;
    rc = factor(ctx, &n, o->epsilon, c, &f, in);
    tds_la_free(f);
    tds_nsys_free(&n);
  }
  /* nothing moves; the pressures computed are kept */
  if (rc == TDS_OK) {
    tds_snap_free(&sn);
    return rc;
  }
  return tds_snap_end(ctx, s, &sn, rc);
}

int tds_newton_step(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double seekmax,
                    tds_inertia *inertia, double *scale) {
  if (seekmax < 0 || !isfinite(seekmax))
    return tds_seterr(ctx, TDS_ERANGE, "hessian_seek: the largest scale must be positive and finite");
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  if ((rc = tds_recalc_if_stale(ctx, s)) != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  tds_nsys n;
  tds_la *f = NULL;
  double *w = NULL;
  start st = {0};
  rc = tds_nsys_build(ctx, s, o, &n);
  if (rc != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  tds_inertia in = {0};
  rc = factor(ctx, &n, o->epsilon, 0, &f, &in);
  if (rc == TDS_OK) {
    w = tds_calloc(&ctx->alloc, (size_t)(n.m + n.nq) + 1, sizeof *w);
    if (!w) rc = tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
  }
  if (rc == TDS_OK) {
    for (int32_t j = 0; j < n.m; j++) w[j] = -n.grad[j];
    for (int32_t q = 0; q < n.nq; q++) w[n.m + q] = n.target[q] - n.value[q];
    rc = in.zero ? singular_solve(ctx, &n, f, w, in.zero) : tds_la_solve(ctx, f, w, 0);
  }
  if (rc == TDS_OK) rc = start_take(ctx, s, &st);
  double E = NAN, t = 1;
  if (rc == TDS_OK) {
    if (seekmax > 0) {
      t = seek(ctx, s, &st, &n, w, n.energy, seekmax, &E);
      if (t == 0) { /* no decrease forward: look the other way */
        for (int32_t j = 0; j < n.m; j++) w[j] = -w[j];
        t = -seek(ctx, s, &st, &n, w, n.energy, seekmax, &E);
        for (int32_t j = 0; j < n.m; j++) w[j] = -w[j];
        if (t == 0) E = place(ctx, s, &st, &n, w, 0);
      }
    }
    else E = place(ctx, s, &st, &n, w, 1);
    if (st.nomem)
      rc = tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
    else if (!isfinite(E))
      rc = tds_seterr(ctx, TDS_ENUM, "hessian: the step gives a non-finite energy");
  }
  if (rc == TDS_OK) /* the new multipliers: H w + A y = -(grad E - A mult) */
    for (int32_t q = 0; q < n.nq; q++) set_mult(s, q, n.mult[q] - t * w[n.m + q]);
  start_free(&st);
  tds_free(&ctx->alloc, w);
  tds_la_free(f);
  tds_nsys_free(&n);
  if (rc != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  s->energy = E;
  s->iterations++;
  if (inertia) *inertia = in;
  if (scale) *scale = t;
  if (in.neg) tds_printf(ctx, "WARNING 1825: Hessian not positive definite. Index: %d\n", (int)in.neg);
  if (seekmax > 0)
    tds_printf(ctx, "%3d. %s: %#17.15g energy: %#17.15g  scale: %#g\n", 1, s->str ? "length" : "area",
               tds_surf_area(s), s->energy, t);
  else
    tds_printf(ctx, "%3d. %s: %#17.15g energy: %#17.15g\n", 1, s->str ? "length" : "area",
               tds_surf_area(s), s->energy);
  tds_snap_free(&sn);
  return TDS_OK;
}

/* The unknowns' amounts of a displacement per vertex: w_j = dx_j . vec[v]
** (a vertex's unknowns move it along directions orthonormal in space). */
static void amounts(const tds_nsys *n, const double (*vec)[3], double *w) {
  for (int32_t j = 0; j < n->m; j++) w[j] = v3_dot(n->dx[j], vec[n->vert[j]]);
}

/* Least energy along t w, t of either sign: from t0, doubling while the
** energy falls (up to tmax), then a parabola through the last three.
** Leaves the surface at the best t found (0: where it started) and
** returns that t. */
static double expand(tds_ctx *ctx, tds_surf *s, start *st, const tds_nsys *n,
                     const double *w, double E0, double t0, double tmax, double *E) {
  double bt = 0, bE = E0;
  for (int sign = -1; sign <= 1; sign += 2) {
    double tp = 0, ep = E0, t = t0, e;
    double t1 = 0, e1 = E0; /* the point before tp */
    for (;;) {
      e = place(ctx, s, st, n, w, sign * t);
      if (!(e < ep)) break;
      t1 = tp, e1 = ep, tp = t, ep = e;
      if (t >= tmax) break;
      t = fmin(2 * t, tmax);
    }
    if (tp > 0 && isfinite(e) && e > ep) { /* parabola through (t1, tp, t) */
      double num = (tp - t1) * (tp - t1) * (ep - e) - (tp - t) * (tp - t) * (ep - e1);
      double den = (tp - t1) * (ep - e) - (tp - t) * (ep - e1);
      double tq = den != 0 ? tp - 0.5 * num / den : tp;
      if (tq > t1 && tq < t) {
        double eq = place(ctx, s, st, n, w, sign * tq);
        if (eq < ep) tp = tq, ep = eq;
      }
    }
    if (tp > 0 && ep < bE) bE = ep, bt = sign * tp;
  }
  *E = place(ctx, s, st, n, w, bt);
  return bt;
}

int tds_newton_move(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, const double (*vec)[3],
                    int32_t nv, double t) {
  if (!isfinite(t)) return tds_seterr(ctx, TDS_ERANGE, "move: the step is not finite");
  if (!vec || nv != s->m.nv)
    return tds_seterr(ctx, TDS_ERANGE, "move: there is no eigenvector of this surface "
                      "(run ritz first; the surface has changed since)");
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  tds_nsys n;
  start st = {0};
  double *w = NULL;
  rc = tds_nsys_build(ctx, s, o, &n);
  if (rc != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  rc = start_take(ctx, s, &st);
  if (rc == TDS_OK && !(w = tds_calloc(&ctx->alloc, (size_t)n.m + 1, sizeof *w)))
    rc = tds_seterr(ctx, TDS_ENOMEM, "move: out of memory");
  if (rc == TDS_OK) {
    amounts(&n, vec, w);
    double E = place(ctx, s, &st, &n, w, t);
    if (st.nomem)
      rc = tds_seterr(ctx, TDS_ENOMEM, "move: out of memory");
    else if (!isfinite(E))
      rc = tds_seterr(ctx, TDS_ENUM, "move: the energy is not finite after the move");
  }
  tds_free(&ctx->alloc, w);
  start_free(&st);
  tds_nsys_free(&n);
  if (rc != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  tds_snap_free(&sn);
  return TDS_OK;
}

int tds_newton_saddle(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double maxscale,
                      double *lowest, int *moved) {
  *moved = 0;
  if (!isfinite(maxscale)) return tds_seterr(ctx, TDS_ERANGE, "saddle: the scale is not finite");
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  if ((rc = tds_recalc_if_stale(ctx, s)) != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  tds_inertia in;
  double val = 0;
  int32_t got = 0;
  int iters;
  double (*vec)[3] = tds_calloc(&ctx->alloc, (size_t)s->m.nv + 1, sizeof *vec);
  if (!vec) return tds_snap_end(ctx, s, &sn, tds_seterr(ctx, TDS_ENOMEM, "saddle: out of memory"));
  rc = tds_newton_ritz(ctx, s, o, NAN, 1, &val, &got, &in, vec, &iters, NULL);
  if (rc == TDS_OK && got == 0) rc = tds_seterr(ctx, TDS_ERANGE, "saddle: nothing can move");
  if (rc != TDS_OK) {
    tds_free(&ctx->alloc, vec);
    return tds_snap_end(ctx, s, &sn, rc);
  }
  *lowest = val;
  if (val >= 0) {
    tds_printf(ctx, "Lowest eigenvalue %.15g. Not a saddle point.\n", val);
    tds_free(&ctx->alloc, vec);
    tds_snap_free(&sn);
    return TDS_OK;
  }
  tds_printf(ctx, "Lowest eigenvalue %.15g\n", val);
  tds_nsys n;
  start st = {0};
  double *w = NULL, E = NAN, t = 0;
  rc = tds_nsys_build(ctx, s, o, &n);
  if (rc == TDS_OK) {
    rc = start_take(ctx, s, &st);
    if (rc == TDS_OK && !(w = tds_calloc(&ctx->alloc, (size_t)n.m + 1, sizeof *w)))
      rc = tds_seterr(ctx, TDS_ENOMEM, "saddle: out of memory");
    if (rc == TDS_OK) {
      amounts(&n, (const double(*)[3])vec, w);
      /* the largest displacement of a vertex at t = 1 sets the scales */
      double big = 0;
      for (int32_t j = 0; j < n.m; j++) big = fmax(big, fabs(w[j]));
      double t0 = big > 0 ? 1e-4 / big : 1e-4, tmax = maxscale > 0 ? maxscale : 1e3 * t0;
      t = expand(ctx, s, &st, &n, w, n.energy, fmin(t0, tmax), tmax, &E);
      if (st.nomem)
        rc = tds_seterr(ctx, TDS_ENOMEM, "saddle: out of memory");
      else if (!isfinite(E))
        rc = tds_seterr(ctx, TDS_ENUM, "saddle: the energy is not finite");
    }
    tds_nsys_free(&n);
  }
  tds_free(&ctx->alloc, w);
  start_free(&st);
  tds_free(&ctx->alloc, vec);
  if (rc != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  *moved = t != 0;
  s->energy = E;
  tds_printf(ctx, "stepsize %g\n1. %s: %#17.15g energy: %#17.15g \n", t, s->str ? "length" : "area",
             tds_surf_area(s), s->energy);
  tds_snap_free(&sn);
  return TDS_OK;
}
