/* pg_pass.c: the fused evaluation pass of pg (see pg_int.h).
**
** One loop over the facets gathers each facet's corners once and computes
** everything an iteration needs from it: the facet's area vector N, its
** tension energy and area gradient, the Hessian of the area in each corner
** (the star model's A2 for any direction), the restricted Voronoi cells of
** its corners, the cotangents of its angles (the Delaunay test), and the
** body terms (volume and its gradient, gravity, prescribed pressure) exactly
** as eval.c's facet pass computes them. The edge and quantity terms are
** eval.c's own (tds_eval_edges, tds_eval_quantities). A unit test checks
** energy, gradient and quantities against tds_eval.
**
** The star model. Moving corner v of a facet by t d changes N by t w with
** w = d x e, e the edge opposite v; the area |N + t w|/2 has
** A'' = |w_perp|^2 / (2|N|), w_perp the part of w normal to the facet. As
** e lies in the facet, w_perp = |e| (d . n) n x e/|e|, so
**   A'' = |e|^2 (d . n)^2 / (2 |N|) = d^T (|e|^2 / (2|N|^3) N N^T) d:
** the Hessian of a facet's area in one corner is a rank-one matrix, and the
** star's is their sum, accumulated here once for every direction.
*/
#include <math.h>
#include <string.h>

#include "eval_int.h"
#include "geom.h"
#include "pg_int.h"
#include "vec3.h"

/* Restricted Voronoi cells of a triangle's corners: area[k] and moment
** mom[k] = area[k] * (centroid[k] - p[k]), from the edge vectors
** e[k] = p[k+1] - p[k], the area vector N (|N| = nl, |N|^2 = nn), the
** squared edge lengths l2 and the dot products dk at the corners. Exact
** for obtuse triangles (the cell is clipped at the opposite edge). */
static inline void voronoi_cells(const double e[3][3], const double N[3],
                                 double nn, double nl, const double l2[3],
                                 const double dk[3], double area[3],
                                 double mom[3][3]) {
  int o = dk[0] < 0 ? 0 : dk[1] < 0 ? 1 : dk[2] < 0 ? 2 : -1;
  if (o < 0) {
    /* Circumcentre relative to p0: (|a|^2 (b x N) + |b|^2 (N x a)) / 2|N|^2
    ** with a = p1 - p0 = e[0], b = p2 - p0 = -e[2]. */
    double b[3] = {-e[2][0], -e[2][1], -e[2][2]}, t1[3], t2[3], O[3][3];
    v3_cross(t1, b, N);
    v3_cross(t2, N, e[0]);
    double inv = 1 / (2 * nn);
    for (int i = 0; i < 3; i++) O[0][i] = (l2[0] * t1[i] + l2[2] * t2[i]) * inv;
    v3_sub(O[1], O[0], e[0]);
    v3_add(O[2], O[0], e[2]);
    /* Half-cell of corner k on edge k (to k+1), right-angled at the
    ** midpoint: area |e_k|^2 cot(angle at k+2) / 8, cot = d / |N|. */
    double h[3], s8 = 1 / (8 * nl);
    h[0] = l2[0] * dk[2] * s8;
    h[1] = l2[1] * dk[0] * s8;
    h[2] = l2[2] * dk[1] * s8;
    for (int k = 0; k < 3; k++) {
      int km = k == 0 ? 2 : k - 1; /* edge km runs from p[km] to p[k] */
      double ha = h[k], hb = h[km];
      area[k] = ha + hb;
      for (int i = 0; i < 3; i++)
        mom[k][i] = (ha * (0.5 * e[k][i] + O[k][i]) +
                     hb * (O[k][i] - 0.5 * e[km][i])) * (1.0 / 3);
    }
    return;
  }
  /* Obtuse at o; j = o+1, k = o+2. Cell of j: triangle (p_j, M_oj, X1) with
  ** X1 = p_j + s1 (p_k - p_j), s1 = |p_o p_j|^2 / (2 d_j); likewise k. */
  int j = (o + 1) % 3, k = (o + 2) % 3;
  double sj = l2[o] / (2 * dk[j]), sk = l2[k] / (2 * dk[k]);
  double A = 0.5 * nl;
  area[j] = sj * nl / 4;
  area[k] = sk * nl / 4;
  area[o] = A - area[j] - area[k];
  for (int i = 0; i < 3; i++) {
    /* p_o - p_j = -e[o]; p_k - p_j = e[j]; p_o - p_k = e[k] */
    double cj = (-0.5 * e[o][i] + sj * e[j][i]) / 3;
    double ck = (0.5 * e[k][i] - sk * e[j][i]) / 3;
    mom[j][i] = area[j] * cj;
    mom[k][i] = area[k] * ck;
    double poj = e[o][i], pok = -e[k][i];
    mom[o][i] = A * (poj + pok) / 3 - area[j] * (poj + cj) - area[k] * (pok + ck);
  }
}

