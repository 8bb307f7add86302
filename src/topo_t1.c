/* topo_t1.c: the foam T1 moves pop_edge_to_tri and pop_tri_to_edge.
**
** Both go through one vertex: pop_edge_to_tri collapses the edge
** between two tetrahedral points (topo_collapse.c) and expands the
** resulting vertex, where six triple edges meet, into a triangle;
** pop_tri_to_edge collapses the triangle and expands the vertex into an
** edge. The expansion works on the fans of facets at the vertex (facets
** joined through its edges of valence 2, bounded by two triple edges):
** each triple edge goes to one of the new vertices; a fan whose two ends
** go to the same new vertex follows them; a fan whose ends go to
** different ones P and Q follows P and gains a facet (P, u, Q) on the
** edge P-Q, where u is the far end of the triple edge at Q. Each edge is
** done under its own snapshot, so one that does not fit the pattern is
** skipped with the surface as before. */
#include "torus.h"
#include "topo_edit.h"
#include "string_model.h"

#include <math.h>
#include <stdlib.h>

#include "motion.h"
#include "topo.h"
#include "topo_t1.h"
#include "snap.h"
#include "vec3.h"

static int root(int *p, int i) {
  while (p[i] != i) i = p[i] = p[p[i]];
  return i;
}

static int32_t oref_from(const tds_mesh *m, tds_id e, tds_id from) {
  return TDS_OREF(e, m->ev[e][0] == from ? 0 : 1);
}

/* Edge between new vertices p and q among conn[0..nc-1], or TDS_NONE. */
static tds_id conn_edge(const tds_mesh *m, const tds_id *conn, int nc, tds_id p, tds_id q) {
  for (int i = 0; i < nc; i++) {
    tds_id e = conn[i];
    if ((m->ev[e][0] == p && m->ev[e][1] == q) || (m->ev[e][0] == q && m->ev[e][1] == p)) return e;
  }
  return TDS_NONE;
}

#define MAXF 256

static tds_id far_end(const tds_mesh *m, tds_id e, tds_id v) {
  return m->ev[e][0] == v ? m->ev[e][1] : m->ev[e][0];
}

/* The live facets at v into fl (at most MAXF), each its own label in lab
** (for joining into fans); their count, or -1 when there are more. */
static int star_facets(const tds_mesh *m, tds_id v, tds_id *fl, int *lab) {
  int nf = 0;
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f) && (m->fv[f][0] == v || m->fv[f][1] == v || m->fv[f][2] == v)) {
      if (nf == MAXF) return -1;
      fl[nf] = f;
      lab[nf] = nf;
      nf++;
    }
  return nf;
}

