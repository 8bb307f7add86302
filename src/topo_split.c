/* topo_split.c: l (edge_divide), K (skinny triangles), n (notch) and
** edgeswap. */
#include "torus.h"
#include "topo_edit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gather.h"
#include "geom.h"
#include "motion.h"
#include "snap.h"
#include "string_model.h"
#include "topo.h"
#include "vec3.h"

static double edge_len(const tds_mesh *m, tds_id e) {
  tds_corners C;
  tds_gather_edge(m, TDS_OREF(e, 0), &C);
  double d[3];
  v3_sub(d, C.x[1], C.x[0]);
  return v3_norm(d);
}

static int check_cut(tds_ctx *ctx, double v, const char *what) {
  if (!isfinite(v)) return tds_seterr(ctx, TDS_ERANGE, "%s must be a finite number", what);
  return TDS_OK;
}

/* Split edge e at its midpoint as Evolver's l does, one edge at a time:
** e keeps its tail half, a new edge takes the head half (mid -> head), and
** each facet on e is cut by a new edge from the midpoint to its opposite
** vertex; the facet keeps the part with the head half, a new facet takes
** the other. The new vertex inherits fixedness, constraints and boundary
** from the edge and is projected onto them. Room must be reserved: 1
** vertex, 1 + valence edges, valence facets. Returns the new edge (the
** head half). */
static tds_id split_one(tds_surf *s, tds_id e) {
  tds_mesh *m = &s->m;
  tds_id h = m->ev[e][1];
  tds_id v = tds_edge_midpoint(s, e);
  /* The facets on e, before the rings change. */
  int nfe = tds_edge_valence(m, e);
  tds_id fs[nfe > 0 ? nfe : 1];
  int ks[nfe > 0 ? nfe : 1];
  if (nfe) {
    int32_t sd = m->eside[e];
    for (int i = 0; i < nfe; i++, sd = m->side_next[sd]) {
      fs[i] = sd / 3;
      ks[i] = sd % 3;
    }
    for (int i = 1; i < nfe; i++) /* in facet id order */
      for (int j = i; j > 0 && fs[j - 1] > fs[j]; j--) {
        tds_id tf = fs[j];
        fs[j] = fs[j - 1];
        fs[j - 1] = tf;
        int tk = ks[j];
        ks[j] = ks[j - 1];
        ks[j - 1] = tk;
      }
  }
  tds_id n = tds_mesh_add_edge(m, v, h);
  tds_edge_inherit(m, n, e);
  m->ev[e][1] = v;
  /* torus: the midpoint is on the edge unwrapped from its tail, so the
  ** head half carries the whole wrap (as r's split) */
  if (m->ewrap) {
    m->ewrap[n] = m->ewrap[e];
    m->ewrap[e] = 0;
  }
  for (int i = 0; i < nfe; i++) {
    tds_id f = fs[i];
    int k = ks[i];
    int32_t o0 = m->fe[f][k], o1 = m->fe[f][(k + 1) % 3], o2 = m->fe[f][(k + 2) % 3];
    tds_id c = tds_oe_head(m, o1); /* opposite vertex */
    tds_id d = tds_mesh_add_edge(m, v, c);
    m->eflags[d] = m->fflags[f] & (TDS_FIXED | TDS_NO_REFINE);
    m->econ[d] = m->fcon[f];
    int32_t first, second; /* halves of o0 in the facet's direction */
    if (!TDS_OREV(o0)) {
      first = TDS_OREF(e, 0);  /* t -> v */
      second = TDS_OREF(n, 0); /* v -> h */
    } else {
      first = TDS_OREF(n, 1);  /* h -> v */
      second = TDS_OREF(e, 1); /* v -> t */
    }
    /* Facet a -> b -> c with o0 = a->b: parts (a, v, c) and (v, b, c);
    ** the facet keeps the part with the head half (listed from the new
    ** inner edge), the new facet gets the one with e (listed from e). */
    int32_t pa[3], pb[3];
    if (!TDS_OREV(o0)) {
      int32_t add3[3] = {first, TDS_OREF(d, 0), o2}, keep3[3] = {TDS_OREF(d, 1), second, o1};
      memcpy(pa, add3, sizeof pa);
      memcpy(pb, keep3, sizeof pb);
    } else {
      int32_t add3[3] = {second, o1, TDS_OREF(d, 1)}, keep3[3] = {TDS_OREF(d, 0), o2, first};
      memcpy(pa, add3, sizeof pa);
      memcpy(pb, keep3, sizeof pb);
    }
    int32_t *add = pa, *keep = pb;
    tds_id g = tds_mesh_add_facet(m, add);
    tds_facet_inherit(m, g, f);
    /* the inner edge d closes the new facet (the kept one then closes) */
    if (m->ewrap) tds_torus_close(m, g, TDS_OID(add[1]) == d ? 1 : 2);
    tds_mesh_set_facet(m, f, keep);
  }
  m->topo_gen++;
  tds_motion_enforce(s, v);
  return n;
}