void tds_pg_voronoi(const double p[3][3], double area[3], double cen[3][3]) {
  double e[3][3], N[3], l2[3], dk[3], mom[3][3];
  v3_sub(e[0], p[1], p[0]);
  v3_sub(e[1], p[2], p[1]);
  v3_sub(e[2], p[0], p[2]);
  v3_cross(N, e[0], e[1]);
  double nn = v3_dot(N, N), nl = sqrt(nn);
  for (int k = 0; k < 3; k++) {
    l2[k] = v3_dot(e[k], e[k]);
    dk[k] = -v3_dot(e[k], e[(k + 2) % 3]);
    area[k] = 0;
    v3_zero(mom[k]);
  }
  if (nl > 0) voronoi_cells((const double(*)[3])e, N, nn, nl, l2, dk, area, mom);
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 3; i++)
      cen[k][i] = p[k][i] + (area[k] > 0 ? mom[k][i] / area[k] : 0);
}

/* Body terms of facet f, as eval.c's facet pass: volumes (and their
** gradients into fq), prescribed pressures and gravity (into grad). */
static double body_terms(tds_surf *s, pgw *w, tds_id f, const double *a,
                         const double *b, const double *c) {
  tds_mesh *m = &s->m;
  tds_fixq *fq = &w->fq;
  const tds_id *fv = m->fv[f];
  double g[3][3], gw[3][3], W = 0, energy = 0;
  double V = s->symmetric_content ? geom_volume_sym(a, b, c, g)
                                  : geom_volume_z(a, b, c, g);
  int wdone = 0;
  const int grav = s->gravity_on && s->gravity != 0;
  for (int j = 0; j < 2; j++) {
    tds_id bd = m->fb[f][j];
    if (bd == TDS_NONE) continue;
    double sign = j ? -1.0 : 1.0;
    m->bvol[bd] += sign * V;
    if (fq->nq && fq->bq[bd] >= 0) {
      int32_t q = fq->bq[bd];
      for (int k = 0; k < 3; k++) {
        double gk[3] = {sign * g[k][0], sign * g[k][1], sign * g[k][2]};
        tds_fixq_add(fq, fv[k], q, gk);
      }
    }
    if (m->bflags[bd] & TDS_PRESSURE) { /* energy -p V */
      double p = m->bpressure[bd];
      energy -= sign * p * V;
      for (int k = 0; k < 3; k++) v3_axpy(w->grad[fv[k]], -sign * p, g[k]);
    }
    if (grav && m->bdensity[bd] != 0) {
      if (!wdone) {
        W = geom_zmoment(a, b, c, gw);
        wdone = 1;
      }
      double wt = sign * s->gravity * m->bdensity[bd];
      energy += wt * W;
      for (int k = 0; k < 3; k++) v3_axpy(w->grad[fv[k]], wt, gw[k]);
    }
  }
  return energy;
}

