/* pg_pass.c: the fused evaluation pass of pg (see pg_int.h).
**
** One loop over the facets gathers each facet's corners once and computes
** everything an iteration needs from it: the facet's area vector N, its
** tension energy and area gradient, the Hessian of the area in each corner
** (the star model's A2 for any direction), the restricted Voronoi cells of
** its corners, the cotangents of its angles (the Delaunay test), and the
** body terms (volume and its gradient, gravity, prescribed pressure): a
** fused specialisation of the method table's facet rows (facet_area,
** facet_volume(_symmetric), full_gravity_method) with their weights as
** eval.c gives them. The edge and quantity terms are the table's own
** assembly (tds_eval_terms). A unit test (test_pg: test_fused_pass)
** checks energy, gradient and quantities against tds_eval, i.e. the rows.
**
** The star model. Moving corner v of a facet by t d changes N by t w with
** w = d x e, e the edge opposite v; the area |N + t w|/2 has
** A'' = |w_perp|^2 / (2|N|), w_perp the part of w normal to the facet. As
** e lies in the facet, w_perp = |e| (d . n) n x e/|e|, so
**   A'' = |e|^2 (d . n)^2 / (2 |N|) = d^T (|e|^2 / (2|N|^3) N N^T) d:
** the Hessian of a facet's area in one corner is a rank-one matrix, and the
** star's is their sum, accumulated here once for every direction.
**
** Halves and threads. The pass visits the facets in the order of their
** centroids along the longest side of the bounding box, split in two
** halves of equal work (the "plan": the order is chosen once per run, the
** rest is rebuilt when the topology changes). A vertex with facets in
** both halves (about one row of vertices along the split) gets the second
** half's sums in a slot of its own (nv + i), added to the first half's
** after the loop; every other vertex gets its sums in place. The halves
** may run on two threads (OpenMP: built with -fopenmp and w->threads > 1);
** every sum is the same either way, to the last bit.
**
** Four facets at once. Within a half the facets go in blocks of four
** through vector arithmetic (GCC/Clang vector extensions, compiled twice:
** for AVX2, chosen at run time when the processor has it, and generic,
** which is pairs of SSE2 operations on x86-64). Both do the same IEEE
** operations in the same order (C11 mode: no contraction into fused
** multiply-adds), so they give the same bits; a unit test checks it.
** Obtuse facets take voronoi_obtuse lane by lane, blocks with a
** degenerate facet the scalar path (facet_scalar); the sums into the
** vertices are scalar, lane after lane.
*/
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "eval.h"
#include "gather.h"
#include "geom.h"
#include "method.h"
#include "pg_int.h"
#include "vec3.h"

