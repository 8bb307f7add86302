/* pg.c: the projected-gradient iteration (see pg.h and doc/method.md). */
#include "pg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "eval.h"
#include "fixq.h"
#include "motion.h"
#include "topo.h"
#include "vec3.h"

/* Vertex kinds: how a vertex moves. */
enum { VK_FIXED = 0, VK_FREE, VK_LEVEL, VK_BDRY, VK_JUNCTION };

/* Set of undirected vertex pairs (the mesh's edges), open addressing. */
typedef struct pairset {
  uint64_t *key;
  size_t cap;
} pairset;

static uint64_t pkey(tds_id a, tds_id b) {
  uint64_t lo = (uint32_t)(a < b ? a : b), hi = (uint32_t)(a < b ? b : a);
  return (hi << 32 | lo) + 1;
}
static size_t phash(uint64_t k, size_t cap) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdULL;
  k ^= k >> 33;
  return (size_t)k & (cap - 1);
}
static size_t pfind(const pairset *ps, uint64_t k) {
  size_t i = phash(k, ps->cap);
  while (ps->key[i] && ps->key[i] != k) i = (i + 1) & (ps->cap - 1);
  return i;
}
static int phas(const pairset *ps, tds_id a, tds_id b) {
  return ps->key[pfind(ps, pkey(a, b))] != 0;
}
static void pput(pairset *ps, tds_id a, tds_id b) {
  uint64_t k = pkey(a, b);
  ps->key[pfind(ps, k)] = k;
}
static void pdel(pairset *ps, tds_id a, tds_id b) {
  size_t i = pfind(ps, pkey(a, b));
  if (!ps->key[i]) return;
  size_t j = i;
  for (;;) {
    ps->key[i] = 0;
    for (;;) {
      j = (j + 1) & (ps->cap - 1);
      if (!ps->key[j]) return;
      size_t h = phash(ps->key[j], ps->cap);
      if (i <= j ? (i < h && h <= j) : (i < h || h <= j)) continue;
      break;
    }
    ps->key[i] = ps->key[j];
    i = j;
  }
}

/* Work arrays of one run; allocated once. */
typedef struct pgw {
  int32_t nv, ne, nmov;
  int rigid;              /* no fixed vertex: remove rigid drift of moves */
  uint8_t *kind;          /* per vertex slot: VK_* */
  int32_t (*bnb)[2];      /* constrained vertex: its two neighbours along
                             the film's border (edges of one facet), or -1 */
  int32_t *mov;           /* movable vertex ids */
  double (*grad)[3];      /* energy gradient from tds_eval */
  double (*nsum)[3];      /* sum of facet area vectors */
  double (*mom)[3];       /* Voronoi moment: sum area * (centroid - x) */
  double *varea;          /* Voronoi area */
  double (*d)[3];         /* direction of the normal move (unit) */
  double (*nrm)[3];       /* unit vertex normal */
  double (*model)[3];     /* A0, A1, A2 along d */
  double (*vel)[3];       /* the move v_i */
  double (*rest)[3];      /* restoring motion */
  double (*tan)[3];       /* tangential (mesh-quality) part of the move */
  double (*P)[9];         /* motion-space projector (constrained vertices) */
  double (*Jinv)[6];      /* boundary: dp = Jinv v (2 x 3) */
  double (*xbest)[3];
  double (*pbest)[2];
  tds_fixq fq;
  double *an;             /* normal component of each fq entry */
  double *gram, *rhs, *mult;
  /* flips */
  pairset ps;
  int32_t *stack, *cand, ncand;
  uint8_t *queued;
  uint64_t cand_gen;
  /* Anderson */
  int depth, hist, head;
  int32_t N;
  double *X, *G, *Gprev, *Fprev, *dF, *dG, *M, *Ms, *gam;
  double fmin;
  int have_prev;
  int64_t nreset;         /* safeguard resets */
} pgw;

