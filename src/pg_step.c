/* pg_step.c: the move of every vertex from one pass (see pg_int.h and
** doc/method.md, "One iteration"), the rigid-motion gauge of surfaces
** without a fixed vertex, and applying moves or state vectors. */
#include <math.h>
#include <string.h>

#include "motion.h"
#include "pg_int.h"
#include "vec3.h"

/* Motion frames. ------------------------------------------------------ */

/* Projector onto the motion space of a constrained vertex (and, on a
** boundary, the map from a 3-D move to a parameter move). */
static void motion_frame(const tds_surf *s, pgw *w, tds_id v) {
  double *P = w->P[v];
  if (w->kind[v] == VK_LEVEL) {
    for (int k = 0; k < 3; k++) {
      double e[3] = {0, 0, 0};
      e[k] = 1;
      tds_motion_project(s, v, e); /* column k of the symmetric projector */
      for (int i = 0; i < 3; i++) P[3 * i + k] = e[i];
    }
    return;
  }
  /* Boundary: rows of J from J^T e_k. */
  int np = s->bdry[s->m.vbdry[v]].nparams;
  double J[3][2] = {{0, 0}, {0, 0}, {0, 0}};
  for (int k = 0; k < 3; k++) {
    double e[3] = {0, 0, 0};
    e[k] = 1;
    tds_motion_project(s, v, e);
    J[k][0] = e[0];
    J[k][1] = np > 1 ? e[1] : 0;
  }
  double A[4] = {0, 0, 0, 0};
  for (int i = 0; i < np; i++)
    for (int j = 0; j < np; j++)
      for (int k = 0; k < 3; k++) A[i * 2 + j] += J[k][i] * J[k][j];
  double inv[4] = {0, 0, 0, 0};
  if (np == 1) {
    if (A[0] > 0) inv[0] = 1 / A[0];
  } else {
    double det = A[0] * A[3] - A[1] * A[2];
    if (det != 0) {
      inv[0] = A[3] / det;
      inv[3] = A[0] / det;
      inv[1] = -A[1] / det;
      inv[2] = -A[2] / det;
    }
  }
  double *Ji = w->Jinv[v]; /* Ji[3*i + k] = ((J^T J)^-1 J^T)[i][k] */
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 3; k++) {
      double t = 0;
      for (int j = 0; j < np; j++) t += inv[i * 2 + j] * J[k][j];
      Ji[3 * i + k] = i < np ? t : 0;
    }
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) {
      double t = 0;
      for (int j = 0; j < np; j++) t += J[i][j] * Ji[3 * j + k];
      P[3 * i + k] = t;
    }
}

static inline void mat3_apply(const double *P, const double in[3], double out[3]) {
  double o0 = P[0] * in[0] + P[1] * in[1] + P[2] * in[2];
  double o1 = P[3] * in[0] + P[4] * in[1] + P[5] * in[2];
  double o2 = P[6] * in[0] + P[7] * in[1] + P[8] * in[2];
  out[0] = o0;
  out[1] = o1;
  out[2] = o2;
}

/* Project vector a into vertex v's motion space, in place. */
static inline void to_motion(const pgw *w, tds_id v, double a[3]) {
  switch (w->kind[v]) {
  case VK_FREE:
  case VK_JUNCTION: return;
  case VK_FIXED: v3_zero(a); return;
  default: mat3_apply(w->P[v], a, a);
  }
}

/* A surface without fixed vertices may drift rigidly (slide or turn on a
** table, float in space): the tangential moves are not a gradient, so a
** steadily drifting mesh would never reach r = 0. Remove from the moves
** their least-squares component along every rigid motion (translation,
** rotation about the centroid) that lies in all vertices' motion spaces.
** Only the tangential part of the moves is changed (drift comes from it),
** using the tangential parts of the rigid motions: at a fixed point the
** tangential field is then the tangential part of a rigid motion, which
** is not applied, while the normal (energy) conditions hold exactly. The
** allowed motions are chosen once (pg_gauge_init). */
static void tangent_part(const pgw *w, tds_id v, double a[3]) {
  if (w->kind[v] == VK_FREE) {
    v3_axpy(a, -v3_dot(a, w->nrm[v]), w->nrm[v]);
  } else if (w->kind[v] == VK_JUNCTION) {
    v3_zero(a);
  } else {
    mat3_apply(w->P[v], a, a);
    v3_axpy(a, -v3_dot(a, w->d[v]), w->d[v]);
  }
}


