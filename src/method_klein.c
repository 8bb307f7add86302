/* method_klein.c: edge length in the Klein model of hyperbolic space
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

double tds_klein_dist(const double a[3], const double b[3]) {
  double p = 1 - (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  double q = 1 - (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (!(p > 0 && q > 0)) return INFINITY;
  double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double ad = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
  double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  return asinh(sqrt((p * dd + ad * ad) / (p * q)));
}

double tds_mk_klein_length(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  const double *a = L->x[0], *b = L->x[1];
  if (g) memset(g, 0, sizeof(double[3][3]));
  if (h) memset(h, 0, sizeof(double[9][9]));
  double p = 1 - (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  double q = 1 - (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (!(p > 0 && q > 0)) return INFINITY;
  double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double ad = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
  double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double S = sqrt((p * dd + ad * ad) / (p * q));
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
