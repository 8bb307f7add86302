/*
** string_topo.c: topology changes of the string model: popping vertices
** where four or more edges meet (Evolver's o / pop for strings).
**
** Evolver's rule, measured on evolver-nox-d (popstr.fe and a 5-edge star):
** a vertex on no constraint or boundary, with k >= 4 edges splits off the
** two edges with the smallest angle between them onto a new vertex,
** joined to the old one by a new edge; repeated until three edges remain
** (k - 3 pops). A fixed vertex pops too (a 2-D foam's wall junction after
** t, tests/evolver/foam_t1.sh), but only its edges that are not fixed
** move: the new vertex and edge are free. The new vertex lies along the bisector of the
** two edges at a tenth of the shorter one's length. Ties in the angle go to
** the first pair in the order (first edge, last edge, ..., second edge) of
** the vertex's edges by id in 3-D space (Evolver's choice on popstr); in
** 2-D space the edges are taken in angular order (atan2) and the later of
** tied neighbouring pairs wins, the pair across the -x axis last (Evolver's
** choice on tests/evolver/string/pop4.fe).
** The cells whose edge lists pass between a moved and a kept edge take the
** new edge.
*/
#include "string_model.h"

#include <math.h>
#include <string.h>

#include "gather.h"
#include "snap.h"
#include "torus.h"
#include "vec3.h"

#define MAXSTAR 64 /* edges at one vertex considered */

/* Put bridge edge n (from v to w) into the cell lists between an edge that
** now ends at w and one that still starts at v, or the other way round.
** TDS_OK or TDS_ENOMEM (nothing changed). */
static int bridge_cells(tds_strings *st, const tds_mesh *m, tds_id v, tds_id w, tds_id n) {
  int32_t extra = 0;
  for (int pass = 0; pass < 2; pass++) {
    int32_t *out = NULL, k = 0;
    if (pass) {
      out = tds_malloc(&st->alloc, (size_t)(st->noe + extra + 1) * sizeof *out);
      if (!out) return TDS_ENOMEM;
    }
    for (tds_id f = 0; f < st->nf; f++) {
      int32_t a = st->start[f], b = st->start[f + 1];
      if (pass) st->start[f] = k;
      for (int32_t i = a; i < b; i++) {
        if (pass) out[k++] = st->oe[i];
        int last = i + 1 == b;
        if (last && (st->flags[f] & TDS_DEAD)) continue;
        tds_id h = tds_oe_head(m, st->oe[i]);
        tds_id t = tds_oe_tail(m, st->oe[last ? a : i + 1]);
        int32_t r = -1;
        if (h == w && t == v) r = TDS_OREF(n, 1);
        else if (h == v && t == w) r = TDS_OREF(n, 0);
        if (r < 0) continue;
        if (pass) out[k++] = r;
        else extra++;
      }
    }
    if (pass) {
      st->start[st->nf] = k;
      tds_free(&st->alloc, st->oe);
      st->oe = out;
      st->noe = st->capoe = k;
      st->gen++;
    } else if (!extra) {
      return TDS_OK;
    }
  }
  return TDS_OK;
}