static void work_free(pgw *w) {
  free(w->kind);
  free(w->bnb);
  free(w->mov);
  free(w->grad);
  free(w->nsum);
  free(w->mom);
  free(w->varea);
  free(w->d);
  free(w->nrm);
  free(w->model);
  free(w->vel);
  free(w->rest);
  free(w->tan);
  free(w->P);
  free(w->Jinv);
  free(w->xbest);
  free(w->pbest);
  tds_fixq_free(&w->fq);
  free(w->an);
  free(w->gram);
  free(w->rhs);
  free(w->mult);
  free(w->ps.key);
  free(w->stack);
  free(w->cand);
  free(w->queued);
  free(w->X);
  free(w->G);
  free(w->Gprev);
  free(w->Fprev);
  free(w->dF);
  free(w->dG);
  free(w->M);
  free(w->Ms);
  free(w->gam);
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

static int work_init(tds_ctx *ctx, tds_surf *s, pgw *w, int depth) {
  tds_mesh *m = &s->m;
  memset(w, 0, sizeof *w);
  if (tds_mesh_adjacency(m) != TDS_OK) goto nomem;
  size_t nv = (size_t)m->nv, ne = (size_t)m->ne;
  w->nv = m->nv;
  w->ne = m->ne;
  w->kind = tds_calloc(nv, 1);
  w->bnb = tds_calloc(nv, sizeof *w->bnb);
  w->mov = tds_calloc(nv, sizeof *w->mov);
  w->grad = tds_calloc(nv, sizeof *w->grad);
  w->nsum = tds_calloc(nv, sizeof *w->nsum);
  w->mom = tds_calloc(nv, sizeof *w->mom);
  w->varea = tds_calloc(nv, sizeof *w->varea);
  w->d = tds_calloc(nv, sizeof *w->d);
  w->nrm = tds_calloc(nv, sizeof *w->nrm);
  w->model = tds_calloc(nv, sizeof *w->model);
  w->vel = tds_calloc(nv, sizeof *w->vel);
  w->rest = tds_calloc(nv, sizeof *w->rest);
  w->tan = tds_calloc(nv, sizeof *w->tan);
  w->P = tds_calloc(nv, sizeof *w->P);
  w->Jinv = tds_calloc(nv, sizeof *w->Jinv);
  w->xbest = tds_calloc(nv, sizeof *w->xbest);
  w->pbest = tds_calloc(nv, sizeof *w->pbest);
  w->stack = tds_calloc(ne, sizeof *w->stack);
  w->cand = tds_calloc(ne, sizeof *w->cand);
  w->queued = tds_calloc(ne, 1);
  if (!w->kind || !w->bnb || !w->mov || !w->grad || !w->nsum || !w->mom || !w->varea ||
      !w->d || !w->nrm || !w->model || !w->vel || !w->rest || !w->tan || !w->P ||
      !w->Jinv || !w->xbest || !w->pbest || !w->stack || !w->cand || !w->queued)
    goto nomem;
  int rc = tds_fixq_build(ctx, s, &w->fq);
  if (rc != TDS_OK) {
    work_free(w);
    return rc;
  }
  int32_t nq = w->fq.nq;
  w->an = tds_calloc((size_t)w->fq.nent, sizeof *w->an);
  w->gram = tds_calloc((size_t)nq * (size_t)nq, sizeof *w->gram);
  w->rhs = tds_calloc((size_t)nq, sizeof *w->rhs);
  w->mult = tds_calloc((size_t)nq, sizeof *w->mult);
  if (!w->an || !w->gram || !w->rhs || !w->mult) goto nomem;
  w->ps.cap = 16;
  while (w->ps.cap < 2 * ne + 16) w->ps.cap *= 2;
  w->ps.key = calloc(w->ps.cap, sizeof *w->ps.key);
  if (!w->ps.key) goto nomem;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) pput(&w->ps, m->ev[e][0], m->ev[e][1]);
  w->cand_gen = (uint64_t)-1;
  classify(s, w);
  w->depth = depth;
  if (depth > 0) {
    size_t N = 3 * (size_t)w->nmov, dd = (size_t)depth;
    w->N = (int32_t)N;
    w->X = tds_calloc(N, sizeof *w->X);
    w->G = tds_calloc(N, sizeof *w->G);
    w->Gprev = tds_calloc(N, sizeof *w->Gprev);
    w->Fprev = tds_calloc(N, sizeof *w->Fprev);
    w->dF = tds_calloc(N * dd, sizeof *w->dF);
    w->dG = tds_calloc(N * dd, sizeof *w->dG);
    w->M = tds_calloc(dd * dd, sizeof *w->M);
    w->Ms = tds_calloc(dd * dd, sizeof *w->Ms);
    w->gam = tds_calloc(dd, sizeof *w->gam);
    if (!w->X || !w->G || !w->Gprev || !w->Fprev || !w->dF || !w->dG ||
        !w->M || !w->Ms || !w->gam)
      goto nomem;
  }
  return TDS_OK;
nomem:
  work_free(w);
  return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
}

/* Kernels. ------------------------------------------------------------ */

/* Restricted Voronoi cells of a triangle's corners: area[k] and moment
** mom[k] = area[k] * (centroid[k] - p[k]). Returns 2 * triangle area. */
static double voronoi_rel(const double *p0, const double *p1, const double *p2,
                          double area[3], double mom[3][3]) {
  const double *p[3] = {p0, p1, p2};
  double e[3][3]; /* e[k] = p[k+1] - p[k] */
  v3_sub(e[0], p1, p0);
  v3_sub(e[1], p2, p1);
  v3_sub(e[2], p0, p2);
  double N[3];
  v3_cross(N, e[0], e[1]);
  double nn = v3_dot(N, N), nl = sqrt(nn);
  /* dot at corner k: (p[k+1] - p[k]) . (p[k-1] - p[k]) = -e[k] . e[k-1] */
  double dk[3] = {-v3_dot(e[0], e[2]), -v3_dot(e[1], e[0]), -v3_dot(e[2], e[1])};
  double l2[3] = {v3_dot(e[0], e[0]), v3_dot(e[1], e[1]), v3_dot(e[2], e[2])};
  for (int k = 0; k < 3; k++) {
    area[k] = 0;
    v3_zero(mom[k]);
  }
  if (!(nl > 0)) return 0;
  int o = dk[0] < 0 ? 0 : dk[1] < 0 ? 1 : dk[2] < 0 ? 2 : -1;
  if (o < 0) {
    /* Circumcentre relative to p0: (|a|^2 (b x N) + |b|^2 (N x a)) / 2|N|^2
    ** with a = p1 - p0, b = p2 - p0 = -e[2]. */
    double b[3] = {-e[2][0], -e[2][1], -e[2][2]}, t1[3], t2[3], O[3][3];
    v3_cross(t1, b, N);
    v3_cross(t2, N, e[0]);
    for (int i = 0; i < 3; i++) O[0][i] = (l2[0] * t1[i] + l2[2] * t2[i]) / (2 * nn);
    v3_sub(O[1], O[0], e[0]);
    v3_add(O[2], O[0], e[2]);
    /* Half-cell of corner k on edge k (to k+1), right-angled at the midpoint:
    ** area |e_k|^2 cot(angle at k+2) / 8, cot = d/|N|. */
    double h[3];
    for (int k = 0; k < 3; k++) h[k] = l2[k] * dk[(k + 2) % 3] / (8 * nl);
    for (int k = 0; k < 3; k++) {
      int km = (k + 2) % 3; /* edge km runs from p[km] to p[k] */
      double ha = h[k], hb = h[km];
      area[k] = ha + hb;
      for (int i = 0; i < 3; i++)
        mom[k][i] = (ha * (0.5 * e[k][i] + O[k][i]) +
                     hb * (O[k][i] - 0.5 * e[km][i])) / 3;
    }
    return nl;
  }
  /* Obtuse at o; j = o+1, k = o+2. Cell of j: triangle (p_j, M_oj, X1) with
  ** X1 = p_j + s1 (p_k - p_j), s1 = |p_o p_j|^2 / (2 d_j); likewise k. */
  int j = (o + 1) % 3, k = (o + 2) % 3;
  double sj = l2[o] / (2 * dk[j]), sk = l2[k] / (2 * dk[k]);
  double A = 0.5 * nl;
  area[j] = sj * nl / 4;
  area[k] = sk * nl / 4;
  area[o] = A - area[j] - area[k];
  double cj[3], ck[3]; /* centroids relative to their corners */
  for (int i = 0; i < 3; i++) {
    /* p_o - p_j = -e[o]; p_k - p_j = e[j]; p_o - p_k = e[k]; p_j - p_k = -e[j] */
    cj[i] = (-0.5 * e[o][i] + sj * e[j][i]) / 3;
    ck[i] = (0.5 * e[k][i] - sk * e[j][i]) / 3;
    mom[j][i] = area[j] * cj[i];
    mom[k][i] = area[k] * ck[i];
    /* about p_o: A (e_oj + e_ok)/3 - area_j (p_j - p_o + cj) - area_k (..) */
    double poj = e[o][i], pok = -e[k][i];
    mom[o][i] = A * (poj + pok) / 3 - area[j] * (poj + cj[i]) -
                area[k] * (pok + ck[i]);
  }
  (void)p;
  return nl;
}

