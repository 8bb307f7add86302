/* pg_polish.c: the tangential polish after pg (see pg.h and doc/method.md,
** "Curvature polish").
**
** At pg's fixed point the normal condition makes Meyer's K . n equal the
** local curvature times r_i = |grad V_i| / A_mixed,i, a property of the
** star's shape alone (1 for a regular valence-6 star, 1/1.146 for a
** regular valence-5 one). The polish moves the free vertices along their
** tangent planes by steepest descent of Phi = sum_i (r_i - 1)^2 over the
** measured vertices, with the gradient by central differences on the
** stars; a step never takes a facet's smallest angle below a floor
** (the vertices of such a facet keep their places for that step). The
** normal equilibrium is then restored by plain pg with no tangential
** step (lua/pg.lua, pg_polish). */
#include "pg.h"

#include <math.h>
#include <string.h>

#include "gather.h"
#include "geom.h"
#include "metrics.h"
#include "motion.h"
#include "snap.h"
#include "topo.h"
#include "torus.h"
#include "vec3.h"

/* A vertex is measured when it can move and every incident edge lies
** between exactly two facets (as metrics.c's curvature). */
/* r_v = |sum of the star's area vectors| / (3 A_mixed) (= |grad V_v| /
** A_mixed on a closed star); the star's unit normal into n (may be NULL).
** NAN for a degenerate star. */
static double star_ratio(const tds_surf *s, tds_id v, double n[3]) {
  double S[3], amix;
  if (!tds_vertex_star_sums(s, v, NULL, S, &amix, NULL)) return NAN;
  double sl = v3_norm(S);
  if (n) for (int c = 0; c < 3; c++) n[c] = sl > 0 ? S[c] / sl : 0;
  return sl / (6 * amix);
}

static double facet_min_angle(const tds_mesh *m, tds_id f) {
  tds_corners F;
  tds_gather_facet(m, f, &F);
  double A = geom_angle(F.x[0], F.x[1], F.x[2]), B = geom_angle(F.x[1], F.x[2], F.x[0]);
  double C = TDS_PI - A - B, mn = A < B ? A : B;
  return C < mn ? C : mn;
}

typedef struct {
  const tds_surf *s;
  const uint8_t *meas;
  uint32_t *stamp; /* per vertex: last visit */
  uint32_t tick;
} polish_ctx;

/* (r_j - 1)^2 summed over the measured vertices of v's closed star
** (v and its neighbours). */
static double phi_local(polish_ctx *p, tds_id v) {
  const tds_mesh *m = &p->s->m;
  double sum = 0;
  p->tick++;
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    for (int k = 0; k < 3; k++) {
      tds_id u = m->fv[f][k];
      if (p->stamp[u] == p->tick) continue;
      p->stamp[u] = p->tick;
      if (!p->meas[u]) continue;
      double r = star_ratio(p->s, u, NULL) - 1;
      sum += r * r;
    }
  }
  return sum;
}

static double phi_all(const tds_surf *s, const uint8_t *meas) {
  double sum = 0;
  for (tds_id v = 0; v < s->m.nv; v++)
    if (meas[v]) {
      double r = star_ratio(s, v, NULL) - 1;
      sum += r * r;
    }
  return sum;
}

/* Mean of the measured facets' smallest angles (radians), as quality(). */
static double mean_min_angle(const tds_mesh *m) {
  double sum = 0;
  int32_t n = 0;
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_facet_measured(m, f)) {
      sum += facet_min_angle(m, f);
      n++;
    }
  return n ? sum / n : 0;
}