/* Expand vertex v (topo_t1.h). */
int tds_t1_expand(tds_mesh *m, tds_id v, int nt, const tds_id *te, const tds_id *tv,
                  const tds_id *conn, int nc, int flip, const double *axis, tds_id follow) {
  tds_id fl[MAXF];
  int lab[MAXF], nf = star_facets(m, v, fl, lab);
  if (nf < 0) return TDS_ETOPO;
  /* join facets through non-triple edges at v */
  for (int i = 0; i < nf; i++)
    for (int k = 0; k < 3; k++) {
      tds_id e = TDS_OID(m->fe[fl[i]][k]);
      if (m->ev[e][0] != v && m->ev[e][1] != v) continue;
      int triple = 0;
      for (int t = 0; t < nt; t++) triple |= te[t] == e;
      if (triple) continue;
      for (int j = 0; j < nf; j++)
        if (j != i)
          for (int q = 0; q < 3; q++)
            if (TDS_OID(m->fe[fl[j]][q]) == e) lab[root(lab, j)] = root(lab, i);
    }
  for (int i = 0; i < nf; i++) lab[i] = root(lab, i);
  /* the two triple edges bounding each fan */
  int endx[MAXF], endy[MAXF], xfacet[MAXF], yfacet[MAXF];
  for (int i = 0; i < nf; i++) endx[i] = endy[i] = xfacet[i] = yfacet[i] = -1;
  for (int i = 0; i < nf; i++)
    for (int k = 0; k < 3; k++)
      for (int t = 0; t < nt; t++)
        if (TDS_OID(m->fe[fl[i]][k]) == te[t]) {
          int r = lab[i];
          if (endx[r] < 0) { endx[r] = t; xfacet[r] = i; }
          else if (endx[r] != t && endy[r] < 0) { endy[r] = t; yfacet[r] = i; }
          else if (endx[r] != t && endy[r] != t) return TDS_ETOPO;
        }
  if (flip) /* the fans follow their other end */
    for (int i = 0; i < nf; i++) {
      int t = endx[i];
      endx[i] = endy[i], endy[i] = t;
      t = xfacet[i];
      xfacet[i] = yfacet[i], yfacet[i] = t;
    }
  for (int i = 0; i < nf; i++)
    if (lab[i] == i && (endx[i] < 0 || endy[i] < 0)) return TDS_ETOPO;
  if (follow != TDS_NONE) /* fans that part follow `follow` */
    for (int i = 0; i < nf; i++)
      if (lab[i] == i && tv[endy[i]] == follow && tv[endx[i]] != follow) {
        int t = endx[i];
        endx[i] = endy[i], endy[i] = t;
        t = xfacet[i];
        xfacet[i] = yfacet[i], yfacet[i] = t;
      }
  for (int i = 0; axis && i < nf; i++) {
    if (lab[i] != i || tv[endx[i]] == tv[endy[i]]) continue;
    double px[3], py[3], c[3];
    v3_sub(px, m->x[far_end(m, te[endx[i]], v)], m->x[v]);
    v3_sub(py, m->x[far_end(m, te[endy[i]], v)], m->x[v]);
    v3_cross(c, px, py);
    if (v3_dot(c, axis) > 0) { /* y is counterclockwise after x */
      int t = endx[i];
      endx[i] = endy[i], endy[i] = t;
      t = xfacet[i];
      xfacet[i] = yfacet[i], yfacet[i] = t;
    }
  }
  for (int i = 0; i < nf; i++) {
    int r = lab[i];
    if (tv[endx[r]] != tv[endy[r]] &&
        conn_edge(m, conn, nc, tv[endx[r]], tv[endy[r]]) == TDS_NONE)
      return TDS_ETOPO;
  }
  /* Checked: move everything. Inner edges and facets follow their fan's
  ** x end; triple edges their own target. */
  for (int i = 0; i < nf; i++) {
    tds_id f = fl[i], P = tv[endx[lab[i]]];
    for (int k = 0; k < 3; k++) {
      if (m->fv[f][k] == v) m->fv[f][k] = P;
      tds_id e = TDS_OID(m->fe[f][k]);
      int triple = 0;
      for (int t = 0; t < nt; t++) triple |= te[t] == e;
      if (!triple)
        for (int j = 0; j < 2; j++)
          if (m->ev[e][j] == v) m->ev[e][j] = P;
    }
  }
  for (int t = 0; t < nt; t++)
    for (int j = 0; j < 2; j++)
      if (m->ev[te[t]][j] == v) m->ev[te[t]][j] = tv[t];
  /* fans whose ends part: the facet on y takes a new edge to P, and a new
  ** facet (P, u, Q) closes the gap */
  for (int r = 0; r < nf; r++) {
    if (lab[r] != r) continue;
    tds_id P = tv[endx[r]], Q = tv[endy[r]];
    if (P == Q) continue;
    tds_id f = fl[yfacet[r]], y = te[endy[r]];
    int k = 0;
    while (TDS_OID(m->fe[f][k]) != y) k++;
    int32_t oy = m->fe[f][k];
    tds_id u = m->ev[y][0] == Q ? m->ev[y][1] : m->ev[y][0];
    tds_id pq = conn_edge(m, conn, nc, P, Q);
    int32_t oe[3] = {m->fe[f][0], m->fe[f][1], m->fe[f][2]};
    int32_t g3[3];
    tds_id n;
    if (tds_oe_tail(m, oy) == u) { /* f runs u -> Q: now u -> P */
      n = tds_mesh_add_edge(m, u, P);
      oe[k] = TDS_OREF(n, 0);
      g3[0] = TDS_OREF(n, 1);          /* P -> u */
      g3[1] = oy;                      /* u -> Q */
      g3[2] = oref_from(m, pq, Q);     /* Q -> P */
    } else {                           /* f runs Q -> u: now P -> u */
      n = tds_mesh_add_edge(m, P, u);
      oe[k] = TDS_OREF(n, 0);
      g3[0] = oy;                      /* Q -> u */
      g3[1] = TDS_OREF(n, 1);          /* u -> P */
      g3[2] = oref_from(m, pq, P);     /* P -> Q */
    }
    m->eflags[n] = m->fflags[f] & TDS_FIXED;
    m->econ[n] = m->fcon[f];
    tds_mesh_set_facet(m, f, oe);
    tds_id g = tds_mesh_add_facet(m, g3);
    tds_facet_inherit(m, g, f);
  }
  int kept = 0;
  for (int t = 0; t < nt; t++) kept |= tv[t] == v;
  if (!kept) tds_mesh_kill(m, TDS_VERTEX, v);
  m->topo_gen++;
  return TDS_OK;
}

