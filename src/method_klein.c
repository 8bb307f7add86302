/* method_klein.c: edge length and facet area in the Klein model of
** hyperbolic space
** (KLEIN_METRIC; contracts in method.h).
**
** Straight segments are geodesics of the Klein model, so an edge's length
** is the hyperbolic distance of its ends a, b (|a|, |b| < 1):
**   cosh L = A = (1 - a.b) / sqrt(p q),  p = 1 - |a|^2, q = 1 - |b|^2,
**   sinh L = S = sqrt((p |d|^2 + (a.d)^2) / (p q)),  d = b - a,
** the second form (A^2 - 1 written without cancellation) giving L = asinh S
** to full precision for short edges as well. Gradient and Hessian are
** exact: dL = dA / S, d2L = d2A / S - A dA dA^T / S^3. Outside the unit
** ball the length is +infinity (no geodesic), gradient 0.
*/
#include <math.h>
#include <string.h>

#include "method.h"

/* S = sinh of the distance of a and b, with p = 1 - |a|^2, q = 1 - |b|^2;
** +infinity outside the ball. */
static double klein_sinh(const double a[3], const double b[3], double *p, double *q) {
  *p = 1 - (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  *q = 1 - (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (!(*p > 0 && *q > 0)) return INFINITY;
  double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double ad = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
  double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  return sqrt((*p * dd + ad * ad) / (*p * *q));
}

double tds_klein_dist(const double a[3], const double b[3]) {
  double p, q;
  return asinh(klein_sinh(a, b, &p, &q));
}

double tds_mk_klein_length(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  const double *a = L->x[0], *b = L->x[1];
  if (g) memset(g, 0, sizeof(double[3][3]));
  if (h) memset(h, 0, sizeof(double[9][9]));
  double p, q, S = klein_sinh(a, b, &p, &q);
  if (!(p > 0 && q > 0)) return INFINITY;
  double len = asinh(S);
  if (!g || !(S > 0)) return len;
  double N = 1 - (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]), u = sqrt(p * q), A = N / u;
  double gA[2][3]; /* dA/da = (-b + (N/p) a) / u, dA/db = (-a + (N/q) b) / u */
  for (int i = 0; i < 3; i++) {
    gA[0][i] = (-b[i] + N / p * a[i]) / u;
    gA[1][i] = (-a[i] + N / q * b[i]) / u;
    g[0][i] = gA[0][i] / S;
    g[1][i] = gA[1][i] / S;
  }
  if (!h) return len;
  /* d2A: with P = (pq)^-1/2,
  **   aa: P/p [ -(b a^T + a b^T) + N I + 3 N a a^T / p ]
  **   ab: -P I - P/q b b^T - P/p a a^T + P N/(p q) a b^T
  **   bb: as aa with a and b swapped, p and q swapped */
  double P = 1 / u;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double I = i == j;
      double aa = P / p * (-(b[i] * a[j] + a[i] * b[j]) + N * I + 3 * N * a[i] * a[j] / p);
      double bb = P / q * (-(a[i] * b[j] + b[i] * a[j]) + N * I + 3 * N * b[i] * b[j] / q);
      double ab = -P * I - P / q * b[i] * b[j] - P / p * a[i] * a[j] + P * N / (p * q) * a[i] * b[j];
      double c = A / (S * S * S);
      h[i][j] = aa / S - c * gA[0][i] * gA[0][j];
      h[3 + i][3 + j] = bb / S - c * gA[1][i] * gA[1][j];
      h[i][3 + j] = ab / S - c * gA[0][i] * gA[1][j];
      h[3 + j][i] = h[i][3 + j];
    }
  return len;
}