void tds_pg_voronoi(const double p[3][3], double area[3], double cen[3][3]) {
  double mom[3][3];
  voronoi_rel(p[0], p[1], p[2], area, mom);
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 3; i++)
      cen[k][i] = p[k][i] + (area[k] > 0 ? mom[k][i] / area[k] : 0);
}

double tds_pg_normal_root(double A0, double A1, double A2, double c,
                          int *clamped) {
  double b = A1 * A1 + A0 * A2;
  if (clamped) *clamped = 0;
  if (!(b > 0) || !(c * c < b) || !(A0 > 0)) {
    if (clamped) *clamped = 1;
    return 0;
  }
  double s0 = A0 * A1 / b;
  double a = A0 * A0 * A0 * A2 / b;
  if (!(a > 0)) { /* flat star: A is |sqrt(b)(s0 + t)|, A' = +-sqrt(b) */
    if (clamped) *clamped = 1;
    return 0;
  }
  return c * sqrt(a / (b * (b - c * c))) - s0;
}

double tds_pg_vertex_normal(const tds_mesh *m, tds_id v, double n[3]) {
  double S[3] = {0, 0, 0};
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    if (m->ften[f] == 0) continue;
    const tds_id *fv = m->fv[f];
    double a[3], b[3], N[3];
    v3_sub(a, m->x[fv[1]], m->x[fv[0]]);
    v3_sub(b, m->x[fv[2]], m->x[fv[0]]);
    v3_cross(N, a, b);
    v3_add(S, S, N);
  }
  double len = v3_norm(S);
  if (len > 0)
    for (int i = 0; i < 3; i++) n[i] = S[i] / len;
  else
    v3_zero(n);
  return len;
}

/* The star term of facet f at corner k along d: adds tension-weighted
** A, A', A'' of |N + t w| / 2, w = d x (x_next - x_prev). */
static inline void star_term(const tds_mesh *m, tds_id f, int k,
                             const double d[3], double *A0, double *A1,
                             double *A2) {
  const tds_id *fv = m->fv[f];
  const double *a = m->x[fv[0]], *b = m->x[fv[1]], *c = m->x[fv[2]];
  double e1[3], e2[3], N[3], ed[3], wv[3];
  v3_sub(e1, b, a);
  v3_sub(e2, c, a);
  v3_cross(N, e1, e2);
  v3_sub(ed, m->x[fv[(k + 1) % 3]], m->x[fv[(k + 2) % 3]]);
  v3_cross(wv, d, ed);
  double nn = v3_dot(N, N), nl = sqrt(nn), nw = v3_dot(N, wv), ww = v3_dot(wv, wv);
  double ten = m->ften[f];
  if (!(nl > 0)) return;
  *A0 += ten * 0.5 * nl;
  *A1 += ten * 0.5 * nw / nl;
  *A2 += ten * 0.5 * (ww * nn - nw * nw) / (nn * nl);
}

static int corner_of(const tds_mesh *m, tds_id f, tds_id v) {
  return m->fv[f][0] == v ? 0 : m->fv[f][1] == v ? 1 : 2;
}

void tds_pg_star_model(const tds_mesh *m, tds_id v, const double d[3],
                       double *A0, double *A1, double *A2) {
  *A0 = *A1 = *A2 = 0;
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    if (m->ften[f] == 0) continue;
    star_term(m, f, corner_of(m, f, v), d, A0, A1, A2);
  }
}

