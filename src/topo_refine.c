/* topo_refine.c: the r command (edge midpoints, facets into 2, 3 or 4). */
#include "string_model.h"
#include "topo.h"

#include <stdlib.h>

#include "gather.h"
#include "method.h"
#include "motion.h"
#include "recalc.h"
#include "ring.h"
#include "snap.h"
#include "torus.h"
#include "vec3.h"

/* Oriented reference to the first (tail side) or second half of the split
** oriented edge oe; edge e now runs tail->mid and e2[e] mid->head. */
static int32_t half(const int32_t *e2, int32_t oe, int second) {
  tds_id e = TDS_OID(oe);
  if (!TDS_OREV(oe)) return second ? TDS_OREF(e2[e], 0) : TDS_OREF(e, 0);
  return second ? TDS_OREF(e, 1) : TDS_OREF(e2[e], 1);
}

void tds_edge_inherit(tds_mesh *m, tds_id dst, tds_id src) {
  m->eflags[dst] = m->eflags[src];
  m->econ[dst] = m->econ[src];
  m->ebdry[dst] = m->ebdry[src];
  m->eten[dst] = m->eten[src];
  m->ecolor[dst] = m->ecolor[src];
  tds_mesh_inherit(m, TDS_EDGE, dst, src);
}

void tds_facet_inherit(tds_mesh *m, tds_id dst, tds_id src) {
  m->fflags[dst] = m->fflags[src];
  m->fcon[dst] = m->fcon[src];
  m->ften[dst] = m->ften[src];
  m->fcolor[dst] = m->fcolor[src];
  m->fb[dst][0] = m->fb[src][0];
  m->fb[dst][1] = m->fb[src][1];
  m->forig[dst] = m->forig[src] != TDS_NONE ? m->forig[src] : src;
  tds_mesh_inherit(m, TDS_FACET, dst, src);
}

/* A new edge inside facet f, from v0 to v1. */
static tds_id inner_edge(tds_mesh *m, tds_id f, tds_id v0, tds_id v1) {
  tds_id e = tds_mesh_add_edge(m, v0, v1);
  m->eflags[e] = m->fflags[f] & (TDS_FIXED | TDS_NO_REFINE);
  m->econ[e] = m->fcon[f];
  return e;
}

/* A new facet like src from three oriented edges; on a torus the edge on
** side `inner` (0..2, or -1: none) is new and gets the wrap that closes
** the facet. */
static tds_id new_facet(tds_mesh *m, tds_id src, int32_t a, int32_t b, int32_t c, int inner) {
  int32_t oe[3] = {a, b, c};
  tds_id f = tds_mesh_add_facet(m, oe);
  tds_facet_inherit(m, f, src);
  if (m->torus && inner >= 0) tds_torus_close(m, f, inner);
  return f;
}

static void set3(tds_mesh *m, tds_id f, int32_t a, int32_t b, int32_t c) {
  int32_t oe[3] = {a, b, c};
  tds_mesh_set_facet(m, f, oe);
}

/* Squared distance from vertex a translated by wrap wa to b translated by
** wb (wraps 0 without a torus). */
static double dist2(const tds_mesh *m, tds_id a, int32_t wa, tds_id b, int32_t wb) {
  double d[3], pa[3], pb[3];
  v3_sub(d, tds_wrap_point(m, m->x[a], wa, pa), tds_wrap_point(m, m->x[b], wb, pb));
  return v3_dot(d, d);
}

/* The product of the wraps round a facet with corners a and edges o, all
** three split (halves in e2), walked from its axial_point corner; 0 when
** it has none. */
static int32_t holonomy(const tds_mesh *m, const tds_id *a, const int32_t *o,
                        const int32_t *e2) {
  int ax = 0;
  while (ax < 3 && !(m->vflags[a[ax]] & TDS_AXIAL)) ax++;
  if (ax == 3) return 0;
  int32_t w = 0;
  for (int i = 0, k = ax; i < 3; i++, k = (k + 1) % 3)
    w = tds_wrap_mul(m, w, tds_wrap_mul(m, tds_oe_wrap(m, half(e2, o[k], 0)),
                                        tds_oe_wrap(m, half(e2, o[k], 1))));
  return w;
}

