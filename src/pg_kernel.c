/* pg_kernel.c: per-star kernels of the projected-gradient method, exported
** in pg.h (the unit tests check them against finite differences and
** Newton's method; pg_pass.c accumulates the same quantities in its fused
** facet loop). */
#include <math.h>

#include "gather.h"
#include "pg.h"
#include "vec3.h"

double tds_pg_normal_root(double A0, double A1, double A2, double c,
                          int *clamped) {
  double b = A1 * A1 + A0 * A2;
  if (clamped) *clamped = 0;
  if (!(b > 0) || !(c * c < b) || !(A0 > 0)) {
    if (clamped) *clamped = 1;
    return 0;
  }
  double ib = 1 / b;
  double s0 = A0 * A1 * ib;
  double a = A0 * A0 * A0 * A2 * ib;
  if (!(a > 0)) { /* flat star: A is |sqrt(b)(s0 + t)|, A' = +-sqrt(b) */
    if (clamped) *clamped = 1;
    return 0;
  }
  return c * sqrt(a * ib / (b - c * c)) - s0;
}

double tds_pg_vertex_normal(const tds_mesh *m, tds_id v, double n[3]) {
  double S[3] = {0, 0, 0};
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    if (m->ften[f] == 0) continue;
    tds_corners C;
    tds_gather_facet(m, f, &C);
    double a[3], b[3], N[3];
    v3_sub(a, C.x[1], C.x[0]);
    v3_sub(b, C.x[2], C.x[0]);
    v3_cross(N, a, b);
    v3_add(S, S, N);
  }
  double len = v3_norm(S);
  if (len > 0)
    for (int i = 0; i < 3; i++) n[i] = S[i] / len;
  else
    v3_zero(n);
  return len;
}

/* The star term of facet f at corner k along d: adds tension-weighted
** A, A', A'' of |N + t w| / 2, w = d x (x_next - x_prev). */
static inline void star_term(const tds_mesh *m, tds_id f, int k,
                             const double d[3], double *A0, double *A1,
                             double *A2) {
  tds_corners C;
  tds_gather_facet(m, f, &C);
  const double *a = C.x[0], *b = C.x[1], *c = C.x[2];
  double e1[3], e2[3], N[3], ed[3], wv[3];
  v3_sub(e1, b, a);
  v3_sub(e2, c, a);
  v3_cross(N, e1, e2);
  v3_sub(ed, C.x[(k + 1) % 3], C.x[(k + 2) % 3]);
  v3_cross(wv, d, ed);
  double nn = v3_dot(N, N), nl = sqrt(nn), nw = v3_dot(N, wv), ww = v3_dot(wv, wv);
  double ten = m->ften[f];
  if (!(nl > 0)) return;
  *A0 += ten * 0.5 * nl;
  *A1 += ten * 0.5 * nw / nl;
  *A2 += ten * 0.5 * (ww * nn - nw * nw) / (nn * nl);
}

void tds_pg_star_model(const tds_mesh *m, tds_id v, const double d[3],
                       double *A0, double *A1, double *A2) {
  *A0 = *A1 = *A2 = 0;
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    if (m->ften[f] == 0) continue;
    star_term(m, f, tds_facet_corner(m, f, v), d, A0, A1, A2);
  }
}

double tds_pg_star_area(const tds_mesh *m, tds_id v, const double d[3],
                        double t) {
  double A = 0;
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    double p[3][3], e1[3], e2[3], N[3];
    tds_corners C;
    tds_gather_facet(m, f, &C);
    for (int k = 0; k < 3; k++) {
      v3_copy(p[k], C.x[k]);
      if (m->fv[f][k] == v) v3_axpy(p[k], t, d);
    }
    v3_sub(e1, p[1], p[0]);
    v3_sub(e2, p[2], p[0]);
    v3_cross(N, e1, e2);
    A += m->ften[f] * 0.5 * v3_norm(N);
  }
  return A;
}