double tds_pg_star_area(const tds_mesh *m, tds_id v, const double d[3],
                        double t) {
  double A = 0;
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    double p[3][3], e1[3], e2[3], N[3];
    for (int k = 0; k < 3; k++) {
      v3_copy(p[k], m->x[m->fv[f][k]]);
      if (m->fv[f][k] == v) v3_axpy(p[k], t, d);
    }
    v3_sub(e1, p[1], p[0]);
    v3_sub(e2, p[2], p[0]);
    v3_cross(N, e1, e2);
    A += m->ften[f] * 0.5 * v3_norm(N);
  }
  return A;
}

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
** using the tangential parts of the rigid motions. */
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

static void remove_drift(const tds_surf *s, pgw *w) {
  const tds_mesh *m = &s->m;
  double xc[3] = {0, 0, 0};
  for (int32_t j = 0; j < w->nmov; j++) v3_add(xc, xc, m->x[w->mov[j]]);
  if (w->nmov) v3_scale(xc, 1.0 / w->nmov);
  int use[6] = {1, 1, 1, 1, 1, 1};
  double G[36] = {0}, b[6] = {0};
  for (int pass = 0; pass < 2; pass++)
    for (int32_t j = 0; j < w->nmov; j++) {
      tds_id v = w->mov[j];
      double md[6][3], rel[3];
      v3_sub(rel, m->x[v], xc);
      for (int k = 0; k < 3; k++) {
        double e[3] = {0, 0, 0};
        e[k] = 1;
        v3_copy(md[k], e);
        v3_cross(md[3 + k], e, rel);
      }
      if (pass == 0) {
        if (w->kind[v] == VK_LEVEL)
          for (int k = 0; k < 6; k++) {
            double pm[3], dd[3];
            mat3_apply(w->P[v], md[k], pm);
            v3_sub(dd, pm, md[k]);
            if (v3_norm(dd) > 1e-9 * (1 + v3_norm(md[k]))) use[k] = 0;
          }
        continue;
      }
      for (int k = 0; k < 6; k++) tangent_part(w, v, md[k]);
      for (int k = 0; k < 6; k++) {
        if (!use[k]) continue;
        b[k] += v3_dot(md[k], w->tan[v]);
        for (int l = 0; l < 6; l++)
          if (use[l]) G[6 * k + l] += v3_dot(md[k], md[l]);
      }
    }
  int idx[6], n = 0;
  double gmax = 0;
  for (int k = 0; k < 6; k++) if (G[7 * k] > gmax) gmax = G[7 * k];
  for (int k = 0; k < 6; k++)
    if (use[k] && G[7 * k] > 1e-12 * gmax) idx[n++] = k;
  double A[36], c[6];
  for (int i = 0; i < n; i++) {
    c[i] = b[idx[i]];
    for (int j = 0; j < n; j++) A[n * i + j] = G[6 * idx[i] + idx[j]];
    A[n * i + i] *= 1 + 1e-12;
  }
  if (n == 0 || tds_dense_solve(n, A, c) != 0) return;
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    double rel[3];
    v3_sub(rel, m->x[v], xc);
    for (int i = 0; i < n; i++) {
      int k = idx[i];
      double e[3] = {0, 0, 0}, md[3];
      e[k % 3] = 1;
      if (k < 3) v3_copy(md, e);
      else v3_cross(md, e, rel);
      tangent_part(w, v, md);
      v3_axpy(w->tan[v], -c[i], md);
    }
  }
}

/* One evaluation: the move v_i of every movable vertex at the current
** positions. Returns r = max |v_i| (or NAN). */
typedef struct stepinfo {
  double r, energy, lambda0;
  int64_t clamps;
} stepinfo;