/* Triple edges at v other than `not` (up to 4), and whether every other
** edge at v has valence 2: a tetrahedral point. */
int tds_t1_tetra(const tds_mesh *m, tds_id v, tds_id not, tds_id *t3) {
  int n3 = 0, nt = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e) || (m->ev[e][0] != v && m->ev[e][1] != v)) continue;
    int val = tds_edge_valence(m, e);
    if (val == 3) {
      if (n3 == 4) return 0;
      if (e != not) t3[nt++] = e;
      n3++;
    } else if (val != 2) {
      return 0;
    }
  }
  return n3 == 4;
}

int tds_t1_free_vertex(const tds_surf *s, tds_id v) {
  const tds_mesh *m = &s->m;
  return !(m->vflags[v] & TDS_FIXED) && !(m->vcon[v] & ~tds_surf_global_cons(s)) &&
         m->vbdry[v] == TDS_NONE;
}

/* Bodies on the facets around edge e contain b? */
int tds_t1_around_has(const tds_mesh *m, tds_id e, tds_id b) {
  int32_t h = m->eside[e], sd = h;
  if (h == TDS_NONE) return 0;
  do {
    tds_id f = sd / 3;
    if (m->fb[f][0] == b || m->fb[f][1] == b) return 1;
    sd = m->side_next[sd];
  } while (sd != h);
  return 0;
}

/* Bodies on the facets around edge e (distinct, up to 8); count. */
int tds_t1_bodies_around(const tds_mesh *m, tds_id e, tds_id *out) {
  int n = 0;
  int32_t h = m->eside[e], sd = h;
  if (h == TDS_NONE) return 0;
  do {
    tds_id f = sd / 3;
    for (int q = 0; q < 2; q++) {
      int dup = 0;
      for (int z = 0; z < n; z++) dup |= out[z] == m->fb[f][q];
      if (!dup && n < 8) out[n++] = m->fb[f][q];
    }
    sd = m->side_next[sd];
  } while (sd != h);
  return n;
}

/* The body around all three triple edges t[0..2]: the one beyond their
** common vertex; -2 if there is none or more than one. */
static tds_id common_body(const tds_mesh *m, const tds_id *t) {
  tds_id bs[8], found = -2;
  int nb = tds_t1_bodies_around(m, t[0], bs);
  for (int z = 0; z < nb; z++)
    if (tds_t1_around_has(m, t[1], bs[z]) && tds_t1_around_has(m, t[2], bs[z])) {
      if (found != -2) return -2;
      found = bs[z];
    }
  return found;
}

/* The other edge of facet f at vertex v than g. */
static tds_id other_at(const tds_mesh *m, tds_id f, tds_id v, tds_id g) {
  for (int k = 0; k < 3; k++) {
    tds_id h = TDS_OID(m->fe[f][k]);
    if (h != g && (m->ev[h][0] == v || m->ev[h][1] == v)) return h;
  }
  return TDS_NONE;
}