/* Restricted Voronoi cells of an obtuse triangle (obtuse at o): area[k] and
** moment mom[k] = area[k] * (centroid[k] - p[k]). Cell of j = o+1: the
** triangle (p_j, M_oj, X1) with X1 = p_j + s1 (p_k - p_j),
** s1 = |p_o p_j|^2 / (2 d_j); likewise k = o+2; o gets the rest. */
static void voronoi_obtuse(int o, const double e[3][3], double nl,
                           const double l2[3], const double dk[3],
                           double area[3], double mom[3][3]) {
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

/* Restricted Voronoi cells of a triangle's corners: area[k] and moment
** mom[k] = area[k] * (centroid[k] - p[k]), from the edge vectors
** e[k] = p[k+1] - p[k], |N| = nl (> 0) and 1/nl = inl, the squared edge
** lengths l2 and the dot products dk at the corners. Exact for obtuse
** triangles (the cell is clipped at the opposite edge).
**
** Non-obtuse: the cell of corner k is the quadrilateral (p_k, M_k, O,
** M_{k-1}) (M_k the midpoint of edge k, O the circumcentre), two right
** triangles of areas hh_k and hh_{k-1}, hh_k = |e_k|^2 cot(angle at k+2)/8
** = l2_k d_{k+2} / (8 nl). The circumcentre's barycentric coordinates are
** w_k = l2_{k+1} d_k / (2 |N|^2) = 4 hh_{k+1} / nl, so O - p_k =
** w_{k+1} e_k - w_{k+2} e_{k+2}, and the moment is
**   ((hh_k + hh_{k-1}) (O - p_k) + (hh_k e_k - hh_{k-1} e_{k-1}) / 2) / 3
** = a_k e_k - b_k e_{k+2}: two scalars per corner, no cross product. */
static inline __attribute__((always_inline)) void
voronoi_cells(const double e[3][3], double nl, double inl, const double l2[3],
              const double dk[3], double area[3], double mom[3][3]) {
  if (dk[0] < 0 || dk[1] < 0 || dk[2] < 0) {
    voronoi_obtuse(dk[0] < 0 ? 0 : dk[1] < 0 ? 1 : 2, e, nl, l2, dk, area, mom);
    return;
  }
  double s8 = 0.125 * inl;
  double h0 = l2[0] * dk[2] * s8, h1 = l2[1] * dk[0] * s8, h2 = l2[2] * dk[1] * s8;
  double q = 4 * inl;
  double w0 = q * h1, w1 = q * h2, w2 = q * h0;
  double a0 = h0 + h2, a1 = h1 + h0, a2 = h2 + h1;
  const double t = 1.0 / 3;
  /* corner k: a_k = (area_k w_{k+1} + hh_k / 2) / 3,
  **           b_k = (area_k w_{k+2} + hh_{k+2} / 2) / 3 */
  double x0 = (a0 * w1 + 0.5 * h0) * t, y0 = (a0 * w2 + 0.5 * h2) * t;
  double x1 = (a1 * w2 + 0.5 * h1) * t, y1 = (a1 * w0 + 0.5 * h0) * t;
  double x2 = (a2 * w0 + 0.5 * h2) * t, y2 = (a2 * w1 + 0.5 * h1) * t;
  area[0] = a0;
  area[1] = a1;
  area[2] = a2;
  for (int i = 0; i < 3; i++) {
    mom[0][i] = x0 * e[0][i] - y0 * e[2][i];
    mom[1][i] = x1 * e[1][i] - y1 * e[0][i];
    mom[2][i] = x2 * e[2][i] - y2 * e[1][i];
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
  if (nl > 0) voronoi_cells((const double(*)[3])e, nl, 1 / nl, l2, dk, area, mom);
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 3; i++)
      cen[k][i] = p[k][i] + (area[k] > 0 ? mom[k][i] / area[k] : 0);
}

/* The plan. ----------------------------------------------------------- */

enum { FM_WORK = 1, FM_BODY = 2, FM_LIVE = 4, FM_BODY1 = 8 };
/* FM_BODY1: one body, on side 0 or 1 (FM_SIDE1), no prescribed pressure,
** z-volume: the body terms of the vector path. */
enum { FM_SIDE1 = 16 };

void pg_plan_free(pgw *w) {
  tds_free(&w->al, w->forder);
  tds_free(&w->al, w->fpos);
  tds_free(&w->al, w->vent);
  tds_free(&w->al, w->fmode);
  tds_free(&w->al, w->fslot);
  tds_free(&w->al, w->fent);
  tds_free(&w->al, w->shared);
  tds_free(&w->al, w->sbase);
  tds_free(&w->al, w->fgbuf);
  tds_free(&w->al, w->side);
  for (int h = 0; h < 2; h++) tds_free_aligned(&w->al, w->half[h].bvol);
  w->forder = w->shared = w->sbase = w->fpos = w->vent = NULL;
  w->fmode = w->side = NULL;
  w->fslot = NULL;
  w->fent = NULL;
  w->fgbuf = NULL;
  memset(w->half, 0, sizeof w->half);
}

typedef struct {
  double key;
  int32_t f;
} fkey;

static int fkey_cmp(const void *a, const void *b) {
  const fkey *x = a, *y = b;
  if (x->key != y->key) return x->key < y->key ? -1 : 1;
  return (x->f > y->f) - (x->f < y->f);
}

int pg_plan_init(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  size_t nf = (size_t)(m->nf > 0 ? m->nf : 1), nv = (size_t)(m->nv > 0 ? m->nv : 1);
  size_t nb = (size_t)(m->nb > 0 ? m->nb : 1), nent = (size_t)w->fq.nent + 1;
  w->forder = tds_calloc(&w->al, nf, sizeof *w->forder);
  w->fpos = tds_calloc(&w->al, nf, sizeof *w->fpos);
  w->vent = tds_calloc(&w->al, nv, sizeof *w->vent);
  w->fmode = tds_calloc(&w->al, nf, 1);
  w->fslot = tds_calloc(&w->al, nf, sizeof *w->fslot);
  w->fent = tds_calloc(&w->al, nf, sizeof *w->fent);
  w->shared = tds_calloc(&w->al, nv, sizeof *w->shared);
  w->sbase = tds_calloc(&w->al, nv, sizeof *w->sbase);
  w->fgbuf = tds_calloc(&w->al, nent, sizeof *w->fgbuf);
  w->side = tds_calloc(&w->al, nv, 1);
  fkey *k = tds_calloc(&w->al, nf, sizeof *k);
  /* the halves' volume sums on cache lines of their own */
  size_t nbb = (nb * sizeof(double) + 63) / 64 * 64;
  for (int h = 0; h < 2; h++) {
    w->half[h].bvol = tds_calloc_aligned(&w->al, nbb);
  }
  if (!w->fpos || !w->vent || !w->forder || !w->fmode || !w->fslot || !w->fent || !w->shared ||
      !w->sbase || !w->fgbuf || !w->side || !k || !w->half[0].bvol ||
      !w->half[1].bvol) {
    tds_free(&w->al, k);
    return TDS_ENOMEM;
  }
  /* The order: live facets by their centroid's coordinate along the
  ** longest side of the bounding box (kept for the whole run: flips
  ** change facets only locally). */
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (tds_id v = 0; v < m->nv; v++) {
    if (m->vflags[v] & TDS_DEAD) continue;
    for (int i = 0; i < 3; i++) {
      if (m->x[v][i] < lo[i]) lo[i] = m->x[v][i];
      if (m->x[v][i] > hi[i]) hi[i] = m->x[v][i];
    }
  }
  int ax = 0;
  for (int i = 1; i < 3; i++)
    if (hi[i] - lo[i] > hi[ax] - lo[ax]) ax = i;
  int32_t n = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    tds_corners C;
    tds_gather_facet(m, f, &C);
    k[n].key = C.x[0][ax] + C.x[1][ax] + C.x[2][ax];
    k[n++].f = f;
  }
  qsort(k, (size_t)n, sizeof *k, fkey_cmp);
  for (tds_id f = 0; f < m->nf; f++) w->fpos[f] = 0;
  for (int32_t i = 0; i < n; i++) {
    w->forder[i] = k[i].f;
    w->fpos[k[i].f] = i;
  }
  w->norder = n;
  tds_free(&w->al, k);
  w->plan_gen = m->topo_gen - 1; /* slots are built at the first pass */
  return TDS_OK;
}