/* Make room for splitting one more edge of valence nfe. */
static int room_for_split(tds_mesh *m, int nfe) {
  if (tds_mesh_room(m, TDS_VERTEX, m->nv + 1) ||
      tds_mesh_room(m, TDS_EDGE, m->ne + 1 + nfe) ||
      tds_mesh_room(m, TDS_FACET, m->nf + nfe))
    return TDS_ENOMEM;
  return TDS_OK;
}

/* Split, once each and in id order, the live edges longer than len,
** or with sel the selected ones (len ignored). */
static int divide_some(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, double len, int32_t *n) {
  tds_mesh *m = &s->m;
  int32_t ne0 = m->ne, cnt = 0;
  /* the string model: the cells' loops take both halves of a split edge
  ** (tds_strings_split), as after r */
  tds_id *half = NULL;
  if (s->str) {
    half = tds_malloc(&m->alloc, ((size_t)ne0 + 1) * sizeof *half);
    if (!half) return tds_seterr(ctx, TDS_ENOMEM, "out of memory while dividing edges");
    for (tds_id e = 0; e < ne0; e++) half[e] = TDS_NONE;
  }
  for (tds_id e = 0; e < ne0; e++) {
    if (!tds_alive(m->eflags, e) || (sel ? !sel[e] : !(edge_len(m, e) > len))) continue;
    if (room_for_split(m, tds_edge_valence(m, e)) != TDS_OK) {
      tds_free(&m->alloc, half);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory while dividing edges");
    }
    tds_id h = split_one(s, e);
    if (half) half[e] = h;
    cnt++;
  }
  int rc = half && cnt ? tds_strings_split(s->str, half, ne0) : TDS_OK;
  tds_free(&m->alloc, half);
  if (rc != TDS_OK) return tds_seterr(ctx, rc, "out of memory while dividing edges");
  *n = cnt;
  if (cnt) m->coord_gen++;
  return tds_surf_update(ctx, s);
}

static int divide(tds_ctx *ctx, tds_surf *s, double len, int32_t *n) {
  return divide_some(ctx, s, NULL, len, n);
}

static int divide_set(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  return divide_some(ctx, s, sel, 0, n);
}

static double min_angle(const tds_mesh *m, tds_id f, int *klong) {
  tds_corners C;
  tds_gather_facet(m, f, &C);
  double amin = INFINITY, lmax = -1;
  for (int k = 0; k < 3; k++) {
    double a = geom_angle(C.x[k], C.x[(k + 1) % 3], C.x[(k + 2) % 3]);
    if (a < amin) amin = a;
    double l = edge_len(m, TDS_OID(m->fe[f][k]));
    if (l > lmax) {
      lmax = l;
      *klong = k;
    }
  }
  return amin;
}

static int skinny(tds_ctx *ctx, tds_surf *s, double angle, int32_t *n) {
  tds_mesh *m = &s->m;
  int32_t nf0 = m->nf, cnt = 0;
  uint8_t *done = tds_calloc(&m->alloc, (size_t)nf0 + 1, 1);
  if (!done) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (tds_id f = 0; f < nf0; f++) {
    int k = 0;
    if (done[f] || !tds_alive(m->fflags, f) || !(min_angle(m, f, &k) < angle)) continue;
    tds_id e = TDS_OID(m->fe[f][k]);
    if (room_for_split(m, tds_edge_valence(m, e)) != TDS_OK) {
      tds_free(&m->alloc, done);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory while splitting edges");
    }
    for (int32_t sd = m->eside[e], i = 0; sd != TDS_NONE && (i == 0 || sd != m->eside[e]); sd = m->side_next[sd], i++)
      if (sd / 3 < nf0) done[sd / 3] = 1;
    (void)split_one(s, e);
    cnt++;
  }
  tds_free(&m->alloc, done);
  *n = cnt;
  if (cnt) m->coord_gen++;
  return tds_surf_update(ctx, s);
}