/* The wall of facet f (on edge e at v) runs through v's valence-2 edges
** to a triple edge: that edge, or TDS_NONE (a loop, or another valence). */
static tds_id wall_end(const tds_mesh *m, tds_id v, tds_id e, tds_id f) {
  for (int steps = 0; steps <= MAXF; steps++) {
    tds_id g = other_at(m, f, v, e);
    if (g == TDS_NONE) return TDS_NONE;
    int val = tds_edge_valence(m, g);
    if (val == 3) return g;
    if (val != 2) return TDS_NONE;
    int32_t sd = m->eside[g];
    tds_id f2 = sd / 3;
    f = f2 == f ? m->side_next[sd] / 3 : f2;
    e = g;
  }
  return TDS_NONE;
}

/* The triple edge joining v and w, or TDS_NONE. */
static tds_id triple_to(const tds_mesh *m, tds_id v, tds_id w) {
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e) && far_end(m, e, v) == w && (m->ev[e][0] == v || m->ev[e][1] == v) &&
        tds_edge_valence(m, e) == 3)
      return e;
  return TDS_NONE;
}

/* One edge to a triangle; 1 done, 0 not applicable, <0 error code. */
static int edge_to_tri(tds_surf *s, tds_id e, int dry) {
  tds_mesh *m = &s->m;
  if (!tds_alive(m->eflags, e) || (m->eflags[e] & TDS_FIXED) || m->econ[e] ||
      m->ebdry[e] != TDS_NONE || tds_edge_valence(m, e) != 3)
    return 0;
  tds_id a = m->ev[e][0], b = m->ev[e][1], ta[4], tb[4];
  if (!tds_t1_free_vertex(s, a) || !tds_t1_free_vertex(s, b) || !tds_t1_tetra(m, a, e, ta) || !tds_t1_tetra(m, b, e, tb))
    return 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      if (far_end(m, ta[i], a) == far_end(m, tb[j], b)) return 0;
  tds_id D = common_body(m, ta), E = common_body(m, tb);
  /* a film with no bodies (both sides none) pops as Evolver's does */
  if (D == -2 || E == -2 || (D == E && D != TDS_NONE)) return 0;
  /* the three walls on e: each joins a triple edge at a to one at b (by
  ** their far ends, which the collapse keeps) */
  tds_id fa[3], fb[3];
  int nw = 0;
  int32_t h0 = m->eside[e], sd = h0;
  do {
    tds_id f = sd / 3, ga = wall_end(m, a, e, f), gb = wall_end(m, b, e, f);
    if (ga == TDS_NONE || gb == TDS_NONE) return 0;
    fa[nw] = far_end(m, ga, a);
    fb[nw] = far_end(m, gb, b);
    for (int j = 0; j < nw; j++)
      if (fa[j] == fa[nw] || fb[j] == fb[nw]) return 0;
    nw++;
    sd = m->side_next[sd];
  } while (sd != h0 && nw < 3);
  if (sd != h0) return 0;
  if (dry) return 1;
  double xa[3], xb[3], dab[3];
  v3_copy(xa, m->x[a]);
  v3_copy(xb, m->x[b]);
  v3_sub(dab, xa, xb);
  if (tds_mesh_room(m, TDS_VERTEX, m->nv + 3) || tds_mesh_room(m, TDS_EDGE, m->ne + 12) ||
      tds_mesh_room(m, TDS_FACET, m->nf + 8))
    return TDS_ENOMEM;
  int r = tds_collapse_edge(s, e);
  if (r <= 0) return r < 0 ? TDS_ENOMEM : 0;
  tds_id v = tds_alive(m->vflags, a) ? a : b;
  /* each wall's two triple edges at v go to one new vertex, a third of
  ** the way from the collapse point to the midpoint of their far ends
  ** (as Evolver's, to 1e-10 on a five-bubble cluster) */
  tds_id p[3], te[6], tv[6], conn[3];
  for (int k = 0; k < 3; k++) {
    te[2 * k] = triple_to(m, v, fa[k]);
    te[2 * k + 1] = triple_to(m, v, fb[k]);
    if (te[2 * k] == TDS_NONE || te[2 * k + 1] == TDS_NONE) return TDS_ETOPO;
    p[k] = tds_mesh_add_vertex(m, m->x[v]);
    m->vcon[p[k]] = m->vcon[v];
    tv[2 * k] = tv[2 * k + 1] = p[k];
    double q[3];
    v3_add(q, m->x[fa[k]], m->x[fb[k]]);
    v3_scale(q, 0.5);
    for (int i = 0; i < 3; i++) m->x[p[k]][i] = m->x[v][i] + (q[i] - m->x[v][i]) / 3;
  }
  for (int k = 0; k < 3; k++) conn[k] = tds_mesh_add_edge(m, p[k], p[(k + 1) % 3]);
  /* each film between two triple edges at one end follows the corner
  ** counterclockwise after the other about the old edge a -> b (as
  ** Evolver's on the cluster and on twelve seeded prisms) */
  double axis[3];
  v3_sub(axis, xb, xa);
  int rc = tds_t1_expand(m, v, 6, te, tv, conn, 3, 0, axis, TDS_NONE);
  if (rc != TDS_OK) return rc;
  /* the loop starts at the corner of the second wall (Evolver's, which
  ** pop_tri_to_edge then collapses from its first edge) */
  int32_t t3[3] = {TDS_OREF(conn[1], 0), TDS_OREF(conn[2], 0), TDS_OREF(conn[0], 0)};
  tds_id T = tds_mesh_add_facet(m, t3);
  double n[3], u1[3], u2[3];
  v3_sub(u1, m->x[p[1]], m->x[p[0]]);
  v3_sub(u2, m->x[p[2]], m->x[p[0]]);
  v3_cross(n, u1, u2);
  /* the normal points out of the front body; D lies beyond a */
  int toward_d = v3_dot(n, dab) > 0;
  m->fb[T][0] = toward_d ? E : D;
  m->fb[T][1] = toward_d ? D : E;
  for (int k = 0; k < 3; k++) tds_motion_enforce(s, p[k]);
  m->coord_gen++;
  return 1;
}

