/* topo_popneck.c: o / pop with Evolver's pop_enjoin toggle: a vertex where
** two cones of facets meet (a neck pinched by t) widens into a neck
** instead of splitting in two.
**
** As measured on Evolver 2.70 (cat.fe's pinched neck, tests/evolver/
** enjoin.sh): every edge at the vertex v is paired with one edge of the
** other cone (going round the two rims together, each edge with the one
** in the nearest direction round the axis); each pair becomes one ring
** vertex at (2 v + a + b)/4, a and b the pair's far ends (the mean of the
** two edges' midpoints). Every facet (v, a, b) loses its corner as in a
** sphere pop (topo_popcone.c): it becomes (r_a, a, b) and a new facet
** (r_a, b, r_b) is added, with the arc r_b -> r_a (shared by the two
** cones) and the diagonal b -> r_a. The ring is then closed by a film
** fanned from its centroid (a triangle for a ring of three), between the
** regions inside the two cones, which v kept apart: Evolver keeps
** separated regions separate. v goes. Cones with different numbers of
** edges, or with edges at v of other than two facets, are left to the
** split. */
#include "topo_edit.h"

#include <math.h>

#include "topo.h"
#include "vec3.h"

#define MAXR 128 /* edges in one cone */

typedef struct neck {
  int n;                         /* edges per cone */
  tds_id e[2][MAXR], w[2][MAXR]; /* cone c's edges at v in rim order, far ends */
} neck;

/* The facet's corner after v: a (edge v-a = ga), then b (edge gb). */
static int corner(const tds_mesh *m, tds_id f, tds_id v, tds_id *a, tds_id *b, tds_id *ga,
                  tds_id *gb, int32_t *eab) {
  int k = 0;
  while (k < 3 && m->fv[f][k] != v) k++;
  if (k == 3) return 0;
  *a = m->fv[f][(k + 1) % 3];
  *b = m->fv[f][(k + 2) % 3];
  *eab = m->fe[f][(k + 1) % 3];
  *ga = TDS_OID(m->fe[f][k]);
  *gb = TDS_OID(m->fe[f][(k + 2) % 3]);
  return 1;
}

/* Cone c's rim in order: the facets' links a -> b chained; 1 if the
** cone's facets make one cycle through all its edges at v. */
static int rim(const tds_mesh *m, tds_id v, const tds_id *fl, const int *lab, int nf, int want,
               neck *k, int c) {
  int cnt = 0, start = -1;
  for (int i = 0; i < nf; i++)
    if (lab[i] == want) {
      if (start < 0) start = i;
      cnt++;
    }
  if (cnt < 3 || cnt > MAXR) return 0;
  int i = start, n = 0;
  do {
    tds_id a, b, ga, gb;
    int32_t eab;
    if (!corner(m, fl[i], v, &a, &b, &ga, &gb, &eab)) return 0;
    k->e[c][n] = ga;
    k->w[c][n] = a;
    n++;
    int next = -1; /* the facet of this cone whose corner starts at b */
    for (int j = 0; j < nf && next < 0; j++) {
      tds_id a2, b2, ga2, gb2;
      int32_t e2;
      if (lab[j] == want && corner(m, fl[j], v, &a2, &b2, &ga2, &gb2, &e2) && ga2 == gb) next = j;
    }
    if (next < 0 || n > cnt) return 0;
    i = next;
  } while (i != start);
  if (n != cnt) return 0;
  k->n = n;
  return 1;
}