/* One pop at v if it has four or more edges: 1 if done, 0 if not, or
** -status. Adjacency must be current. */
static int pop_once(tds_surf *s, tds_id v) {
  tds_mesh *m = &s->m;
  int32_t a = m->ve_start[v], k = m->ve_start[v + 1] - a;
  if (k < 4 || k > MAXSTAR) return 0;
  int32_t ord[MAXSTAR];
  double u[MAXSTAR][3], len[MAXSTAR];
  ord[0] = m->ve[a];
  for (int32_t i = 1; i < k; i++) ord[i] = m->ve[a + k - i];
  for (int32_t i = 0; i < k; i++) {
    tds_edge_vec(m, ord[i], u[i]);
    len[i] = v3_norm(u[i]);
    if (!(len[i] > 0)) return 0;
    v3_scale(u[i], 1 / len[i]);
  }
  /* at a fixed vertex only its free edges move (a fixed wall stays) */
  int movable[MAXSTAR], nm = 0;
  for (int32_t i = 0; i < k; i++) {
    movable[i] = !(m->vflags[v] & TDS_FIXED) || !(m->eflags[TDS_OID(ord[i])] & TDS_FIXED);
    nm += movable[i];
  }
  if (nm < 2) return 0;
  int bi = -1, bj = -1;
  if (s->str->space_dim == 2) {
    /* movable edges in angular order; the smallest gap between
    ** neighbours, ties (within rounding) to the later pair, the
    ** wrap-around pair last */
    int idx[MAXSTAR], n = 0;
    double ang[MAXSTAR];
    for (int i = 0; i < k; i++) {
      ang[i] = atan2(u[i][1], u[i][0]);
      if (movable[i]) idx[n++] = i;
    }
    for (int i = 1; i < n; i++) /* insertion sort: k is small */
      for (int j = i; j > 0 && ang[idx[j]] < ang[idx[j - 1]]; j--) {
        int t = idx[j];
        idx[j] = idx[j - 1];
        idx[j - 1] = t;
      }
    double best = INFINITY;
    for (int i = 0; i < n; i++) {
      int p = idx[i], q = idx[(i + 1) % n];
      if (n == 2 && i == 1) break; /* two edges: one pair */
      double gap = i + 1 < n ? ang[q] - ang[p] : 2 * 3.14159265358979323846 - (ang[p] - ang[q]);
      if (gap <= best + 1e-12) {
        if (gap < best) best = gap;
        bi = p;
        bj = q;
      }
    }
  } else {
    double best = -2;
    for (int i = 0; i < k; i++)
      for (int j = i + 1; j < k; j++) {
        if (!movable[i] || !movable[j]) continue;
        double d = v3_dot(u[i], u[j]);
        if (d > best) best = d, bi = i, bj = j;
      }
  }
  double dir[3];
  v3_add(dir, u[bi], u[bj]);
  double dn = v3_norm(dir);
  if (!(dn > 1e-12)) return 0;
  double step = 0.1 * (len[bi] < len[bj] ? len[bi] : len[bj]) / dn, x[3];
  for (int i = 0; i < 3; i++) x[i] = m->x[v][i] + step * dir[i];
  if (tds_mesh_room(m, TDS_VERTEX, m->nv + 1) || tds_mesh_room(m, TDS_EDGE, m->ne + 1))
    return -TDS_ENOMEM;
  tds_id w = tds_mesh_add_vertex(m, x);
  tds_id n = tds_mesh_add_edge(m, v, w);
  m->eten[n] = 1;
  int32_t mv[2] = {ord[bi], ord[bj]};
  for (int c = 0; c < 2; c++) /* the edge's end at v (its tail if it leaves v) */
    m->ev[TDS_OID(mv[c])][TDS_OREV(mv[c])] = w;
  m->topo_gen++;
  m->coord_gen++;
  if (bridge_cells(s->str, m, v, w, n) != TDS_OK) return -TDS_ENOMEM;
  return 1;
}