/* One triangle to an edge; 1 done, 0 not applicable, <0 error. */
static int tri_to_edge(tds_surf *s, tds_id f, int dry) {
  tds_mesh *m = &s->m;
  if (!tds_alive(m->fflags, f)) return 0;
  tds_id D = m->fb[f][1], E = m->fb[f][0]; /* normal points into D */
  if (D == E) return 0;
  tds_id pv[3], tx[3][4], x[3], y[3];
  for (int k = 0; k < 3; k++) {
    tds_id e = TDS_OID(m->fe[f][k]);
    if ((m->eflags[e] & TDS_FIXED) || m->econ[e] || m->ebdry[e] != TDS_NONE ||
        tds_edge_valence(m, e) != 3)
      return 0;
    pv[k] = m->fv[f][k];
    if (!tds_t1_free_vertex(s, pv[k]) || !tds_t1_tetra(m, pv[k], TDS_NONE, tx[k])) return 0;
    /* the two triple edges off the triangle: x toward D, y toward E */
    x[k] = y[k] = TDS_NONE;
    for (int i = 0; i < 4; i++) {
      tds_id t = tx[k][i];
      int onf = 0;
      for (int q = 0; q < 3; q++) onf |= TDS_OID(m->fe[f][q]) == t;
      if (onf) continue;
      int hd = tds_t1_around_has(m, t, D), he = tds_t1_around_has(m, t, E);
      if (hd && !he) x[k] = t;
      else if (he && !hd) y[k] = t;
    }
    if (x[k] == TDS_NONE || y[k] == TDS_NONE) return 0;
  }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      if (i != j && (far_end(m, x[i], pv[i]) == far_end(m, x[j], pv[j]) ||
                     far_end(m, y[i], pv[i]) == far_end(m, y[j], pv[j]) ||
                     far_end(m, x[i], pv[i]) == far_end(m, y[j], pv[j])))
        return 0;
  if (dry) return 1;
  double cd[3] = {0, 0, 0}; /* the centroid of the far ends on D's side */
  for (int k = 0; k < 3; k++) v3_axpy(cd, 1.0 / 3, m->x[far_end(m, x[k], pv[k])]);
  if (tds_mesh_room(m, TDS_VERTEX, m->nv + 2) || tds_mesh_room(m, TDS_EDGE, m->ne + 6) ||
      tds_mesh_room(m, TDS_FACET, m->nf + 6))
    return TDS_ENOMEM;
  /* collapse the triangle: one edge, then what is left of it */
  tds_id e0 = TDS_OID(m->fe[f][0]);
  int r = tds_collapse_edge(s, e0);
  if (r <= 0) return r < 0 ? TDS_ENOMEM : TDS_ETOPO;
  tds_id left = TDS_NONE;
  for (tds_id e = 0; e < m->ne && left == TDS_NONE; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    int hit = 0;
    for (int k = 0; k < 3; k++) hit += tds_alive(m->vflags, pv[k]) && (m->ev[e][0] == pv[k] || m->ev[e][1] == pv[k]);
    if (hit == 2) left = e;
  }
  if (left == TDS_NONE) return TDS_ETOPO;
  r = tds_collapse_edge(s, left);
  if (r <= 0) return r < 0 ? TDS_ENOMEM : TDS_ETOPO;
  tds_id v = TDS_NONE;
  for (int k = 0; k < 3; k++)
    if (tds_alive(m->vflags, pv[k])) v = pv[k];
  /* As Evolver's (to 1e-10 on a five-bubble cluster): v is where the
  ** two collapses left it, half way from the triangle's third corner to
  ** the midpoint of its first edge; the new edge runs from b to a, a on
  ** D's side a quarter of the way to cd and b opposite it through v. */
  double xa[3], xb[3];
  for (int i = 0; i < 3; i++) {
    xa[i] = m->x[v][i] + (cd[i] - m->x[v][i]) / 4;
    xb[i] = 2 * m->x[v][i] - xa[i];
  }
  tds_id a = tds_mesh_add_vertex(m, xa), b = tds_mesh_add_vertex(m, xb);
  tds_id ab = tds_mesh_add_edge(m, b, a);
  /* the triple edges at v now (merges may have renamed some): D's side
  ** goes to a, E's to b */
  tds_id te[6], tv[6];
  int nt = 0;
  for (tds_id d = 0; d < m->ne; d++) {
    if (d == ab || !tds_alive(m->eflags, d) || (m->ev[d][0] != v && m->ev[d][1] != v)) continue;
    if (tds_edge_valence(m, d) != 3) continue;
    int hd = tds_t1_around_has(m, d, D), he = tds_t1_around_has(m, d, E);
    if (nt == 6 || hd == he) return TDS_ETOPO;
    te[nt] = d;
    tv[nt++] = hd ? a : b;
  }
  if (nt != 6) return TDS_ETOPO;
  /* the films beside the new edge all follow b, as Evolver's (a gets gap facets) */
  int rc = tds_t1_expand(m, v, 6, te, tv, &ab, 1, 0, NULL, b);
  if (rc != TDS_OK) return rc;
  tds_motion_enforce(s, a);
  tds_motion_enforce(s, b);
  m->coord_gen++;
  return 1;
}

