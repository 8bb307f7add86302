/*
** gather.h: the one place that reads element geometry out of the mesh.
**
** Every kernel that needs the corner positions of a facet or an edge (its
** area, normal, volume, angles, length, vector) gets them here, never by
** indexing m->x with the element's vertices itself. Without a torus a
** corner is just a pointer into m->x and every helper compiles to the same
** loads as the direct reads did. In the torus model (m->torus) a facet's
** corners are its first vertex and the others translated by the wraps of
** the facet's edges (written into the tds_corners scratch, which is why
** callers pass one), and an edge's head is x[head] + wrap . periods. Callers only ever
** use differences of corners of one gathered element, or the corners
** themselves as points of that element.
**
** Direct reads of m->x that remain, and why:
**  - a vertex's own position: moving, projecting or placing one vertex
**    (motion.c, pg_step.c, topo_vavg.c's result, iterate.c, recalc.c,
**    build.c, mesh.c, lua_elem.c's x/y/z getters and setters), gravity's
**    z at a vertex (metrics.c), bounding boxes (pg_pass.c);
**  - whole-array copies and dumps of coordinates (dump.c, snap.c,
**    live_snap.c, export.c's vertex table and displacement from marks,
**    lua_export.c's marks, mesh_check.c's finiteness check);
**  - patches that span more than one element, which the torus model must
**    unwrap along a path, not per element: the quad around an edge for
**    Delaunay flips (pg_flip.c, topo_flip.c), pg's boundary neighbours
**    of a vertex (pg_step.c, kept as vertex ids), the diagonal choice when
**    refining (topo_refine.c's dist2, a corner to a new midpoint) and a
**    datafile polygon's centroid (build.c). topo_vavg.c's over_facets
**    compares gathered facet centroids with the vertex's own position: on
**    a torus those facets must be gathered from v's corner.
*/
#ifndef TDS_GATHER_H
#define TDS_GATHER_H

#include "mesh.h"
#include "symgroup.h"
#include "wrap.h"

/* Gathered corners of one element: x[0..2] (facet) or x[0..1] (edge:
** tail, head), valid while the mesh's coordinates and this struct are
** unchanged. tmp is the gatherer's scratch (unused without a torus). */
typedef struct tds_corners {
  const double *x[3];
  double tmp[3][3];
} tds_corners;

/* Whether the mesh's wraps are elements of a group other than the torus's
** translations (symgroup.h): then they compose in order and act by
** isometries that may rotate. */
static inline int tds_mesh_rotates(const tds_mesh *m) {
  return m->sym > TDS_SYM_TORUS;
}

/* Wrap products and inverses in the mesh's group: a b (b first, then a;
** lattice counts added in the torus), a^-1. */
static inline int32_t tds_wrap_mul(const tds_mesh *m, int32_t a, int32_t b) {
  if (__builtin_expect(tds_mesh_rotates(m), 0)) return tds_sym_mul(m->sym, m->symp, a, b);
  return tds_wrap_add(a, b);
}
static inline int32_t tds_wrap_inv(const tds_mesh *m, int32_t a) {
  if (!a) return 0;
  if (__builtin_expect(tds_mesh_rotates(m), 0)) return tds_sym_inv(m->sym, m->symp, a);
  return tds_wrap_neg(a);
}

/* The wrap of oriented edge oe (0 without a torus). */
static inline int32_t tds_oe_wrap(const tds_mesh *m, int32_t oe) {
  int32_t w = m->ewrap ? m->ewrap[TDS_OID(oe)] : 0;
  return TDS_OREV(oe) && w ? tds_wrap_inv(m, w) : w;
}

/* Point x of the mesh moved by wrap w (translated in the torus, the
** group element's isometry otherwise), into out (or x itself when w is
** 0); returns the pointer to use. */
static inline __attribute__((always_inline)) const double *
tds_wrap_point(const tds_mesh *m, const double *x, int32_t w, double out[3]) {
  if (!w) return x;
  double d[3];
  if (__builtin_expect(tds_mesh_rotates(m), 0)) { /* out of line: rare */
    tds_sym_apply(m->sym, m->symp, m->period, w, x, out);
    return out;
  }
  tds_wrap_vec(m->period, w, d);
  out[0] = x[0] + d[0];
  out[1] = x[1] + d[1];
  out[2] = x[2] + d[2];
  return out;
}