static int pop_all(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *npopped) {
  tds_mesh *m = &s->m;
  int32_t count = 0, nv = m->nv;
  for (tds_id v = 0; v < nv; v++) {
    if ((sel && !sel[v]) || !tds_alive(m->vflags, v) || m->vcon[v] || m->vbdry[v] != TDS_NONE)
      continue;
    for (;;) {
      if (tds_mesh_adjacency(m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      int r = pop_once(s, v);
      if (r < 0) return tds_seterr(ctx, -r, "out of memory");
      if (!r) break;
      count++;
    }
  }
  if (npopped) *npopped = count;
  return tds_surf_update(ctx, s);
}

int tds_strings_pop_raw(tds_ctx *ctx, tds_surf *s, int32_t *npopped) {
  if (npopped) *npopped = 0;
  if (!s->str) return tds_seterr(ctx, TDS_ERANGE, "string pop works in the string model only (STRING)");
  return pop_all(ctx, s, NULL, npopped);
}

int tds_strings_pop(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *npopped) {
  if (npopped) *npopped = 0;
  if (!s->str) return tds_seterr(ctx, TDS_ERANGE, "tds.string_pop works in the string model only (STRING)");
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  return tds_snap_end(ctx, s, &sn, pop_all(ctx, s, sel, npopped));
}

/* ---- T1 (Evolver's t1_edgeswap for strings, 2-D space) ----
** Measured on evolver-nox-d (tests/evolver/string/t1.fe): the edge e from
** t to h, both ends triple points, turns a quarter about its midpoint,
** keeping its length. The edge on the right of t->h at t stays at t and
** the one on the right at h moves to t; the left ones go to h. t goes to
** the right of the old edge when the cells using e are counterclockwise
** (positive area), to the left when they are clockwise, as Evolver
** places it. Cells lose e where it separated them and take it where their
** lists now pass between t and h. */

static double cross2(const double a[3], const double b[3]) { return a[0] * b[1] - a[1] * b[0]; }

/* The other two edges at end v of e as oriented refs leaving v; 0 if v
** does not have exactly three edges. */
static int other_two(const tds_mesh *m, tds_id v, tds_id e, int32_t out[2]) {
  int32_t a = m->ve_start[v], k = m->ve_start[v + 1] - a, n = 0;
  if (k != 3) return 0;
  for (int32_t i = 0; i < k; i++)
    if (TDS_OID(m->ve[a + i]) != e) {
      if (n == 2) return 0;
      out[n++] = m->ve[a + i];
    }
  return n == 2;
}

static int t1_once(tds_ctx *ctx, tds_surf *s, tds_id e) {
  tds_mesh *m = &s->m;
  tds_strings *st = s->str;
  if (!tds_alive(m->eflags, e) || (m->eflags[e] & TDS_FIXED) || m->econ[e] ||
      m->ebdry[e] != TDS_NONE)
    return 0;
  tds_id t = m->ev[e][0], h = m->ev[e][1];
  int32_t at[2], ah[2];
  for (int c = 0; c < 2; c++) {
    tds_id v = c ? h : t;
    if ((m->vflags[v] & TDS_FIXED) || m->vcon[v] || m->vbdry[v] != TDS_NONE) return 0;
  }
  if (!other_two(m, t, e, at) || !other_two(m, h, e, ah)) return 0;
  double d[3], u[4][3];
  tds_edge_vec(m, TDS_OREF(e, 0), d);
  tds_edge_vec(m, at[0], u[0]);
  tds_edge_vec(m, at[1], u[1]);
  tds_edge_vec(m, ah[0], u[2]);
  tds_edge_vec(m, ah[1], u[3]);
  for (int i = 0; i < 4; i++) {
    double l = sqrt(u[i][0] * u[i][0] + u[i][1] * u[i][1]);
    if (!(l > 0)) return 0;
    u[i][0] /= l, u[i][1] /= l;
  }
  /* the right one at each end: the smaller cross product with d */
  int rt = cross2(d, u[0]) <= cross2(d, u[1]) ? 0 : 1;
  int rh = cross2(d, u[2]) <= cross2(d, u[3]) ? 0 : 1;
  int32_t t_left = at[!rt], h_right = ah[rh];
  tds_id ends[4] = {tds_oe_head(m, at[0]), tds_oe_head(m, at[1]), tds_oe_head(m, ah[0]),
                    tds_oe_head(m, ah[1])};
  for (int i = 0; i < 4; i++) /* no edge back into the pair, no double edges */
    for (int j = i + 1; j < 4; j++)
      if (ends[i] == ends[j] || ends[i] == t || ends[i] == h) return 0;
  /* the side t goes to: right (-perp) unless the cells are clockwise */
  double sgn = -1;
  for (tds_id f = 0; f < st->nf; f++) {
    if (st->flags[f] & TDS_DEAD) continue;
    int32_t i = st->start[f];
    while (i < st->start[f + 1] && TDS_OID(st->oe[i]) != e) i++;
    if (i == st->start[f + 1]) continue;
    double A = tds_strings_area(s, f); /* its orientation, whichever side */
    if (A != 0) {
      sgn = A > 0 ? -1 : 1;
      break;
    }
  }
  /* the torus: h moves to the copy that e reaches (wrap_vertex keeps the
  ** surface), so e has no wrap and its two ends, their new places and the
  ** reconnected edges are all in t's frame */
  if (m->ewrap && m->ewrap[e]) {
    if (tds_mesh_rotates(m) || tds_torus_wrap_vertex(ctx, s, h, m->ewrap[e]) != TDS_OK) return 0;
  }
  double mid[3], perp[3] = {-d[1], d[0], 0};
  for (int i = 0; i < 3; i++) mid[i] = (m->x[t][i] + m->x[h][i]) / 2;
  for (int i = 0; i < 2; i++) {
    m->x[t][i] = mid[i] + sgn * perp[i] / 2;
    m->x[h][i] = mid[i] - sgn * perp[i] / 2;
  }
  /* reconnect: t's left edge to h, h's right edge to t */
  m->ev[TDS_OID(t_left)][TDS_OREV(t_left)] = h;
  m->ev[TDS_OID(h_right)][TDS_OREV(h_right)] = t;
  m->topo_gen++;
  m->coord_gen++;
  return 1;
}

/* Drop e from every cell list, then put it back (bridge_cells) where a
** list passes between t and h. */
static int t1_cells(tds_strings *st, const tds_mesh *m, tds_id e) {
  int32_t k = 0;
  for (tds_id f = 0; f < st->nf; f++) {
    int32_t a = st->start[f], b = st->start[f + 1];
    st->start[f] = k;
    for (int32_t i = a; i < b; i++)
      if (TDS_OID(st->oe[i]) != e) st->oe[k++] = st->oe[i];
  }
  st->start[st->nf] = k;
  st->noe = k;
  st->gen++;
  return bridge_cells(st, m, m->ev[e][0], m->ev[e][1], e);
}

static int t1_all(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *nflip) {
  tds_mesh *m = &s->m;
  int32_t count = 0, ne = m->ne;
  if (s->str->space_dim == 2)
    for (tds_id e = 0; e < ne; e++) {
      if (sel && !sel[e]) continue;
      if (tds_mesh_adjacency(m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      if (!t1_once(ctx, s, e)) continue;
      if (t1_cells(s->str, m, e) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      count++;
    }
  if (nflip) *nflip = count;
  return tds_surf_update(ctx, s);
}

int tds_strings_t1(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *nflip) {
  if (nflip) *nflip = 0;
  if (!s->str) return tds_seterr(ctx, TDS_ERANGE, "t1_edgeswap (tds.string_t1) works in the string model only (STRING)");
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  return tds_snap_end(ctx, s, &sn, t1_all(ctx, s, sel, nflip));
}

/* ---- facet_crosscut ----
** Measured on evolver-nox-d (tests/evolver/string/pop4.fe): the new edge
** runs from the tail vertex to the head vertex with tension 0; the cell
** keeps the new edge followed by its edges from the head round to the
** tail, and a new cell (next id, same bodies, flags and colour) takes the
** new edge reversed followed by the edges from the tail to the head. */
static int crosscut(tds_ctx *ctx, tds_surf *s, tds_id f, tds_id tv, tds_id hv, tds_id *ne) {
  tds_mesh *m = &s->m;
  tds_strings *st = s->str;
  if (f < 0 || f >= st->nf || (st->flags[f] & TDS_DEAD))
    return tds_seterr(ctx, TDS_ERANGE, "facet_crosscut: facet %d does not exist", f + 1);
  int32_t a = st->start[f], n = st->start[f + 1] - a, i = -1, j = -1;
  for (int32_t k = 0; k < n; k++) {
    tds_id v = tds_oe_tail(m, st->oe[a + k]);
    if (v == tv) i = k;
    if (v == hv) j = k;
  }
  if (i < 0 || j < 0 || i == j || tds_oe_head(m, st->oe[a + n - 1]) != tds_oe_tail(m, st->oe[a]))
    return tds_seterr(ctx, TDS_ERANGE, "facet_crosscut: vertices %d and %d are not two "
                      "corners of facet %d's closed edge list", tv + 1, hv + 1, f + 1);
  if (tds_mesh_room(m, TDS_EDGE, m->ne + 1) || tds_strings_room(st, st->nf + 1, st->noe + 2))
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  int32_t *oe = tds_malloc(&st->alloc, (size_t)(st->noe + 2) * sizeof *oe);
  if (!oe) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  tds_id e = tds_mesh_add_edge(m, tv, hv);
  m->eten[e] = 0;
  /* the torus: the new edge reaches hv where the cell's edges from tv do
  ** (the product of their wraps), so both new loops still close */
  if (m->ewrap) {
    int32_t w = 0;
    for (int32_t q = i; q != j; q = (q + 1) % n) w = tds_wrap_mul(m, w, tds_oe_wrap(m, st->oe[a + q]));
    m->ewrap[e] = w;
  }
  int32_t k = 0;
  for (tds_id g = 0; g < st->nf; g++) {
    int32_t b0 = st->start[g], b1 = st->start[g + 1];
    st->start[g] = k;
    if (g != f) {
      for (int32_t q = b0; q < b1; q++) oe[k++] = st->oe[q];
      continue;
    }
    oe[k++] = TDS_OREF(e, 0); /* tail -> head, then head round to tail */
    for (int32_t q = j; q != i; q = (q + 1) % n) oe[k++] = st->oe[a + q];
  }
  tds_id nf = st->nf;
  st->start[nf] = k;
  oe[k++] = TDS_OREF(e, 1); /* the new cell: head -> tail, then tail to head */
  for (int32_t q = i; q != j; q = (q + 1) % n) oe[k++] = st->oe[a + q];
  st->flags[nf] = st->flags[f];
  st->fb[nf][0] = st->fb[f][0];
  st->fb[nf][1] = st->fb[f][1];
  st->color[nf] = st->color[f];
  st->start[nf + 1] = k;
  st->nf = nf + 1;
  tds_free(&st->alloc, st->oe);
  st->oe = oe;
  st->noe = k;
  st->capoe = st->noe;
  st->gen++;
  m->topo_gen++;
  *ne = e;
  return tds_surf_update(ctx, s);
}

int tds_strings_crosscut(tds_ctx *ctx, tds_surf *s, tds_id f, tds_id tv, tds_id hv,
                         tds_id *newedge) {
  *newedge = TDS_NONE;
  if (!s->str) return tds_seterr(ctx, TDS_ERANGE, "facet_crosscut works in the string model only (STRING)");
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  return tds_snap_end(ctx, s, &sn, crosscut(ctx, s, f, tv, hv, newedge));
}

/* ---- edge deletion (t, delete edge: topo_collapse.c) ---- */

void tds_strings_drop_edge(tds_strings *st, const tds_mesh *m, tds_id e) {
  int32_t k = 0;
  for (tds_id f = 0; f < st->nf; f++) {
    int32_t a = st->start[f], b = st->start[f + 1];
    /* a closed loop that loses its first edge starts at its last one, as
    ** Evolver's does (measured: its cell's first edge becomes the one
    ** before the deleted edge) */
    int rot = b - a > 1 && TDS_OID(st->oe[a]) == e && TDS_OID(st->oe[b - 1]) != e &&
              tds_oe_head(m, st->oe[b - 1]) == tds_oe_tail(m, st->oe[a]);
    st->start[f] = k;
    if (rot) st->oe[k++] = st->oe[b - 1]; /* over oe[a] at the latest: edge e */
    for (int32_t i = a + rot; i < b - rot; i++)
      if (TDS_OID(st->oe[i]) != e) st->oe[k++] = st->oe[i];
  }
  st->start[st->nf] = k;
  st->noe = k;
  st->gen++;
}

void tds_strings_rename_edge(tds_strings *st, tds_id from, tds_id to, int flip) {
  for (int32_t i = 0; i < st->noe; i++)
    if (TDS_OID(st->oe[i]) == from) {
      int r = TDS_OREV(st->oe[i]);
      st->oe[i] = TDS_OREF(to, flip ? !r : r);
    }
  st->gen++;
}

void tds_strings_prune(tds_strings *st) {
  for (tds_id f = 0; f < st->nf; f++) {
    if (st->flags[f] & TDS_DEAD) continue;
    int32_t a = st->start[f], b = st->start[f + 1];
    int empty = 1;
    for (int32_t i = a; i < b && empty; i++) {
      int paired = 0;
      for (int32_t j = a; j < b && !paired; j++)
        paired = st->oe[j] == (st->oe[i] ^ 1); /* the same edge the other way */
      empty = paired;
    }
    if (!empty) continue;
    st->flags[f] |= TDS_DEAD;
    for (int32_t i = a; i < b; i++) st->oe[i] = -1;
  }
  /* compact away the dead cells' entries */
  int32_t k = 0;
  for (tds_id f = 0; f < st->nf; f++) {
    int32_t a = st->start[f], b = st->start[f + 1];
    st->start[f] = k;
    for (int32_t i = a; i < b; i++)
      if (st->oe[i] >= 0) st->oe[k++] = st->oe[i];
  }
  st->start[st->nf] = k;
  st->noe = k;
  st->gen++;
}