typedef int (*one_fn)(tds_surf *, tds_id, int);

/* Each selected element under its own snapshot: one that does not fit
** is put back and skipped. */
static int each(tds_ctx *ctx, tds_surf *s, int kind, const uint8_t *sel, one_fn fn,
                int32_t *n) {
  int32_t cnt = 0, nslot = kind == TDS_EDGE ? s->m.ne : s->m.nf;
  for (tds_id i = 0; i < nslot; i++) {
    if ((sel && !sel[i]) || fn(s, i, 1) != 1) continue;
    tds_snap sn;
    int rc = tds_snap_take(ctx, s, &sn);
    if (rc != TDS_OK) return rc;
    int r = fn(s, i, 0);
    if (r == 1) {
      tds_snap_free(&sn);
      cnt++;
    } else {
      tds_snap_restore(s, &sn);
      if (r == TDS_ENOMEM) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    }
  }
  *n = cnt;
  return tds_surf_update(ctx, s);
}

static int run(tds_ctx *ctx, tds_surf *s, int kind, const uint8_t *sel, one_fn fn, int32_t *n) {
  if (n) *n = 0;
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  int32_t cnt = 0;
  rc = tds_snap_end(ctx, s, &sn, each(ctx, s, kind, sel, fn, &cnt));
  if (n) *n = rc == TDS_OK ? cnt : 0;
  return rc;
}

int tds_pop_edge_to_tri(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  if (n) *n = 0;
  if (s->str) return tds_string_unsupported(ctx, "pop_edge_to_tri");
  if (s->m.torus) return tds_torus_unsupported(ctx, "pop_edge_to_tri");
  return run(ctx, s, TDS_EDGE, sel, edge_to_tri, n);
}

