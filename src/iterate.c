/* iterate.c: gradient descent with optimizing scale (the g command). */
#include "iterate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "eval.h"
#include "motion.h"
#include "vec3.h"

typedef struct work {
  int32_t nv;
  double (*x0)[3];   /* positions at the start of the step */
  double (*p0)[2];   /* boundary parameters at the start */
  double (*grad)[3]; /* energy gradient */
  double (*vel)[3];  /* motion-space velocity */
  double (*rest)[3]; /* restoring motion */
  tds_fixq fq;
  int unconverged;   /* a projection hit its step limit */
} work;

static void work_free(work *w) {
  free(w->x0);
  free(w->p0);
  free(w->grad);
  free(w->vel);
  free(w->rest);
  tds_fixq_free(&w->fq);
}

static int work_init(tds_ctx *ctx, tds_surf *s, work *w) {
  memset(w, 0, sizeof *w);
  size_t nv = (size_t)s->m.nv;
  w->nv = s->m.nv;
  w->x0 = tds_calloc(nv, sizeof *w->x0);
  w->p0 = tds_calloc(nv, sizeof *w->p0);
  w->grad = tds_calloc(nv, sizeof *w->grad);
  w->vel = tds_calloc(nv, sizeof *w->vel);
  w->rest = tds_calloc(nv, sizeof *w->rest);
  if (!w->x0 || !w->p0 || !w->grad || !w->vel || !w->rest) {
    work_free(w);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int rc = tds_fixq_build(ctx, s, &w->fq);
  if (rc != TDS_OK) work_free(w);
  return rc;
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

/* Evaluate gradient and quantities, then map into motion space and take
** out the constraint directions. Leaves vel, rest and pressures set. */
static int direction(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_mesh *m = &s->m;
  tds_eval_out out = {.grad = w->grad, .fq = &w->fq};
  int rc = tds_eval(ctx, s, &out);
  if (rc != TDS_OK) return rc;
  tds_fixq *fq = &w->fq;
  for (tds_id v = 0; v < m->nv; v++) {
    if (m->vflags[v] & TDS_DEAD) continue;
    tds_motion_project(s, v, w->grad[v]);
    for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
      tds_motion_project(s, v, fq->g[i]);
  }
  rc = tds_fixq_multipliers(ctx, fq, w->grad);
  if (rc != TDS_OK) return rc;
  store_pressures(s, fq);
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
  }
  return TDS_OK;
}

/* Newton steps onto the constrained quantities' targets: x += sum mu_q g_q
** with G mu = target - value, until every value is within 1e-12 of its
** target (relative) or ten steps are done. Leaves s->energy and s->area
** at the final positions. Returns 0, or -1 if a value is not finite. */
static int project_quantities(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_mesh *m = &s->m;
  tds_fixq *fq = &w->fq;
  for (int it = 0;; it++) {
    tds_eval_out out = {.fq = fq->nq ? fq : NULL};
    if (tds_eval(ctx, s, &out) != TDS_OK) return -1;
    s->energy = out.energy;
    s->area = out.area;
    double worst = 0;
    for (int32_t q = 0; q < fq->nq; q++) {
      double tol = 1e-12 * (fabs(fq->target[q]) > 1e-300 ? fabs(fq->target[q]) : 1);
      double err = fabs(fq->target[q] - fq->value[q]) / tol;
      if (!(err <= worst)) worst = err; /* NaN propagates as failure */
    }
    if (worst <= 1) return 0;
    if (!isfinite(worst)) return -1;
    if (it == 10) {
      w->unconverged = 1;
      return 0;
    }
    for (tds_id v = 0; v < m->nv; v++)
      for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
        tds_motion_project(s, v, fq->g[i]);
    if (tds_fixq_restore(ctx, fq, m->nv, w->rest) != TDS_OK) return -1;
    for (tds_id v = 0; v < m->nv; v++) {
      if (!tds_vertex_free(s, v)) continue;
      double x[3], p[2] = {m->vp[v][0], m->vp[v][1]};
      v3_copy(x, m->x[v]);
      tds_motion_apply(s, v, x, p, w->rest[v]);
    }
    m->coord_gen++;
  }
}

/* Place every free vertex at x0 + scale*vel, project onto the quantity
** targets, and return the energy there (NAN if not finite). */
static double trial(tds_ctx *ctx, tds_surf *s, work *w, double scale) {
  tds_mesh *m = &s->m;
  int bad = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_vertex_free(s, v)) continue;
    double d[3] = {scale * w->vel[v][0], scale * w->vel[v][1],
                   scale * w->vel[v][2]};
    if (tds_motion_apply(s, v, w->x0[v], w->p0[v], d) != TDS_OK) bad = 1;
  }
  m->coord_gen++;
  if (project_quantities(ctx, s, w) != 0 || bad) return NAN;
  return s->energy;
}