/* ---- facet area (KLEIN_METRIC on films) ----
** A flat triangle of the Klein ball is a geodesic triangle; its area is
** its angle defect. On the hyperboloid (x, 1)/sqrt(1 - |x|^2) the defect
** of corners A, B, C satisfies tan(D/2) = sqrt(-det Gram) / (1 - <A,B> -
** <B,C> - <C,A>) (the hyperbolic analogue of the spherical excess
** formula). Written in the Klein coordinates x_0, x_1, x_2, with
**   s_i = sqrt(p_i), p_i = 1 - |x_i|^2,  n_ij = 1 - x_i.x_j,
**   N = (x_1 - x_0) x (x_2 - x_0),  T = x_0.N = det[x_0 x_1 x_2],
** -det Gram (Cauchy-Binet) is U^2 = |N|^2 - T^2 (|N| times the sine of
** the plane's angular distance from the origin), and
**   area = 2 atan2(U, D),  D = s_0 s_1 s_2 + n_12 s_0 + n_02 s_1 + n_01 s_2,
** D > 0 inside the ball, so no cancellation for small or thin triangles.
** Gradient exact:
**   dU/dx_c = ((x_a - x_b) x N - T (x_a x x_b)) / U   (a, b = c+1, c+2),
**   dD/dx_c = -(s_a s_b + n_ab) x_c / s_c - s_b x_a - s_a x_b,
**   d area = 2 (D dU - U dD) / (U^2 + D^2).
** (U = 0, a degenerate facet: the dU term is left out.) */
static double karea(const double *const x[3], double g[3][3]) {
  double p[3], s[3];
  for (int c = 0; c < 3; c++) {
    p[c] = 1 - (x[c][0] * x[c][0] + x[c][1] * x[c][1] + x[c][2] * x[c][2]);
    if (!(p[c] > 0)) {
      if (g) memset(g, 0, sizeof(double[3][3]));
      return INFINITY;
    }
    s[c] = sqrt(p[c]);
  }
  double e1[3], e2[3], N[3];
  for (int i = 0; i < 3; i++) e1[i] = x[1][i] - x[0][i], e2[i] = x[2][i] - x[0][i];
  N[0] = e1[1] * e2[2] - e1[2] * e2[1];
  N[1] = e1[2] * e2[0] - e1[0] * e2[2];
  N[2] = e1[0] * e2[1] - e1[1] * e2[0];
  double T = x[0][0] * N[0] + x[0][1] * N[1] + x[0][2] * N[2];
  double U2 = N[0] * N[0] + N[1] * N[1] + N[2] * N[2] - T * T;
  double U = U2 > 0 ? sqrt(U2) : 0;
  double n[3]; /* n[c] = n_ab, a and b the other two corners */
  for (int c = 0; c < 3; c++) {
    const double *a = x[(c + 1) % 3], *b = x[(c + 2) % 3];
    n[c] = 1 - (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
  }
  double D = s[0] * s[1] * s[2] + n[0] * s[0] + n[1] * s[1] + n[2] * s[2];
  double area = 2 * atan2(U, D);
  if (!g) return area;
  double r = 2 / (U * U + D * D);
  for (int c = 0; c < 3; c++) {
    int ia = (c + 1) % 3, ib = (c + 2) % 3;
    const double *a = x[ia], *b = x[ib];
    double dU[3] = {0, 0, 0}, dD[3];
    if (U > 0) {
      double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
      double dN[3] = {d[1] * N[2] - d[2] * N[1], d[2] * N[0] - d[0] * N[2], d[0] * N[1] - d[1] * N[0]};
      double ab[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
      for (int i = 0; i < 3; i++) dU[i] = (dN[i] - T * ab[i]) / U;
    }
    double k = (s[ia] * s[ib] + n[c]) / s[c];
    for (int i = 0; i < 3; i++) {
      dD[i] = -k * x[c][i] - s[ib] * a[i] - s[ia] * b[i];
      g[c][i] = r * (D * dU[i] - U * dD[i]);
    }
  }
  return area;
}

double tds_klein_area(const double a[3], const double b[3], const double c[3]) {
  const double *x[3] = {a, b, c};
  return karea(x, NULL);
}

/* The Hessian by central differences of the exact gradient (the row is
** TDS_MF_HESS_FD), step 1e-5 of the facet's size, kept well inside the
** ball (at most 1e-5 of the smallest 1 - |x|^2). */
double tds_mk_klein_area(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double v = karea(L->x, g);
  if (!h) return v;
  memset(h, 0, sizeof(double[9][9]));
  if (!isfinite(v)) return v;
  double xs[3][3], size = 0, room = 1;
  for (int c = 0; c < 3; c++) {
    memcpy(xs[c], L->x[c], sizeof xs[c]);
    double r2 = 0, e2 = 0;
    for (int i = 0; i < 3; i++) {
      double d = L->x[(c + 1) % 3][i] - L->x[c][i];
      r2 += L->x[c][i] * L->x[c][i];
      e2 += d * d;
    }
    size = fmax(size, sqrt(e2));
    room = fmin(room, 1 - r2);
  }
  double step = 1e-5 * fmin(size, room);
  if (!(step > 0)) return v;
  const double *xp[3] = {xs[0], xs[1], xs[2]};
  for (int c = 0; c < 3; c++)
    for (int i = 0; i < 3; i++) {
      double gp[3][3], gm[3][3], keep = xs[c][i];
      xs[c][i] = keep + step;
      karea(xp, gp);
      xs[c][i] = keep - step;
      karea(xp, gm);
      xs[c][i] = keep;
      for (int e = 0; e < 3; e++)
        for (int j = 0; j < 3; j++) h[3 * e + j][3 * c + i] = (gp[e][j] - gm[e][j]) / (2 * step);
    }
  for (int k = 0; k < 9; k++)
    for (int j = 0; j < k; j++) h[k][j] = h[j][k] = (h[k][j] + h[j][k]) / 2;
  return v;
}