/* The rigid motion k (0-2: translation e_k; 3-5: rotation about e_k
** through xc) at position x. */
static void rigid_motion(int k, const double xc[3], const double x[3],
                         double md[3]) {
  double e[3] = {0, 0, 0};
  e[k % 3] = 1;
  if (k < 3) {
    v3_copy(md, e);
  } else {
    double rel[3];
    v3_sub(rel, x, xc);
    v3_cross(md, e, rel);
  }
}

static void centroid(const tds_surf *s, const pgw *w, double xc[3]) {
  v3_zero(xc);
  for (int32_t j = 0; j < w->nmov; j++) v3_add(xc, xc, s->m.x[w->mov[j]]);
  if (w->nmov) v3_scale(xc, 1.0 / w->nmov);
}

void pg_gauge_init(const tds_surf *s, pgw *w) {
  w->nrig = 0;
  if (!w->rigid) return;
  double xc[3];
  centroid(s, w, xc);
  int use[6] = {1, 1, 1, 1, 1, 1};
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    if (w->kind[v] != VK_LEVEL) continue;
    motion_frame(s, w, v);
    for (int k = 0; k < 6; k++) {
      double md[3], pm[3], dd[3];
      rigid_motion(k, xc, s->m.x[v], md);
      mat3_apply(w->P[v], md, pm);
      v3_sub(dd, pm, md);
      if (v3_norm(dd) > 1e-9 * (1 + v3_norm(md))) use[k] = 0;
    }
  }
  for (int k = 0; k < 6; k++)
    if (use[k]) w->rig[w->nrig++] = k;
}

/* remove_drift's sums at a free vertex (normal n, r = x - xc), written
** out: the tangential part of translation k is e_k - n_k n, that of
** rotation k is e_k x r - (r x n)_k n, so their products are
**   T_k . T_l = delta_kl - n_k n_l,
**   T_k . R_l = (e_l x r)_k - n_k (r x n)_l,
**   R_k . R_l = delta_kl |r|^2 - r_k r_l - (r x n)_k (r x n)_l,
** and with the move t: T_k . t = t_k - n_k (n . t),
** R_k . t = (r x t)_k - (r x n)_k (n . t). */
static void drift_sums_free(const pgw *w, tds_id v, const double r[3],
                            double G[36], double b[6]) {
  const double *n = w->nrm[v], *t = w->tan[v];
  double rn[3], rt[3];
  v3_cross(rn, r, n);
  v3_cross(rt, r, t);
  double nt = v3_dot(n, t), r2 = v3_dot(r, r);
  /* (e_l x r)_k: e_x x r = (0, -r_z, r_y), e_y x r = (r_z, 0, -r_x),
  ** e_z x r = (-r_y, r_x, 0) */
  double er[3][3] = {{0, -r[2], r[1]}, {r[2], 0, -r[0]}, {-r[1], r[0], 0}};
  for (int k = 0; k < 3; k++) {
    b[k] += t[k] - n[k] * nt;
    b[3 + k] += rt[k] - rn[k] * nt;
    for (int l = k; l < 3; l++) {
      G[6 * k + l] += (k == l) - n[k] * n[l];
      G[6 * (3 + k) + 3 + l] += (k == l ? r2 : 0) - r[k] * r[l] - rn[k] * rn[l];
    }
    for (int l = 0; l < 3; l++) G[6 * k + 3 + l] += er[l][k] - n[k] * rn[l];
  }
}