int tds_pop_tri_to_edge(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  if (n) *n = 0;
  if (s->str) return tds_string_unsupported(ctx, "pop_tri_to_edge");
  if (s->m.torus) return tds_torus_unsupported(ctx, "pop_tri_to_edge");
  return run(ctx, s, TDS_FACET, sel, tri_to_edge, n);
}

/* The cone over a triangular prism frame at v (Evolver's pop_to_edge and
** pop_to_face toggles): v free, six triple edges and every other edge at
** v of valence 2, and the films at v (fans of facets between two triple
** edges) join the triple edges as the edges of a prism join its corners:
** two triangles t[0..2] and t[3..5], t[k] joined to t[k + 3]. Fills t;
** 1 if so, 0 if not. */
static int prism(const tds_surf *s, tds_id v, tds_id t[6]) {
  const tds_mesh *m = &s->m;
  if (!tds_t1_free_vertex(s, v)) return 0;
  tds_id te[6];
  int nt = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e) || (m->ev[e][0] != v && m->ev[e][1] != v)) continue;
    int val = tds_edge_valence(m, e);
    if (val == 3) {
      if (nt == 6) return 0;
      te[nt++] = e;
    } else if (val != 2) {
      return 0;
    }
  }
  if (nt != 6) return 0;
  /* fans: facets at v joined through the valence-2 edges at v */
  tds_id fl[MAXF];
  int lab[MAXF], nf = star_facets(m, v, fl, lab);
  if (nf < 0) return 0;
  for (int i = 0; i < nf; i++)
    for (int k = 0; k < 3; k++) {
      tds_id e = TDS_OID(m->fe[fl[i]][k]);
      if ((m->ev[e][0] != v && m->ev[e][1] != v) || tds_edge_valence(m, e) != 2) continue;
      for (int j = 0; j < nf; j++)
        for (int q = 0; q < 3; q++)
          if (j != i && TDS_OID(m->fe[fl[j]][q]) == e) lab[root(lab, j)] = root(lab, i);
    }
  int ends[MAXF][2], adj[6][6] = {{0}}, nfan = 0;
  for (int i = 0; i < nf; i++) ends[i][0] = ends[i][1] = -1;
  for (int i = 0; i < nf; i++) {
    int r = root(lab, i);
    for (int k = 0; k < 3; k++)
      for (int q = 0; q < 6; q++)
        if (TDS_OID(m->fe[fl[i]][k]) == te[q] && ends[r][0] != q) {
          if (ends[r][0] < 0) ends[r][0] = q;
          else if (ends[r][1] < 0) ends[r][1] = q;
          else return 0;
        }
  }
  for (int i = 0; i < nf; i++) {
    if (root(lab, i) != i) continue;
    if (ends[i][0] < 0 || ends[i][1] < 0 || adj[ends[i][0]][ends[i][1]]) return 0;
    adj[ends[i][0]][ends[i][1]] = adj[ends[i][1]][ends[i][0]] = 1;
    nfan++;
  }
  if (nfan != 9) return 0;
  /* the triangle through te[0]; the other one is the rest */
  int tri[3] = {0, -1, -1}, in1[6] = {1, 0, 0, 0, 0, 0};
  for (int a = 1; a < 6 && tri[1] < 0; a++)
    for (int b = a + 1; b < 6; b++)
      if (adj[0][a] && adj[0][b] && adj[a][b]) {
        tri[1] = a, tri[2] = b;
        break;
      }
  if (tri[1] < 0) return 0;
  in1[tri[1]] = in1[tri[2]] = 1;
  for (int k = 0; k < 3; k++) {
    t[k] = te[tri[k]];
    int partner = -1;
    for (int q = 0; q < 6; q++)
      if (!in1[q] && adj[tri[k]][q]) {
        if (partner >= 0) return 0;
        partner = q;
      }
    if (partner < 0) return 0;
    t[k + 3] = te[partner];
  }
  for (int k = 0; k < 3; k++) /* the second triple joined as a triangle */
    for (int j = k + 1; j < 3; j++) {
      int a = -1, b = -1;
      for (int q = 0; q < 6; q++) {
        if (te[q] == t[k + 3]) a = q;
        if (te[q] == t[j + 3]) b = q;
      }
      if (a < 0 || b < 0 || a == b || !adj[a][b]) return 0;
    }
  return 1;
}