/* fixq entry of quantity q at vertex v, or -1. */
static int32_t entry_of(const tds_fixq *fq, tds_id v, int32_t q) {
  for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
    if (fq->eq[i] == q) return i;
  return -1;
}

static int facet_weight(uint8_t md) {
  return 1 + ((md & FM_WORK) ? 4 : 0) + ((md & FM_BODY) ? 2 : 0);
}

/* Facet modes, the split into halves, slots and fixq entries for the
** current topology. */
static void plan_build(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  const tds_fixq *fq = &w->fq;
  int64_t total = 0;
  for (int32_t i = 0; i < w->norder; i++) {
    tds_id f = w->forder[i];
    const tds_id *fv = m->fv[f];
    uint8_t md = FM_LIVE;
    if ((w->kind[fv[0]] | w->kind[fv[1]] | w->kind[fv[2]]) && m->ften[f] != 0)
      md |= FM_WORK;
    if ((m->fb[f][0] != TDS_NONE || m->fb[f][1] != TDS_NONE) &&
        !(m->fflags[f] & TDS_NONCONTENT)) {
      md |= FM_BODY;
      int j = m->fb[f][0] != TDS_NONE ? 0 : 1;
      tds_id b = m->fb[f][j];
      if (m->fb[f][1 - j] == TDS_NONE && !(m->bflags[b] & TDS_PRESSURE) &&
          !s->symmetric_content)
        md |= FM_BODY1 | (j ? FM_SIDE1 : 0);
    }
    w->fmode[f] = md;
  }
  /* One-body facets add their volume gradients into acc.vg of their
  ** corners, which go to the fixq entry vent[v] after the pass: a vertex
  ** whose one-body facets would need two entries sends them the scalar
  ** way (body_terms) instead. */
  for (tds_id v = 0; v < m->nv; v++) w->vent[v] = -2; /* -2: none yet */
  for (int pass = 0; pass < 2; pass++)
    for (int32_t i = 0; i < w->norder; i++) {
      tds_id f = w->forder[i];
      if (!(w->fmode[f] & FM_BODY1)) continue;
      tds_id b = m->fb[f][(w->fmode[f] & FM_SIDE1) ? 1 : 0];
      int conflict = 0;
      for (int k = 0; k < 3; k++) {
        tds_id v = m->fv[f][k];
        int32_t e = fq->nq && fq->bq[b] >= 0 ? entry_of(fq, v, fq->bq[b]) : -1;
        if (pass == 0) {
          if (w->vent[v] == -2) w->vent[v] = e;
          else if (w->vent[v] != e) w->vent[v] = -3; /* two entries */
        } else if (w->vent[v] == -3) {
          conflict = 1;
        }
      }
      if (conflict) w->fmode[f] &= (uint8_t)~(FM_BODY1 | FM_SIDE1);
    }
  for (tds_id v = 0; v < m->nv; v++)
    if (w->vent[v] < 0) w->vent[v] = -1;
  for (int32_t i = 0; i < w->norder; i++) total += facet_weight(w->fmode[w->forder[i]]);
  /* Two halves of about equal work. */
  int64_t run = 0;
  int32_t split = w->norder;
  for (int32_t i = 0; i < w->norder; i++) {
    run += facet_weight(w->fmode[w->forder[i]]);
    if (2 * run >= total) {
      split = i + 1;
      break;
    }
  }
  w->half[0].i0 = 0;
  w->half[0].i1 = split;
  w->half[1].i0 = split;
  w->half[1].i1 = w->norder;
  /* Vertices with facets (that add into them) in both halves. */
  memset(w->side, 0, (size_t)m->nv);
  for (int32_t i = 0; i < w->norder; i++) {
    tds_id f = w->forder[i];
    if (!(w->fmode[f] & (FM_WORK | FM_BODY))) continue;
    uint8_t bit = i < split ? 1 : 2;
    for (int k = 0; k < 3; k++) w->side[m->fv[f][k]] |= bit;
  }
  int32_t ns = 0, nfg = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (w->side[v] != 3) continue;
    w->sbase[ns] = nfg;
    if (fq->nq) nfg += fq->start[v + 1] - fq->start[v];
    w->shared[ns++] = v;
  }
  w->nshared = ns;
  /* Slots: the vertex itself, except second-half corners at shared
  ** vertices (nv + their index in the shared list). */
  for (int32_t j = 0; j < ns; j++) w->side[w->shared[j]] = 4; /* mark */
  for (int32_t i = 0; i < w->norder; i++) {
    tds_id f = w->forder[i];
    const tds_id *fv = m->fv[f];
    for (int k = 0; k < 6; k++) w->fent[f][k] = -1;
    for (int k = 0; k < 3; k++) w->fslot[f][k] = fv[k];
    if (i >= split)
      for (int k = 0; k < 3; k++)
        if (w->side[fv[k]] == 4) {
          /* binary search: shared is sorted by vertex id */
          int32_t a = 0, b = ns - 1;
          while (a < b) {
            int32_t c = (a + b) / 2;
            if (w->shared[c] < fv[k]) a = c + 1;
            else b = c;
          }
          w->fslot[f][k] = m->nv + a;
        }
    if (!(w->fmode[f] & FM_BODY) || !fq->nq) continue;
    for (int j = 0; j < 2; j++) {
      tds_id b = m->fb[f][j];
      if (b == TDS_NONE || fq->bq[b] < 0) continue;
      for (int k = 0; k < 3; k++) {
        tds_id v = fv[k];
        int32_t e = entry_of(fq, v, fq->bq[b]);
        if (e < 0) continue;
        int32_t sl = w->fslot[f][k];
        w->fent[f][3 * j + k] = sl < m->nv ? 2 * e
                              : 2 * (w->sbase[sl - m->nv] + e - fq->start[v]) + 1;
      }
    }
  }
  w->plan_gen = m->topo_gen;
}

