/* topo_popedge.c: popping edges where more than three facets meet
** (Evolver's O, `pop edge`, and the edge half of o).
**
** Behaviour, measured on Evolver 2.70 (tests/evolver/popedge.sh):
** * The facets around the edge are taken in their angular order (counter-
**   clockwise about the edge's direction, starting at the lowest facet
**   id); the two neighbours with the smallest angle between them (the
**   first such pair) are the *wedge*.
** * The edge is part of a *chain*: through each end that is a free vertex
**   whose only edges of valence other than 2 are two edges of the same
**   valence, and whose facets form fins joining those two edges, the
**   chain goes on. A chain with no such interior vertex is first split at
**   its midpoint (the facets on it split in their angular order; each
**   keeps its head part and the tail part is a new facet).
** * Where the chain stops at a free vertex at which the wedge's two fins
**   both end on one other edge (a run of 4 facets parting into two triple
**   edges), that end vertex is pulled too (measured on octa.fe's gogo:
**   tests/evolver/popo.sh).
** * Each such vertex v, from the popped edge outwards (head side first),
**   is pulled apart: a new vertex v' = v + 0.01 |e| (u1 + u2) (e the
**   popped edge, u1, u2 the unit directions of the two wedge facets on
**   it, perpendicular to it: one offset for the whole chain) takes the
**   wedge's fins; a
**   spoke edge v -> v', copies of the incoming and outgoing chain edges
**   for the other facets, and two triangles (a, v, v') and (v, b, v')
**   between the two chains are new, in that order, turned round where
**   that makes them one sheet with the second wedge facet (octa.fe's O:
**   tests/evolver/popo.sh, O-orient). Each vertex pulled
**   counts as one edge popped (Evolver's count).
** The new triangles separate the two regions beside the wedge: they take
** the body on either side. Volumes change by the slivers; g brings bodies
** with targets back.
*/
#include "torus.h"
#include "topo_edit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "snap.h"
#include "topo.h"
#include "vec3.h"

#define MAXVAL 64 /* facets around one edge that we sort */

static int free_vertex(const tds_surf *s, tds_id v) {
  const tds_mesh *m = &s->m;
  return !(m->vflags[v] & TDS_FIXED) && !(m->vcon[v] & ~tds_surf_global_cons(s)) &&
         m->vbdry[v] == TDS_NONE;
}

static tds_id other_end(const tds_mesh *m, tds_id e, tds_id v) {
  return m->ev[e][0] == v ? m->ev[e][1] : m->ev[e][0];
}

/* Vertex of facet f that is on neither end of edge e. */
static tds_id opposite(const tds_mesh *m, tds_id f, tds_id e) {
  for (int k = 0; k < 3; k++) {
    tds_id w = m->fv[f][k];
    if (w != m->ev[e][0] && w != m->ev[e][1]) return w;
  }
  return TDS_NONE;
}

/* Unit direction from edge (p -> q) into facet f, perpendicular to it. */
static void perp(const tds_mesh *m, tds_id f, tds_id e, tds_id p, tds_id q, double u[3]) {
  double d[3], w[3];
  v3_sub(d, m->x[q], m->x[p]);
  double dd = v3_dot(d, d);
  v3_sub(w, m->x[opposite(m, f, e)], m->x[p]);
  if (dd > 0) v3_axpy(w, -v3_dot(w, d) / dd, d);
  double n = v3_norm(w);
  if (n > 0) v3_scale(w, 1 / n);
  v3_copy(u, w);
}

/* Does facet f come before g in Evolver's ring? A split facet's new part
** takes the old one's place, so the facet descending from the lowest
** datafile facet heads the ring (measured: tests/evolver/popedge.sh). */
static int before(const tds_mesh *m, tds_id f, tds_id g) {
  tds_id af = m->forig[f] != TDS_NONE ? m->forig[f] : f;
  tds_id ag = m->forig[g] != TDS_NONE ? m->forig[g] : g;
  return af != ag ? af < ag : f < g;
}

