/* topo_vavg_ev.c: where Evolver 2.70's V, rawv and rawestv move one vertex
** of the soapfilm model (topo.h, tds_vavg_target).
**
** The rule was found by measuring evolver-nox-d on small stars, border
** fans, triple lines and constrained vertices, and confirmed to 1e-15 on
** seeded random ones (tests/evolver/vavg.sh, doc/commands.md):
**
**  - Each edge e from v has a weight g_e, the summed area of the facets on
**    e that take part; the target is T = sum g_e^2 x_e / sum g_e^2 over
**    the far ends x_e, and the vertex moves a quarter of the way:
**    v + (T - v) / 4.
**  - V and rawv average only over edges with v's constraints (g_e still
**    counts every facet on e), and need a facet with v's constraints (a
**    "like" facet). A
**    vertex on exactly two triple edges (valence >= 3) takes the mean of
**    their far ends; on other numbers of triple edges it stays. A
**    constrained vertex without like facets takes the mean of the far ends
**    of its two like edges (edges on the same constraints: a contact line),
**    or stays. A vertex on a border edge (valence 1) takes the plain mean
**    of all its neighbours.
**  - V then removes the normal part of the move: along the triple line
**    (the chord between the two ends) for a triple vertex, else
**    perpendicular to the facets' summed area vector, summed in star order
**    with each facet's sign chosen to agree with the sum so far (a fan of
**    one facet keeps its move); each facet's area vector as its first
**    corner sees it (under a group that rotates, not turned into v's
**    frame: measured on sectors under rotate, flip_rotate, screw, cubocta). That keeps the volume exactly when the
**    star is a fan around v.
**  - rawestv uses every facet and the weighted rule for every vertex.
**  - Under KLEIN_METRIC the areas in g_e are hyperbolic (the rest stays
**    Euclidean; measured, tests/evolver/klein.sh, to 1e-13).
**  - On constraints the move is made tangent to them (before and again
**    after V's removal of the normal part), then the vertex is projected
**    back onto them.
*/
#include "topo.h"

#include <math.h>
#include <stdint.h>

#include "gather.h"
#include "method.h"
#include "torus.h"
#include "motion.h"
#include "vec3.h"

static int edge_slot(const tds_mesh *m, tds_id v, int32_t oe) {
  tds_id e = TDS_OID(oe);
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++)
    if (TDS_OID(m->ve[i]) == e) return (int)(i - m->ve_start[v]);
  return -1;
}

/* v's facets into ord in Evolver's order (tds_star_key). Returns their
** number. */
static int star_order(const tds_mesh *m, tds_id v, int32_t *ord) {
  int32_t f0 = m->vf_start[v], n = m->vf_start[v + 1] - f0;
  tds_id e1 = tds_vertex_min_edge(m, v);
  for (int32_t i = 0; i < n; i++) { /* insertion sort on the key */
    tds_id f = m->vf[f0 + i];
    int32_t key = tds_star_key(m, f, tds_facet_corner(m, f, v), e1), j = i;
    for (; j > 0; j--) {
      tds_id g = ord[j - 1];
      if (tds_star_key(m, g, tds_facet_corner(m, g, v), e1) <= key) break;
      ord[j] = g;
    }
    ord[j] = f;
  }
  return n;
}

static void remove_along(double d[3], const double n[3]) {
  double nn = v3_dot(n, n);
  if (nn > 0) v3_axpy(d, -v3_dot(d, n) / nn, n);
}