/* Subdivide facet f, whose edges k have midpoint mid[k] (TDS_NONE if not
** split). Rotates so the split edges come first, then builds triangles. */
static void split_facet(tds_mesh *m, tds_id f, const tds_id *midv,
                        const int32_t *e2) {
  int32_t oe[3];
  tds_id v[3], mid[3];
  int nsplit = 0;
  for (int k = 0; k < 3; k++) {
    oe[k] = m->fe[f][k];
    v[k] = m->fv[f][k];
    mid[k] = midv[TDS_OID(oe[k])];
    nsplit += mid[k] != TDS_NONE;
  }
  if (nsplit == 0) return;
  /* Rotate: for one split edge put it at 0; for two, the unsplit at 2. */
  int r = 0;
  if (nsplit == 1) r = mid[0] != TDS_NONE ? 0 : mid[1] != TDS_NONE ? 1 : 2;
  if (nsplit == 2) r = mid[2] == TDS_NONE ? 0 : mid[0] == TDS_NONE ? 1 : 2;
  int32_t o[3];
  tds_id a[3], mm[3];
  for (int k = 0; k < 3; k++) {
    o[k] = oe[(k + r) % 3];
    a[k] = v[(k + r) % 3];
    mm[k] = mid[(k + r) % 3];
  }
  if (nsplit == 3 && m->torus && holonomy(m, a, o, e2) != 0) {
    /* A facet at an axial_point whose wraps do not multiply to the
    ** identity: the corners' group elements (frames) walked forward from
    ** the axial corner, where the holonomy is absorbed; each inner edge
    ** gets the wrap from its tail's frame to its head's. Otherwise as
    ** below. */
    int ax = 0;
    while (ax < 2 && !(m->vflags[a[ax]] & TDS_AXIAL)) ax++;
    int32_t Fm[3], w = 0;
    for (int i = 0, k = ax; i < 3; i++, k = (k + 1) % 3) {
      w = tds_wrap_mul(m, w, tds_oe_wrap(m, half(e2, o[k], 0)));
      Fm[k] = w;
      w = tds_wrap_mul(m, w, tds_oe_wrap(m, half(e2, o[k], 1)));
    }
    tds_id c0 = inner_edge(m, f, mm[0], mm[2]);
    tds_id c1 = inner_edge(m, f, mm[1], mm[0]);
    tds_id c2 = inner_edge(m, f, mm[2], mm[1]);
    m->ewrap[c0] = tds_wrap_mul(m, tds_wrap_inv(m, Fm[0]), Fm[2]);
    m->ewrap[c1] = tds_wrap_mul(m, tds_wrap_inv(m, Fm[1]), Fm[0]);
    m->ewrap[c2] = tds_wrap_mul(m, tds_wrap_inv(m, Fm[2]), Fm[1]);
    new_facet(m, f, half(e2, o[0], 0), TDS_OREF(c0, 0), half(e2, o[2], 1), -1);
    new_facet(m, f, half(e2, o[0], 1), half(e2, o[1], 0), TDS_OREF(c1, 0), -1);
    new_facet(m, f, TDS_OREF(c2, 0), half(e2, o[1], 1), half(e2, o[2], 0), -1);
    set3(m, f, TDS_OREF(c2, 1), TDS_OREF(c0, 1), TDS_OREF(c1, 1));
  } else if (nsplit == 3) {
    /* Numbered as Evolver numbers them, so element ids after r agree: the
    ** inner edges cut off the corners a0, a1, a2 in turn, each oriented
    ** along its corner triangle; the corner triangles are new facets in
    ** that order, and f becomes the middle one, starting at m1. */
    tds_id c0 = inner_edge(m, f, mm[0], mm[2]);
    tds_id c1 = inner_edge(m, f, mm[1], mm[0]);
    tds_id c2 = inner_edge(m, f, mm[2], mm[1]);
    new_facet(m, f, half(e2, o[0], 0), TDS_OREF(c0, 0), half(e2, o[2], 1), 1);
    new_facet(m, f, half(e2, o[0], 1), half(e2, o[1], 0), TDS_OREF(c1, 0), 2);
    new_facet(m, f, TDS_OREF(c2, 0), half(e2, o[1], 1), half(e2, o[2], 0), 0);
    set3(m, f, TDS_OREF(c2, 1), TDS_OREF(c0, 1), TDS_OREF(c1, 1));
  } else if (nsplit == 2) {
    /* Edges 0 (a0->a1) and 1 (a1->a2) split: corner at a1, then the quad
    ** a0, m0, m1, a2 cut along its shorter diagonal. */
    /* the corners in the facet's frame (torus): m0, then m1 after the
    ** second half of edge 0 and the first of edge 1 */
    int32_t w0 = tds_oe_wrap(m, half(e2, o[0], 0));
    int32_t w1 = tds_wrap_mul(m, w0, tds_wrap_mul(m, tds_oe_wrap(m, half(e2, o[0], 1)),
                                                  tds_oe_wrap(m, half(e2, o[1], 0))));
    int32_t w2 = tds_wrap_mul(m, w1, tds_oe_wrap(m, half(e2, o[1], 1)));
    tds_id ec = inner_edge(m, f, mm[0], mm[1]);
    new_facet(m, f, half(e2, o[0], 1), half(e2, o[1], 0), TDS_OREF(ec, 1), 2);
    if (dist2(m, a[0], 0, mm[1], w1) <= dist2(m, mm[0], w0, a[2], w2)) {
      tds_id d = inner_edge(m, f, a[0], mm[1]);
      new_facet(m, f, TDS_OREF(d, 0), half(e2, o[1], 1), o[2], 0);
      set3(m, f, half(e2, o[0], 0), TDS_OREF(ec, 0), TDS_OREF(d, 1));
    } else {
      tds_id d = inner_edge(m, f, mm[0], a[2]);
      new_facet(m, f, TDS_OREF(ec, 0), half(e2, o[1], 1), TDS_OREF(d, 1), 2);
      set3(m, f, half(e2, o[0], 0), TDS_OREF(d, 0), o[2]);
    }
  } else {
    tds_id d = inner_edge(m, f, mm[0], a[2]);
    new_facet(m, f, half(e2, o[0], 1), o[1], TDS_OREF(d, 1), 2);
    set3(m, f, half(e2, o[0], 0), TDS_OREF(d, 0), o[2]);
  }
}

