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

/* The vertex of the parabola through (t0, e0), (t1, e1), (t2, e2), e1
** below both (so it lies between t0 and t2). */
static double parabola_vertex(double t0, double e0, double t1, double e1, double t2, double e2) {
  double num = (t1 - t0) * (t1 - t0) * (e1 - e2) - (t1 - t2) * (t1 - t2) * (e1 - e0);
  double den = (t1 - t0) * (e1 - e2) - (t1 - t2) * (e1 - e0);
  return den != 0 ? t1 - 0.5 * num / den : t1;
}

/* Evolver's line search of hessian_seek and saddle along t w, t in
** (0, tmax] (measured on evolver-nox-d 2.70; its manual says only that
** it looks both ways and tests down to 1e-6 of the largest scale; the
** scales it reports are this rule's to 1e-13 on the cube, catenoids and
** drops). The first trial is 0.01 tmax; while it does not lower the
** energy below E0 it is divided by 10, down to 1e-6 tmax (then 0 is
** returned: nothing lowers it this way). From the first lower trial the
** scale doubles (the last trial capped at tmax) while the energy keeps
** falling; where it rises again the scale is the vertex of the parabola
** through the last three trials (t = 0 the first of them when only one
** trial lowered the energy); at tmax and still falling, tmax. Leaves the
** surface at the t returned, *E its energy; a vertex whose energy is not
** below E0 (a strongly skewed line, never measured in Evolver) gives way
** to the best trial, so the command never raises the energy. */
static double seek(tds_ctx *ctx, tds_surf *s, start *st, const tds_nsys *n,
                   const double *w, double E0, double tmax, double *E) {
  double t = 0.01 * tmax, e = place(ctx, s, st, n, w, t);
  for (int k = 0; !(e < E0); k++) {
    if (k == 4 || st->nomem) { /* 1e-6 tmax tried */
      *E = E0;
      return 0;
    }
    t /= 10;
    e = place(ctx, s, st, n, w, t);
  }
  double tp = 0, ep = E0; /* the trial before (t, e) */
  for (;;) {
    if (!(t < tmax)) { /* at the largest scale, still falling */
      *E = e;
      return t;
    }
    double t2 = fmin(2 * t, tmax), e2 = place(ctx, s, st, n, w, t2);
    if (!(e2 < e)) {
      double tv = parabola_vertex(tp, ep, t, e, t2, e2);
      double ev = isfinite(e2) && tv > tp && tv < t2 ? place(ctx, s, st, n, w, tv) : (double)NAN;
      if (ev < E0) {
        *E = ev;
        return tv;
      }
      *E = place(ctx, s, st, n, w, t);
      return t;
    }
    tp = t, ep = e, t = t2, e = e2;
  }
}

/* seek forwards along w, else backwards; 0 (the surface at t = 0) when
** neither lowers the energy. The energies are compared with the energy
** at t = 0 after the restoring moves, not the one before them (as
** Evolver's: on the cube after g; r, whose volume g left 1e-5 off, the
** parabola through 0, 1 and 2 gives Evolver's scale to 1e-15 with that
** energy, and 6e-5 off with the one before). */
static double seek_both(tds_ctx *ctx, tds_surf *s, start *st, const tds_nsys *n, double *w,
                        double tmax, double *E) {
  double E0 = place(ctx, s, st, n, w, 0);
  if (!isfinite(E0)) {
    *E = E0;
    return 0;
  }
  double t = seek(ctx, s, st, n, w, E0, tmax, E);
  if (t != 0 || st->nomem) return t;
  for (int32_t j = 0; j < n->m; j++) w[j] = -w[j];
  t = -seek(ctx, s, st, n, w, E0, tmax, E);
  for (int32_t j = 0; j < n->m; j++) w[j] = -w[j];
  if (t == 0) *E = place(ctx, s, st, n, w, 0);
  return t;
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
    if (seekmax > 0)
      t = seek_both(ctx, s, &st, &n, w, seekmax, &E);
    else E = place(ctx, s, &st, &n, w, 1);
    if (st.nomem)
      rc = tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
    else if (!isfinite(E))
      rc = tds_seterr(ctx, TDS_ENUM, "hessian: the step gives a non-finite energy");
  }
  /* the new multipliers: H w + A y = -(grad E - A mult); after
  ** hessian_seek the whole y too, whatever the scale (Evolver's: the cube's
  ** pressure after g; r; hessian_seek is 3.2404807614 at scale 0.758, the
  ** full step's, and its next hessian_seek agrees only so) */
  if (rc == TDS_OK)
    for (int32_t q = 0; q < n.nq; q++) set_mult(s, q, n.mult[q] - (seekmax > 0 ? 1 : t) * w[n.m + q]);
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

/* Evolver's length of saddle's eigenvector (measured: the displacement
** of its saddle 0.01 against tds's unit eigenvector): the largest
** unknown is 0.1 of the largest distance of a vertex (fixed ones too)
** from the origin; with hessian_normal on an unknown is a vertex's move
** along its unit normal (its length), off a coordinate of its move. On
** the flat square of side pi refined twice, 0.1 pi sqrt 2 at its centre
** (to 1e-15); catman's saddle (normal off) and cat.fe's (on) to 1e-11,
** a drop on slidestr.fe's constraint to 7e-5. Scales w (amounts of the
** unit vector vec) accordingly. */
static void evolver_length(const tds_surf *s, const tds_newton_opts *o, const tds_nsys *n,
                           const double (*vec)[3], double *w) {
  const tds_mesh *m = &s->m;
  double R = 0, big = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_alive(m->vflags, v)) continue;
    R = fmax(R, v3_norm(m->x[v]));
    if (!tds_vertex_free(s, v)) continue;
    if (o->normal) big = fmax(big, v3_norm(vec[v]));
    else
      for (int i = 0; i < 3; i++) big = fmax(big, fabs(vec[v][i]));
  }
  if (!(R > 0 && big > 0)) return;
  double k = 0.1 * R / big;
  for (int32_t j = 0; j < n->m; j++) w[j] *= k;
}

int tds_newton_saddle(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double maxscale,
                      double *lowest, double *step) {
  *step = 0;
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
      evolver_length(s, o, &n, (const double(*)[3])vec, w);
      /* downhill to first order forwards (Evolver's eigenvector has its
      ** own sign; it tries forwards first as hessian_seek does) */
      double D = 0;
      for (int32_t j = 0; j < n.m; j++) D += n.grad[j] * w[j];
      if (D > 0)
        for (int32_t j = 0; j < n.m; j++) w[j] = -w[j];
      t = seek_both(ctx, s, &st, &n, w, maxscale > 0 ? maxscale : 100, &E);
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
  *step = t;
  s->energy = E;
  tds_printf(ctx, "stepsize %g\n1. %s: %#17.15g energy: %#17.15g \n", t, s->str ? "length" : "area",
             tds_surf_area(s), s->energy);
  tds_snap_free(&sn);
  return TDS_OK;
}
