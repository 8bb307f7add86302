/*
** torus_clip.c: the CLIPPED case of tds_torus_detorus (torus.h). Every
** facet, drawn from its first corner, is cut by the faces of the clip box
** and of its translates, and each piece is moved into the box.
**
** The work is in lattice coordinates relative to the box (the box is
** [0,1]^3), so that a point two facets share comes out with the same bits
** in both: a corner is its vertex's coordinates plus whole numbers (one
** addition), a cut point is computed from its segment's ends taken in a
** fixed order, with the coordinate across the cut set to the plane's
** value. Points with the same bits are one vertex, segments between the
** same two vertices one edge. A piece lying in an upper face of the box is
** dropped (the next translate has it in its lower face).
*/
#include "torus.h"

#include <math.h>
#include <string.h>

#include "gather.h"
#include "topo.h"

enum { MAXP = 12 }; /* a triangle cut by six planes has at most 9 points */

typedef struct pt {
  double c[3]; /* a corner: its vertex's coordinates, before adding off */
  int off[3];  /* a corner's whole-cell offset (0 once placed in a cell) */
  tds_id src;  /* vertex of the torus mesh, or the one a cut point inherits from */
  int cut;     /* made by a cut */
} pt;

typedef struct poly {
  int n;
  pt p[MAXP];
  int32_t side[MAXP]; /* edge of the torus mesh under p[i] -> p[i+1], or -1 */
} poly;

static int lexless(const double a[3], const double b[3]) {
  for (int j = 0; j < 3; j++)
    if (a[j] != b[j]) return a[j] < b[j];
  return 0;
}

/* The point of segment ab on plane c[axis] = val (a, b on either side). */
static pt cut_point(const pt *a, const pt *b, int axis, double val) {
  if (lexless(b->c, a->c)) { /* the same bits whichever way the segment runs */
    const pt *t = a;
    a = b;
    b = t;
  }
  double t = (a->c[axis] - val) / (a->c[axis] - b->c[axis]);
  pt x;
  for (int j = 0; j < 3; j++) x.c[j] = a->c[j] + t * (b->c[j] - a->c[j]);
  x.c[axis] = val;
  memset(x.off, 0, sizeof x.off);
  x.src = a->src;
  x.cut = 1;
  return x;
}

/* out = the part of in where sg (c[axis] - val) >= 0 (Sutherland and
** Hodgman), with the sides' edges: a side the plane cuts off becomes -1. */
static void clip(const poly *in, poly *out, int axis, double val, double sg) {
  out->n = 0;
  for (int i = 0; i < in->n; i++) {
    const pt *a = &in->p[i], *b = &in->p[(i + 1) % in->n];
    double da = sg * (a->c[axis] - val), db = sg * (b->c[axis] - val);
    if (da >= 0) {
      out->p[out->n] = *a;
      out->side[out->n++] = db < 0 && da == 0 ? -1 : in->side[i];
      if (da > 0 && db < 0) {
        out->p[out->n] = cut_point(a, b, axis, val);
        out->side[out->n++] = -1;
      }
    } else if (db > 0) {
      out->p[out->n] = cut_point(a, b, axis, val);
      out->side[out->n++] = in->side[i];
    }
  }
}

/* Hash of points (by their bits) and of vertex pairs, to ids. */
typedef struct table {
  uint64_t *key; /* 3 words a point, 1 a pair; 0 = empty for pairs */
  int32_t *id;
  uint32_t mask;
  int words;
} table;

static int table_init(tds_alloc *a, table *t, size_t n, int words) {
  size_t cap = 16;
  while (cap < 2 * n) cap *= 2;
  t->mask = (uint32_t)cap - 1;
  t->words = words;
  t->key = tds_calloc(a, cap * (size_t)words, sizeof *t->key);
  t->id = tds_malloc(a, cap * sizeof *t->id);
  if (!t->key || !t->id) return TDS_ENOMEM;
  for (size_t i = 0; i < cap; i++) t->id[i] = -1;
  return TDS_OK;
}

static void table_free(tds_alloc *a, table *t) {
  tds_free(a, t->key);
  tds_free(a, t->id);
}

/* The slot of key k: found (id >= 0) or empty. */
static uint32_t table_slot(const table *t, const uint64_t *k) {
  uint64_t h = 1469598103934665603u;
  for (int w = 0; w < t->words; w++) h = (h ^ k[w]) * 1099511628211u;
  for (uint32_t s = (uint32_t)(h ^ h >> 29) & t->mask;; s = (s + 1) & t->mask)
    if (t->id[s] < 0 || !memcmp(t->key + (size_t)s * (size_t)t->words, k, (size_t)t->words * 8))
      return s;
}