static void remove_drift(const tds_surf *s, pgw *w) {
  const tds_mesh *m = &s->m;
  int nr = w->nrig;
  if (nr == 0) return;
  double xc[3], cT[3] = {0, 0, 0}, cR[3] = {0, 0, 0};
  if (w->frozen) { /* the last unfrozen call's rigid motion (pg_newton.c) */
    v3_copy(xc, w->gxc);
    v3_copy(cT, w->gT);
    v3_copy(cR, w->gR);
    goto apply;
  }
  centroid(s, w, xc);
  /* The full 6 x 6 Gram (all rigid motions) and right-hand side; the
  ** chosen ones are picked below. */
  double G6[36] = {0}, b6[6] = {0};
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    if (w->bnb[v][0] >= 0) continue; /* on the contact line: see gauge() */
    if (w->kind[v] == VK_FREE) {
      double r[3];
      v3_sub(r, m->x[v], xc);
      drift_sums_free(w, v, r, G6, b6);
      continue;
    }
    double md[6][3];
    for (int i = 0; i < 6; i++) {
      rigid_motion(i, xc, m->x[v], md[i]);
      tangent_part(w, v, md[i]);
    }
    for (int i = 0; i < 6; i++) {
      b6[i] += v3_dot(md[i], w->tan[v]);
      for (int l = i; l < 6; l++) G6[6 * i + l] += v3_dot(md[i], md[l]);
    }
  }
  double G[36], b[6];
  for (int i = 0; i < nr; i++) {
    int ri = w->rig[i];
    b[i] = b6[ri];
    for (int l = 0; l < nr; l++) {
      int rl = w->rig[l];
      G[6 * i + l] = ri <= rl ? G6[6 * ri + rl] : G6[6 * rl + ri];
    }
  }
  int idx[6], n = 0;
  double gmax = 0;
  for (int i = 0; i < nr; i++) if (G[7 * i] > gmax) gmax = G[7 * i];
  for (int i = 0; i < nr; i++)
    if (G[7 * i] > 1e-12 * gmax) idx[n++] = i;
  double A[36], c[6];
  for (int i = 0; i < n; i++) {
    c[i] = b[idx[i]];
    for (int j = 0; j < n; j++) A[n * i + j] = G[6 * idx[i] + idx[j]];
    A[n * i + i] *= 1 + 1e-12;
  }
  if (n > 0 && tds_dense_solve(n, A, c) == 0) {
    /* The move to remove: u = cT + cR x r, in tangential part. */
    for (int i = 0; i < n; i++) {
      int ri = w->rig[idx[i]];
      if (ri < 3) cT[ri] = c[i];
      else cR[ri - 3] = c[i];
    }
  }
  v3_copy(w->gxc, xc);
  v3_copy(w->gT, cT);
  v3_copy(w->gR, cR);
apply:
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    if (w->bnb[v][0] >= 0) continue; /* on the contact line: see gauge() */
    double r[3], u[3];
    v3_sub(r, m->x[v], xc);
    v3_cross(u, cR, r);
    v3_add(u, u, cT);
    tangent_part(w, v, u);
    v3_sub(w->tan[v], w->tan[v], u);
  }
}

/* The gauge of a surface that can slide and turn on its constraints (see
** the comment above remove_drift): the contact-line vertices keep their
** places along the line (they move only across it, by the energy step),
** and the other vertices' tangential moves lose their rigid component.
** Both are needed: the contact line's spacing rule and the interior's
** Lloyd field each carry a net torque, so either alone keeps turning. */
static void gauge(const tds_surf *s, pgw *w) {
  for (int32_t j = 0; j < w->nmov; j++)
    if (w->bnb[w->mov[j]][0] >= 0) v3_zero(w->tan[w->mov[j]]);
  remove_drift(s, w);
}

/* Direction d_i and the star model along it, at vertex v. */
static inline void direction(const tds_surf *s, pgw *w, tds_id v) {
  const pg_acc *a = &w->acc[v];
  double *n = w->nrm[v], *d = w->d[v];
  double len = v3_norm(a->N);
  if (len > 0) {
    double il = 1 / len;
    for (int i = 0; i < 3; i++) n[i] = a->N[i] * il;
  } else {
    v3_zero(n);
  }
  int k = w->kind[v];
  if (k == VK_FREE) {
    v3_copy(d, n);
  } else {
    double gt[3]; /* total energy gradient */
    v3_add(gt, a->ga, w->grad[v]);
    if (k == VK_LEVEL || k == VK_BDRY) motion_frame(s, w, v);
    if (k == VK_JUNCTION) v3_copy(d, gt);
    else mat3_apply(w->P[v], n, d);
    double dl = v3_norm(d);
    if (k != VK_JUNCTION && !(dl > 0.05)) { /* normal nearly off the motion space */
      mat3_apply(w->P[v], gt, d);
      dl = v3_norm(d);
    }
    if (dl > 0) v3_scale(d, 1 / dl);
    else v3_zero(d);
  }
  const double *H = a->H;
  double *M = w->model[v];
  M[0] = a->A0;
  M[1] = v3_dot(a->ga, d);
  M[2] = H[0] * d[0] * d[0] + H[1] * d[1] * d[1] + H[2] * d[2] * d[2] +
         2 * (H[3] * d[0] * d[1] + H[4] * d[0] * d[2] + H[5] * d[1] * d[2]);
}