/* Facets on e in angular order about e's direction, starting at the one
** that heads Evolver's ring (before()); count (0 if more than MAXVAL). *wedge: index of the first facet of
** the wedge (the next one is the second). */
static int sorted_ring(const tds_mesh *m, tds_id e, tds_id *fl, int *wedge) {
  tds_id t = m->ev[e][0], h = m->ev[e][1];
  double ang[MAXVAL], d[3], u0[3];
  int n = 0;
  int32_t h0 = m->eside[e], sd = h0;
  if (h0 == TDS_NONE) return 0;
  do {
    if (n == MAXVAL) return 0;
    fl[n++] = sd / 3;
    sd = m->side_next[sd];
  } while (sd != h0);
  for (int i = 1; i < n; i++) /* by ancestry, then id */
    for (int j = i; j > 0 && before(m, fl[j], fl[j - 1]); j--) {
      tds_id z = fl[j]; fl[j] = fl[j - 1]; fl[j - 1] = z;
    }
  v3_sub(d, m->x[h], m->x[t]);
  double dn = v3_norm(d);
  if (dn > 0) v3_scale(d, 1 / dn);
  perp(m, fl[0], e, t, h, u0);
  for (int i = 0; i < n; i++) {
    double u[3], c[3];
    perp(m, fl[i], e, t, h, u);
    v3_cross(c, u0, u);
    double a = atan2(v3_dot(c, d), v3_dot(u0, u));
    ang[i] = i == 0 ? 0 : a < 0 ? a + 2 * TDS_PI : a;
  }
  for (int i = 1; i < n; i++) /* by angle, stable */
    for (int j = i; j > 0 && ang[j] < ang[j - 1]; j--) {
      double za = ang[j]; ang[j] = ang[j - 1]; ang[j - 1] = za;
      tds_id z = fl[j]; fl[j] = fl[j - 1]; fl[j - 1] = z;
    }
  /* the wedge: first pair with the smallest gap, stored first */
  int best = 0;
  double bg = 1e300;
  for (int i = 0; i < n; i++) {
    double g = (i + 1 < n ? ang[i + 1] : ang[0] + 2 * TDS_PI) - ang[i];
    if (g < bg) { bg = g; best = i; }
  }
  *wedge = best;
  return n;
}

/* The other edge of facet f at vertex v than edge e. */
static tds_id other_edge_at(const tds_mesh *m, tds_id f, tds_id v, tds_id e) {
  for (int k = 0; k < 3; k++) {
    tds_id g = TDS_OID(m->fe[f][k]);
    if (g != e && (m->ev[g][0] == v || m->ev[g][1] == v)) return g;
  }
  return TDS_NONE;
}

/* The other facet on a valence-2 edge g than f. */
static tds_id across(const tds_mesh *m, tds_id g, tds_id f) {
  int32_t sd = m->eside[g];
  tds_id a = sd / 3, b = m->side_next[sd] / 3;
  return a == f ? b : a;
}

/* Walk the fin at v from facet f on edge ein through valence-2 edges;
** appends its facets to out (up to cap) and returns the edge it ends on
** (TDS_NONE on a loop or overflow), *last the facet there. */
static tds_id fin(const tds_mesh *m, tds_id v, tds_id ein, tds_id f, tds_id *out,
                  int *nout, int cap, tds_id *last) {
  tds_id e = ein;
  for (int steps = 0; steps < cap; steps++) {
    if (*nout >= cap) return TDS_NONE;
    out[(*nout)++] = f;
    tds_id g = other_edge_at(m, f, v, e);
    if (g == TDS_NONE) return TDS_NONE;
    if (tds_edge_valence(m, g) != 2) {
      *last = f;
      return g;
    }
    f = across(m, g, f);
    e = g;
  }
  return TDS_NONE;
}

/* Does the chain go on through v (coming in along ein with wedge facets
** w[0], w[1])? Then *eout and the wedge facets on it in wn. */
static int goes_on(const tds_surf *s, tds_id v, tds_id ein, int val, const tds_id w[2],
                   tds_id *eout, tds_id wn[2]) {
  const tds_mesh *m = &s->m;
  if (!free_vertex(s, v)) return 0;
  tds_id other = TDS_NONE;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++) {
    tds_id g = TDS_OID(m->ve[i]);
    int k = tds_edge_valence(m, g);
    if (g == ein || k == 2) continue;
    if (k != val || other != TDS_NONE) return 0;
    other = g;
  }
  if (other == TDS_NONE || other_end(m, other, v) == v) return 0;
  /* every facet on ein must run through a fin to `other` */
  int32_t h = m->eside[ein], sd = h;
  do {
    tds_id scratch[MAXVAL], last = TDS_NONE;
    int ns = 0;
    tds_id f = sd / 3;
    if (fin(m, v, ein, f, scratch, &ns, MAXVAL, &last) != other) return 0;
    for (int j = 0; j < 2; j++)
      if (f == w[j]) wn[j] = last;
    sd = m->side_next[sd];
  } while (sd != h);
  *eout = other;
  return 1;
}