/* The group element that takes facet f's third vertex to its corner,
** seen from the first: back along the third edge, or, when the first
** vertex is an axial_point (the wraps' product then need not be the
** identity, only fix that vertex), forward along the first two. */
static inline int32_t tds_corner2_wrap(const tds_mesh *m, tds_id f) {
  const int32_t *fe = m->fe[f];
  if (__builtin_expect((m->vflags[m->fv[f][0]] & TDS_AXIAL) != 0, 0))
    return tds_wrap_mul(m, tds_oe_wrap(m, fe[0]), tds_oe_wrap(m, fe[1]));
  return tds_wrap_inv(m, tds_oe_wrap(m, fe[2]));
}

/* x + sg w . periods into out (x itself when w is 0): a translation of
** the torus, sg = -1 for the inverse. */
static inline __attribute__((always_inline)) const double *
tds_torus_shift(const tds_mesh *m, const double *x, double sg, int32_t w, double out[3]) {
  if (!w) return x;
  int k[3];
  tds_wrap_unpack(w, k);
  const double(*p)[3] = m->period; /* written out: see tds_wrap_vec */
  out[0] = x[0] + sg * (k[0] * p[0][0] + k[1] * p[1][0] + k[2] * p[2][0]);
  out[1] = x[1] + sg * (k[0] * p[0][1] + k[1] * p[1][1] + k[2] * p[2][1]);
  out[2] = x[2] + sg * (k[0] * p[0][2] + k[1] * p[1][2] + k[2] * p[2][2]);
  return out;
}

/* Corners of facet f in its orientation: x[k] is vertex fv[f][k]. On a
** torus the corners are unwrapped from the first: x[0] is the first
** vertex's position, x[1] and x[2] follow the facet's edges (so they may
** lie outside the unit cell). */
static inline __attribute__((always_inline)) void
tds_gather_facet(const tds_mesh *m, tds_id f, tds_corners *c) {
  TDS_ASSERT(f >= 0 && f < m->nf);
  const tds_id *fv = m->fv[f];
  if (__builtin_expect(m->torus != 0, 0) && !tds_mesh_rotates(m)) {
    /* translations: the lattice vectors of the edges' wraps, negated
    ** as the edges run (the same numbers as through tds_wrap_inv) */
    const int32_t *fe = m->fe[f];
    c->x[0] = m->x[fv[0]];
    c->x[1] = tds_torus_shift(m, m->x[fv[1]], TDS_OREV(fe[0]) ? -1.0 : 1.0,
                              m->ewrap ? m->ewrap[TDS_OID(fe[0])] : 0, c->tmp[1]);
    c->x[2] = tds_torus_shift(m, m->x[fv[2]], TDS_OREV(fe[2]) ? 1.0 : -1.0,
                              m->ewrap ? m->ewrap[TDS_OID(fe[2])] : 0, c->tmp[2]);
    return;
  }
  if (__builtin_expect(m->torus != 0, 0)) {
    const int32_t *fe = m->fe[f];
    c->x[0] = m->x[fv[0]];
    c->x[1] = tds_wrap_point(m, m->x[fv[1]], tds_oe_wrap(m, fe[0]), c->tmp[1]);
    c->x[2] = tds_wrap_point(m, m->x[fv[2]], tds_corner2_wrap(m, f), c->tmp[2]);
    return;
  }
  c->x[0] = m->x[fv[0]];
  c->x[1] = m->x[fv[1]];
  c->x[2] = m->x[fv[2]];
}

/* Tail and head of oriented edge oe: x[0] tail, x[1] head. */
static inline __attribute__((always_inline)) void
tds_gather_edge(const tds_mesh *m, int32_t oe, tds_corners *c) {
  TDS_ASSERT(oe >= 0 && TDS_OID(oe) < m->ne);
  const tds_id *ev = m->ev[TDS_OID(oe)];
  int r = TDS_OREV(oe);
  c->x[0] = m->x[ev[r]];
  c->x[1] = m->x[ev[!r]];
  if (__builtin_expect(m->torus != 0, 0))
    c->x[1] = tds_wrap_point(m, c->x[1], tds_oe_wrap(m, oe), c->tmp[1]);
}

/* d = head - tail of oriented edge oe. */
static inline __attribute__((always_inline)) void
tds_edge_vec(const tds_mesh *m, int32_t oe, double d[3]) {
  tds_corners c;
  tds_gather_edge(m, oe, &c);
  d[0] = c.x[1][0] - c.x[0][0];
  d[1] = c.x[1][1] - c.x[0][1];
  d[2] = c.x[1][2] - c.x[0][2];
}

#endif