/* Directions of every movable vertex and, with constraints, the
** multipliers (least squares over the normal components) and the
** coefficients of the restoring motion (a Newton step onto the targets
** along the constraint gradients projected into the motion spaces: fixed
** vertices contribute nothing), as tds_fixq_restore computes them; the
** restoring motion itself is formed per vertex by pg_step. */
static int directions_multipliers(tds_ctx *ctx, const tds_surf *s, pgw *w) {
  tds_fixq *fq = &w->fq;
  int32_t nq = fq->nq;
  double *gr = fq->gram; /* restoring motion's Gram matrix */
  if (nq) {
    memset(w->gram, 0, (size_t)nq * (size_t)nq * sizeof *w->gram);
    memset(gr, 0, (size_t)nq * (size_t)nq * sizeof *gr);
    memset(w->rhs, 0, (size_t)nq * sizeof *w->rhs);
  }
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    direction(s, w, v);
    if (!nq) continue;
    const double *d = w->d[v];
    if (w->frozen) {
      for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++) {
        w->an[e] = v3_dot(fq->g[e], d);
        to_motion(w, v, fq->g[e]);
      }
      continue;
    }
    double gd = v3_dot(w->acc[v].ga, d) + v3_dot(w->grad[v], d);
    int32_t e0 = fq->start[v], e1 = fq->start[v + 1];
    for (int32_t e = e0; e < e1; e++) {
      double an = v3_dot(fq->g[e], d);
      w->an[e] = an;
      w->rhs[fq->eq[e]] += an * gd;
      to_motion(w, v, fq->g[e]);
    }
    for (int32_t e = e0; e < e1; e++)
      for (int32_t e2 = e0; e2 < e1; e2++) {
        int32_t ij = fq->eq[e] * nq + fq->eq[e2];
        w->gram[ij] += w->an[e] * w->an[e2];
        gr[ij] += v3_dot(fq->g[e], fq->g[e2]);
      }
  }
  if (!nq || w->frozen) return TDS_OK;
  for (int32_t q = 0; q < nq; q++)
    if (!(w->gram[q * nq + q] > 0)) w->gram[q * nq + q] = 1; /* no movable vertex */
  if (tds_dense_solve(nq, w->gram, w->rhs) != 0)
    return tds_seterr(ctx, TDS_ENUM, "volume constraints are dependent");
  for (int32_t q = 0; q < nq; q++) w->mult[q] = w->rhs[q];
  double *mu = fq->mult;
  for (int32_t q = 0; q < nq; q++) mu[q] = fq->target[q] - fq->value[q];
  if (tds_dense_solve(nq, gr, mu) != 0)
    return tds_seterr(ctx, TDS_ENUM,
                      "volume constraints are dependent (singular Gram "
                      "matrix): a body without free vertices, or redundant targets");
  return TDS_OK;
}