/* Where the chain stops at v (coming in along ein with wedge facets w[0],
** w[1]): Evolver still pulls v when it is free and the wedge's two fins
** at v both end on the same edge *eout (a run of 4 facets ending where it
** parts into two triple edges); wn as for goes_on. */
static int end_pull(const tds_surf *s, tds_id v, tds_id ein, const tds_id w[2], tds_id *eout,
                    tds_id wn[2]) {
  const tds_mesh *m = &s->m;
  if (!free_vertex(s, v)) return 0;
  tds_id g[2];
  for (int j = 0; j < 2; j++) {
    tds_id scratch[MAXVAL], last = TDS_NONE;
    int ns = 0;
    g[j] = fin(m, v, ein, w[j], scratch, &ns, MAXVAL, &last);
    if (g[j] == TDS_NONE || g[j] == ein) return 0;
    wn[j] = last;
  }
  if (g[0] != g[1] || other_end(m, g[0], v) == v) return 0;
  *eout = g[0];
  return 1;
}

typedef struct chain {
  int n;           /* interior vertices */
  tds_id v[MAXVAL];
  tds_id e[MAXVAL + 1]; /* e[i] comes into v[i]; e[n] leaves v[n-1] */
  tds_id w[MAXVAL + 1][2]; /* wedge facets on e[i] */
} chain;

/* Trace the chain through e (wedge facets w0, w1 on it). 0 if it closes on
** itself or is too long. */
static int trace(const tds_surf *s, tds_id e, tds_id w0, tds_id w1, chain *c) {
  const tds_mesh *m = &s->m;
  int val = tds_edge_valence(m, e);
  tds_id bv[MAXVAL], be[MAXVAL], bw[MAXVAL][2];
  int nb = 0;
  /* backwards through the tail */
  tds_id v = m->ev[e][0], ein = e, w[2] = {w0, w1}, eo, wn[2];
  while (goes_on(s, v, ein, val, w, &eo, wn)) {
    if (eo == e || nb == MAXVAL - 1) return 0;
    bv[nb] = v;
    be[nb] = eo;
    bw[nb][0] = wn[0];
    bw[nb][1] = wn[1];
    nb++;
    v = other_end(m, eo, v);
    ein = eo;
    w[0] = wn[0];
    w[1] = wn[1];
  }
  if (end_pull(s, v, ein, w, &eo, wn)) { /* the tail end is pulled too */
    if (nb == MAXVAL - 1) return 0;
    bv[nb] = v;
    be[nb] = eo;
    bw[nb][0] = wn[0];
    bw[nb][1] = wn[1];
    nb++;
  }
  c->n = 0;
  for (int i = nb - 1; i >= 0; i--) {
    c->e[c->n] = be[i];
    c->w[c->n][0] = bw[i][0];
    c->w[c->n][1] = bw[i][1];
    c->v[c->n++] = bv[i];
  }
  c->e[c->n] = e;
  c->w[c->n][0] = w0;
  c->w[c->n][1] = w1;
  v = m->ev[e][1];
  ein = e;
  w[0] = w0;
  w[1] = w1;
  while (goes_on(s, v, ein, val, w, &eo, wn)) {
    if (eo == e || c->n >= MAXVAL - 1) return 0;
    c->v[c->n++] = v;
    c->e[c->n] = eo;
    c->w[c->n][0] = wn[0];
    c->w[c->n][1] = wn[1];
    v = other_end(m, eo, v);
    ein = eo;
    w[0] = wn[0];
    w[1] = wn[1];
  }
  if (end_pull(s, v, ein, w, &eo, wn)) { /* the head end */
    if (c->n >= MAXVAL - 1) return 0;
    c->v[c->n++] = v;
    c->e[c->n] = eo;
    c->w[c->n][0] = wn[0];
    c->w[c->n][1] = wn[1];
  }
  return 1;
}

static int room(tds_mesh *m, int nv, int ne, int nf) {
  return tds_mesh_room(m, TDS_VERTEX, m->nv + nv) || tds_mesh_room(m, TDS_EDGE, m->ne + ne) ||
         tds_mesh_room(m, TDS_FACET, m->nf + nf);
}