int tds_vavg_target(const tds_surf *s, tds_id v, int mode, double *g,
                    int32_t *ord, double out[3]) {
  const tds_mesh *m = &s->m;
  int32_t e0 = m->ve_start[v], deg = m->ve_start[v + 1] - e0;
  if (deg <= 0) return 0;
  int rawest = mode == TDS_VAVG_RAWEST;
  for (int i = 0; i < deg; i++) g[i] = 0;
  double nall[3] = {0, 0, 0};
  int cl = 0, ca = 0;
  int nf = star_order(m, v, ord);
  for (int i = 0; i < nf; i++) {
    tds_id f = ord[i];
    int k = tds_facet_corner(m, f, v);
    /* the facet's area vector where its first corner sees it, not in v's
    ** frame: under a group that rotates, Evolver 2.70 sums the normals so
    ** (measured: V on sectors under rotate and flip_rotate) */
    tds_corners P;
    tds_gather_facet(m, f, &P);
    double ab[3], ac[3], N[3];
    v3_sub(ab, P.x[1], P.x[0]);
    v3_sub(ac, P.x[2], P.x[0]);
    v3_cross(N, ab, ac);
    /* the sum in star order, each facet signed to agree with it */
    v3_axpy(nall, ca++ && v3_dot(N, nall) < 0 ? -1 : 1, N);
    double A = s->klein ? tds_klein_area(P.x[0], P.x[1], P.x[2]) : 0.5 * v3_norm(N);
    int a = edge_slot(m, v, m->fe[f][k]), b = edge_slot(m, v, m->fe[f][(k + 2) % 3]);
    if (a >= 0) g[a] += A;
    if (b >= 0) g[b] += A;
    if (!rawest && m->fcon[f] != m->vcon[v]) continue;
    cl++;
  }
  /* far ends, relative to v's own position (gathered from v) */
  double T[3] = {0, 0, 0}, d[3], dir[3] = {0, 0, 0};
  const double *proj = NULL; /* the normal V removes, or NULL */
  int along = 0;             /* V keeps only the part along dir */
  int ntri = 0, nbord = 0, nlk = 0;
  if (!rawest)
    for (int i = 0; i < deg; i++) {
      int val = tds_edge_valence(m, TDS_OID(m->ve[e0 + i]));
      ntri += val >= 3;
      nbord += val <= 1;
    }
  tds_corners E;
  if (!rawest && (ntri || (m->vcon[v] && !cl))) {
    /* the two far ends along triple edges, or along like edges */
    const double *ends[2];
    double tmp[2][3];
    for (int i = 0; i < deg; i++) {
      tds_id e = TDS_OID(m->ve[e0 + i]);
      int on = ntri ? tds_edge_valence(m, e) >= 3 : m->econ[e] == m->vcon[v];
      if (!on) continue;
      if (nlk == 2) return 0;
      tds_gather_edge(m, m->ve[e0 + i], &E);
      v3_copy(tmp[nlk], E.x[1]);
      ends[nlk] = tmp[nlk];
      nlk++;
    }
    if (nlk != 2) return 0;
    v3_add(T, ends[0], ends[1]);
    v3_scale(T, 0.5);
    if (ntri) {
      v3_sub(dir, ends[1], ends[0]);
      along = 1;
    } else {
      proj = nall;
    }
  } else if (!rawest && !cl) {
    return 0; /* no facet with v's constraints */
  } else if (!rawest && nbord) {
    for (int i = 0; i < deg; i++) {
      tds_gather_edge(m, m->ve[e0 + i], &E);
      v3_add(T, T, E.x[1]);
    }
    v3_scale(T, 1.0 / deg);
    if (ca >= 2) proj = nall;
  } else {
    double W = 0;
    for (int i = 0; i < deg; i++) {
      if (!(g[i] > 0)) continue;
      if (!rawest && m->econ[TDS_OID(m->ve[e0 + i])] != m->vcon[v]) continue;
      tds_gather_edge(m, m->ve[e0 + i], &E);
      v3_axpy(T, g[i] * g[i], E.x[1]);
      W += g[i] * g[i];
    }
    if (!(W > 0)) return 0;
    v3_scale(T, 1 / W);
    proj = nall;
  }
  v3_sub(d, T, m->x[v]);
  v3_scale(d, 0.25);
  if (m->vcon[v]) tds_motion_project(s, v, d);
  if (mode == TDS_VAVG_V) {
    if (along) {
      double tt = v3_dot(dir, dir);
      if (!(tt > 0)) return 0;
      double c = v3_dot(d, dir) / tt;
      v3_copy(d, dir);
      v3_scale(d, c);
    } else if (proj) {
      remove_along(d, proj);
    }
    if (m->vcon[v]) tds_motion_project(s, v, d); /* tangent again */
  }
  v3_add(out, m->x[v], d);
  return isfinite(out[0] + out[1] + out[2]);
}
