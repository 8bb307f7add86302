/* stall.c: noticing when `g` stalls (see stall.h). */
#include "stall.h"

#include <float.h>
#include <math.h>

#include "gather.h"
#include "metrics.h"
#include "vec3.h"

/* The squared parts of facet f's shape, from the edge vectors: nn =
** (2A)^2 and pp, the largest product of two squared sides. The smallest
** angle (at most 60 degrees) is opposite the shortest side, and its sine
** is 2A over the product of the two longer sides, sqrt(nn / pp); that
** product is the largest of the three products of two (no branch on
** which side is shortest: it is unpredictable, and this runs over every
** facet after each step). */
static inline __attribute__((always_inline)) void
parts(const double a[3], const double b[3], const double c[3], double *nn, double *pp) {
  double e[3][3], l2[3], n[3];
  v3_sub(e[0], b, a);
  v3_sub(e[1], c, b);
  v3_sub(e[2], a, c);
  for (int k = 0; k < 3; k++) l2[k] = v3_dot(e[k], e[k]);
  v3_cross(n, e[0], e[1]);
  *nn = v3_dot(n, n);
  double p0 = l2[1] * l2[2], p1 = l2[2] * l2[0], p2 = l2[0] * l2[1];
  double p01 = p0 > p1 ? p0 : p1;
  *pp = p01 > p2 ? p01 : p2;
}

/* parts() of facet f. */
static inline __attribute__((always_inline)) void
shape_parts(const tds_mesh *m, tds_id f, double *nn, double *pp) {
  tds_corners F;
  tds_gather_facet(m, f, &F);
  parts(F.x[0], F.x[1], F.x[2], nn, pp);
}

/* Sine of the smallest angle of facet f and its area. */
static void facet_shape(const tds_mesh *m, tds_id f, double *sine, double *area) {
  double nn, pp;
  shape_parts(m, f, &nn, &pp);
  double twoA = sqrt(nn);
  *area = 0.5 * twoA;
  double p = sqrt(pp);
  double sn = p > 0 ? twoA / p : 0;
  if (!(sn < 1)) sn = sn >= 1 ? 1 : 0; /* NaN counts as degenerate */
  *sine = sn;
}

int tds_stall_clear(const tds_surf *s) {
  const tds_mesh *m = &s->m;
  /* the tolerances squared, with a margin of 1e-6 for the rounding of
  ** these sums and of the scan's square roots (1e-15) */
  double r = sin(TDS_STALL_ANGLE * TDS_PI / 180);
  const double K = r * r * (1 + 1e-6), C = TDS_STALL_AREA * TDS_STALL_AREA * (1 + 1e-6);
  double sum = 0, mn = INFINITY;
  int32_t n = 0;
  int ok = 1;
  for (tds_id f = 0; f < m->nf; f++) {
    if (!tds_facet_measured(m, f)) continue;
    double nn, pp;
    shape_parts(m, f, &nn, &pp);
    n++;
    sum += nn;
    mn = nn < mn ? nn : mn;
    ok &= (nn >= K * pp) & (pp > 0) & (nn <= DBL_MAX); /* no branch: one answer */
  }
  /* the mean area is at most half the root of the mean of nn (Jensen),
  ** so the smallest area is above the tolerance times the mean when mn is
  ** above C times the mean of nn */
  return !n || (ok && mn >= C * (sum / n));
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