/* Split edge e at its midpoint, its facets (angular order fl[0..n-1]) each
** into a tail part (a new facet) and a head part (kept), as Evolver numbers
** them. Returns the new vertex, or TDS_NONE out of memory (nothing done). */
static tds_id split(tds_surf *s, tds_id e, const tds_id *fl, int n) {
  tds_mesh *m = &s->m;
  if (room(m, 1, 1 + n, n)) return TDS_NONE;
  tds_id a = m->ev[e][0], b = m->ev[e][1];
  int fwd[MAXVAL];
  int32_t ca[MAXVAL], bc[MAXVAL];
  tds_id c[MAXVAL];
  for (int i = 0; i < n; i++) {
    tds_id f = fl[i];
    c[i] = opposite(m, f, e);
    for (int k = 0; k < 3; k++) {
      int32_t oe = m->fe[f][k];
      tds_id g = TDS_OID(oe);
      if (g == e) fwd[i] = !TDS_OREV(oe);
      else if (m->ev[g][0] == a || m->ev[g][1] == a) ca[i] = oe;
      else bc[i] = oe;
    }
  }
  tds_id mid = tds_edge_midpoint(s, e);
  tds_id e2 = tds_mesh_add_edge(m, mid, b);
  tds_edge_inherit(m, e2, e);
  m->ev[e][1] = mid;
  for (int i = 0; i < n; i++) {
    tds_id f = fl[i];
    tds_id d = tds_mesh_add_edge(m, mid, c[i]);
    m->eflags[d] = m->fflags[f] & (TDS_FIXED | TDS_NO_REFINE);
    m->econ[d] = m->fcon[f];
    int32_t tail[3], head[3];
    if (fwd[i]) { /* a -> b -> c */
      tail[0] = TDS_OREF(e, 0); tail[1] = TDS_OREF(d, 0); tail[2] = ca[i];
      head[0] = TDS_OREF(e2, 0); head[1] = bc[i]; head[2] = TDS_OREF(d, 1);
    } else { /* b -> a -> c */
      tail[0] = TDS_OREF(e, 1); tail[1] = ca[i]; tail[2] = TDS_OREF(d, 1);
      head[0] = TDS_OREF(e2, 1); head[1] = TDS_OREF(d, 0); head[2] = bc[i];
    }
    tds_mesh_set_facet(m, f, head);
    tds_id t = tds_mesh_add_facet(m, tail);
    tds_facet_inherit(m, t, f);
  }
  m->topo_gen++;
  return mid;
}

/* Is facet f in list l[0..n-1]? */
static int in(const tds_id *l, int n, tds_id f) {
  for (int i = 0; i < n; i++)
    if (l[i] == f) return 1;
  return 0;
}

/* The body on the side of facet f that faces direction u. */
static tds_id body_toward(const tds_mesh *m, tds_id f, const double u[3]) {
  double p[3], q[3], n[3];
  v3_sub(p, m->x[m->fv[f][1]], m->x[m->fv[f][0]]);
  v3_sub(q, m->x[m->fv[f][2]], m->x[m->fv[f][0]]);
  v3_cross(n, p, q);
  /* the front body (listed +) is behind the normal */
  return v3_dot(n, u) > 0 ? m->fb[f][1] : m->fb[f][0];
}

/* The triangle between the two chains along chain edge g (now at v'),
** with copy c of it still at v: (p, q, v') for g stored p -> q (one of
** them v), following g's direction, or with flip the other way round,
** starting from c reversed (Evolver's orders). */
static tds_id between(tds_mesh *m, tds_id g, tds_id c, tds_id spoke, tds_id v, int flip) {
  int32_t oe[3];
  int cv = m->ev[c][0] == v;
  if (flip) { /* -c, then g and the spoke the other way round */
    oe[0] = TDS_OREF(c, 1);
    oe[1] = cv ? TDS_OREF(spoke, 0) : TDS_OREF(g, 0);
    oe[2] = cv ? TDS_OREF(g, 0) : TDS_OREF(spoke, 1);
  } else if (cv) { /* (v, q, v'): v -> q, q -> v', v' -> v */
    oe[0] = TDS_OREF(c, 0);
    oe[1] = TDS_OREF(g, 1);
    oe[2] = TDS_OREF(spoke, 1);
  } else { /* (p, v, v'): p -> v, v -> v', v' -> p */
    oe[0] = TDS_OREF(c, 0);
    oe[1] = TDS_OREF(spoke, 0);
    oe[2] = TDS_OREF(g, 1);
  }
  return tds_mesh_add_facet(m, oe);
}

