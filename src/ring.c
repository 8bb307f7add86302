/* ring.c: the order of the facets around an edge (contracts in ring.h). */
#include "ring.h"

#include <math.h>

#include "gather.h"
#include "vec3.h"

void tds_ring_set(tds_mesh *m, tds_id e, const int32_t *sides, int n) {
  TDS_ASSERT(n == tds_edge_valence(m, e));
  if (n == 0) return;
  for (int i = 0; i < n; i++) {
    TDS_ASSERT(TDS_OID(m->fe[sides[i] / 3][sides[i] % 3]) == e);
    m->side_next[sides[i]] = sides[(i + 1) % n];
  }
  m->eside[e] = sides[0];
}

/* The direction from side sd's edge into its facet (the facet's third
** corner, in the facet's frame), and the edge's own direction (tail to
** head, whichever way the facet runs along it). */
static void side_dirs(const tds_mesh *m, int32_t sd, double u[3], double w[3]) {
  tds_id f = sd / 3;
  int k = sd % 3;
  tds_corners C;
  tds_gather_facet(m, f, &C);
  v3_sub(u, C.x[(k + 1) % 3], C.x[k]);
  if (TDS_OREV(m->fe[f][k])) v3_scale(u, -1);
  v3_sub(w, C.x[(k + 2) % 3], C.x[k]);
}

void tds_ring_sort_angular(tds_mesh *m, tds_id from) {
  for (tds_id e = from < 0 ? 0 : from; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    int n = tds_edge_valence(m, e);
    if (n < 3 || n > TDS_RING_MAX) continue;
    int32_t sd[TDS_RING_MAX];
    double ang[TDS_RING_MAX], u[3], w0[3], w[3], c[3];
    int32_t s = m->eside[e];
    for (int i = 0; i < n; i++, s = m->side_next[s]) sd[i] = s;
    side_dirs(m, sd[0], u, w0);
    double len = v3_norm(u);
    if (!(len > 0)) continue;
    v3_scale(u, 1 / len);
    v3_axpy(w0, -v3_dot(w0, u), u);
    ang[0] = 0;
    for (int i = 1; i < n; i++) {
      double ui[3];
      side_dirs(m, sd[i], ui, w);
      v3_axpy(w, -v3_dot(w, u), u);
      v3_cross(c, w0, w);
      double a = atan2(v3_dot(c, u), v3_dot(w0, w));
      ang[i] = a < 0 ? a + 2 * 3.14159265358979323846 : a;
    }
    for (int i = 2; i < n; i++) /* insertion sort of sd[1..n) by angle */
      for (int j = i; j > 1 && ang[j] < ang[j - 1]; j--) {
        double ta = ang[j];
        ang[j] = ang[j - 1];
        ang[j - 1] = ta;
        int32_t ts = sd[j];
        sd[j] = sd[j - 1];
        sd[j - 1] = ts;
      }
    tds_ring_set(m, e, sd, n);
  }
}