typedef struct builder {
  tds_mesh *m;
  const double *lo;
  table pts, pairs;
  int32_t *vsrc; /* grows with the vertices */
} builder;

static tds_id vertex_of(builder *B, const pt *p) {
  uint64_t k[3];
  memcpy(k, p->c, sizeof k);
  uint32_t s = table_slot(&B->pts, k);
  if (B->pts.id[s] >= 0) return B->pts.id[s];
  tds_mesh *m = B->m;
  double y[3], x[3] = {0, 0, 0};
  for (int i = 0; i < 3; i++) y[i] = p->c[i] + B->lo[i];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) x[j] += y[i] * m->period[i][j];
  tds_id v = tds_mesh_add_vertex(m, x);
  m->vflags[v] = m->vflags[p->src] & ~(uint32_t)TDS_BARE;
  m->vcon[v] = m->vcon[p->src];
  m->vbdry[v] = m->vbdry[p->src];
  memcpy(m->vp[v], m->vp[p->src], sizeof m->vp[v]);
  tds_mesh_inherit(m, TDS_VERTEX, v, p->src);
  B->vsrc[v] = p->cut ? -1 : p->src;
  memcpy(B->pts.key + 3 * (size_t)s, k, sizeof k);
  B->pts.id[s] = v;
  return v;
}

/* The oriented edge from a to b (made, inheriting from edge e >= 0). */
static int32_t edge_of(builder *B, tds_id a, tds_id b, int32_t e) {
  uint64_t k = (uint64_t)(uint32_t)(a < b ? a : b) << 32 | (uint32_t)(a < b ? b : a);
  k += 1; /* 0 is never a key */
  uint32_t s = table_slot(&B->pairs, &k);
  tds_id id = B->pairs.id[s];
  if (id < 0) {
    id = tds_mesh_add_edge(B->m, a, b);
    if (e >= 0) tds_edge_inherit(B->m, id, e);
    B->pairs.key[s] = k;
    B->pairs.id[s] = id;
  }
  return TDS_OREF(id, B->m->ev[id][0] != a);
}

/* Whether every point of P lies on the face c[axis] = 1 for some axis. */
static int on_upper_face(const poly *P) {
  for (int axis = 0; axis < 3; axis++) {
    int all = 1;
    for (int i = 0; i < P->n && all; i++) all = P->p[i].c[axis] == 1.0;
    if (all) return 1;
  }
  return 0;
}

/* The lattice range of cells a set of points reaches: floor of min..max. */
static void cell_range(const pt *p, int n, int lo[3], int hi[3]) {
  for (int j = 0; j < 3; j++) {
    double a = p[0].c[j] + p[0].off[j], b = a;
    for (int i = 1; i < n; i++) {
      double x = p[i].c[j] + p[i].off[j];
      if (x < a) a = x;
      if (x > b) b = x;
    }
    lo[j] = (int)floor(a);
    hi[j] = (int)floor(b);
  }
}

/* The pieces of facet f (corners P, in cell-relative lattice coordinates)
** as new facets. */
static void add_pieces(builder *B, tds_id f, const poly *P, int32_t *fsrc) {
  int lo[3], hi[3];
  cell_range(P->p, P->n, lo, hi);
  for (int a = lo[0]; a <= hi[0]; a++)
    for (int b = lo[1]; b <= hi[1]; b++)
      for (int c = lo[2]; c <= hi[2]; c++) {
        poly Q = *P, R;
        const int n[3] = {a, b, c};
        for (int i = 0; i < Q.n; i++) /* one rounding: the same bits from every facet */
          for (int j = 0; j < 3; j++) {
            Q.p[i].c[j] = P->p[i].c[j] + (double)(P->p[i].off[j] - n[j]);
            Q.p[i].off[j] = 0;
          }
        for (int axis = 0; axis < 3; axis++) {
          clip(&Q, &R, axis, 0.0, 1.0);
          clip(&R, &Q, axis, 1.0, -1.0);
        }
        if (Q.n < 3 || on_upper_face(&Q)) continue;
        tds_id v[MAXP];
        for (int i = 0; i < Q.n; i++) v[i] = vertex_of(B, &Q.p[i]);
        for (int i = 1; i + 1 < Q.n; i++) { /* a fan from the first point */
          int32_t oe[3] = {edge_of(B, v[0], v[i], i == 1 ? Q.side[0] : -1),
                           edge_of(B, v[i], v[i + 1], Q.side[i]),
                           edge_of(B, v[i + 1], v[0], i + 2 == Q.n ? Q.side[Q.n - 1] : -1)};
          tds_id g = tds_mesh_add_facet(B->m, oe);
          tds_facet_inherit(B->m, g, f);
          fsrc[g] = f;
        }
      }
}