/* Does facet f run along edge g from g's tail to its head? */
static int runs_forward(const tds_mesh *m, tds_id f, tds_id g) {
  for (int k = 0; k < 3; k++)
    if (TDS_OID(m->fe[f][k]) == g) return !TDS_OREV(m->fe[f][k]);
  return 0;
}

/* Pull interior vertex v apart to a new vertex at x: near is the chain
** edge on the popped edge's side, far the other; W the facets of the
** wedge's fins at v, wi the wedge facets on near. */
static int pull(tds_surf *s, tds_id v, tds_id near, tds_id far, const tds_id *W, int nw,
                const tds_id wi[2], const double x[3]) {
  tds_mesh *m = &s->m;
  if (room(m, 1, 3, 2)) return TDS_ENOMEM;
  tds_id a = other_end(m, near, v);
  double u1[3], u2[3], dif[3];
  perp(m, wi[0], near, a, v, u1);
  perp(m, wi[1], near, a, v, u2);
  /* the bodies beside the wedge: beyond wi[0] (away from wi[1]), and
  ** beyond wi[1] */
  double mu1[3], mu2[3];
  v3_copy(mu1, u1);
  v3_scale(mu1, -1);
  v3_copy(mu2, u2);
  v3_scale(mu2, -1);
  tds_id B1 = body_toward(m, wi[0], mu2), B2 = body_toward(m, wi[1], mu1);
  tds_id vp = tds_mesh_add_vertex(m, x);
  m->vflags[vp] = m->vflags[v];
  m->vcon[vp] = m->vcon[v];
  m->vbdry[vp] = m->vbdry[v];
  tds_mesh_inherit(m, TDS_VERTEX, vp, v);
  tds_id spoke = tds_mesh_add_edge(m, v, vp);
  tds_edge_inherit(m, spoke, near);
  m->efile[spoke] = 0;
  tds_id cn = tds_mesh_add_edge(m, m->ev[near][0], m->ev[near][1]);
  tds_edge_inherit(m, cn, near);
  tds_id cf = tds_mesh_add_edge(m, m->ev[far][0], m->ev[far][1]);
  tds_edge_inherit(m, cf, far);
  /* the other facets on near and far go to the copies */
  tds_id move[2 * MAXVAL];
  int nm = 0;
  for (int j = 0; j < 2; j++) {
    tds_id g = j ? far : near;
    int32_t h = m->eside[g], sd = h;
    do {
      tds_id f = sd / 3;
      if (!in(W, nw, f) && !in(move, nm, f)) move[nm++] = f;
      sd = m->side_next[sd];
    } while (sd != h);
  }
  for (int i = 0; i < nm; i++) {
    tds_id f = move[i];
    int32_t oe[3];
    for (int k = 0; k < 3; k++) {
      tds_id g = TDS_OID(m->fe[f][k]);
      oe[k] = g == near ? TDS_OREF(cn, TDS_OREV(m->fe[f][k]))
            : g == far ? TDS_OREF(cf, TDS_OREV(m->fe[f][k])) : m->fe[f][k];
    }
    tds_mesh_set_facet(m, f, oe);
  }
  /* the wedge's fins move to v' with their edges at v */
  for (int i = 0; i < nw; i++) {
    tds_id f = W[i];
    for (int k = 0; k < 3; k++) {
      if (m->fv[f][k] == v) m->fv[f][k] = vp;
      tds_id g = TDS_OID(m->fe[f][k]);
      for (int j = 0; j < 2; j++)
        if (m->ev[g][j] == v) m->ev[g][j] = vp;
    }
  }
  /* Evolver orients the new triangles as one sheet with the second wedge
  ** facet (measured on octa.fe's O: five of its six pops run the other
  ** way round from tds's former fixed order, and the cut corners of o
  ** depend on it). Unturned, the first runs along near backwards. */
  int flip = !runs_forward(m, wi[1], near);
  tds_id T[2] = {between(m, near, cn, spoke, v, flip), between(m, far, cf, spoke, v, flip)};
  v3_sub(dif, u1, u2);
  for (int j = 0; j < 2; j++) {
    tds_facet_inherit(m, T[j], wi[0]);
    m->ffile[T[j]] = 0;
    m->forig[T[j]] = TDS_NONE;
    /* B1 is on the side toward wi[0] (direction u1 - u2) */
    double p[3], q[3], n[3];
    v3_sub(p, m->x[m->fv[T[j]][1]], m->x[m->fv[T[j]][0]]);
    v3_sub(q, m->x[m->fv[T[j]][2]], m->x[m->fv[T[j]][0]]);
    v3_cross(n, p, q);
    int nside = v3_dot(n, dif) > 0; /* the normal points toward B1 */
    m->fb[T[j]][1] = nside ? B1 : B2;
    m->fb[T[j]][0] = nside ? B2 : B1;
  }
  m->topo_gen++;
  return TDS_OK;
}