/* Where Evolver 2.70 puts a new edge vertex under KLEIN_METRIC without a
** symmetry group (measured on every edge of seeded random films: their
** 1/16ths are exact): at the middle, unless the hyperbolic lengths of
** the halves, tail side l1 and head side l2, have l1/l2 outside
** [0.8, 1.2] (so the head's half may be up to 1.25 times the other);
** then by bisection towards the hyperbolic midpoint until it is inside.
** (Under a group Evolver's edge lengths read 0 and its new vertices are
** at the middle.) */
static double klein_split(const double *a, const double *b) {
  double lo = 0, hi = 1, t = 0.5;
  for (int it = 0; it < 60; it++) {
    double p[3];
    for (int i = 0; i < 3; i++) p[i] = a[i] + t * (b[i] - a[i]);
    double l1 = tds_klein_dist(a, p), l2 = tds_klein_dist(p, b);
    if (l1 >= 0.8 * l2 && l1 <= 1.2 * l2) break;
    if (l1 > l2) hi = t;
    else lo = t;
    t = (lo + hi) / 2;
  }
  return t;
}

tds_id tds_edge_midpoint(tds_surf *s, tds_id e) {
  tds_mesh *m = &s->m;
  tds_id t = m->ev[e][0], h = m->ev[e][1];
  double x[3];
  tds_corners C;
  tds_gather_edge(m, TDS_OREF(e, 0), &C);
  v3_add(x, C.x[0], C.x[1]);
  v3_scale(x, 0.5);
  if (s->klein && !m->torus) {
    double u = klein_split(C.x[0], C.x[1]);
    for (int i = 0; i < 3; i++) x[i] = C.x[0][i] + u * (C.x[1][i] - C.x[0][i]);
  }
  tds_id v = tds_mesh_add_vertex(m, x);
  m->vflags[v] = m->eflags[e] & TDS_FIXED;
  m->vcon[v] = m->econ[e] | tds_surf_global_cons(s);
  m->vbdry[v] = m->ebdry[e];
  if (m->ebdry[e] != TDS_NONE) {
    tds_id from = m->vbdry[h] == m->ebdry[e] ? h : t;
    tds_boundary_param_toward(s, m->ebdry[e], x, m->vp[from], m->vp[v]);
  }
  return v;
}

