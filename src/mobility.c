/* mobility.c: area normalization weights (contracts in mobility.h). */
#include "mobility.h"

#include <math.h>

#include "gather.h"
#include "method.h"
#include "vec3.h"

void tds_area_norm_weights(const tds_surf *s, double *r) {
  const tds_mesh *m = &s->m;
  for (tds_id v = 0; v < m->nv; v++) r[v] = 0;
  if (s->str) {
    for (tds_id e = 0; e < m->ne; e++) {
      if (!tds_alive(m->eflags, e)) continue;
      double d[3];
      tds_edge_vec(m, TDS_OREF(e, 0), d);
      double L = sqrt(v3_dot(d, d));
      if (s->klein) { /* KLEIN_METRIC: hyperbolic lengths, as Evolver */
        tds_corners c;
        tds_gather_edge(m, TDS_OREF(e, 0), &c);
        L = tds_klein_dist(c.x[0], c.x[1]);
      }

      r[m->ev[e][0]] += L / 2;
      r[m->ev[e][1]] += L / 2;
    }
  } else {
    for (tds_id f = 0; f < m->nf; f++) {
      if (!tds_alive(m->fflags, f)) continue;
      tds_corners c;
      tds_gather_facet(m, f, &c);
      double a[3], b[3], n[3];
      v3_sub(a, c.x[1], c.x[0]);
      v3_sub(b, c.x[2], c.x[0]);
      v3_cross(n, a, b);
      double A = s->klein ? tds_klein_area(c.x[0], c.x[1], c.x[2]) /* as Evolver */
                          : 0.5 * sqrt(v3_dot(n, n));
      for (int k = 0; k < 3; k++) r[m->fv[f][k]] += A / 3;
    }
  }
  for (tds_id v = 0; v < m->nv; v++) r[v] = r[v] > 0 ? 1 / sqrt(r[v]) : 0;
}