int pg_pass(tds_ctx *ctx, tds_surf *s, pgw *w, double *energy_out) {
  tds_mesh *m = &s->m;
  tds_fixq *fq = &w->fq;
  double energy = 0, area_total = 0;
  for (int32_t j = 0; j < w->nmov; j++) memset(&w->acc[w->mov[j]], 0, sizeof *w->acc);
  memset(w->grad, 0, (size_t)m->nv * sizeof *w->grad);
  if (fq->nq) tds_fixq_clear(fq);
  for (tds_id b = 0; b < m->nb; b++)
    m->bvol[b] = (m->bflags[b] & TDS_DEAD) ? 0 : m->bvolconst[b];

  for (tds_id f = 0; f < m->nf; f++) {
    const uint32_t ff = m->fflags[f];
    if (ff & TDS_DEAD) continue;
    const tds_id *fv = m->fv[f];
    const double *p0 = m->x[fv[0]], *p1 = m->x[fv[1]], *p2 = m->x[fv[2]];
    double e[3][3], N[3];
    v3_sub(e[0], p1, p0);
    v3_sub(e[1], p2, p1);
    v3_sub(e[2], p0, p2);
    v3_cross(N, e[0], e[1]); /* = (p1 - p0) x (p2 - p0) */
    double nn = v3_dot(N, N), nl = sqrt(nn);
    double ten = m->ften[f];
    double A = 0.5 * nl;
    area_total += A;
    energy += ten * A;
    double l2[3] = {v3_dot(e[0], e[0]), v3_dot(e[1], e[1]), v3_dot(e[2], e[2])};
    double dk[3] = {-v3_dot(e[0], e[2]), -v3_dot(e[1], e[0]), -v3_dot(e[2], e[1])};
    double *cot = w->fcot + 3 * (size_t)f;
    if (nl > 0) {
      double inl = 1 / nl;
      cot[0] = dk[0] * inl;
      cot[1] = dk[1] * inl;
      cot[2] = dk[2] * inl;
    } else {
      cot[0] = cot[1] = cot[2] = 0;
    }
    const int movable = w->kind[fv[0]] | w->kind[fv[1]] | w->kind[fv[2]];
    if (movable && ten != 0 && nl > 0) {
      double area[3], mom[3][3];
      voronoi_cells((const double(*)[3])e, N, nn, nl, l2, dk, area, mom);
      double gs = 0.5 * ten / nl, hs = 0.5 * ten / (nl * nn);
      double NN[6] = {N[0] * N[0], N[1] * N[1], N[2] * N[2],
                      N[0] * N[1], N[0] * N[2], N[1] * N[2]};
      for (int k = 0; k < 3; k++) {
        tds_id v = fv[k];
        if (!w->kind[v]) continue;
        pg_acc *a = &w->acc[v];
        const double *eo = e[k == 2 ? 0 : k + 1]; /* edge opposite corner k */
        double go[3];
        v3_cross(go, N, eo);
        v3_axpy(a->ga, gs, go);
        double h = hs * l2[k == 2 ? 0 : k + 1];
        for (int i = 0; i < 6; i++) a->H[i] += h * NN[i];
        v3_add(a->N, a->N, N);
        v3_add(a->mom, a->mom, mom[k]);
        a->area += area[k];
        a->A0 += ten * A;
      }
    }
    if ((m->fb[f][0] != TDS_NONE || m->fb[f][1] != TDS_NONE) &&
        !(ff & TDS_NONCONTENT))
      energy += body_terms(s, w, f, p0, p1, p2);
  }

  /* Edge tensions (eval.c's edge pass), then constraint and boundary
  ** integrals and named quantities: eval.c's own code. */
  tds_eval_out out = {.energy = energy, .area = area_total, .grad = w->grad,
                      .fq = fq->nq ? fq : NULL};
  if (w->has_edge_tension)
    for (tds_id e = 0; e < m->ne; e++) {
      if ((m->eflags[e] & TDS_DEAD) || m->eten[e] == 0) continue;
      const double *a = m->x[m->ev[e][0]], *b = m->x[m->ev[e][1]];
      double d[3];
      v3_sub(d, b, a);
      double len = v3_norm(d);
      out.energy += m->eten[e] * len;
      if (len > 0) {
        double t = m->eten[e] / len;
        v3_axpy(w->grad[m->ev[e][1]], t, d);
        v3_axpy(w->grad[m->ev[e][0]], -t, d);
      }
    }
  tds_eval_edges(s, &out);
  tds_eval_quantities(s, &out);
  for (int32_t q = 0; q < fq->nq; q++) {
    tds_id b = fq->qbody[q];
    if (b != TDS_NONE) fq->value[q] = m->bvol[b];
  }
  s->energy = out.energy;
  s->area = out.area;
  *energy_out = out.energy;
  if (!isfinite(out.energy))
    return tds_seterr(ctx, TDS_ENUM, "energy is not finite (%g)", out.energy);
  return TDS_OK;
}