/* Split edge e at its midpoint: e runs tail->mid, e2[e] mid->head. */
static tds_id split_edge(tds_surf *s, tds_id e, int32_t *e2) {
  tds_mesh *m = &s->m;
  tds_id h = m->ev[e][1];
  tds_id v = tds_edge_midpoint(s, e);
  tds_id n = tds_mesh_add_edge(m, v, h);
  m->ev[e][1] = v;
  tds_edge_inherit(m, n, e);
  /* the midpoint is on the unwrapped edge, seen from the tail: the second
  ** half carries the whole wrap */
  if (m->ewrap) {
    m->ewrap[n] = m->ewrap[e];
    m->ewrap[e] = 0;
  }
  e2[e] = n;
  return v;
}

/* The rings of the edges of the facets being split, before: pstart[e] ..
** pstart[e + 1] index the facets of edge e's ring in plist, in order
** (edges of facets not split have none). */
static void save_rings(const tds_mesh *m, int32_t ne, int32_t nf, const tds_id *midv,
                       int32_t *pstart, int32_t *plist) {
  uint8_t *touched = (uint8_t *)(pstart + ne + 1); /* scratch after pstart: see caller */
  for (tds_id e = 0; e < ne; e++) touched[e] = 0;
  for (tds_id f = 0; f < nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    int split = 0;
    for (int k = 0; k < 3; k++) split |= midv[TDS_OID(m->fe[f][k])] != TDS_NONE;
    for (int k = 0; split && k < 3; k++) touched[TDS_OID(m->fe[f][k])] = 1;
  }
  int32_t n = 0;
  for (tds_id e = 0; e < ne; e++) {
    int t = touched[e];
    pstart[e] = n;
    int32_t h = m->eside[e], sd = h;
    if (t && h != TDS_NONE) do {
      plist[n++] = sd / 3;
      sd = m->side_next[sd];
    } while (sd != h);
  }
  pstart[ne] = n;
}

/* Put the rings of edge e's halves (or of e itself, not split) back in the
** order of its parent ring plist[a..b) (ring.h): the facet of each half
** descended from parent p is found through par (a facet's parent). */
static void restore_ring(tds_mesh *m, tds_id e, int second, const int32_t *plist, int32_t a,
                         int32_t b, int32_t nf, const tds_id *par) {
  int n = b - a;
  if (n < 1 || n > TDS_RING_MAX || tds_edge_valence(m, e) != n) return;
  int32_t have[TDS_RING_MAX], out[TDS_RING_MAX];
  int32_t h = m->eside[e], sd = h;
  int k = 0;
  do {
    have[k++] = sd;
    sd = m->side_next[sd];
  } while (sd != h);
  for (int i = 0; i < n; i++) {
    tds_id p = plist[a + (second ? (i + n - 1) % n : i)];
    int found = -1;
    for (int j = 0; j < n; j++) {
      tds_id g = have[j] / 3;
      if (have[j] >= 0 && (g < nf ? g : par[g - nf]) == p) {
        found = j;
        break;
      }
    }
    if (found < 0) return; /* a facet twice on the edge: leave it */
    out[i] = have[found];
    have[found] = -1;
  }
  tds_ring_set(m, e, out, n);
}

