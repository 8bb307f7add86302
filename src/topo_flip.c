/* topo_flip.c: edge flips and equiangulation (the u command). */
#include "topo.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vec3.h"

/* The side of facet f that lies on edge e (0..2). */
static int side_of(const tds_mesh *m, tds_id f, tds_id e) {
  for (int k = 0; k < 3; k++)
    if (TDS_OID(m->fe[f][k]) == e) return k;
  return -1;
}

int tds_flip_ok(const tds_surf *s, tds_id e, tds_id *f1, tds_id *f2) {
  const tds_mesh *m = &s->m;
  if (!tds_alive(m->eflags, e)) return 0;
  if ((m->eflags[e] & TDS_FIXED) || m->econ[e] || m->ebdry[e] != TDS_NONE)
    return 0;
  int32_t h = m->eside[e];
  if (h == TDS_NONE) return 0;
  int32_t h2 = m->side_next[h];
  if (h2 == h || m->side_next[h2] != h) return 0; /* valence must be 2 */
  tds_id a = h / 3, b = h2 / 3;
  if (a == b) return 0;
  int32_t oa = m->fe[a][h % 3], ob = m->fe[b][h2 % 3];
  if (TDS_OREV(oa) == TDS_OREV(ob)) return 0; /* inconsistent orientation */
  if (m->ften[a] != m->ften[b] || m->fcon[a] != m->fcon[b] ||
      ((m->fflags[a] ^ m->fflags[b]) & (TDS_FIXED | TDS_NO_REFINE)) ||
      (m->fflags[a] & TDS_FIXED) || m->fb[a][0] != m->fb[b][0] ||
      m->fb[a][1] != m->fb[b][1])
    return 0;
  tds_id c = m->fv[a][(h % 3 + 2) % 3], d = m->fv[b][(h2 % 3 + 2) % 3];
  if (c == d) return 0;
  *f1 = TDS_OREV(oa) ? b : a; /* f1 runs along e forwards */
  *f2 = TDS_OREV(oa) ? a : b;
  return 1;
}

void tds_flip(tds_surf *s, tds_id e, tds_id f1, tds_id f2) {
  tds_mesh *m = &s->m;
  int k1 = side_of(m, f1, e), k2 = side_of(m, f2, e);
  /* f1 = (a, b, c) with e = a->b; f2 = (b, a, d). */
  int32_t bc = m->fe[f1][(k1 + 1) % 3], ca = m->fe[f1][(k1 + 2) % 3];
  int32_t ad = m->fe[f2][(k2 + 1) % 3], db = m->fe[f2][(k2 + 2) % 3];
  tds_id c = m->fv[f1][(k1 + 2) % 3], d = m->fv[f2][(k2 + 2) % 3];
  m->ev[e][0] = c; /* e becomes c->d */
  m->ev[e][1] = d;
  int32_t t1[3] = {ad, TDS_OREF(e, 1), ca}; /* a, d, c */
  int32_t t2[3] = {db, bc, TDS_OREF(e, 0)}; /* d, b, c */
  tds_mesh_set_facet(m, f1, t1);
  tds_mesh_set_facet(m, f2, t2);
}

/* Angle at p between the directions to q and r. */
static double angle_at(const double *p, const double *q, const double *r) {
  double u[3], v[3], w[3];
  v3_sub(u, q, p);
  v3_sub(v, r, p);
  v3_cross(w, u, v);
  return atan2(v3_norm(w), v3_dot(u, v));
}

/* Sum of the two angles opposite edge e (f1 forwards, f2 backwards). */
static double opposite_sum(const tds_mesh *m, tds_id e, tds_id f1, tds_id f2) {
  tds_id a = m->ev[e][0], b = m->ev[e][1];
  int k1 = side_of(m, f1, e), k2 = side_of(m, f2, e);
  tds_id c = m->fv[f1][(k1 + 2) % 3], d = m->fv[f2][(k2 + 2) % 3];
  return angle_at(m->x[c], m->x[a], m->x[b]) +
         angle_at(m->x[d], m->x[a], m->x[b]);
}

/* A set of vertex pairs (undirected edges), open addressing. */
typedef struct {
  uint64_t *key;
  size_t cap;
} pairset;

static uint64_t pkey(tds_id a, tds_id b) {
  uint64_t lo = (uint32_t)(a < b ? a : b), hi = (uint32_t)(a < b ? b : a);
  return (hi << 32 | lo) + 1; /* 0 marks an empty slot */
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
/* Deletion with backward-shift, keeping probe chains intact. */
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

int tds_equiangulate(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                     int32_t *nflips) {
  tds_mesh *m = &s->m;
  int32_t ne = m->ne, flips = 0;
  pairset ps = {0};
  ps.cap = 16;
  while (ps.cap < 2 * (size_t)ne + 16) ps.cap *= 2;
  ps.key = calloc(ps.cap, sizeof *ps.key);
  tds_id *stack = malloc((size_t)(ne > 0 ? ne : 1) * sizeof *stack);
  uint8_t *queued = calloc((size_t)(ne > 0 ? ne : 1), 1);
  if (!ps.key || !stack || !queued) {
    free(ps.key);
    free(stack);
    free(queued);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int32_t top = 0;
  for (tds_id e = 0; e < ne; e++)
    if (tds_alive(m->eflags, e)) {
      pput(&ps, m->ev[e][0], m->ev[e][1]);
      if (!sel || sel[e]) {
        stack[top++] = e;
        queued[e] = 1;
      }
    }
  /* Each flip strictly improves a planar triangulation; on skew quads a
  ** cap guards against cycling. */
  int64_t budget = 20 * (int64_t)ne + 100;
  while (top > 0 && budget-- > 0) {
    tds_id e = stack[--top], f1, f2;
    queued[e] = 0;
    if (!tds_flip_ok(s, e, &f1, &f2)) continue;
    if (opposite_sum(m, e, f1, f2) <= TDS_PI + 1e-12) continue;
    int k1 = side_of(m, f1, e), k2 = side_of(m, f2, e);
    tds_id c = m->fv[f1][(k1 + 2) % 3], d = m->fv[f2][(k2 + 2) % 3];
    if (phas(&ps, c, d)) continue;
    pdel(&ps, m->ev[e][0], m->ev[e][1]);
    tds_flip(s, e, f1, f2);
    pput(&ps, c, d);
    flips++;
    for (int k = 0; k < 3; k++) {
      tds_id q1 = TDS_OID(m->fe[f1][k]), q2 = TDS_OID(m->fe[f2][k]);
      if (q1 != e && !queued[q1] && (!sel || sel[q1])) {
        stack[top++] = q1;
        queued[q1] = 1;
      }
      if (q2 != e && !queued[q2] && (!sel || sel[q2])) {
        stack[top++] = q2;
        queued[q2] = 1;
      }
    }
  }
  free(ps.key);
  free(stack);
  free(queued);
  if (nflips) *nflips = flips;
  if (flips) m->coord_gen++;
  return tds_surf_update(ctx, s);
}