int tds_pg_polish(tds_ctx *ctx, tds_surf *s, int steps, double floor_deg,
                  double mean_floor_deg, double *phi0, double *phi1, int32_t *nmoved) {
  if (s->m.torus) return tds_torus_unsupported(ctx, "pg_polish");
  if (s->str)
    return tds_seterr(ctx, TDS_ERANGE, "pg_polish works on soap films; the string "
                                       "model is not supported");
  tds_mesh *m = &s->m;
  tds_snap sn; /* all or nothing: a failure leaves the surface as it was */
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  if (tds_mesh_adjacency(m) != TDS_OK)
    return tds_snap_end(ctx, s, &sn, tds_seterr(ctx, TDS_ENOMEM, "out of memory"));
  tds_alloc al = ctx->alloc;
  size_t nv = (size_t)(m->nv > 0 ? m->nv : 1);
  uint8_t *meas = tds_calloc(&al, nv, 1), *mov = tds_calloc(&al, nv, 1);
  uint8_t *frozen = tds_calloc(&al, nv, 1);
  uint32_t *stamp = tds_calloc(&al, nv, sizeof *stamp);
  double (*g)[3] = tds_calloc(&al, nv, sizeof *g);
  double (*x0)[3] = tds_calloc(&al, nv, sizeof *x0);
  if (!meas || !mov || !frozen || !stamp || !g || !x0) {
    rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    goto done;
  }
  double hbar = 0;
  int32_t ne = 0;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) {
      double d[3];
      v3_sub(d, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
      hbar += v3_norm(d);
      ne++;
    }
  hbar = ne ? hbar / ne : 1;
  int32_t nm = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    meas[v] = (uint8_t)tds_vertex_measured(s, v);
    /* moved: free of constraints and boundaries, with a closed star */
    mov[v] = meas[v] && tds_vertex_free(s, v) && !m->vcon[v] && m->vbdry[v] == TDS_NONE;
    nm += mov[v];
  }
  *nmoved = nm;
  polish_ctx p = {s, meas, stamp, 0};
  double floor = floor_deg * TDS_PI / 180, mfloor = mean_floor_deg * TDS_PI / 180;
  double phi = phi_all(s, meas);
  *phi0 = phi;
  double tau = 0.02; /* largest move of a step, in mean edges */
  double eps = 1e-6 * hbar;
  for (int it = 0; it < steps && nm > 0; it++) {
    double gmax = 0;
    for (tds_id v = 0; v < m->nv; v++) {
      if (!mov[v]) continue;
      double n[3];
      star_ratio(s, v, n);
      for (int c = 0; c < 3; c++) {
        double o = m->x[v][c];
        m->x[v][c] = o + eps;
        double fp = phi_local(&p, v);
        m->x[v][c] = o - eps;
        double fm = phi_local(&p, v);
        m->x[v][c] = o;
        g[v][c] = (fp - fm) / (2 * eps);
      }
      double gn = v3_dot(g[v], n);
      for (int c = 0; c < 3; c++) g[v][c] -= gn * n[c];
      double gl = v3_norm(g[v]);
      if (!(gl < (double)INFINITY)) gl = 0, g[v][0] = g[v][1] = g[v][2] = 0;
      if (gl > gmax) gmax = gl;
    }
    if (!(gmax > 0)) break;
    memcpy(x0, m->x, (size_t)m->nv * sizeof *x0);
    int accepted = 0;
    for (int tries = 0; tries < 8 && !accepted; tries++) {
      double a = tau * hbar / gmax;
      memset(frozen, 0, nv);
      for (int bad = 1; bad;) {
        bad = 0;
        for (tds_id v = 0; v < m->nv; v++)
          for (int c = 0; c < 3; c++)
            m->x[v][c] = mov[v] && !frozen[v] ? x0[v][c] - a * g[v][c] : x0[v][c];
        for (tds_id f = 0; f < m->nf; f++) {
          if (m->fflags[f] & TDS_DEAD) continue;
          int moved = 0;
          for (int k = 0; k < 3; k++) moved |= mov[m->fv[f][k]] && !frozen[m->fv[f][k]];
          if (moved && facet_min_angle(m, f) < floor)
            for (int k = 0; k < 3; k++)
              if (mov[m->fv[f][k]] && !frozen[m->fv[f][k]]) {
                frozen[m->fv[f][k]] = 1;
                bad = 1;
              }
        }
      }
      double np = phi_all(s, meas);
      if (np < phi && mean_min_angle(m) >= mfloor) {
        phi = np;
        accepted = 1;
        tau *= 1.25;
        if (tau > 0.1) tau = 0.1;
      } else {
        tau *= 0.5;
      }
    }
    if (!accepted) {
      memcpy(m->x, x0, (size_t)m->nv * sizeof *x0);
      break;
    }
  }
  *phi1 = phi;
  m->coord_gen++;
  rc = tds_surf_update(ctx, s);
done:
  tds_free(&al, meas);
  tds_free(&al, mov);
  tds_free(&al, frozen);
  tds_free(&al, stamp);
  tds_free(&al, g);
  tds_free(&al, x0);
  return tds_snap_end(ctx, s, &sn, rc);
}