/* The facets. --------------------------------------------------------- */

/* Body terms of facet f with eval.c's weights: the volume rows (their
** gradients into the fixq sums), prescribed pressures and gravity (into
** grad). */
static double body_terms(const tds_surf *s, pgw *w, pg_half *hf, tds_id f,
                         const double *a, const double *b, const double *c) {
  const tds_mesh *m = &s->m;
  const int32_t *sl = w->fslot[f];
  double(*fg[2])[3] = {w->fq.g, w->fgbuf};
  double g[3][3], gw[3][3], W = 0, energy = 0;
  tds_mlocal L = {.x = {a, b, c}};
  const tds_method *vol =
      &tds_methods[s->symmetric_content ? TDS_M_FACET_VOLUME_SYM : TDS_M_FACET_VOLUME];
  double V = vol->eval(&L, g, NULL);
  int wdone = 0;
  const int grav = s->gravity_on && s->gravity != 0;
  for (int j = 0; j < 2; j++) {
    tds_id bd = m->fb[f][j];
    if (bd == TDS_NONE) continue;
    double sign = j ? -1.0 : 1.0;
    hf->bvol[bd] += sign * V;
    const int32_t *ent = w->fent[f] + 3 * j;
    for (int k = 0; k < 3; k++)
      if (ent[k] >= 0) v3_axpy(fg[ent[k] & 1][ent[k] >> 1], sign, g[k]);
    if (m->bflags[bd] & TDS_PRESSURE) { /* energy -p V */
      double p = m->bpressure[bd];
      energy -= sign * p * V;
      for (int k = 0; k < 3; k++) v3_axpy(w->grad[sl[k]], -sign * p, g[k]);
    }
    if (grav && m->bdensity[bd] != 0) {
      if (!wdone) {
        W = tds_methods[TDS_M_FULL_GRAVITY].eval(&L, gw, NULL);
        wdone = 1;
      }
      double wt = sign * s->gravity * m->bdensity[bd];
      energy += wt * W;
      for (int k = 0; k < 3; k++) v3_axpy(w->grad[sl[k]], wt, gw[k]);
    }
  }
  return energy;
}