/* Vertex of the parabola through three points (a < b < c, fb <= fa, fc). */
static double parabola(double a, double fa, double b, double fb, double c,
                       double fc) {
  double p = (b - a) * (fb - fc), q = (b - c) * (fb - fa);
  double den = 2 * (p - q);
  if (den == 0) return b;
  double t = b - ((b - a) * p - (b - c) * q) / den;
  if (!(t > a && t < c)) return b;
  return t;
}

/* Bracket the minimum of the energy along the step and interpolate.
** Returns the chosen scale; *E is the energy there, positions are set. */
static double line_search(tds_ctx *ctx, tds_surf *s, work *w, double *E) {
  const double lim = s->scale_limit, tiny = 1e-12 * lim;
  double start = s->scale > tiny ? s->scale : 0.1 * lim;
  if (start > lim) start = lim;
  double E0 = trial(ctx, s, w, 0);
  double a = 0, Ea = E0, b, Eb, c, Ec;
  double s1 = start, E1 = trial(ctx, s, w, s1);
  if (E1 < E0) {
    b = s1;
    Eb = E1;
    for (;;) {
      if (b >= lim) {
        *E = Eb; /* positions are at b already */
        return b;
      }
      c = 2 * b < lim ? 2 * b : lim;
      Ec = trial(ctx, s, w, c);
      if (!(Ec < Eb)) break;
      a = b;
      Ea = Eb;
      b = c;
      Eb = Ec;
    }
  } else {
    c = s1;
    Ec = E1;
    for (;;) {
      b = c / 2;
      Eb = trial(ctx, s, w, b);
      if (Eb < E0) break;
      c = b;
      Ec = Eb;
      if (b < tiny) {
        *E = trial(ctx, s, w, 0);
        return 0;
      }
    }
  }
  double t = parabola(a, Ea, b, Eb, c, Ec);
  double Et = trial(ctx, s, w, t);
  if (Et <= Eb) {
    *E = Et;
    return t;
  }
  *E = trial(ctx, s, w, b);
  return b;
}

static int step(tds_ctx *ctx, tds_surf *s, work *w) {
  tds_mesh *m = &s->m;
  memcpy(w->x0, m->x, (size_t)m->nv * sizeof *w->x0);
  memcpy(w->p0, m->vp, (size_t)m->nv * sizeof *w->p0);
  int rc = direction(ctx, s, w);
  if (rc != TDS_OK) return rc;
  double E, scale;
  if (s->fixed_scale) {
    scale = s->scale;
    E = trial(ctx, s, w, scale);
  } else {
    scale = line_search(ctx, s, w, &E);
    s->scale = scale;
  }
  if (!isfinite(E)) {
    memcpy(m->x, w->x0, (size_t)m->nv * sizeof *w->x0);
    memcpy(m->vp, w->p0, (size_t)m->nv * sizeof *w->p0);
    m->coord_gen++;
    tds_surf_update(ctx, s);
    return tds_seterr(ctx, TDS_ENUM,
                      "iteration produced a non-finite energy; step undone");
  }
  s->energy = E;
  s->iterations++;
  return TDS_OK;
}

int tds_iterate(tds_ctx *ctx, tds_surf *s, int n) {
  work w;
  int rc = work_init(ctx, s, &w);
  if (rc != TDS_OK) return rc;
  for (int i = n; i > 0; i--) {
    rc = step(ctx, s, &w);
    if (rc != TDS_OK) break;
    tds_printf(ctx, "%3d. area: %#17.15g energy: %#17.15g  scale: %g\n", i,
               s->area, s->energy, s->scale);
    if (w.unconverged) {
      tds_warnf(ctx, "warning: volume or quantity constraints did not converge "
                "in 10 projections\n");
      w.unconverged = 0;
    }
    if (ctx->interrupt) {
      ctx->interrupt = 0;
      rc = tds_seterr(ctx, TDS_EINTR, "interrupted: %d of %d iterations done",
                      n - i + 1, n);
      break;
    }
  }
  work_free(&w);
  tds_surf_update(ctx, s);
  return rc;
}

int tds_pressures(tds_ctx *ctx, tds_surf *s) {
  work w;
  int rc = work_init(ctx, s, &w);
  if (rc == TDS_OK) rc = direction(ctx, s, &w);
  work_free(&w);
  return rc;
}