/* Pop edge e if it has more than three facets and may move; *npulled
** gets the vertices pulled (Evolver's count), 0 when skipped. */
/* The ends of the edges of the chain through e (its tail first), for
** unwrapping them (torus.h); the count, 0 when e does not pop, -1 when the
** ends of e cannot be unwrapped. The chain is found in the frame of e's
** tail, where the wedge's angles are measured. */
static int chain_seeds(tds_surf *s, tds_id e, tds_id *seed, int cap) {
  tds_mesh *m = &s->m;
  tds_torus_local L;
  tds_id two[2] = {m->ev[e][0], m->ev[e][1]};
  if (two[0] == two[1] || tds_torus_local_begin(m, two, 2, &L)) return -1;
  tds_id fl[MAXVAL];
  int bi = 0, n = sorted_ring(m, e, fl, &bi), ns = 0;
  chain *c = tds_malloc(&m->alloc, sizeof *c);
  if (c && n == tds_edge_valence(m, e) && trace(s, e, fl[bi], fl[(bi + 1) % n], c)) {
    seed[ns++] = two[0];
    seed[ns++] = two[1];
    for (int i = 0; i <= c->n && ns >= 0; i++)
      for (int j = 0; j < 2 && ns >= 0; j++) {
        tds_id x = m->ev[c->e[i]][j];
        int seen = 0;
        for (int k = 0; k < ns; k++) seen |= seed[k] == x;
        if (!seen) ns = ns == cap ? -1 : (seed[ns] = x, ns + 1);
      }
  }
  tds_free(&m->alloc, c);
  tds_torus_local_end(m, &L);
  return ns;
}

static int pop_one(tds_surf *s, tds_id e, int32_t *npulled);

/* In the torus the chain's neighbourhood is first unwrapped into the frame
** of e's tail (torus.h); TDS_ERANGE when it cannot be. */
int tds_pop_one_edge(tds_surf *s, tds_id e, int32_t *npulled) {
  tds_mesh *m = &s->m;
  *npulled = 0;
  if (!m->torus || !tds_alive(m->eflags, e) || tds_edge_valence(m, e) <= 3 ||
      (m->eflags[e] & TDS_FIXED) || (m->econ[e] & ~tds_surf_global_cons(s)) ||
      m->ebdry[e] != TDS_NONE || m->ev[e][0] == m->ev[e][1])
    return pop_one(s, e, npulled); /* (nothing to unwrap: it does not pop) */
  if (tds_mesh_adjacency(m) != TDS_OK) return TDS_ENOMEM;
  tds_id seed[64];
  int ns = chain_seeds(s, e, seed, 64);
  if (ns == 0) return TDS_OK;
  tds_torus_local L;
  if (ns < 0 || tds_torus_local_begin(m, seed, ns, &L)) return TDS_ERANGE;
  int rc = pop_one(s, e, npulled);
  tds_torus_local_end(m, &L);
  return rc;
}