typedef int (*cut_fn)(tds_ctx *, tds_surf *, double, int32_t *);

static int with_snap(tds_ctx *ctx, tds_surf *s, cut_fn fn, double v, int32_t *n) {
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  int32_t cnt = 0;
  rc = tds_snap_end(ctx, s, &sn, fn(ctx, s, v, &cnt));
  if (n) *n = rc == TDS_OK ? cnt : 0;
  return rc;
}

int tds_edge_divide(tds_ctx *ctx, tds_surf *s, double len, int32_t *n) {
  if (n) *n = 0;
  int rc = check_cut(ctx, len, "the edge length");
  return rc != TDS_OK ? rc : with_snap(ctx, s, divide, len, n);
}

int tds_edge_divide_set(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  /* strings have no facets to cut; the torus splits edges as r does */
  if (s->m.torus || s->str) return tds_refine(ctx, s, sel, n);
  if (n) *n = 0;
  return tds_snap_run(ctx, s, divide_set, sel, n);
}

int tds_skinny(tds_ctx *ctx, tds_surf *s, double angle, int32_t *n) {
  if (n) *n = 0;
  int rc = check_cut(ctx, angle, "the angle");
  return rc != TDS_OK ? rc : with_snap(ctx, s, skinny, angle, n);
}

/* Split facet f into three at its centroid. Room must be reserved. */
static void split_centre(tds_surf *s, tds_id f) {
  tds_mesh *m = &s->m;
  tds_corners C;
  tds_gather_facet(m, f, &C);
  double x[3] = {0, 0, 0};
  for (int k = 0; k < 3; k++) v3_add(x, x, C.x[k]);
  v3_scale(x, 1.0 / 3);
  /* torus: c is in the first corner's frame; corner k's spoke gets the
  ** inverse of the corner's wrap, so all three parts close */
  int32_t cw[3] = {0, 0, 0};
  if (m->ewrap)
    for (int k = 1; k < 3; k++) cw[k] = tds_wrap_inv(m, tds_torus_corner_wrap(m, f, k));
  tds_id c = tds_mesh_add_vertex(m, x);
  m->vflags[c] = m->fflags[f] & TDS_FIXED;
  m->vcon[c] = m->fcon[f] | tds_surf_global_cons(s);
  tds_id sp[3];
  for (int k = 0; k < 3; k++) {
    sp[k] = tds_mesh_add_edge(m, m->fv[f][k], c);
    if (m->ewrap) m->ewrap[sp[k]] = cw[k];
    m->eflags[sp[k]] = m->fflags[f] & (TDS_FIXED | TDS_NO_REFINE);
    m->econ[sp[k]] = m->fcon[f];
  }
  int32_t oe[3] = {m->fe[f][0], m->fe[f][1], m->fe[f][2]};
  for (int k = 1; k < 3; k++) {
    int32_t t[3] = {oe[k], TDS_OREF(sp[(k + 1) % 3], 0), TDS_OREF(sp[k], 1)};
    tds_id g = tds_mesh_add_facet(m, t);
    tds_facet_inherit(m, g, f);
  }
  int32_t t0[3] = {oe[0], TDS_OREF(sp[1], 0), TDS_OREF(sp[0], 1)};
  tds_mesh_set_facet(m, f, t0);
  tds_motion_enforce(s, c);
}

static void normal(double n[3], const double *a, const double *b, const double *c) {
  double u[3], v[3];
  v3_sub(u, b, a);
  v3_sub(v, c, a);
  v3_cross(n, u, v);
}