static inline void acc_add(pg_acc *a, const double N[3], const double g[3],
                           double h, const double NN[6], const double mom[3],
                           double area, double A0) {
  a->N[0] += N[0];
  a->N[1] += N[1];
  a->N[2] += N[2];
  a->ga[0] += g[0];
  a->ga[1] += g[1];
  a->ga[2] += g[2];
  for (int i = 0; i < 6; i++) a->H[i] += h * NN[i];
  a->mom[0] += mom[0];
  a->mom[1] += mom[1];
  a->mom[2] += mom[2];
  a->area += area;
  a->A0 += A0;
}

/* One facet (the scalar path: blocks with a degenerate facet). */
static void facet_scalar(const tds_surf *s, pgw *w, pg_half *hf, tds_id f,
                         double *energy, double *area_total) {
  const tds_mesh *m = &s->m;
  const uint8_t md = w->fmode[f];
  tds_corners C;
  tds_gather_facet(m, f, &C);
  const double *p0 = C.x[0], *p1 = C.x[1], *p2 = C.x[2];
  double e[3][3], N[3];
  v3_sub(e[0], p1, p0);
  v3_sub(e[1], p2, p1);
  v3_sub(e[2], p0, p2);
  v3_cross(N, e[0], e[1]); /* = (p1 - p0) x (p2 - p0) */
  double nn = v3_dot(N, N), nl = sqrt(nn);
  double ten = m->ften[f];
  double A = 0.5 * nl;
  *area_total += A;
  *energy += ten * A;
  double dk[3] = {-v3_dot(e[0], e[2]), -v3_dot(e[1], e[0]), -v3_dot(e[2], e[1])};
  double *cot = w->fcot + 3 * (size_t)w->fpos[f];
  if (nl > 0) {
    double inl = 1 / nl;
    cot[0] = dk[0] * inl;
    cot[1] = dk[1] * inl;
    cot[2] = dk[2] * inl;
    if (md & FM_WORK) {
      double l2[3] = {v3_dot(e[0], e[0]), v3_dot(e[1], e[1]), v3_dot(e[2], e[2])};
      double area[3], mom[3][3];
      voronoi_cells((const double(*)[3])e, nl, inl, l2, dk, area, mom);
      double gs = 0.5 * ten * inl, hs = gs * inl * inl, A0 = ten * A;
      double NN[6] = {N[0] * N[0], N[1] * N[1], N[2] * N[2],
                      N[0] * N[1], N[0] * N[2], N[1] * N[2]};
      /* area gradient at corner k: gs N x (edge opposite k); they sum
      ** to zero */
      double g0[3], g1[3], g2[3];
      v3_cross(g0, N, e[1]);
      v3_cross(g1, N, e[2]);
      for (int k = 0; k < 3; k++) {
        g0[k] *= gs;
        g1[k] *= gs;
        g2[k] = -(g0[k] + g1[k]);
      }
      const int32_t *sl = w->fslot[f];
      acc_add(&w->acc[sl[0]], N, g0, hs * l2[1], NN, mom[0], area[0], A0);
      acc_add(&w->acc[sl[1]], N, g1, hs * l2[2], NN, mom[1], area[1], A0);
      acc_add(&w->acc[sl[2]], N, g2, hs * l2[0], NN, mom[2], area[2], A0);
    }
  } else {
    cot[0] = cot[1] = cot[2] = 0;
  }
  if (md & FM_BODY) *energy += body_terms(s, w, hf, f, p0, p1, p2);
}

/* Four facets at once (GCC/Clang vector extensions: AVX2 when the machine
** has it, pairs of SSE2 operations otherwise; the same operations in the
** same order either way, so the same bits). Lane l of every vector
** belongs to facet forder[i + l]. */
typedef double vd __attribute__((vector_size(32)));
typedef struct pg_block {
  vd N[3], A0, g[3][3], h[3], NN[6], area[3], mom[3][3], cot[3];
} pg_block;

