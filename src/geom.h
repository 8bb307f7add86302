/*
** geom.h: per-facet geometry kernels on gathered coordinates.
**
** Each kernel takes a facet's three corner positions a, b, c (in the
** facet's orientation) and returns a value and, if g is not NULL, its
** gradient with respect to the corners, g[0..2]. Orientation follows the
** right-hand rule: N = (b - a) x (c - a) is the facet's area normal.
*/
#ifndef TDS_GEOM_H
#define TDS_GEOM_H

#include "vec3.h"

/* Area |N|/2. Gradient: dA/da = (b - c) x n / 2 and cyclic (n = N/|N|). */
static inline __attribute__((always_inline)) double
geom_area(const double a[3], const double b[3],
          const double c[3], double g[3][3]) {
  double ab[3], ac[3], N[3];
  v3_sub(ab, b, a);
  v3_sub(ac, c, a);
  v3_cross(N, ab, ac);
  double len = v3_norm(N);
  if (g) {
    double n[3] = {0, 0, 0}, d[3];
    if (len > 0) {
      n[0] = N[0] / len;
      n[1] = N[1] / len;
      n[2] = N[2] / len;
    }
    v3_sub(d, b, c);
    v3_cross(g[0], d, n);
    v3_sub(d, c, a);
    v3_cross(g[1], d, n);
    v3_sub(d, a, b);
    v3_cross(g[2], d, n);
    for (int k = 0; k < 3; k++) v3_scale(g[k], 0.5);
  }
  return 0.5 * len;
}

/* Signed volume under the facet translated by tz along z (tz = 0: the
** facet itself; the torus's lifted facets otherwise), Evolver's default
** content z k . dS: V = (za + zb + zc + 3 tz)/3 * Nz/2. */
static inline __attribute__((always_inline)) double
geom_volume_zshift(const double a[3], const double b[3], const double c[3], double tz,
                   double g[3][3]) {
  double Nz = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  double zs = a[2] + b[2] + c[2] + 3 * tz;
  if (g) {
    /* dNz/da = (b_y - c_y, c_x - b_x), cyclic. */
    const double *p[3] = {a, b, c};
    for (int k = 0; k < 3; k++) {
      const double *q = p[(k + 1) % 3], *r = p[(k + 2) % 3];
      g[k][0] = zs / 6 * (q[1] - r[1]);
      g[k][1] = zs / 6 * (r[0] - q[0]);
      g[k][2] = Nz / 6;
    }
  }
  return zs * Nz / 6;
}

static inline __attribute__((always_inline)) double
geom_volume_z(const double a[3], const double b[3],
              const double c[3], double g[3][3]) {
  return geom_volume_zshift(a, b, c, 0, g);
}

/* Signed volume of the cone from the origin, symmetric content
** (x, y, z)/3 . dS: V = a . (b x c) / 6. */
static inline __attribute__((always_inline)) double
geom_volume_sym(const double a[3], const double b[3],
                const double c[3], double g[3][3]) {
  double bc[3];
  v3_cross(bc, b, c);
  if (g) {
    v3_copy(g[0], bc);
    v3_cross(g[1], c, a);
    v3_cross(g[2], a, b);
    for (int k = 0; k < 3; k++) v3_scale(g[k], 1.0 / 6);
  }
  return v3_dot(a, bc) / 6;
}

/* Gravity integrand of a body, the flux of (0, 0, z^2/2) through the facet:
** W = (Nz/2) * (S/6) / 2 = Nz S / 24 with S = za^2 + zb^2 + zc^2 + za zb +
** zb zc + zc za. Summed over a closed body it is the moment int z dV. */
static inline __attribute__((always_inline)) double
geom_zmoment(const double a[3], const double b[3],
             const double c[3], double g[3][3]) {
  double Nz = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  double za = a[2], zb = b[2], zc = c[2];
  double S = za * za + zb * zb + zc * zc + za * zb + zb * zc + zc * za;
  if (g) {
    const double *p[3] = {a, b, c};
    double dS[3] = {2 * za + zb + zc, 2 * zb + za + zc, 2 * zc + za + zb};
    for (int k = 0; k < 3; k++) {
      const double *q = p[(k + 1) % 3], *r = p[(k + 2) % 3];
      g[k][0] = S / 24 * (q[1] - r[1]);
      g[k][1] = S / 24 * (r[0] - q[0]);
      g[k][2] = Nz / 24 * dS[k];
    }
  }
  return Nz * S / 24;
}

/* The angle at p between the directions to q and r, in [0, pi]; atan2
** keeps it accurate near 0 and pi. */
static inline double geom_angle(const double p[3], const double q[3],
                                const double r[3]) {
  double u[3], v[3], w[3];
  v3_sub(u, q, p);
  v3_sub(v, r, p);
  v3_cross(w, u, v);
  return atan2(v3_norm(w), v3_dot(u, v));
}

#endif