static int compute_move(tds_ctx *ctx, tds_surf *s, pgw *w, double sfac,
                        stepinfo *si) {
  tds_mesh *m = &s->m;
  tds_fixq *fq = &w->fq;
  tds_eval_out out = {.grad = w->grad, .fq = fq->nq ? fq : NULL};
  int rc = tds_eval(ctx, s, &out);
  if (rc != TDS_OK) return rc;
  si->energy = out.energy;
  s->energy = out.energy;
  s->area = out.area;

  /* Pass 1: facet area vectors and restricted Voronoi cells. */
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    v3_zero(w->nsum[v]);
    v3_zero(w->mom[v]);
    w->varea[v] = 0;
    v3_zero(w->model[v]);
  }
  for (tds_id f = 0; f < m->nf; f++) {
    if ((m->fflags[f] & TDS_DEAD) || m->ften[f] == 0) continue;
    const tds_id *fv = m->fv[f];
    if (!w->kind[fv[0]] && !w->kind[fv[1]] && !w->kind[fv[2]]) continue;
    const double *a = m->x[fv[0]], *b = m->x[fv[1]], *c = m->x[fv[2]];
    double area[3], mom[3][3], e1[3], e2[3], N[3];
    voronoi_rel(a, b, c, area, mom);
    v3_sub(e1, b, a);
    v3_sub(e2, c, a);
    v3_cross(N, e1, e2);
    for (int k = 0; k < 3; k++) {
      tds_id v = fv[k];
      v3_add(w->nsum[v], w->nsum[v], N);
      v3_add(w->mom[v], w->mom[v], mom[k]);
      w->varea[v] += area[k];
    }
  }

  /* Directions. */
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    double *n = w->nrm[v], *d = w->d[v];
    double len = v3_norm(w->nsum[v]);
    if (len > 0)
      for (int i = 0; i < 3; i++) n[i] = w->nsum[v][i] / len;
    else
      v3_zero(n);
    int k = w->kind[v];
    if (k == VK_FREE) {
      v3_copy(d, n);
      continue;
    }
    if (k == VK_LEVEL || k == VK_BDRY) motion_frame(s, w, v);
    if (k == VK_JUNCTION) v3_copy(d, w->grad[v]);
    else mat3_apply(w->P[v], n, d);
    double dl = v3_norm(d);
    if (k != VK_JUNCTION && !(dl > 0.05)) { /* normal nearly off the motion space */
      mat3_apply(w->P[v], w->grad[v], d);
      dl = v3_norm(d);
    }
    if (dl > 0) v3_scale(d, 1 / dl);
    else v3_zero(d);
  }

  /* Pass 2: star area model along d. */
  for (tds_id f = 0; f < m->nf; f++) {
    if ((m->fflags[f] & TDS_DEAD) || m->ften[f] == 0) continue;
    const tds_id *fv = m->fv[f];
    if (!w->kind[fv[0]] && !w->kind[fv[1]] && !w->kind[fv[2]]) continue;
    const double *p[3] = {m->x[fv[0]], m->x[fv[1]], m->x[fv[2]]};
    double e1[3], e2[3], N[3];
    v3_sub(e1, p[1], p[0]);
    v3_sub(e2, p[2], p[0]);
    v3_cross(N, e1, e2);
    double nn = v3_dot(N, N), nl = sqrt(nn), ten = m->ften[f];
    if (!(nl > 0)) continue;
    double h0 = ten * 0.5 * nl, h1 = ten * 0.5 / nl, h2 = ten * 0.5 / (nn * nl);
    for (int k = 0; k < 3; k++) {
      tds_id v = fv[k];
      if (!w->kind[v]) continue;
      double ed[3], wv[3];
      v3_sub(ed, p[(k + 1) % 3], p[(k + 2) % 3]);
      v3_cross(wv, w->d[v], ed);
      double nw = v3_dot(N, wv), ww = v3_dot(wv, wv);
      double *M = w->model[v];
      M[0] += h0;
      M[1] += h1 * nw;
      M[2] += h2 * (ww * nn - nw * nw);
    }
  }

  /* Multipliers: least squares over the normal components. */
  int32_t nq = fq->nq;
  if (nq) {
    memset(w->gram, 0, (size_t)nq * (size_t)nq * sizeof *w->gram);
    memset(w->rhs, 0, (size_t)nq * sizeof *w->rhs);
    for (int32_t j = 0; j < w->nmov; j++) {
      tds_id v = w->mov[j];
      double gd = v3_dot(w->grad[v], w->d[v]);
      for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++) {
        double a = v3_dot(fq->g[e], w->d[v]);
        w->an[e] = a;
        w->rhs[fq->eq[e]] += a * gd;
        for (int32_t e2 = fq->start[v]; e2 < fq->start[v + 1]; e2++)
          w->gram[fq->eq[e] * nq + fq->eq[e2]] += a * v3_dot(fq->g[e2], w->d[v]);
      }
    }
    for (int32_t q = 0; q < nq; q++)
      if (!(w->gram[q * nq + q] > 0)) w->gram[q * nq + q] = 1; /* no movable vertex */
    if (tds_dense_solve(nq, w->gram, w->rhs) != 0)
      return tds_seterr(ctx, TDS_ENUM, "volume constraints are dependent");
    memcpy(w->mult, w->rhs, (size_t)nq * sizeof *w->mult);
    /* Restoring motion: project constraint gradients into the motion spaces
    ** (fixed vertices get zero), then a Newton step onto the targets. */
    for (tds_id v = 0; v < m->nv; v++)
      for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++)
        to_motion(w, v, fq->g[e]);
    rc = tds_fixq_restore(ctx, fq, m->nv, w->rest);
    if (rc != TDS_OK) return rc;
    si->lambda0 = -w->mult[0];
  } else {
    si->lambda0 = 0;
  }

  /* The moves. */
  double r = 0;
  int64_t clamps = 0;
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    const double *d = w->d[v], *M = w->model[v];
    double force[3]; /* gradient of the Lagrangian */
    v3_copy(force, w->grad[v]);
    if (nq)
      for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++)
        v3_axpy(force, -w->mult[fq->eq[e]], fq->g[e]);
    double F = v3_dot(force, d);
    double c = M[1] - F;
    int cl;
    double t = tds_pg_normal_root(M[0], M[1], M[2], c, &cl);
    double lim = 0.5 * sqrt(M[0]);
    if (fabs(t) > lim) {
      t = t > 0 ? lim : -lim;
      cl = 1;
    }
    clamps += cl;
    double *vel = w->vel[v];
    for (int i = 0; i < 3; i++) vel[i] = t * d[i];
    if (nq) v3_add(vel, vel, w->rest[v]);
    int k = w->kind[v];
    if (k != VK_JUNCTION && w->varea[v] > 0) {
      double u[3];
      for (int i = 0; i < 3; i++) u[i] = w->mom[v][i] / w->varea[v];
      if (k != VK_FREE && w->bnb[v][0] >= 0) {
        /* On the film's border (a contact line): the centroid of the 1-D
        ** Voronoi cell along the border, (x_prev + 2 x + x_next) / 4. */
        const double *xa = m->x[w->bnb[v][0]], *xb = m->x[w->bnb[v][1]];
        for (int i = 0; i < 3; i++) u[i] = 0.25 * (xa[i] + xb[i]) - 0.5 * m->x[v][i];
      }
      if (k == VK_FREE) {
        double un = v3_dot(u, w->nrm[v]);
        v3_axpy(u, -un, w->nrm[v]);
      } else {
        mat3_apply(w->P[v], u, u);
        double ud = v3_dot(u, d);
        v3_axpy(u, -ud, d);
      }
      for (int i = 0; i < 3; i++) w->tan[v][i] = sfac * u[i];
    } else {
      v3_zero(w->tan[v]);
    }
  }
  if (w->rigid) remove_drift(s, w);
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    double *vel = w->vel[v];
    v3_add(vel, vel, w->tan[v]);
    double vl = v3_dot(vel, vel);
    if (vl > r) r = vl;
  }
  si->r = sqrt(r);
  si->clamps = clamps;
  if (!isfinite(si->r))
    return tds_seterr(ctx, TDS_ENUM, "projected gradient: a move is not finite");
  return TDS_OK;
}