int tds_pop_neck(tds_surf *s, tds_id v, const tds_id *fl, const int *lab, int nf, int *done) {
  tds_mesh *m = &s->m;
  *done = 0;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++)
    if (tds_edge_valence(m, TDS_OID(m->ve[i])) != 2) return TDS_OK;
  int other = -1;
  for (int i = 0; i < nf; i++)
    if (lab[i] != lab[0]) {
      if (other >= 0 && lab[i] != other) return TDS_OK; /* more than two cones */
      other = lab[i];
    }
  if (other < 0) return TDS_OK;
  neck *k = tds_calloc(&m->alloc, 1, sizeof *k);
  if (!k) return TDS_ENOMEM;
  int rc = TDS_OK;
  neck k1;
  if (!rim(m, v, fl, lab, nf, lab[0], k, 0) || !rim(m, v, fl, lab, nf, other, &k1, 0) ||
      k1.n != k->n)
    goto out;
  int n = k->n;
  for (int q = 0; q < n; q++) k->e[1][q] = k1.e[0][q], k->w[1][q] = k1.w[0][q];
  /* the axis from cone 0's rim to cone 1's; directions round it */
  double mid[2][3] = {{0, 0, 0}, {0, 0, 0}}, ax[3], dir[2][MAXR][3], turn[2] = {0, 0};
  for (int c = 0; c < 2; c++)
    for (int q = 0; q < n; q++) v3_axpy(mid[c], 1.0 / n, m->x[k->w[c][q]]);
  v3_sub(ax, mid[1], mid[0]);
  double an = v3_norm(ax);
  if (!(an > 0)) goto out;
  v3_scale(ax, 1 / an);
  for (int c = 0; c < 2; c++) {
    for (int q = 0; q < n; q++) {
      double *d = dir[c][q];
      v3_sub(d, m->x[k->w[c][q]], m->x[v]);
      v3_axpy(d, -v3_dot(d, ax), ax);
      double dn = v3_norm(d);
      if (!(dn > 0)) goto out;
      v3_scale(d, 1 / dn);
    }
    for (int q = 0; q < n; q++) {
      double cr[3];
      v3_cross(cr, dir[c][q], dir[c][(q + 1) % n]);
      turn[c] += v3_dot(cr, ax);
    }
  }
  int rev = (turn[0] > 0) != (turn[1] > 0);
  if (rev) { /* cone 1's rim the same way round */
    for (int q = 0; q < n / 2; q++) {
      tds_id t = k->e[1][q];
      k->e[1][q] = k->e[1][n - 1 - q], k->e[1][n - 1 - q] = t;
      t = k->w[1][q];
      k->w[1][q] = k->w[1][n - 1 - q], k->w[1][n - 1 - q] = t;
      double tmp[3];
      v3_copy(tmp, dir[1][q]);
      v3_copy(dir[1][q], dir[1][n - 1 - q]);
      v3_copy(dir[1][n - 1 - q], tmp);
    }
  }
  int off = 0;
  double best = INFINITY;
  for (int o = 0; o < n; o++) {
    double sum = 0;
    for (int q = 0; q < n; q++) {
      double d[3];
      v3_sub(d, dir[0][q], dir[1][(q + o) % n]);
      sum += v3_dot(d, d);
    }
    if (sum < best) best = sum, off = o;
  }
  int low_in_1 = 0; /* the lowest-numbered facet at v is in cone 1 */
  {
    tds_id low = fl[0];
    for (int i = 0; i < nf; i++)
      if (fl[i] <= low) low = fl[i], low_in_1 = lab[i] != lab[0];
  }
  /* the bodies inside each cone: on the side of its facets facing its axis */
  tds_id inside[2];
  for (int c = 0; c < 2; c++) {
    double a[3], nrm[3], p[3], q2[3];
    v3_sub(a, mid[c], m->x[v]);
    tds_id f = TDS_NONE;
    for (int i = 0; i < nf && f == TDS_NONE; i++)
      if (lab[i] == (c ? other : lab[0])) f = fl[i];
    v3_sub(p, m->x[m->fv[f][1]], m->x[m->fv[f][0]]);
    v3_sub(q2, m->x[m->fv[f][2]], m->x[m->fv[f][0]]);
    v3_cross(nrm, p, q2);
    inside[c] = v3_dot(nrm, a) > 0 ? m->fb[f][1] : m->fb[f][0];
  }
  if (tds_mesh_room(m, TDS_VERTEX, m->nv + n + 1) || tds_mesh_room(m, TDS_EDGE, m->ne + 4 * n) ||
      tds_mesh_room(m, TDS_FACET, m->nf + 3 * n)) {
    rc = TDS_ENOMEM;
    goto out;
  }
  /* ring vertices; every edge at v now starts at its pair's */
  tds_id ring[MAXR], arc[MAXR];
  double ctr[3] = {0, 0, 0};
  for (int q = 0; q < n; q++) {
    double x[3];
    v3_add(x, m->x[k->w[0][q]], m->x[k->w[1][(q + off) % n]]);
    v3_scale(x, 0.25);
    v3_axpy(x, 0.5, m->x[v]);
    ring[q] = tds_mesh_add_vertex(m, x);
    m->vflags[ring[q]] = m->vflags[v];
    m->vcon[ring[q]] = m->vcon[v];
    tds_mesh_inherit(m, TDS_VERTEX, ring[q], v);
    m->vfile[ring[q]] = 0;
    v3_axpy(ctr, 1.0 / n, x);
  }
  for (int q = 0; q < n; q++) arc[q] = tds_mesh_add_edge(m, ring[(q + 1) % n], ring[q]);
  /* every edge at v now starts at its ring vertex */
  for (int c = 0; c < 2; c++)
    for (int q = 0; q < n; q++) {
      tds_id e = k->e[c][q], r = ring[c ? (q - off + n) % n : q];
      for (int j = 0; j < 2; j++)
        if (m->ev[e][j] == v) m->ev[e][j] = r;
    }
  /* facets lose their corner at v (their corners still name it) */
  tds_id src = TDS_NONE;
  for (int i = 0; i < nf; i++) {
    tds_id f = fl[i], a, b, ga, gb;
    int32_t eab;
    corner(m, f, v, &a, &b, &ga, &gb, &eab);
    int c = lab[i] == lab[0] ? 0 : 1, ia = -1, ib = -1;
    for (int q = 0; q < n; q++) {
      if (k->e[c][q] == ga) ia = q;
      if (k->e[c][q] == gb) ib = q;
    }
    if (c) ia = (ia - off + n) % n, ib = (ib - off + n) % n; /* the ring's numbering */
    /* Evolver's diagonal: from the rim vertex ahead to the ring vertex
    ** behind, going round the ring against the way the facets of the cone
    ** with the lowest-numbered facet run (measured: cat.fe's neck and
    ** double cones with either cone's facets turned round) */
    int up = ib == (ia + 1) % n, fwd = low_in_1 && rev ? up : !up;
    tds_id pa = ring[ia], pb = ring[ib];
    /* arc[q] runs ring[q + 1] -> ring[q] */
    int32_t ar = up ? TDS_OREF(arc[ia], 0) : TDS_OREF(arc[ib], 1); /* pb -> pa */
    int32_t oga = TDS_OREF(ga, m->ev[ga][0] == pa ? 0 : 1);           /* pa -> a */
    int32_t ogb = TDS_OREF(gb, m->ev[gb][0] == pb ? 1 : 0);           /* b -> pb */
    /* fwd: diagonal b -> pa, kept (pa, a, b), cut (pa, b, pb);
    ** else: diagonal a -> pb, kept (a, b, pb), cut (a, pb, pa) */
    tds_id dg = fwd ? tds_mesh_add_edge(m, b, pa) : tds_mesh_add_edge(m, a, pb);
    m->eflags[dg] = m->fflags[f] & TDS_NO_REFINE;
    int32_t kept[3] = {fwd ? oga : eab, fwd ? eab : ogb, TDS_OREF(dg, !fwd)};
    int32_t cut[3] = {TDS_OREF(dg, fwd), fwd ? ogb : ar, fwd ? ar : oga};
    tds_mesh_set_facet(m, f, kept);
    tds_facet_inherit(m, tds_mesh_add_facet(m, cut), f);
    if (src == TDS_NONE) src = f;
  }
  /* the film across the ring, between the two cones' insides */
  tds_id made[MAXR];
  int nmade = 0;
  if (n == 3) {
    int32_t t[3] = {TDS_OREF(arc[0], 1), TDS_OREF(arc[1], 1), TDS_OREF(arc[2], 1)};
    made[nmade++] = tds_mesh_add_facet(m, t); /* ring 0 -> 1 -> 2 */
  } else {
    tds_id cv = tds_mesh_add_vertex(m, ctr), sp[MAXR];
    m->vflags[cv] = m->vflags[v];
    m->vcon[cv] = m->vcon[v];
    tds_mesh_inherit(m, TDS_VERTEX, cv, v);
    m->vfile[cv] = 0;
    for (int q = 0; q < n; q++) sp[q] = tds_mesh_add_edge(m, ring[q], cv);
    for (int q = 0; q < n; q++) { /* ring q -> q + 1 -> centre */
      int32_t t[3] = {TDS_OREF(arc[q], 1), TDS_OREF(sp[(q + 1) % n], 0), TDS_OREF(sp[q], 1)};
      made[nmade++] = tds_mesh_add_facet(m, t);
    }
  }
  for (int q = 0; q < nmade; q++) {
    tds_id f = made[q];
    double p[3], q2[3], nrm[3];
    v3_sub(p, m->x[m->fv[f][1]], m->x[m->fv[f][0]]);
    v3_sub(q2, m->x[m->fv[f][2]], m->x[m->fv[f][0]]);
    v3_cross(nrm, p, q2);
    tds_facet_inherit(m, f, src);
    m->ffile[f] = 0;
    m->forig[f] = TDS_NONE;
    m->fflags[f] &= ~TDS_FIXED;
    int to1 = v3_dot(nrm, ax) > 0; /* the normal points out of the front body */
    m->fb[f][0] = inside[to1 ? 0 : 1];
    m->fb[f][1] = inside[to1 ? 1 : 0];
  }
  tds_mesh_kill(m, TDS_VERTEX, v);
  m->topo_gen++;
  m->coord_gen++;
  *done = 1;
out:
  tds_free(&m->alloc, k);
  return rc;
}