static int refine(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *nsplit) {
  tds_mesh *m = &s->m;
  int32_t ne = m->ne, nf = m->nf, nv0 = m->nv;
  tds_id *midv = tds_malloc(&s->m.alloc, (size_t)(ne > 0 ? ne : 1) * sizeof *midv);
  int32_t *e2 = tds_malloc(&s->m.alloc, (size_t)(ne > 0 ? ne : 1) * sizeof *e2);
  if (!midv || !e2) {
    tds_free(&s->m.alloc, midv);
    tds_free(&s->m.alloc, e2);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int32_t nsp = 0, nnewf = 0, nnewe = 0;
  for (tds_id e = 0; e < ne; e++) {
    midv[e] = TDS_NONE;
    e2[e] = TDS_NONE;
    int want = sel ? sel[e] : !(m->eflags[e] & TDS_NO_REFINE);
    if (want && tds_alive(m->eflags, e)) {
      midv[e] = 0; /* marked; vertex made below */
      nsp++;
    }
  }
  for (tds_id f = 0; f < nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    int k = 0;
    for (int j = 0; j < 3; j++) k += midv[TDS_OID(m->fe[f][j])] != TDS_NONE;
    nnewf += k; /* 3 split: +3 facets, 2: +2, 1: +1 */
    nnewe += k; /* and as many inner edges */
  }
  /* Reserve exactly, so nothing below can fail. pstart has ne + 1 entries
  ** and room for ne flags after them (save_rings' scratch). */
  int32_t *pstart = tds_malloc(&s->m.alloc, (size_t)(ne + 1) * sizeof *pstart + (size_t)ne + 1);
  int32_t *plist = tds_malloc(&s->m.alloc, (size_t)(3 * nf + 1) * sizeof *plist);
  tds_id *par = tds_malloc(&s->m.alloc, (size_t)(nnewf + 1) * sizeof *par);
  if (!pstart || !plist || !par || tds_mesh_reserve(m, TDS_VERTEX, nv0 + nsp) ||
      tds_mesh_reserve(m, TDS_EDGE, ne + nsp + nnewe) ||
      tds_mesh_reserve(m, TDS_FACET, nf + nnewf)) {
    tds_free(&s->m.alloc, midv);
    tds_free(&s->m.alloc, e2);
    tds_free(&s->m.alloc, pstart);
    tds_free(&s->m.alloc, plist);
    tds_free(&s->m.alloc, par);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory while refining");
  }
  for (tds_id e = 0; e < ne; e++)
    if (midv[e] != TDS_NONE) midv[e] = split_edge(s, e, e2);
  /* the string model's cells take the new halves (the snapshot of
  ** tds_refine puts everything back if this fails) */
  if (s->str && tds_strings_split(s->str, e2, ne) != TDS_OK) {
    tds_free(&s->m.alloc, midv);
    tds_free(&s->m.alloc, e2);
    tds_free(&s->m.alloc, pstart);
    tds_free(&s->m.alloc, plist);
    tds_free(&s->m.alloc, par);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory while refining");
  }
  /* Evolver's facet order around the edges (ring.h): the rings before,
  ** each new facet's parent, the rings put back in order after */
  save_rings(m, ne, nf, midv, pstart, plist);
  for (tds_id f = 0; f < nf; f++)
    if (tds_alive(m->fflags, f)) {
      int32_t f0 = m->nf;
      split_facet(m, f, midv, e2);
      for (tds_id g = f0; g < m->nf; g++) par[g - nf] = f;
    }
  for (tds_id e = 0; e < ne; e++) {
    if (pstart[e] == pstart[e + 1]) continue;
    restore_ring(m, e, 0, plist, pstart[e], pstart[e + 1], nf, par);
    if (e2[e] != TDS_NONE) restore_ring(m, e2[e], 1, plist, pstart[e], pstart[e + 1], nf, par);
  }
  tds_free(&s->m.alloc, midv);
  tds_free(&s->m.alloc, e2);
  tds_free(&s->m.alloc, pstart);
  tds_free(&s->m.alloc, plist);
  tds_free(&s->m.alloc, par);
  int bad = 0;
  for (tds_id v = nv0; v < m->nv; v++)
    if (tds_motion_enforce(s, v) != TDS_OK) bad++;
  m->coord_gen++;
  if (nsplit) *nsplit = nsp;
  if (bad)
    tds_warnf(ctx, "refine: %d new vertices could not be projected onto "
              "their constraints\n", bad);
  /* As Evolver: new vertices are made from the positions as they were, and
  ** then the whole surface follows changed parameters. */
  if (s->placed_gen != s->param_gen && tds_recalc(ctx, s) != TDS_OK)
    tds_warnf(ctx, "refine: %s\n", ctx->errmsg);
  return tds_surf_update(ctx, s);
}

/* All or nothing: a failure (out of memory, a non-finite energy after the
** split) leaves the surface as it was. */
int tds_refine(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *nsplit) {
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  return tds_snap_end(ctx, s, &sn, refine(ctx, s, sel, nsplit));
}
