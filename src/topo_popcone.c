/* topo_popcone.c: popping a vertex whose star is one cone that is not
** minimal (o / pop on vertices), Evolver's sphere construction.
**
** As measured on Evolver 2.70 (tests/evolver/popvertex.sh): every edge at
** the vertex v is cut at its midpoint p (the edge now starts there); every
** facet (v, a, b) loses its corner: it becomes (p_a, a, b) and a new facet
** (p_a, b, p_b) is added, with a new arc edge p_b -> p_a and a diagonal
** b -> p_a. The arcs divide the small sphere of midpoints into cells, one
** per region of space around v; the largest cell is left open,
** so its region flows through the middle (the size of a cell is its
** solid angle seen from v), and every other cell becomes
** film between its region and that one: a triangle as it is, a
** quadrilateral cut by the diagonal from the point on the lowest edge id,
** a longer cell fanned from a new vertex at its points' centroid. v goes.
*/
#include "topo_edit.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "topo.h"
#include "vec3.h"

#define MAXF 128 /* facets at the vertex */

static int root(int *p, int i) {
  while (p[i] != i) i = p[i] = p[p[i]];
  return i;
}

typedef struct cone {
  int nf, ng;
  tds_id f[MAXF];           /* facets at v */
  tds_id ga[MAXF], gb[MAXF]; /* edges v-a, v-b of facet (v, a, b) */
  tds_id a[MAXF], b[MAXF];
  int32_t eab[MAXF];        /* oriented edge a -> b */
  tds_id g[MAXF];           /* edges at v, in id order */
  tds_id p[MAXF];           /* midpoint vertex of g[i] */
  int lab[2 * MAXF];        /* regions of facet sides (2i: back, 2i+1: normal side) */
} cone;

static int gindex(const cone *c, tds_id g) {
  for (int i = 0; i < c->ng; i++)
    if (c->g[i] == g) return i;
  return -1;
}

static int findex(const cone *c, tds_id f) {
  for (int i = 0; i < c->nf; i++)
    if (c->f[i] == f) return i;
  return -1;
}

/* Facet normal (unnormalised). */
static void fnormal(const tds_mesh *m, tds_id f, double n[3]) {
  double p[3], q[3];
  v3_sub(p, m->x[m->fv[f][1]], m->x[m->fv[f][0]]);
  v3_sub(q, m->x[m->fv[f][2]], m->x[m->fv[f][0]]);
  v3_cross(n, p, q);
}

/* Join the regions between facets neighbouring around edge g (at v). */
static int join_around(const tds_mesh *m, cone *c, tds_id v, tds_id g) {
  tds_id w = m->ev[g][0] == v ? m->ev[g][1] : m->ev[g][0];
  double d[3], ang[MAXF], t[MAXF][3], u0[3] = {0, 0, 0};
  int idx[MAXF], n = 0;
  v3_sub(d, m->x[w], m->x[v]);
  double dd = v3_dot(d, d);
  if (dd <= 0) return 0;
  int32_t h = m->eside[g], sd = h;
  if (h == TDS_NONE) return 0;
  do {
    if (n == MAXF) return 0;
    tds_id f = sd / 3;
    int i = findex(c, f);
    if (i < 0) return 0;
    tds_id o = c->a[i] == w ? c->b[i] : c->a[i];
    double u[3];
    v3_sub(u, m->x[o], m->x[v]);
    v3_axpy(u, -v3_dot(u, d) / dd, d);
    double un = v3_norm(u);
    if (un <= 0) return 0;
    v3_scale(u, 1 / un);
    if (n == 0) v3_copy(u0, u);
    double cr[3];
    v3_cross(cr, u0, u);
    double a = atan2(v3_dot(cr, d) / sqrt(dd), v3_dot(u0, u));
    ang[n] = a < 0 ? a + 2 * TDS_PI : a;
    if (n == 0) ang[n] = 0;
    v3_cross(t[n], d, u); /* the counter-clockwise turn at f */
    idx[n++] = i;
    sd = m->side_next[sd];
  } while (sd != h);
  /* sort by angle */
  int ord[MAXF];
  for (int i = 0; i < n; i++) ord[i] = i;
  for (int i = 1; i < n; i++)
    for (int j = i; j > 0 && ang[ord[j]] < ang[ord[j - 1]]; j--) {
      int z = ord[j]; ord[j] = ord[j - 1]; ord[j - 1] = z;
    }
  for (int k = 0; k < n; k++) {
    int i = ord[k], j = ord[(k + 1) % n];
    double ni[3], nj[3];
    fnormal(m, c->f[idx[i]], ni);
    fnormal(m, c->f[idx[j]], nj);
    int si = v3_dot(ni, t[i]) > 0;  /* side of f_i facing f_j */
    int sj = !(v3_dot(nj, t[j]) > 0); /* side of f_j facing back */
    int x = root(c->lab, 2 * idx[i] + si), y = root(c->lab, 2 * idx[j] + sj);
    if (x != y) c->lab[x] = y;
  }
  return 1;
}