/* Evolver's choice with neither toggle on, as measured (doc/commands.md):
** a triangle when the sums of the unit directions from v to the two
** triangles' corners have squared lengths adding up to less than 3. */
static int face_wins(const tds_mesh *m, tds_id v, const tds_id t[6]) {
  double q = 0;
  for (int h = 0; h < 2; h++) {
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
      double u[3];
      v3_sub(u, m->x[far_end(m, t[3 * h + k], v)], m->x[v]);
      double n = v3_norm(u);
      if (n > 0) v3_axpy(sum, 1 / n, u);
    }
    q += v3_dot(sum, sum);
  }
  return q < 3;
}

int tds_pop_prism(tds_surf *s, tds_id v, int to_face) {
  tds_mesh *m = &s->m;
  tds_id t[6];
  if (!prism(s, v, t)) return 0;
  if (to_face < 0) to_face = face_wins(m, v, t);
  tds_id D = common_body(m, t), E = common_body(m, t + 3);
  if (to_face && (D == -2 || E == -2)) return 0;
  if (tds_mesh_room(m, TDS_VERTEX, m->nv + 3) || tds_mesh_room(m, TDS_EDGE, m->ne + 12) ||
      tds_mesh_room(m, TDS_FACET, m->nf + 8))
    return -TDS_ENOMEM;
  double x[3], far[6][3];
  v3_copy(x, m->x[v]);
  for (int k = 0; k < 6; k++) v3_copy(far[k], m->x[far_end(m, t[k], v)]);
  tds_id tv[6], nw[3];
  int nn = to_face ? 3 : 2;
  for (int k = 0; k < nn; k++) {
    /* a quarter of the way toward the far ends the new vertex takes */
    double c[3] = {0, 0, 0};
    int cnt = 0;
    for (int q = 0; q < 6; q++)
      if (to_face ? q % 3 == k : q / 3 == k) {
        v3_add(c, c, far[q]);
        cnt++;
      }
    v3_scale(c, 1.0 / cnt);
    double p[3];
    double w = to_face ? 1.0 / 3 : 0.25;
    for (int i = 0; i < 3; i++) p[i] = x[i] + w * (c[i] - x[i]);
    nw[k] = tds_mesh_add_vertex(m, p);
    m->vcon[nw[k]] = m->vcon[v];
  }
  for (int q = 0; q < 6; q++) tv[q] = to_face ? nw[q % 3] : nw[q / 3];
  tds_id conn[3];
  int nc = to_face ? 3 : 1;
  for (int k = 0; k < nc; k++) conn[k] = tds_mesh_add_edge(m, nw[k], nw[(k + 1) % nn]);
  int rc = tds_t1_expand(m, v, 6, t, tv, conn, nc, to_face, NULL, TDS_NONE); /* as Evolver triangulates */
  if (rc != TDS_OK) return -rc;
  if (to_face) {
    int32_t t3[3] = {TDS_OREF(conn[0], 0), TDS_OREF(conn[1], 0), TDS_OREF(conn[2], 0)};
    tds_id T = tds_mesh_add_facet(m, t3);
    double n[3], u1[3], u2[3], d[3] = {0, 0, 0};
    v3_sub(u1, m->x[nw[1]], m->x[nw[0]]);
    v3_sub(u2, m->x[nw[2]], m->x[nw[0]]);
    v3_cross(n, u1, u2);
    for (int q = 0; q < 3; q++) { /* from the second triangle's side to the first's */
      v3_add(d, d, far[q]);
      v3_sub(d, d, far[q + 3]);
    }
    int toward_d = v3_dot(n, d) > 0; /* D is enclosed by the first triangle's films */
    m->fb[T][0] = toward_d ? E : D;
    m->fb[T][1] = toward_d ? D : E;
  }
  for (int k = 0; k < nn; k++) tds_motion_enforce(s, nw[k]);
  m->coord_gen++;
  return 1;
}