/* The angle between the normals of the two facets on e, as seen
** consistently across e; -1 when e does not have exactly two facets. */
static double crease(const tds_mesh *m, tds_id e, tds_id *fa, tds_id *fb) {
  int32_t h = m->eside[e];
  if (h == TDS_NONE) return -1;
  int32_t h2 = m->side_next[h];
  if (h2 == h || m->side_next[h2] != h) return -1;
  tds_id a = h / 3, b = h2 / 3;
  if (a == b) return -1;
  double na[3], nb[3];
  tds_corners C;
  tds_gather_facet(m, a, &C);
  normal(na, C.x[0], C.x[1], C.x[2]);
  tds_gather_facet(m, b, &C);
  normal(nb, C.x[0], C.x[1], C.x[2]);
  if (TDS_OREV(m->fe[a][h % 3]) == TDS_OREV(m->fe[b][h2 % 3])) v3_scale(nb, -1);
  double w[3];
  v3_cross(w, na, nb);
  *fa = a;
  *fb = b;
  return atan2(v3_norm(w), v3_dot(na, nb));
}

static int notch(tds_ctx *ctx, tds_surf *s, double angle, int32_t *n) {
  tds_mesh *m = &s->m;
  int32_t nf = m->nf, cnt = 0, nsplit = 0;
  uint8_t *mark = tds_calloc(&m->alloc, (size_t)nf + 1, 1);
  if (!mark) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (tds_id e = 0; e < m->ne; e++) {
    tds_id a = 0, b = 0;
    if (!tds_alive(m->eflags, e) || crease(m, e, &a, &b) <= angle) continue;
    cnt++;
    nsplit += !mark[a] + !mark[b];
    mark[a] = mark[b] = 1;
  }
  if (tds_mesh_reserve(m, TDS_VERTEX, m->nv + nsplit) ||
      tds_mesh_reserve(m, TDS_EDGE, m->ne + 3 * nsplit) ||
      tds_mesh_reserve(m, TDS_FACET, nf + 2 * nsplit)) {
    tds_free(&m->alloc, mark);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory while notching");
  }
  for (tds_id f = 0; f < nf; f++)
    if (mark[f]) split_centre(s, f);
  tds_free(&m->alloc, mark);
  if (n) *n = cnt;
  if (cnt) m->coord_gen++;
  return tds_surf_update(ctx, s);
}

int tds_notch(tds_ctx *ctx, tds_surf *s, double angle, int32_t *n) {
  if (n) *n = 0;
  int rc = check_cut(ctx, angle, "the angle");
  return rc != TDS_OK ? rc : with_snap(ctx, s, notch, angle, n);
}

static int has_edge_between(const tds_mesh *m, tds_id a, tds_id b) {
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e) &&
        ((m->ev[e][0] == a && m->ev[e][1] == b) || (m->ev[e][0] == b && m->ev[e][1] == a)))
      return 1;
  return 0;
}

static int edgeswap(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  tds_mesh *m = &s->m;
  int32_t cnt = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    tds_id f1, f2;
    if ((sel && !sel[e]) || !tds_flip_ok(s, e, &f1, &f2)) continue;
    tds_id c = TDS_NONE, d = TDS_NONE;
    for (int k = 0; k < 3; k++) {
      if (m->fv[f1][k] != m->ev[e][0] && m->fv[f1][k] != m->ev[e][1]) c = m->fv[f1][k];
      if (m->fv[f2][k] != m->ev[e][0] && m->fv[f2][k] != m->ev[e][1]) d = m->fv[f2][k];
    }
    if (has_edge_between(m, c, d)) continue;
    tds_flip(s, e, f1, f2);
    cnt++;
  }
  if (n) *n = cnt;
  if (cnt) m->coord_gen++;
  return tds_surf_update(ctx, s);
}

int tds_edgeswap(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  if (n) *n = 0;
  if (s->str)
    return tds_seterr(ctx, TDS_ERANGE, "edgeswap works on soap films only, not in the string "
                      "model (its T1 is t1_edgeswap)");
  return tds_snap_run(ctx, s, edgeswap, sel, n);
}

int tds_split_edge_raw(tds_surf *s, tds_id e) {
  if (room_for_split(&s->m, tds_edge_valence(&s->m, e)) != TDS_OK) return TDS_ENOMEM;
  split_one(s, e);
  return TDS_OK;
}