/* Facet f's corners in cell-relative lattice coordinates. */
static void facet_poly(const tds_mesh *m, const double (*L)[3], tds_id f, poly *P) {
  P->n = 3;
  for (int k = 0; k < 3; k++) {
    int kk[3];
    tds_id v = m->fv[f][k];
    tds_wrap_unpack(tds_torus_corner_wrap(m, f, k), kk);
    memcpy(P->p[k].c, L[v], sizeof P->p[k].c);
    memcpy(P->p[k].off, kk, sizeof kk);
    P->p[k].src = v;
    P->p[k].cut = 0;
    P->side[k] = TDS_OID(m->fe[f][k]);
  }
}

/* Edge e's ends (the head unwrapped from the tail) as facet_poly's. */
static void edge_points(const tds_mesh *m, const double (*L)[3], tds_id e, pt p[2]) {
  int kk[3];
  tds_wrap_unpack(m->ewrap[e], kk);
  for (int k = 0; k < 2; k++) {
    tds_id v = m->ev[e][k];
    memcpy(p[k].c, L[v], sizeof p[k].c);
    for (int j = 0; j < 3; j++) p[k].off[j] = k ? kk[j] : 0;
    p[k].src = v;
    p[k].cut = 0;
  }
}

/* Bare edge e (no facets) cut into the box. */
static void add_segment(builder *B, tds_id e, const double (*L)[3]) {
  int lo[3], hi[3];
  pt p[2];
  edge_points(B->m, L, e, p);
  cell_range(p, 2, lo, hi);
  for (int a = lo[0]; a <= hi[0]; a++)
    for (int b = lo[1]; b <= hi[1]; b++)
      for (int c = lo[2]; c <= hi[2]; c++) {
        const int n[3] = {a, b, c};
        pt q[2] = {p[0], p[1]};
        for (int k = 0; k < 2; k++)
          for (int j = 0; j < 3; j++) {
            q[k].c[j] = p[k].c[j] + (double)(p[k].off[j] - n[j]);
            q[k].off[j] = 0;
          }
        int keep = 1;
        for (int axis = 0; axis < 3 && keep; axis++)
          for (int side = 0; side < 2 && keep; side++) {
            double val = side, sg = side ? -1.0 : 1.0;
            double d0 = sg * (q[0].c[axis] - val), d1 = sg * (q[1].c[axis] - val);
            if (d0 < 0 && d1 < 0) keep = 0;
            else if (d0 < 0) q[0] = cut_point(&q[0], &q[1], axis, val);
            else if (d1 < 0) q[1] = cut_point(&q[0], &q[1], axis, val);
          }
        if (!keep || !memcmp(q[0].c, q[1].c, sizeof q[0].c)) continue;
        poly P = {2, {q[0], q[1]}, {0}};
        if (on_upper_face(&P)) continue;
        edge_of(B, vertex_of(B, &q[0]), vertex_of(B, &q[1]), e);
      }
}

/* Cells a point list reaches, for the room to reserve. */
static size_t cells(const pt *p, int n) {
  int lo[3], hi[3];
  cell_range(p, n, lo, hi);
  return (size_t)(hi[0] - lo[0] + 1) * (size_t)(hi[1] - lo[1] + 1) * (size_t)(hi[2] - lo[2] + 1);
}