static int pop_one(tds_surf *s, tds_id e, int32_t *npulled) {
  tds_mesh *m = &s->m;
  *npulled = 0;
  if (!tds_alive(m->eflags, e) || (m->eflags[e] & TDS_FIXED) ||
      (m->econ[e] & ~tds_surf_global_cons(s)) || m->ebdry[e] != TDS_NONE)
    return TDS_OK;
  int val = tds_edge_valence(m, e);
  if (val <= 3 || val >= MAXVAL - 1) return TDS_OK;
  if (m->ev[e][0] == m->ev[e][1]) return TDS_OK;
  if (tds_mesh_adjacency(m) != TDS_OK) return TDS_ENOMEM;
  tds_id fl[MAXVAL];
  int bi = 0;
  int n = sorted_ring(m, e, fl, &bi);
  if (n != val) return TDS_OK;
  tds_id w0 = fl[bi], w1 = fl[(bi + 1) % n];
  chain *c = tds_malloc(&m->alloc, sizeof *c);
  if (!c) return TDS_ENOMEM;
  if (!trace(s, e, w0, w1, c)) {
    tds_free(&m->alloc, c);
    return TDS_OK;
  }
  int rc = TDS_OK;
  if (c->n == 0) {
    tds_id mid = split(s, e, fl, n);
    if (mid == TDS_NONE) rc = TDS_ENOMEM;
    else if (tds_mesh_adjacency(m) != TDS_OK) rc = TDS_ENOMEM;
    else {
      /* the wedge facets on e are now the new tail parts: the facets on e
      ** made from w0 and w1 */
      tds_id nw0 = TDS_NONE, nw1 = TDS_NONE;
      /* the tail parts were appended in the order of fl */
      tds_id first = m->nf - n;
      for (int i = 0; i < n; i++) {
        if (fl[i] == w0) nw0 = first + i;
        if (fl[i] == w1) nw1 = first + i;
      }
      if (!trace(s, e, nw0, nw1, c) || c->n != 1) rc = TDS_ETOPO;
    }
  }
  /* the popped edge's place in the chain; then its head side outwards,
  ** then its tail side outwards (Evolver's order) */
  int p = 0;
  while (p < c->n && c->e[p] != e) p++;
  double d[3];
  v3_sub(d, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
  double len = v3_norm(d);
  /* every new place from the chain as it is: v + 0.01 len (u1 + u2) */
  double (*pos)[3] = tds_malloc(&m->alloc, (size_t)(c->n + 1) * sizeof *pos);
  if (!pos) rc = TDS_ENOMEM;
  if (rc == TDS_OK) { /* one offset for the whole chain, from the popped edge's wedge */
    double u1[3], u2[3], off[3];
    perp(m, c->w[p][0], e, m->ev[e][0], m->ev[e][1], u1);
    perp(m, c->w[p][1], e, m->ev[e][0], m->ev[e][1], u2);
    v3_add(off, u1, u2);
    v3_scale(off, 0.01 * len);
    for (int i = 0; i < c->n; i++) v3_add(pos[i], m->x[c->v[i]], off);
  }
  for (int k = 0; k < c->n && rc == TDS_OK; k++) {
    int i = p + k < c->n ? p + k : p - 1 - (k - (c->n - p));
    int head = p + k < c->n;
    tds_id near = head ? c->e[i] : c->e[i + 1], far = head ? c->e[i + 1] : c->e[i];
    const tds_id *wn = head ? c->w[i] : c->w[i + 1];
    if (tds_mesh_adjacency(m) != TDS_OK) {
      rc = TDS_ENOMEM;
      break;
    }
    /* the wedge's fins at v[i], from the wedge facets on near */
    tds_id W[2 * MAXVAL], last;
    int nw = 0;
    tds_id v = c->v[i];
    for (int j = 0; j < 2; j++)
      if (fin(m, v, near, wn[j], W, &nw, 2 * MAXVAL, &last) != far) rc = TDS_ETOPO;
    if (rc == TDS_OK) rc = pull(s, v, near, far, W, nw, wn, pos[i]);
    if (rc == TDS_OK) (*npulled)++;
  }
  tds_free(&m->alloc, pos);
  tds_free(&m->alloc, c);
  return rc;
}

static int pop_edges(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  tds_mesh *m = &s->m;
  int32_t ne0 = m->ne, cnt = 0;
  for (tds_id e = 0; e < ne0; e++) {
    if (sel && !sel[e]) continue;
    int32_t k = 0;
    int rc = tds_pop_one_edge(s, e, &k);
    if (rc == TDS_ENOMEM) return tds_seterr(ctx, rc, "out of memory while popping edges");
    if (rc == TDS_ERANGE) return tds_torus_pop_refused(ctx, &s->m, "pop", e);
    if (rc != TDS_OK) return tds_seterr(ctx, rc, "pop: edge %d: the chain changed while popping", e + 1);
    cnt += k;
  }
  *n = cnt;
  return tds_surf_update(ctx, s);
}

int tds_pop_edges(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  return tds_snap_run(ctx, s, pop_edges, sel, n);
}