/* Cell polygon of region r: points (indices into g) in order; count, or
** -1 when the arcs do not close into one simple cycle. */
static int cell_cycle(const cone *c, int r, int *pt, int cap) {
  int arcs[MAXF], na = 0;
  for (int i = 0; i < 2 * c->nf; i++)
    if (c->lab[i] == r) {
      if (na == MAXF) return -1;
      arcs[na++] = i / 2;
    }
  if (na < 3 || na > cap) return -1;
  int used[MAXF] = {0};
  int first = gindex(c, c->ga[arcs[0]]), cur = gindex(c, c->gb[arcs[0]]);
  used[0] = 1;
  pt[0] = first;
  int n = 1;
  while (cur != first) {
    if (n >= na) return -1;
    pt[n++] = cur;
    int k = -1;
    for (int j = 0; j < na; j++) {
      if (used[j]) continue;
      int x = gindex(c, c->ga[arcs[j]]), y = gindex(c, c->gb[arcs[j]]);
      if (x == cur || y == cur) {
        k = j;
        cur = x == cur ? y : x;
        break;
      }
    }
    if (k < 0) return -1;
    used[k] = 1;
  }
  return n == na ? n : -1;
}

int tds_pop_cone(tds_surf *s, tds_id v, int *done) {
  tds_mesh *m = &s->m;
  *done = 0;
  if (tds_mesh_adjacency(m) != TDS_OK) return TDS_ENOMEM;
  cone *c = tds_calloc(&m->alloc, 1, sizeof *c);
  if (!c) return TDS_ENOMEM;
  int rc = TDS_OK;
  c->nf = m->vf_start[v + 1] - m->vf_start[v];
  c->ng = m->ve_start[v + 1] - m->ve_start[v];
  if (c->nf > MAXF || c->ng > MAXF || c->nf < 3) goto out;
  for (int i = 0; i < c->ng; i++) c->g[i] = TDS_OID(m->ve[m->ve_start[v] + i]);
  for (int i = 1; i < c->ng; i++)
    for (int j = i; j > 0 && c->g[j] < c->g[j - 1]; j--) {
      tds_id z = c->g[j]; c->g[j] = c->g[j - 1]; c->g[j - 1] = z;
    }
  for (int i = 0; i < c->ng; i++)
    if (m->ev[c->g[i]][0] == m->ev[c->g[i]][1]) goto out;
  for (int i = 0; i < c->nf; i++) {
    tds_id f = m->vf[m->vf_start[v] + i];
    c->f[i] = f;
    int k = 0;
    while (k < 3 && m->fv[f][k] != v) k++;
    if (k == 3) goto out;
    c->a[i] = m->fv[f][(k + 1) % 3];
    c->b[i] = m->fv[f][(k + 2) % 3];
    c->eab[i] = m->fe[f][(k + 1) % 3];
    c->ga[i] = TDS_OID(m->fe[f][k]);
    c->gb[i] = TDS_OID(m->fe[f][(k + 2) % 3]);
  }
  for (int i = 0; i < 2 * c->nf; i++) c->lab[i] = i;
  for (int i = 0; i < c->ng; i++)
    if (!join_around(m, c, v, c->g[i])) goto out;
  for (int i = 0; i < 2 * c->nf; i++) c->lab[i] = root(c->lab, i);
  /* the midpoints (not yet made: their places) and the cells */
  double (*px)[3] = tds_malloc(&m->alloc, (size_t)c->ng * sizeof *px);
  int *cyc = tds_malloc(&m->alloc, (size_t)(2 * c->nf) * (size_t)(c->nf + 1) * sizeof *cyc);
  int *clen = tds_malloc(&m->alloc, (size_t)(2 * c->nf) * sizeof *clen);
  if (!px || !cyc || !clen) {
    rc = TDS_ENOMEM;
    goto free3;
  }
  for (int i = 0; i < c->ng; i++) {
    tds_id w = m->ev[c->g[i]][0] == v ? m->ev[c->g[i]][1] : m->ev[c->g[i]][0];
    v3_add(px[i], m->x[v], m->x[w]);
    v3_scale(px[i], 0.5);
  }
  int ncell = 0, big = -1;
  double bigarea = -1;
  int *cell = cyc;
  for (int r = 0; r < 2 * c->nf; r++) {
    if (c->lab[r] != r) continue;
    int *pt = cell + ncell * (c->nf + 1);
    int n = cell_cycle(c, r, pt, c->nf);
    if (n < 0) goto free3; /* not a simple sphere of cells: leave it */
    clen[ncell] = n;
    /* orient outwards (Newell normal against the centroid's direction) */
    double ctr[3] = {0, 0, 0}, nn[3] = {0, 0, 0}, out[3];
    for (int k = 0; k < n; k++) v3_axpy(ctr, 1.0 / n, px[pt[k]]);
    double area = 0;
    for (int k = 0; k < n; k++) {
      double p[3], q[3], cr[3];
      v3_sub(p, px[pt[k]], ctr);
      v3_sub(q, px[pt[(k + 1) % n]], ctr);
      v3_cross(cr, p, q);
      v3_add(nn, nn, cr);
      area += 0.5 * v3_norm(cr);
    }
    /* Evolver's measure of a cell: its solid angle seen from v */
    area = 0;
    for (int k = 1; k + 1 < n; k++) {
      double a[3], b[3], cc[3], bc[3];
      v3_sub(a, px[pt[0]], m->x[v]);
      v3_sub(b, px[pt[k]], m->x[v]);
      v3_sub(cc, px[pt[k + 1]], m->x[v]);
      v3_scale(a, 1 / v3_norm(a));
      v3_scale(b, 1 / v3_norm(b));
      v3_scale(cc, 1 / v3_norm(cc));
      v3_cross(bc, b, cc);
      area += 2 * atan2(v3_dot(a, bc), 1 + v3_dot(a, b) + v3_dot(b, cc) + v3_dot(cc, a));
    }
    area = fabs(area);
    v3_sub(out, ctr, m->x[v]);
    if (v3_dot(nn, out) < 0)
      for (int k = 0; k < n / 2; k++) {
        int z = pt[k]; pt[k] = pt[n - 1 - k]; pt[n - 1 - k] = z;
      }
    pt[c->nf] = r; /* the region, kept after the points */
    if (area > bigarea) {
      bigarea = area;
      big = ncell;
    }
    ncell++;
  }
  if (ncell < 2) goto free3;
  /* room for everything */
  int nnv = c->ng, nne = 2 * c->nf, nnf = c->nf;
  for (int k = 0; k < ncell; k++) {
    if (k == big) continue;
    int n = clen[k];
    if (n == 4) { nne += 1; nnf += 2; }
    else if (n > 4) { nnv += 1; nne += n; nnf += n; }
    else nnf += 1;
  }
  if (tds_mesh_room(m, TDS_VERTEX, m->nv + nnv) || tds_mesh_room(m, TDS_EDGE, m->ne + nne) ||
      tds_mesh_room(m, TDS_FACET, m->nf + nnf)) {
    rc = TDS_ENOMEM;
    goto free3;
  }
  /* the region's body beyond a cell, and the body of the big region */
  tds_id bbig = TDS_NONE;
  {
    int r = cell[big * (c->nf + 1) + c->nf];
    for (int i = 0; i < 2 * c->nf; i++)
      if (c->lab[i] == r) {
        bbig = m->fb[c->f[i / 2]][i % 2];
        break;
      }
  }
  /* midpoints; the edges now start there */
  for (int i = 0; i < c->ng; i++) {
    tds_id p = tds_mesh_add_vertex(m, px[i]);
    m->vflags[p] = m->vflags[v];
    m->vcon[p] = m->vcon[v];
    m->vbdry[p] = TDS_NONE;
    tds_mesh_inherit(m, TDS_VERTEX, p, v);
    m->vfile[p] = 0;
    c->p[i] = p;
  }
  /* arcs first (new facets need them), facets cut */
  tds_id *arc = tds_malloc(&m->alloc, (size_t)c->nf * sizeof *arc);
  if (!arc) {
    rc = TDS_ENOMEM;
    goto free3;
  }
  for (int i = 0; i < c->ng; i++) {
    tds_id g = c->g[i];
    for (int j = 0; j < 2; j++)
      if (m->ev[g][j] == v) m->ev[g][j] = c->p[i];
  }
  for (int i = 0; i < c->nf; i++) {
    tds_id f = c->f[i];
    int ia = gindex(c, c->ga[i]), ib = gindex(c, c->gb[i]);
    tds_id pa = c->p[ia], pb = c->p[ib];
    tds_id ar = tds_mesh_add_edge(m, pb, pa);
    tds_id dg = tds_mesh_add_edge(m, c->b[i], pa);
    m->eflags[ar] = m->eflags[dg] = m->fflags[f] & TDS_NO_REFINE;
    arc[i] = ar;
    int32_t kept[3] = {TDS_OREF(c->ga[i], m->ev[c->ga[i]][0] != pa), c->eab[i], TDS_OREF(dg, 0)};
    int32_t cut[3] = {TDS_OREF(dg, 1), TDS_OREF(c->gb[i], m->ev[c->gb[i]][0] != c->b[i]),
                      TDS_OREF(ar, 0)};
    tds_mesh_set_facet(m, f, kept);
    tds_id nf = tds_mesh_add_facet(m, cut);
    tds_facet_inherit(m, nf, f);
  }
  /* the cells but the big one */
  for (int k = 0; k < ncell; k++) {
    if (k == big) continue;
    int n = clen[k], *pt = cell + k * (c->nf + 1), r = pt[c->nf];
    tds_id bc = TDS_NONE, fsrc = TDS_NONE;
    for (int i = 0; i < 2 * c->nf; i++)
      if (c->lab[i] == r) {
        fsrc = c->f[i / 2];
        bc = m->fb[fsrc][i % 2];
        break;
      }
    /* the arc between points x and y, oriented x -> y */
    int32_t side[MAXF];
    for (int q = 0; q < n; q++) {
      tds_id x = c->p[pt[q]], y = c->p[pt[(q + 1) % n]];
      side[q] = -1;
      for (int i = 0; i < c->nf; i++) {
        if (c->lab[2 * i] != r && c->lab[2 * i + 1] != r) continue;
        tds_id e = arc[i];
        if (m->ev[e][0] == x && m->ev[e][1] == y) side[q] = TDS_OREF(e, 0);
        else if (m->ev[e][0] == y && m->ev[e][1] == x) side[q] = TDS_OREF(e, 1);
      }
    }
    tds_id made[MAXF];
    int nmade = 0;
    if (n == 3) {
      made[nmade++] = tds_mesh_add_facet(m, side);
    } else if (n == 4) {
      int s0 = 0; /* the diagonal from the point on the lowest edge id */
      for (int q = 1; q < 4; q++)
        if (pt[q] < pt[s0]) s0 = q;
      tds_id x = c->p[pt[s0]], z = c->p[pt[(s0 + 2) % 4]];
      tds_id dg = tds_mesh_add_edge(m, x, z);
      int32_t t1[3] = {side[s0], side[(s0 + 1) % 4], TDS_OREF(dg, 1)};
      int32_t t2[3] = {TDS_OREF(dg, 0), side[(s0 + 2) % 4], side[(s0 + 3) % 4]};
      made[nmade++] = tds_mesh_add_facet(m, t1);
      made[nmade++] = tds_mesh_add_facet(m, t2);
    } else {
      double ctr[3] = {0, 0, 0};
      for (int q = 0; q < n; q++) v3_axpy(ctr, 1.0 / n, px[pt[q]]);
      tds_id w = tds_mesh_add_vertex(m, ctr);
      m->vflags[w] = m->vflags[v];
      m->vcon[w] = m->vcon[v];
      tds_mesh_inherit(m, TDS_VERTEX, w, v);
      m->vfile[w] = 0;
      tds_id sp[MAXF];
      for (int q = 0; q < n; q++) sp[q] = tds_mesh_add_edge(m, c->p[pt[q]], w);
      for (int q = 0; q < n; q++) {
        int32_t t[3] = {side[q], TDS_OREF(sp[(q + 1) % n], 0), TDS_OREF(sp[q], 1)};
        made[nmade++] = tds_mesh_add_facet(m, t);
      }
    }
    for (int q = 0; q < nmade; q++) {
      tds_id f = made[q];
      tds_facet_inherit(m, f, fsrc);
      m->ffile[f] = 0;
      m->forig[f] = TDS_NONE;
      m->fflags[f] &= ~TDS_FIXED;
      /* normal outwards: the cell's region on the normal side */
      m->fb[f][1] = bc;
      m->fb[f][0] = bbig;
    }
  }
  tds_free(&m->alloc, arc);
  tds_mesh_kill(m, TDS_VERTEX, v);
  m->topo_gen++;
  *done = 1;
free3:
  tds_free(&m->alloc, px);
  tds_free(&m->alloc, cyc);
  tds_free(&m->alloc, clen);
out:
  tds_free(&m->alloc, c);
  return rc;
}