int tds_torus_clip(tds_ctx *ctx, tds_mesh *m, int32_t *src[2]) {
  if (tds_mesh_rotates(m))
    return tds_seterr(ctx, TDS_ERANGE,
                      "clipped: SYMMETRY_GROUP \"%s\" has no unit cell to clip to "
                      "(use raw_cells or connected)",
                      tds_sym_name(m->sym));
  int32_t nv = m->nv, ne = m->ne, nf = m->nf;
  tds_alloc *a = &m->alloc;
  double lo[3];
  tds_torus_box(m, lo);
  builder B = {m, lo, {0}, {0}, NULL};
  int32_t *fsrc = NULL;
  double(*L)[3] = tds_malloc(a, (size_t)(nv > 0 ? nv : 1) * sizeof *L);
  int rc = L ? TDS_OK : TDS_ENOMEM;
  if (rc) goto fail;
  for (tds_id v = 0; v < nv; v++) {
    tds_torus_to_lattice(m, m->x[v], L[v]);
    for (int j = 0; j < 3; j++) L[v][j] -= lo[j];
  }
  /* room: a piece has at most 9 points, 7 triangles and 15 edges */
  size_t np = 0, ns = 0;
  for (tds_id f = 0; f < nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    poly P;
    facet_poly(m, (const double(*)[3])L, f, &P);
    np += cells(P.p, 3);
  }
  for (tds_id e = 0; e < ne; e++) {
    if (!tds_alive(m->eflags, e) || m->eside[e] != TDS_NONE) continue;
    pt p[2];
    edge_points(m, (const double(*)[3])L, e, p);
    ns += cells(p, 2);
  }
  size_t room_v = 9 * np + 2 * ns + 1, room_e = 15 * np + ns + 1, room_f = 7 * np + 1;
  if (room_v + (size_t)nv > INT32_MAX / 2 || room_e + (size_t)ne > INT32_MAX / 2 ||
      room_f + (size_t)nf > INT32_MAX / 2) {
    rc = TDS_ENOMEM;
    goto fail;
  }
  rc = table_init(a, &B.pts, room_v, 3);
  if (!rc) rc = table_init(a, &B.pairs, room_e, 1);
  if (!rc && (tds_mesh_reserve(m, TDS_VERTEX, nv + (int32_t)room_v) ||
              tds_mesh_reserve(m, TDS_EDGE, ne + (int32_t)room_e) ||
              tds_mesh_reserve(m, TDS_FACET, nf + (int32_t)room_f)))
    rc = TDS_ENOMEM;
  if (!rc && !(B.vsrc = tds_malloc(a, ((size_t)nv + room_v + 1) * sizeof *B.vsrc))) rc = TDS_ENOMEM;
  if (!rc && !(fsrc = tds_malloc(a, ((size_t)nf + room_f + 1) * sizeof *fsrc))) rc = TDS_ENOMEM;
  if (rc) goto fail;
  for (size_t f = 0; f < (size_t)nf + room_f; f++) fsrc[f] = -1;
  for (tds_id f = 0; f < nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    poly P;
    facet_poly(m, (const double(*)[3])L, f, &P);
    add_pieces(&B, f, &P, fsrc);
  }
  for (tds_id e = 0; e < ne; e++)
    if (tds_alive(m->eflags, e) && m->eside[e] == TDS_NONE) add_segment(&B, e, (const double(*)[3])L);
  /* the torus mesh's elements go, but for vertices on no edge, which are
  ** moved into the box */
  for (tds_id f = 0; f < nf; f++)
    if (tds_alive(m->fflags, f)) tds_mesh_kill(m, TDS_FACET, f);
  for (tds_id v = 0; v < nv; v++) B.vsrc[v] = -2; /* -2: on no edge so far */
  for (tds_id e = 0; e < ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    B.vsrc[m->ev[e][0]] = B.vsrc[m->ev[e][1]] = -1;
    tds_mesh_kill(m, TDS_EDGE, e);
  }
  for (tds_id v = 0; v < nv; v++) {
    if (!tds_alive(m->vflags, v)) continue;
    if (B.vsrc[v] == -1) {
      tds_mesh_kill(m, TDS_VERTEX, v);
      continue;
    }
    for (int i = 0; i < 3; i++) {
      double k = -floor(L[v][i]);
      for (int j = 0; j < 3; j++) m->x[v][j] += k * m->period[i][j];
    }
    B.vsrc[v] = v;
  }
  for (tds_id e = 0; e < m->ne; e++) m->ewrap[e] = 0;
  tds_mesh_set_torus(m, 0);
  m->topo_gen++;
  m->coord_gen++;
  if (src) {
    src[0] = B.vsrc;
    src[1] = fsrc;
    B.vsrc = fsrc = NULL;
  }
fail:
  if (rc) { /* only new elements were made: drop them */
    for (tds_id f = nf; f < m->nf; f++)
      if (tds_alive(m->fflags, f)) tds_mesh_kill(m, TDS_FACET, f);
    tds_mesh_truncate(m, TDS_FACET, nf);
    tds_mesh_truncate(m, TDS_EDGE, ne);
    tds_mesh_truncate(m, TDS_VERTEX, nv);
  }
  tds_free(a, L);
  table_free(a, &B.pts);
  table_free(a, &B.pairs);
  tds_free(a, B.vsrc);
  tds_free(a, fsrc);
  return rc ? tds_seterr(ctx, rc, "out of memory") : TDS_OK;
}