/* Store the multipliers as body pressures / quantity pressures. */
static void store_pressures(tds_surf *s, const pgw *w) {
  const tds_fixq *fq = &w->fq;
  for (int32_t q = 0; q < fq->nq; q++) {
    if (fq->qbody[q] != TDS_NONE) s->m.bpressure[fq->qbody[q]] = w->mult[q];
    else s->quant[fq->qquant[q]].pressure = w->mult[q];
  }
}

/* State vector of the movable vertices (x, or boundary parameters). */
static void get_state(const tds_surf *s, const pgw *w, double *X) {
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

static int set_state(tds_surf *s, const pgw *w, const double *X) {
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

/* Apply the plain move: every vertex at once. */
static int apply_moves(tds_surf *s, pgw *w) {
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

/* Anderson acceleration (type II) on the state. --------------------- */

static void anderson_reset(pgw *w) {
  w->hist = 0;
  w->head = 0;
  w->have_prev = 0;
  w->fmin = INFINITY;
}

static double dotn(const double *a, const double *b, int32_t n) {
  double s0 = 0, s1 = 0;
  int32_t i = 0;
  for (; i + 1 < n; i += 2) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
  }
  if (i < n) s0 += a[i] * b[i];
  return s0 + s1;
}

/* Given X (state at the start) and G (state after the plain move), write
** the accelerated state into X. Returns 1 if mixing was used. F = G - X. */
static int anderson_mix(pgw *w, double lim2) {
  int32_t N = w->N;
  int mdep = w->depth;
  double *X = w->X, *G = w->G;
  /* F_k = G - X is formed on the fly. */
  double fn = 0;
  for (int32_t i = 0; i < N; i++) {
    double f = G[i] - X[i];
    fn += f * f;
  }
  if (fn < w->fmin) w->fmin = fn;
  else if (fn > 100 * w->fmin) { /* diverging: start over from this point */
    anderson_reset(w);
    w->nreset++;
    w->fmin = fn;
  }
  if (w->have_prev) {
    int col = w->head;
    double *dF = w->dF + (size_t)col * N, *dG = w->dG + (size_t)col * N;
    for (int32_t i = 0; i < N; i++) {
      double f = G[i] - X[i];
      dF[i] = f - w->Fprev[i];
      dG[i] = G[i] - w->Gprev[i];
    }
    w->head = (w->head + 1) % mdep;
    if (w->hist < mdep) w->hist++;
    for (int c = 0; c < w->hist; c++) {
      double v = dotn(dF, w->dF + (size_t)c * N, N);
      w->M[col * mdep + c] = v;
      w->M[c * mdep + col] = v;
    }
  }
  for (int32_t i = 0; i < N; i++) {
    w->Fprev[i] = G[i] - X[i];
    w->Gprev[i] = G[i];
  }
  w->have_prev = 1;
  int h = w->hist;
  if (h == 0) {
    memcpy(X, G, (size_t)N * sizeof *X);
    return 0;
  }
  /* gamma = argmin |F - dF gamma|: (dF^T dF + eps) gamma = dF^T F. */
  double tr = 0;
  for (int c = 0; c < h; c++) tr += w->M[c * mdep + c];
  for (int a = 0; a < h; a++) {
    for (int b = 0; b < h; b++) w->Ms[a * h + b] = w->M[a * mdep + b];
    w->Ms[a * h + a] += 1e-13 * tr + 1e-300;
    w->gam[a] = dotn(w->dF + (size_t)a * N, w->Fprev, N);
  }
  if (tds_dense_solve(h, w->Ms, w->gam) != 0) {
    anderson_reset(w);
    w->nreset++;
    memcpy(X, G, (size_t)N * sizeof *X);
    return 0;
  }
  for (int32_t i = 0; i < N; i++) X[i] = G[i];
  for (int c = 0; c < h; c++) {
    const double *dG = w->dG + (size_t)c * N;
    double g = w->gam[c];
    for (int32_t i = 0; i < N; i++) X[i] -= g * dG[i];
  }
  /* Safeguard: no vertex may jump far from its plain move. */
  for (int32_t j = 0; j < N; j += 3) {
    double a = X[j] - G[j], b = X[j + 1] - G[j + 1], c = X[j + 2] - G[j + 2];
    if (!(a * a + b * b + c * c <= lim2)) {
      anderson_reset(w);
      w->nreset++;
      memcpy(X, G, (size_t)N * sizeof *X);
      return 0;
    }
  }
  return 1;
}

/* Flips. -------------------------------------------------------------- */

static int side_of(const tds_mesh *m, tds_id f, tds_id e) {
  for (int k = 0; k < 3; k++)
    if (TDS_OID(m->fe[f][k]) == e) return k;
  return 0;
}

/* Opposite vertices of e: c in f1 (which runs along e), d in f2. */
static void opposite(const tds_mesh *m, tds_id e, tds_id f1, tds_id f2,
                     tds_id *c, tds_id *d) {
  *c = m->fv[f1][(side_of(m, f1, e) + 2) % 3];
  *d = m->fv[f2][(side_of(m, f2, e) + 2) % 3];
}

/* Nonzero when the angles at c and d opposite a-b sum to more than pi. */
static int not_delaunay(const double *a, const double *b, const double *c,
                        const double *d) {
  double u1[3], v1[3], u2[3], v2[3], c1[3], c2[3];
  v3_sub(u1, a, c);
  v3_sub(v1, b, c);
  v3_sub(u2, a, d);
  v3_sub(v2, b, d);
  v3_cross(c1, u1, v1);
  v3_cross(c2, u2, v2);
  double s1 = v3_norm(c1), s2 = v3_norm(c2);
  double k1 = v3_dot(u1, v1), k2 = v3_dot(u2, v2);
  /* sin(alpha + beta) * |u1||v1||u2||v2| */
  double sn = s1 * k2 + k1 * s2;
  double scale = sqrt(v3_dot(u1, u1) * v3_dot(v1, v1) * v3_dot(u2, u2) *
                      v3_dot(v2, v2));
  return sn < -1e-12 * scale;
}

static void build_candidates(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  w->ncand = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    tds_id f1, f2;
    if (tds_flip_ok(s, e, &f1, &f2)) w->cand[w->ncand++] = e;
  }
  w->cand_gen = m->topo_gen;
}

static int32_t flip_pass(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  if (w->cand_gen != m->topo_gen) build_candidates(s, w);
  int32_t top = 0, flips = 0;
  for (int32_t i = 0; i < w->ncand; i++) {
    tds_id e = w->cand[i], f1, f2, c, d;
    int32_t h = m->eside[e], h2 = m->side_next[h];
    f1 = h / 3;
    f2 = h2 / 3;
    c = m->fv[f1][(h % 3 + 2) % 3];
    d = m->fv[f2][(h2 % 3 + 2) % 3];
    if (not_delaunay(m->x[m->ev[e][0]], m->x[m->ev[e][1]], m->x[c], m->x[d])) {
      w->stack[top++] = e;
      w->queued[e] = 1;
    }
  }
  int64_t budget = 20 * (int64_t)m->ne + 100;
  while (top > 0 && budget-- > 0) {
    tds_id e = w->stack[--top], f1, f2, c, d;
    w->queued[e] = 0;
    if (!tds_flip_ok(s, e, &f1, &f2)) continue;
    opposite(m, e, f1, f2, &c, &d);
    tds_id a = m->ev[e][0], b = m->ev[e][1];
    if (!not_delaunay(m->x[a], m->x[b], m->x[c], m->x[d])) continue;
    if (phas(&w->ps, c, d)) continue;
    pdel(&w->ps, a, b);
    tds_flip(s, e, f1, f2);
    pput(&w->ps, c, d);
    flips++;
    for (int k = 0; k < 3; k++) {
      tds_id q1 = TDS_OID(m->fe[f1][k]), q2 = TDS_OID(m->fe[f2][k]);
      if (q1 != e && !w->queued[q1]) {
        w->stack[top++] = q1;
        w->queued[q1] = 1;
      }
      if (q2 != e && !w->queued[q2]) {
        w->stack[top++] = q2;
        w->queued[q2] = 1;
      }
    }
  }
  while (top > 0) w->queued[w->stack[--top]] = 0;
  if (flips) m->coord_gen++;
  return flips;
}

int tds_pg_flip_all(tds_ctx *ctx, tds_surf *s, int32_t *nflips) {
  pgw w;
  int rc = work_init(ctx, s, &w, 0);
  if (rc != TDS_OK) return rc;
  int32_t n = flip_pass(s, &w);
  work_free(&w);
  if (nflips) *nflips = n;
  return tds_surf_update(ctx, s);
}

int tds_pg_multipliers(tds_ctx *ctx, tds_surf *s, double *mult) {
  pgw w;
  int rc = work_init(ctx, s, &w, 0);
  if (rc != TDS_OK) return rc;
  stepinfo si;
  rc = compute_move(ctx, s, &w, 2, &si);
  for (tds_id b = 0; b < s->m.nb; b++) mult[b] = 0;
  if (rc == TDS_OK)
    for (int32_t q = 0; q < w.fq.nq; q++)
      if (w.fq.qbody[q] != TDS_NONE) mult[w.fq.qbody[q]] = w.mult[q];
  work_free(&w);
  return rc;
}

/* The run. ------------------------------------------------------------ */

void tds_pg_defaults(tds_pg_opts *o) {
  memset(o, 0, sizeof *o);
  o->max_iterations = 100000;
  o->nmax = 200;
  o->s = 2;
  o->accel = 1;
  o->depth = 8;
  o->flips = 1;
}

static double mean_edge(const tds_mesh *m) {
  double sum = 0;
  int64_t n = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    double d[3];
    v3_sub(d, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
    sum += v3_norm(d);
    n++;
  }
  return n ? sum / (double)n : 0;
}

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void save_best(const tds_surf *s, pgw *w) {
  memcpy(w->xbest, s->m.x, (size_t)w->nv * sizeof *w->xbest);
  memcpy(w->pbest, s->m.vp, (size_t)w->nv * sizeof *w->pbest);
}

static void load_best(tds_surf *s, pgw *w) {
  memcpy(s->m.x, w->xbest, (size_t)w->nv * sizeof *w->xbest);
  memcpy(s->m.vp, w->pbest, (size_t)w->nv * sizeof *w->pbest);
  s->m.coord_gen++;
}

int tds_pg_run(tds_ctx *ctx, tds_surf *s, const tds_pg_opts *o,
               tds_pg_result *res) {
  double t0 = now();
  memset(res, 0, sizeof *res);
  pgw w;
  int accel = o->accel && o->depth > 0;
  int rc = work_init(ctx, s, &w, accel ? o->depth : 0);
  if (rc != TDS_OK) return rc;
  tds_mesh *m = &s->m;
  res->nfree = w.nmov;
  double hbar = mean_edge(m);
  double lim2 = (0.5 * hbar) * (0.5 * hbar);
  int until = o->iterations <= 0;
  int64_t nmaxit = until ? (o->max_iterations > 0 ? o->max_iterations : 100000)
                         : o->iterations;
  int64_t every = o->every;
  if (every == 0) every = until ? 100 : (nmaxit <= 20 ? 1 : (nmaxit + 9) / 10);
  double sfac = o->s;
  double rbest = INFINITY, ebest = 0, lbest = 0;
  int64_t best = 0, since_flip = 0;
  int warm = 5; /* plain iterations after a flip before mixing */
  double aa_best = INFINITY;
  int64_t aa_k = 0;
  stepinfo si = {0};
  int64_t k;
  save_best(s, &w);
  if (accel) anderson_reset(&w);
  tds_printf(ctx, "pg: %d movable vertices, %s%s\n", w.nmov,
             accel ? "accelerated (Anderson)" : "plain",
             until ? ", until converged" : "");
  for (k = 1; k <= nmaxit; k++) {
    rc = compute_move(ctx, s, &w, sfac, &si);
    if (rc != TDS_OK) break;
    res->clamps += si.clamps;
    res->r_last = si.r;
    if (!res->reached && si.r < 1e-13 * hbar) res->reached = k;
    if (si.r < rbest) {
      rbest = si.r;
      best = k;
      ebest = si.energy;
      lbest = si.lambda0;
      if (until) save_best(s, &w);
      store_pressures(s, &w);
    }
    if (every > 0 && (k % every == 0 || k == 1))
      tds_printf(ctx, "pg %7lld  r %.3e  lambda % .12g  energy %.15g  flips %lld\n",
                 (long long)k, si.r, si.lambda0, si.energy, (long long)res->flips);
    if (until) {
      if (accel && k - best >= o->nmax && rbest > 1e-13 * hbar) {
        /* Anderson stalled above the noise level: go on plainly. */
        accel = 0;
        best = k;
        rbest = INFINITY; /* judge the plain run on its own */
        res->restarts++;
        tds_printf(ctx, "pg %7lld  acceleration stalled at r %.3e: continuing plainly\n",
                   (long long)k, rbest);
      }
      if (rbest == 0 || k - best >= o->nmax ||
          (o->rtol > 0 && rbest < o->rtol * hbar)) {
        res->converged = 1;
        break;
      }
    }
    if (accel) {
      /* Stagnation: no new best r since 2 x depth iterations -> restart
      ** the history after a few plain steps. */
      if (si.r < aa_best) {
        aa_best = si.r;
        aa_k = k;
      } else if (k - aa_k > 2 * o->depth) {
        anderson_reset(&w);
        w.nreset++;
        since_flip = 0;
        aa_best = si.r;
        aa_k = k;
      }
      get_state(s, &w, w.X);
    }
    if (apply_moves(s, &w)) {
      rc = tds_seterr(ctx, TDS_ENUM, "projected gradient: a vertex could not "
                                     "be projected onto its constraints");
      break;
    }
    if (accel && since_flip >= warm) {
      get_state(s, &w, w.G);
      if (anderson_mix(&w, lim2)) {
        if (set_state(s, &w, w.X)) {
          rc = tds_seterr(ctx, TDS_ENUM, "projected gradient: a vertex could "
                                         "not be projected onto its constraints");
          break;
        }
      }
    }
    since_flip++;
    s->iterations++;
    if (o->flips) {
      int32_t nf = flip_pass(s, &w);
      if (nf) {
        res->flips += nf;
        since_flip = 0;
        if (accel) {
          anderson_reset(&w);
          res->restarts++;
        }
        rbest = INFINITY; /* the saved mesh has the old topology */
        aa_best = INFINITY;
      }
    }
    if (ctx->interrupt) {
      ctx->interrupt = 0;
      rc = tds_seterr(ctx, TDS_EINTR, "interrupted after %lld iterations",
                      (long long)k);
      break;
    }
  }
  if (k > nmaxit) k = nmaxit;
  res->iterations = k;
  if (rc == TDS_ENUM || (until && rc == TDS_OK)) {
    if (rbest < INFINITY || rc == TDS_ENUM) load_best(s, &w);
  }
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
  res->restarts += w.nreset;
  work_free(&w);
  int rc2 = tds_surf_update(ctx, s);
  if (rc == TDS_OK) rc = rc2;
  res->mean_edge = mean_edge(m);
  res->seconds = now() - t0;
  if (rc == TDS_OK || rc == TDS_EINTR)
    tds_printf(ctx, "pg: %lld iterations, r %.3e (%.2e x mean edge) at "
                    "iteration %lld, lambda %.15g, energy %.15g, flips %lld, "
                    "clamped %lld, %s\n",
               (long long)res->iterations, res->r,
               res->mean_edge > 0 ? res->r / res->mean_edge : 0,
               (long long)res->best_iteration, res->lambda, s->energy,
               (long long)res->flips, (long long)res->clamps,
               res->converged ? "converged" : "not converged");
  return rc;
}