int pg_step(tds_ctx *ctx, tds_surf *s, pgw *w, double sfac, pg_stepinfo *si) {
  tds_mesh *m = &s->m;
  tds_fixq *fq = &w->fq;
  int32_t nq = fq->nq;
  int rc = directions_multipliers(ctx, s, w);
  if (rc != TDS_OK) return rc;
  si->lambda0 = nq ? -w->mult[0] : 0;
  const double *mu = fq->mult;
  double r = 0;
  int64_t clamps = 0;
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    const double *d = w->d[v], *M = w->model[v];
    /* c = A1 - (grad E - sum mu grad Q) . d; the tension-weighted area's
    ** part of grad E . d is A1 itself, so only the other terms remain. */
    double c = -v3_dot(w->grad[v], d);
    double *rest = w->rest[v];
    v3_zero(rest);
    if (nq)
      for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++) {
        c += w->mult[fq->eq[e]] * w->an[e];
        v3_axpy(rest, mu[fq->eq[e]], fq->g[e]);
      }
    int cl;
    double t = tds_pg_normal_root(M[0], M[1], M[2], c, &cl);
    if (t * t > 0.25 * M[0]) { /* |t| above half the root of the star's area */
      double lim = 0.5 * sqrt(M[0]);
      t = t > 0 ? lim : -lim;
      cl = 1;
    }
    clamps += cl;
    double *vel = w->vel[v];
    for (int i = 0; i < 3; i++) vel[i] = t * d[i] + rest[i];
    int k = w->kind[v];
    const pg_acc *a = &w->acc[v];
    double *tan = w->tan[v];
    if (k != VK_JUNCTION && a->area > 0) {
      double u[3], ia = 1 / a->area;
      for (int i = 0; i < 3; i++) u[i] = a->mom[i] * ia;
      if (k != VK_FREE && w->bnb[v][0] >= 0) {
        /* On the film's border (a contact line): the centroid of the 1-D
        ** Voronoi cell along the border, (x_prev + 2 x + x_next) / 4. */
        const double *xa = m->x[w->bnb[v][0]], *xb = m->x[w->bnb[v][1]];
        for (int i = 0; i < 3; i++) u[i] = 0.25 * (xa[i] + xb[i]) - 0.5 * m->x[v][i];
      }
      if (k == VK_FREE) {
        v3_axpy(u, -v3_dot(u, w->nrm[v]), w->nrm[v]);
      } else {
        mat3_apply(w->P[v], u, u);
        v3_axpy(u, -v3_dot(u, d), d);
      }
      for (int i = 0; i < 3; i++) tan[i] = sfac * u[i];
    } else {
      v3_zero(tan);
    }
    if (!w->nrig) {
      v3_add(vel, vel, tan);
      double vl = v3_dot(vel, vel);
      if (vl > r) r = vl;
    }
  }
  if (w->nrig) {
    gauge(s, w);
    for (int32_t j = 0; j < w->nmov; j++) {
      tds_id v = w->mov[j];
      double *vel = w->vel[v];
      v3_add(vel, vel, w->tan[v]);
      double vl = v3_dot(vel, vel);
      if (vl > r) r = vl;
    }
  }
  si->r = sqrt(r);
  si->clamps = clamps;
  if (!isfinite(si->r))
    return tds_seterr(ctx, TDS_ENUM, "projected gradient: a move is not finite");
  return TDS_OK;
}

void pg_store_pressures(tds_surf *s, const pgw *w) {
  const tds_fixq *fq = &w->fq;
  for (int32_t q = 0; q < fq->nq; q++) {
    if (fq->qbody[q] != TDS_NONE) s->m.bpressure[fq->qbody[q]] = w->mult[q];
    else s->quant[fq->qquant[q]].pressure = w->mult[q];
  }
}

/* States and moves. --------------------------------------------------- */

void pg_get_state(const tds_surf *s, const pgw *w, double *X) {
  const tds_mesh *m = &s->m;
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    double *o = X + 3 * (size_t)j;
    if (w->kind[v] == VK_BDRY) {
      o[0] = m->vp[v][0];
      o[1] = m->vp[v][1];
      o[2] = 0;
    } else {
      v3_copy(o, m->x[v]);
    }
  }
}

int pg_set_state(tds_surf *s, const pgw *w, const double *X) {
  tds_mesh *m = &s->m;
  int bad = 0;
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    const double *o = X + 3 * (size_t)j;
    if (w->kind[v] == VK_BDRY) {
      m->vp[v][0] = o[0];
      m->vp[v][1] = o[1];
      if (tds_motion_enforce(s, v) != TDS_OK) bad = 1;
    } else {
      v3_copy(m->x[v], o);
      if (w->kind[v] == VK_LEVEL && tds_motion_enforce(s, v) != TDS_OK) bad = 1;
    }
  }
  m->coord_gen++;
  return bad;
}

int pg_apply(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  int bad = 0;
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    const double *vel = w->vel[v];
    switch (w->kind[v]) {
    case VK_FREE:
    case VK_JUNCTION: v3_add(m->x[v], m->x[v], vel); break;
    case VK_LEVEL: {
      double x0[3];
      v3_copy(x0, m->x[v]);
      if (tds_motion_apply(s, v, x0, NULL, vel) != TDS_OK) bad = 1;
      break;
    }
    case VK_BDRY: {
      const double *Ji = w->Jinv[v];
      double dp[3] = {v3_dot(Ji, vel), v3_dot(Ji + 3, vel), 0};
      double p0[2] = {m->vp[v][0], m->vp[v][1]};
      if (tds_motion_apply(s, v, m->x[v], p0, dp) != TDS_OK) bad = 1;
      break;
    }
    default: break;
    }
  }
  m->coord_gen++;
  return bad;
}