static inline __attribute__((always_inline)) void
pass_half_impl(const tds_surf *s, pgw *w, pg_half *hf) {
  const tds_mesh *m = &s->m;
  pg_acc *acc = w->acc;
  double energy = 0, area_total = 0;
  vd ven = {0, 0, 0, 0}, var = ven;
  int32_t i = hf->i0;
  for (; i + 4 <= hf->i1; i += 4) {
    const tds_id *f = w->forder + i;
    tds_corners C[4];
    for (int l = 0; l < 4; l++) tds_gather_facet(m, f[l], &C[l]);
    vd p[3][3];
    for (int k = 0; k < 3; k++)
      for (int c = 0; c < 3; c++)
        p[k][c] = (vd){C[0].x[k][c], C[1].x[k][c], C[2].x[k][c], C[3].x[k][c]};
    vd e[3][3], N[3];
    for (int c = 0; c < 3; c++) {
      e[0][c] = p[1][c] - p[0][c];
      e[1][c] = p[2][c] - p[1][c];
      e[2][c] = p[0][c] - p[2][c];
    }
    N[0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    N[1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    N[2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    vd nn = N[0] * N[0] + N[1] * N[1] + N[2] * N[2];
    if (!(nn[0] > 0 && nn[1] > 0 && nn[2] > 0 && nn[3] > 0)) {
      for (int l = 0; l < 4; l++) facet_scalar(s, w, hf, f[l], &energy, &area_total);
      continue;
    }
    vd nl = {sqrt(nn[0]), sqrt(nn[1]), sqrt(nn[2]), sqrt(nn[3])};
    vd ten = {m->ften[f[0]], m->ften[f[1]], m->ften[f[2]], m->ften[f[3]]};
    vd A = 0.5 * nl;
    var += A;
    ven += ten * A;
    vd inl = 1 / nl;
    vd dk[3], l2[3];
    dk[0] = -(e[0][0] * e[2][0] + e[0][1] * e[2][1] + e[0][2] * e[2][2]);
    dk[1] = -(e[1][0] * e[0][0] + e[1][1] * e[0][1] + e[1][2] * e[0][2]);
    dk[2] = -(e[2][0] * e[1][0] + e[2][1] * e[1][1] + e[2][2] * e[1][2]);
    for (int k = 0; k < 3; k++)
      l2[k] = e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2];
    pg_block b;
    for (int k = 0; k < 3; k++) b.cot[k] = dk[k] * inl;
    for (int l = 0; l < 4; l++) {
      double *cot = w->fcot + 3 * (size_t)(i + l);
      cot[0] = b.cot[0][l];
      cot[1] = b.cot[1][l];
      cot[2] = b.cot[2][l];
    }
    const uint8_t md[4] = {w->fmode[f[0]], w->fmode[f[1]], w->fmode[f[2]], w->fmode[f[3]]};
    if ((md[0] | md[1] | md[2] | md[3]) & FM_WORK) {
      /* Voronoi cells as voronoi_cells (non-obtuse), then the obtuse
      ** lanes again by voronoi_obtuse. */
      vd s8 = 0.125 * inl;
      vd h0 = l2[0] * dk[2] * s8, h1 = l2[1] * dk[0] * s8, h2 = l2[2] * dk[1] * s8;
      vd q = 4 * inl;
      vd w0 = q * h1, w1 = q * h2, w2 = q * h0;
      vd a0 = h0 + h2, a1 = h1 + h0, a2 = h2 + h1;
      const double t = 1.0 / 3;
      vd x0 = (a0 * w1 + 0.5 * h0) * t, y0 = (a0 * w2 + 0.5 * h2) * t;
      vd x1 = (a1 * w2 + 0.5 * h1) * t, y1 = (a1 * w0 + 0.5 * h0) * t;
      vd x2 = (a2 * w0 + 0.5 * h2) * t, y2 = (a2 * w1 + 0.5 * h1) * t;
      b.area[0] = a0;
      b.area[1] = a1;
      b.area[2] = a2;
      for (int c = 0; c < 3; c++) {
        b.mom[0][c] = x0 * e[0][c] - y0 * e[2][c];
        b.mom[1][c] = x1 * e[1][c] - y1 * e[0][c];
        b.mom[2][c] = x2 * e[2][c] - y2 * e[1][c];
      }
      for (int l = 0; l < 4; l++) {
        if (!(dk[0][l] < 0 || dk[1][l] < 0 || dk[2][l] < 0)) continue;
        double el[3][3], l2l[3], dkl[3], ar[3], mo[3][3];
        for (int k = 0; k < 3; k++) {
          for (int c = 0; c < 3; c++) el[k][c] = e[k][c][l];
          l2l[k] = l2[k][l];
          dkl[k] = dk[k][l];
        }
        voronoi_obtuse(dkl[0] < 0 ? 0 : dkl[1] < 0 ? 1 : 2, (const double(*)[3])el,
                       nl[l], l2l, dkl, ar, mo);
        for (int k = 0; k < 3; k++) {
          b.area[k][l] = ar[k];
          for (int c = 0; c < 3; c++) b.mom[k][c][l] = mo[k][c];
        }
      }
      vd gs = 0.5 * ten * inl, hs = gs * inl * inl;
      b.A0 = ten * A;
      for (int c = 0; c < 3; c++) b.N[c] = N[c];
      b.NN[0] = N[0] * N[0];
      b.NN[1] = N[1] * N[1];
      b.NN[2] = N[2] * N[2];
      b.NN[3] = N[0] * N[1];
      b.NN[4] = N[0] * N[2];
      b.NN[5] = N[1] * N[2];
      /* area gradient at corner k: gs N x (edge opposite k) */
      b.g[0][0] = (N[1] * e[1][2] - N[2] * e[1][1]) * gs;
      b.g[0][1] = (N[2] * e[1][0] - N[0] * e[1][2]) * gs;
      b.g[0][2] = (N[0] * e[1][1] - N[1] * e[1][0]) * gs;
      b.g[1][0] = (N[1] * e[2][2] - N[2] * e[2][1]) * gs;
      b.g[1][1] = (N[2] * e[2][0] - N[0] * e[2][2]) * gs;
      b.g[1][2] = (N[0] * e[2][1] - N[1] * e[2][0]) * gs;
      for (int c = 0; c < 3; c++) b.g[2][c] = -(b.g[0][c] + b.g[1][c]);
      b.h[0] = hs * l2[1];
      b.h[1] = hs * l2[2];
      b.h[2] = hs * l2[0];
      for (int l = 0; l < 4; l++) {
        if (!(md[l] & FM_WORK)) continue;
        const int32_t *sl = w->fslot[f[l]];
        for (int k = 0; k < 3; k++) {
          pg_acc *a = &acc[sl[k]];
          a->N[0] += b.N[0][l];
          a->N[1] += b.N[1][l];
          a->N[2] += b.N[2][l];
          a->A0 += b.A0[l];
          a->ga[0] += b.g[k][0][l];
          a->ga[1] += b.g[k][1][l];
          a->ga[2] += b.g[k][2][l];
          a->area += b.area[k][l];
          double hk = b.h[k][l];
          for (int j = 0; j < 6; j++) a->H[j] += hk * b.NN[j][l];
          a->mom[0] += b.mom[k][0][l];
          a->mom[1] += b.mom[k][1][l];
          a->mom[2] += b.mom[k][2][l];
        }
      }
    }
    if ((md[0] | md[1] | md[2] | md[3]) & FM_BODY) {
      /* Body terms as body_terms (geom_volume_z, geom_zmoment), four at
      ** a time for facets of one body without a prescribed pressure. */
      vd zs = p[0][2] + p[1][2] + p[2][2], Nz = N[2];
      vd V = zs * Nz / 6, c6 = zs / 6, n6 = Nz / 6;
      vd gx[3], gy[3];
      for (int k = 0; k < 3; k++) { /* q = p[k+1], r = p[k+2] */
        int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        gx[k] = c6 * (p[k1][1] - p[k2][1]);
        gy[k] = c6 * (p[k2][0] - p[k1][0]);
      }
      const int grav = s->gravity_on && s->gravity != 0;
      vd W = {0, 0, 0, 0}, wx[3], wy[3], wz[3];
      if (grav) {
        vd za = p[0][2], zb = p[1][2], zc = p[2][2];
        vd S = za * za + zb * zb + zc * zc + za * zb + zb * zc + zc * za;
        vd s24 = S / 24, n24 = Nz / 24;
        W = Nz * S / 24;
        for (int k = 0; k < 3; k++) {
          int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          wx[k] = s24 * (p[k1][1] - p[k2][1]);
          wy[k] = s24 * (p[k2][0] - p[k1][0]);
          wz[k] = n24 * (2 * p[k][2] + p[k1][2] + p[k2][2]);
        }
      }
      for (int l = 0; l < 4; l++) {
        if (!(md[l] & FM_BODY)) continue;
        if (!(md[l] & FM_BODY1)) {
          energy += body_terms(s, w, hf, f[l], C[l].x[0], C[l].x[1], C[l].x[2]);
          continue;
        }
        int j = (md[l] & FM_SIDE1) ? 1 : 0;
        tds_id bd = m->fb[f[l]][j];
        double sign = j ? -1.0 : 1.0;
        hf->bvol[bd] += sign * V[l];
        const int32_t *sl = w->fslot[f[l]];
        for (int k = 0; k < 3; k++) {
          double *g = acc[sl[k]].vg;
          g[0] += sign * gx[k][l];
          g[1] += sign * gy[k][l];
          g[2] += sign * n6[l];
        }
        if (grav && m->bdensity[bd] != 0) {
          double wt = sign * s->gravity * m->bdensity[bd];
          energy += wt * W[l];
          for (int k = 0; k < 3; k++) {
            double *g = acc[sl[k]].gg;
            g[0] += wt * wx[k][l];
            g[1] += wt * wy[k][l];
            g[2] += wt * wz[k][l];
          }
        }
      }
    }
  }
  for (; i < hf->i1; i++) facet_scalar(s, w, hf, w->forder[i], &energy, &area_total);
  hf->energy = (ven[0] + ven[1]) + (ven[2] + ven[3]) + energy;
  hf->area = (var[0] + var[1]) + (var[2] + var[3]) + area_total;
}

static void pass_half_generic(const tds_surf *s, pgw *w, pg_half *hf) {
  pass_half_impl(s, w, hf);
}

#if defined(__GNUC__) && defined(__x86_64__)
#define PG_HAVE_AVX2_PATH 1
__attribute__((target("avx2"))) static void pass_half_avx2(const tds_surf *s, pgw *w,
                                                           pg_half *hf) {
  pass_half_impl(s, w, hf);
}
#endif

/* The facets of one half, on the widest vector unit allowed. */
static void pass_half(const tds_surf *s, pgw *w, pg_half *hf) {
#ifdef PG_HAVE_AVX2_PATH
  if (w->isa > 0) {
    pass_half_avx2(s, w, hf);
    return;
  }
#endif
  pass_half_generic(s, w, hf);
}

int pg_pass_isa(int want) {
#ifdef PG_HAVE_AVX2_PATH
  __builtin_cpu_init();
  if (want != 0 && __builtin_cpu_supports("avx2")) return 1;
#endif
  (void)want;
  return 0;
}

/* The second half's sums at shared vertices i0 to i1 - 1, added. */
static void add_shared(pgw *w, int32_t i0, int32_t i1) {
  const tds_fixq *fq = &w->fq;
  const int32_t nv = w->nv;
  for (int32_t i = i0; i < i1; i++) {
    tds_id v = w->shared[i];
    double *restrict o = (double *)&w->acc[v];
    const double *restrict a = (const double *)&w->acc[nv + i];
    for (int j = 0; j < (int)(sizeof(pg_acc) / sizeof(double)); j++) o[j] += a[j];
    v3_add(w->grad[v], w->grad[v], w->grad[nv + i]);
    if (fq->nq) {
      const double(*b)[3] = w->fgbuf + w->sbase[i];
      for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++)
        v3_add(fq->g[e], fq->g[e], b[e - fq->start[v]]);
    }
  }
}

int pg_pass(tds_ctx *ctx, tds_surf *s, pgw *w, double *energy_out) {
  tds_mesh *m = &s->m;
  tds_fixq *fq = &w->fq;
  if (w->plan_gen != m->topo_gen) plan_build(s, w);
  size_t nslot = (size_t)m->nv + (size_t)w->nshared;
  memset(w->acc, 0, nslot * sizeof *w->acc);
  memset(w->grad, 0, nslot * sizeof *w->grad);
  if (fq->nq) {
    tds_fixq_clear(fq);
    if (w->nshared) {
      tds_id v = w->shared[w->nshared - 1];
      size_t n = (size_t)w->sbase[w->nshared - 1] + (size_t)(fq->start[v + 1] - fq->start[v]);
      memset(w->fgbuf, 0, n * sizeof *w->fgbuf);
    }
  }
  for (int h = 0; h < 2; h++)
    if (m->nb) memset(w->half[h].bvol, 0, (size_t)m->nb * sizeof(double));
  const int nthr = w->threads > 1 ? 2 : 1;
  (void)nthr;
#pragma omp parallel num_threads(nthr) if (nthr > 1)
  {
#pragma omp for schedule(static, 1)
    for (int h = 0; h < 2; h++) pass_half(s, w, &w->half[h]);
#ifdef _OPENMP
    int t = omp_get_thread_num(), T = omp_get_num_threads();
#else
    int t = 0, T = 1;
#endif
    /* fixed ranges of the shared list, one per thread: each vertex is
    ** summed once, first half plus second half, whatever the threads */
    add_shared(w, (int32_t)((int64_t)w->nshared * t / T),
               (int32_t)((int64_t)w->nshared * (t + 1) / T));
  }
  /* The one-body facets' sums (acc.vg, acc.gg) to their places. */
  if (fq->nq)
    for (tds_id v = 0; v < m->nv; v++)
      if (w->vent[v] >= 0) v3_add(fq->g[w->vent[v]], fq->g[w->vent[v]], w->acc[v].vg);
  if (s->gravity_on && s->gravity != 0)
    for (tds_id v = 0; v < m->nv; v++) v3_add(w->grad[v], w->grad[v], w->acc[v].gg);
  double energy = w->half[0].energy + w->half[1].energy;
  double area_total = w->half[0].area + w->half[1].area;
  for (tds_id b = 0; b < m->nb; b++)
    m->bvol[b] = (m->bflags[b] & TDS_DEAD)
                     ? 0 : m->bvolconst[b] + (w->half[0].bvol[b] + w->half[1].bvol[b]);

  /* Everything but the facet terms (edge tensions, constraint and
  ** boundary integrals, named quantities): the method table's assembly,
  ** as tds_eval runs it. */
  tds_eval_out out = {.energy = energy, .area = area_total, .grad = w->grad,
                      .fq = fq->nq ? fq : NULL};
  int rc = tds_eval_terms(ctx, s, &out, 0);
  w->cot_gen = m->coord_gen;
  s->energy = out.energy;
  s->area = out.area;
  *energy_out = out.energy;
  return rc;
}
