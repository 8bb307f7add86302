/* stall.c: noticing when `g` stalls (see stall.h). */
#include "stall.h"

#include <math.h>

#include "gather.h"
#include "metrics.h"
#include "vec3.h"

/* Sine of the smallest angle of facet f and its area, from the edge
** vectors: the smallest angle (at most 60 degrees) is opposite the
** shortest side, and its sine is 2A over the product of the two longer
** sides. */
static void facet_shape(const tds_mesh *m, tds_id f, double *sine, double *area) {
  tds_corners F;
  tds_gather_facet(m, f, &F);
  double e[3][3], l2[3], n[3];
  v3_sub(e[0], F.x[1], F.x[0]);
  v3_sub(e[1], F.x[2], F.x[1]);
  v3_sub(e[2], F.x[0], F.x[2]);
  for (int k = 0; k < 3; k++) l2[k] = v3_dot(e[k], e[k]);
  v3_cross(n, e[0], e[1]);
  double twoA = sqrt(v3_dot(n, n));
  *area = 0.5 * twoA;
  /* the product of the two longer sides is the largest of the three
  ** products of two (no branch on which side is shortest: it is
  ** unpredictable, and this runs over every facet after each step) */
  double p0 = l2[1] * l2[2], p1 = l2[2] * l2[0], p2 = l2[0] * l2[1];
  double p01 = p0 > p1 ? p0 : p1;
  double p = sqrt(p01 > p2 ? p01 : p2);
  double sn = p > 0 ? twoA / p : 0;
  if (!(sn < 1)) sn = sn >= 1 ? 1 : 0; /* NaN counts as degenerate */
  *sine = sn;
}

void tds_stall_scan(const tds_surf *s, tds_stall_out *o) {
  const tds_mesh *m = &s->m;
  double sum = 0;
  int32_t n = 0;
  o->worst = o->tiny = TDS_NONE;
  double sine = INFINITY;
  o->angle = o->area = o->tiny_area = INFINITY;
  o->mean_area = 0;
  o->degenerate = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    if (!tds_facet_measured(m, f)) continue;
    double sn, a;
    facet_shape(m, f, &sn, &a);
    n++;
    sum += a;
    if (!(sn >= sine)) {
      sine = sn;
      o->area = a;
      o->worst = f;
    }
    if (!(a >= o->tiny_area)) {
      o->tiny_area = a;
      o->tiny = f;
    }
  }
  if (!n) return;
  o->angle = asin(sine) * (180 / TDS_PI);
  o->mean_area = sum / n;
  o->degenerate = !(o->angle >= TDS_STALL_ANGLE) ||
                  !(o->tiny_area >= TDS_STALL_AREA * o->mean_area);
}

int tds_stall_collapsed(const tds_surf *s, double slope, double energy) {
  if (s->fixed_scale) return 0;
  double e = fabs(energy) > 1 ? fabs(energy) : 1;
  return s->scale < 1e-6 * s->scale_limit && -slope > 1e-8 * e;
}

/* Named by its area alone: the smallest angle is fine but the area tiny. */
static int by_area(const tds_stall_out *o) {
  return o->tiny != TDS_NONE && o->angle >= TDS_STALL_ANGLE &&
         o->tiny_area < TDS_STALL_AREA * o->mean_area;
}

tds_id tds_stall_facet(const tds_stall_out *o) {
  return by_area(o) ? o->tiny : o->worst;
}

void tds_stall_warn(tds_ctx *ctx, const tds_surf *s, const tds_stall_out *o,
                    int collapsed) {
  if (o->worst == TDS_NONE) {
    tds_warnf(ctx, "warning: g is stalling: the scale fell to %g\n", s->scale);
    return;
  }
  /* the facet to name: the tiny one if only its area gave it away */
  tds_id f = tds_stall_facet(o);
  if (collapsed)
    tds_warnf(ctx, "warning: g is stalling: the scale fell to %g while the "
              "force is not small\n", s->scale);
  else
    tds_warnf(ctx, "warning: g: a facet has degenerated\n");
  if (!o->degenerate) { /* not the mesh's fault, as far as facets show */
    tds_warnf(ctx, "  no facet is degenerate (smallest angle %g degrees, on "
              "facet %d)\n", o->angle, (int)o->worst + 1);
    tds_warnf(ctx, "  remedies: %s; u and V between runs of g if the mesh "
              "is poor\n", s->conj_grad
                  ? "restart the conjugate gradient history (U 2)"
                  : "conjugate gradient (U) or a fixed scale (m) for a few steps");
    return;
  }
  if (by_area(o))
    tds_warnf(ctx, "  facet %d has area %g (mean facet area %g)\n", (int)f + 1,
              o->tiny_area, o->mean_area);
  else
    tds_warnf(ctx, "  worst facet %d: smallest angle %g degrees, area %g "
              "(mean facet area %g)\n", (int)f + 1, o->angle, o->area, o->mean_area);
  tds_warnf(ctx, "  remedies: u (equiangulate) and V (vertex_average) between "
            "runs of g, e.g. {g 50; u; V} 10, with U (conjugate gradient) on "
            "fine meshes; t (delete short edges) or autopop to remove the "
            "collapsed facet\n");
}
