/* topo_flip.c: edge flips and equiangulation (the u command). */
#include "gather.h"
#include "torus.h"
#include "topo.h"
#include "snap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geom.h"
#include "method.h"
#include "pairset.h"

/* The side of facet f that lies on edge e (0..2). */
static int side_of(const tds_mesh *m, tds_id f, tds_id e) {
  for (int k = 0; k < 3; k++)
    if (TDS_OID(m->fe[f][k]) == e) return k;
  return -1;
}

/* Flip edge e (between f1 and f2) unless its new ends are already joined
** by an edge (ps: the set of joined vertex pairs, kept up to date).
** Returns 1 when it flipped. */
static int flip_kept(tds_surf *s, tds_pairset *ps, tds_id e, tds_id f1, tds_id f2) {
  const tds_mesh *m = &s->m;
  int k1 = side_of(m, f1, e), k2 = side_of(m, f2, e);
  tds_id c = m->fv[f1][(k1 + 2) % 3], d = m->fv[f2][(k2 + 2) % 3];
  if (tds_pairset_has(ps, c, d)) return 0;
  tds_pairset_remove(ps, m->ev[e][0], m->ev[e][1]);
  tds_flip(s, e, f1, f2);
  tds_pairset_add(ps, c, d);
  return 1;
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

/* The corners a, b (e's ends), c (f1's third) and d (f2's third) of the
** quad around e, as one patch: f1 unwrapped from its first corner, f2
** translated to meet it along e (torus.h). Without a torus, the stored
** positions. Returns the packed wrap from c to d in that patch. */
static int32_t quad(const tds_mesh *m, tds_id e, tds_id f1, tds_id f2, double q[4][3]) {
  int k1 = side_of(m, f1, e), k2 = side_of(m, f2, e);
  int ca = k1, cb = (k1 + 1) % 3, cc = (k1 + 2) % 3;  /* f1 = (a, b, c) */
  int da = (k2 + 1) % 3, dd = (k2 + 2) % 3;            /* f2 = (b, a, d) */
  if (!m->torus) {
    memcpy(q[0], m->x[m->fv[f1][ca]], sizeof q[0]);
    memcpy(q[1], m->x[m->fv[f1][cb]], sizeof q[1]);
    memcpy(q[2], m->x[m->fv[f1][cc]], sizeof q[2]);
    memcpy(q[3], m->x[m->fv[f2][dd]], sizeof q[3]);
    return 0;
  }
  /* shift takes f2's frame to f1's (a where f1 has it); group products in
  ** order, as a symmetry group's need not commute (symmetry.h) */
  int32_t shift = tds_wrap_mul(m, tds_torus_corner_wrap(m, f1, ca),
                               tds_wrap_inv(m, tds_torus_corner_wrap(m, f2, da)));
  int32_t wd = tds_wrap_mul(m, shift, tds_torus_corner_wrap(m, f2, dd));
  tds_torus_facet_corner(m, f1, ca, q[0]);
  tds_torus_facet_corner(m, f1, cb, q[1]);
  tds_torus_facet_corner(m, f1, cc, q[2]);
  double t[3];
  const double *xd = tds_wrap_point(m, m->x[m->fv[f2][dd]], wd, t);
  memcpy(q[3], xd, sizeof q[3]);
  return tds_wrap_mul(m, tds_wrap_inv(m, tds_torus_corner_wrap(m, f1, cc)), wd);
}

void tds_flip(tds_surf *s, tds_id e, tds_id f1, tds_id f2) {
  tds_mesh *m = &s->m;
#ifdef TDS_CHECKS
  tds_id g1, g2;
  TDS_ASSERT(tds_flip_ok(s, e, &g1, &g2) && g1 == f1 && g2 == f2);
#endif
  int k1 = side_of(m, f1, e), k2 = side_of(m, f2, e);
  /* f1 = (a, b, c) with e = a->b; f2 = (b, a, d). */
  int32_t bc = m->fe[f1][(k1 + 1) % 3], ca = m->fe[f1][(k1 + 2) % 3];
  int32_t ad = m->fe[f2][(k2 + 1) % 3], db = m->fe[f2][(k2 + 2) % 3];
  tds_id c = m->fv[f1][(k1 + 2) % 3], d = m->fv[f2][(k2 + 2) % 3];
  if (m->torus) {
    double q[4][3];
    m->ewrap[e] = quad(m, e, f1, f2, q);
  }
  m->ev[e][0] = c; /* e becomes c->d */
  m->ev[e][1] = d;
  int32_t t1[3] = {ad, TDS_OREF(e, 1), ca}; /* a, d, c */
  int32_t t2[3] = {db, bc, TDS_OREF(e, 0)}; /* d, b, c */
  tds_mesh_set_facet(m, f1, t1);
  tds_mesh_set_facet(m, f2, t2);
}

/* The cosines of the two angles opposite edge e (f1 forwards, f2
** backwards), at c and d of quad(). Under KLEIN_METRIC, Evolver 2.70's
** rule (measured on 1800 seeded quads near the Delaunay limit, every flip
** agreeing, against 352 disagreements for the Euclidean angles of the
** coordinates and 49 for the hyperbolic angles): the Euclidean law of
** cosines on the edges' hyperbolic lengths. */
static void opposite_cos2(const tds_surf *s, tds_id e, tds_id f1, tds_id f2, double c[2]) {
  double q[4][3];
  quad(&s->m, e, f1, f2, q);
  if (!s->klein) {
    c[0] = cos(geom_angle(q[2], q[0], q[1]));
    c[1] = cos(geom_angle(q[3], q[0], q[1]));
    return;
  }
  double ab = tds_klein_dist(q[0], q[1]);
  for (int i = 0; i < 2; i++) {
    double a = tds_klein_dist(q[2 + i], q[0]), b = tds_klein_dist(q[2 + i], q[1]);
    double r = a > 0 && b > 0 ? (a * a + b * b - ab * ab) / (2 * a * b) : 1; /* no angle: 0 */
    c[i] = r > 1 ? 1 : r < -1 ? -1 : r;
  }
}

/* Sum of the two angles opposite edge e. */
static double opposite_sum(const tds_surf *s, tds_id e, tds_id f1, tds_id f2) {
  double c[2];
  opposite_cos2(s, e, f1, f2, c);
  return acos(c[0]) + acos(c[1]);
}

/* Sum of the cosines of the two angles opposite edge e. */
static double opposite_cos(const tds_surf *s, tds_id e, tds_id f1, tds_id f2) {
  double c[2];
  opposite_cos2(s, e, f1, f2, c);
  return c[0] + c[1];
}

/* Evolver's u: one pass over the selected edges in id order, flipping
** each whose opposite angles have a cosine sum below -TDS_U_COS when its
** turn comes (earlier flips of the pass included); edges that fail it
** only after their turn wait for the next u. */
static int equiangulate_pass(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                             int32_t *nflips) {
  tds_mesh *m = &s->m;
  int32_t ne = m->ne, flips = 0;
  tds_pairset ps;
  if (tds_pairset_init(&ps, &s->m.alloc, (size_t)ne) != TDS_OK) {
    tds_pairset_free(&ps);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  for (tds_id e = 0; e < ne; e++)
    if (tds_alive(m->eflags, e)) tds_pairset_add(&ps, m->ev[e][0], m->ev[e][1]);
  for (tds_id e = 0; e < ne; e++) {
    tds_id f1, f2;
    if (sel && !sel[e]) continue;
    if (!tds_flip_ok(s, e, &f1, &f2)) continue;
    if (!(opposite_cos(s, e, f1, f2) < -TDS_U_COS)) continue;
    if (!flip_kept(s, &ps, e, f1, f2)) continue;
    flips++;
  }
  tds_pairset_free(&ps);
  if (nflips) *nflips = flips;
  if (flips) m->coord_gen++;
  return tds_surf_update(ctx, s);
}

static int equiangulate(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                     int32_t *nflips) {
  tds_mesh *m = &s->m;
  int32_t ne = m->ne, flips = 0;
  tds_pairset ps;
  int prc = tds_pairset_init(&ps, &s->m.alloc, (size_t)ne);
  tds_id *stack = tds_malloc(&s->m.alloc, (size_t)(ne > 0 ? ne : 1) * sizeof *stack);
  uint8_t *queued = tds_calloc(&s->m.alloc, (size_t)(ne > 0 ? ne : 1), 1);
  if (prc != TDS_OK || !stack || !queued) {
    tds_pairset_free(&ps);
    tds_free(&s->m.alloc, stack);
    tds_free(&s->m.alloc, queued);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int32_t top = 0;
  for (tds_id e = 0; e < ne; e++)
    if (tds_alive(m->eflags, e)) {
      tds_pairset_add(&ps, m->ev[e][0], m->ev[e][1]);
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
    if (opposite_sum(s, e, f1, f2) <= TDS_PI + 1e-12) continue;
    if (!flip_kept(s, &ps, e, f1, f2)) continue;
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
  tds_pairset_free(&ps);
  tds_free(&s->m.alloc, stack);
  tds_free(&s->m.alloc, queued);
  if (nflips) *nflips = flips;
  if (flips) m->coord_gen++;
  return tds_surf_update(ctx, s);
}

/* All or nothing, as tds_refine. */
int tds_equiangulate(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *nflips) {
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  return tds_snap_end(ctx, s, &sn, equiangulate(ctx, s, sel, nflips));
}

int tds_equiangulate_once(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                          int32_t *nflips) {
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  return tds_snap_end(ctx, s, &sn, equiangulate_pass(ctx, s, sel, nflips));
}
