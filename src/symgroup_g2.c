/* symgroup_g2.c: Evolver's GENUS2 group on the Klein model (contracts in
** symgroup.h).
**
** The fundamental region is the regular hyperbolic octagon centred at the
** origin with corner angles pi/4 (eight meet at a point: the quotient is a
** closed surface of genus 2). G_k (k = 0..7) is the translation by twice
** the inradius d (cosh d = 5 + 4 sqrt 2) along the direction at angle
** 135 k degrees: G_k = R_k B R_k^-1, B the boost along x, acting on
** homogeneous Klein coordinates (x, y, z, 1) (z like y: the group acts on
** the Klein ball too). Measured against Evolver 2.70: G_0 takes the origin
** to (tanh d, 0), G_1 to angle 135 degrees, and the code byte a + 16 b is
** the product G_a G_(a+1) ... G_(b-1) (indices mod 8; a == b the
** identity), so G_0 G_1 ... G_7 = 1 and G_(k+4) = G_k^-1.
**
** Internal codes: 0 the identity, else a + 16 b with the run of length 7
** written as the generator it equals ([a, a+7) = G_(a+3)), so that equal
** elements have equal codes. Products of runs that are no run (Evolver:
** "Wrap outside known range") are TDS_SYM_OUTSIDE.
*/
#include <math.h>
#include <string.h>

#include "symgroup.h"

/* cos and sin of 45 j degrees, exactly rounded */
static void cs45(int j, double *c, double *s) {
  static const double h = 0.70710678118654752440;
  static const double C[8][2] = {{1, 0}, {h, h}, {0, 1}, {-h, h}, {-1, 0}, {-h, -h}, {0, -1}, {h, -h}};
  *c = C[j & 7][0];
  *s = C[j & 7][1];
}

typedef long double ld;

static void mat_mul(const ld A[4][4], const ld B[4][4], ld C[4][4]) {
  ld T[4][4];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      T[i][j] = A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j] + A[i][3] * B[3][j];
  memcpy(C, T, sizeof T);
}

/* G_k as a 4x4 matrix on (x, y, z, 1). */
static void gen(int k, ld M[4][4]) {
  ld r2 = sqrtl(2.0L), ch = 5 + 4 * r2, sh = sqrtl(56 + 40 * r2); /* sh^2 = ch^2 - 1 */
  double c, s;
  cs45(3 * k, &c, &s);
  /* the boost along u: x -> x + (ch - 1)(u.x) u + sh t u, t -> ch t + sh u.x */
  ld u[2] = {c, s};
  if (c != 0 && s != 0) u[0] = (c > 0 ? 1 : -1) * r2 / 2, u[1] = (s > 0 ? 1 : -1) * r2 / 2;
  memset(M, 0, 16 * sizeof(ld));
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) M[i][j] = (i == j) + (ch - 1) * u[i] * u[j];
  M[2][2] = 1;
  for (int i = 0; i < 2; i++) M[i][3] = M[3][i] = sh * u[i];
  M[3][3] = ch;
}

/* The run [a, b) (length 0..7), in long double: a run longer than 4 is the
** inverse of the complementary run, eta R^T eta (exact), so at most four
** generators are multiplied (their entries reach ch^4 ~ 1e4: the long
** double products keep the result's rounding at double's). */
void tds_g2_matrix(int32_t w, double out[4][4]) {
  int a = w & 7, b = (w >> 4) & 7, len = (b - a) & 7, inv = len > 4;
  if (inv) {
    int t = a;
    a = b, b = t;
  }
  ld M[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  for (int k = a; k != b; k = (k + 1) & 7) {
    ld G[4][4];
    gen(k, G);
    mat_mul(M, G, M);
  }
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) /* eta M^T eta: the time row and column change sign */
      out[i][j] = (double)(inv ? ((i == 3) != (j == 3) ? -M[j][i] : M[j][i]) : M[i][j]);
}

/* The canonical internal code of run [a, b). */
static int32_t canon(int a, int b) {
  a &= 7, b &= 7;
  if (a == b) return 0;
  if (((b - a) & 7) == 7) a = (a + 3) & 7, b = (a + 1) & 7;
  return (int32_t)(a | b << 4);
}

int tds_g2_from_code(double code, int32_t *w) {
  if (!(code >= 0 && code < 256) || code != floor(code)) return -1;
  int c = (int)code;
  *w = canon(c, c >> 4);
  return 0;
}

int32_t tds_g2_inv(int32_t w) {
  return w ? canon(w >> 4, w) : 0;
}

/* Whether M and N are the same isometry (projective matrices with
** M[3][3], N[3][3] >= 1: the Lorentz matrices' time-time entries). */
static int same(const double M[4][4], const double N[4][4]) {
  double big = 0, diff = 0;
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) {
      big = fmax(big, fabs(M[i][j]));
      diff = fmax(diff, fabs(M[i][j] - N[i][j]));
    }
  return diff <= 1e-9 * big;
}

int32_t tds_g2_mul(int32_t x, int32_t y) {
  if (!x) return y;
  if (!y) return x;
  if (((x >> 4) & 7) == (y & 7)) return canon(x, y >> 4); /* [a,b)[b,c) = [a,c) */
  double X[4][4], Y[4][4], P[4][4];
  tds_g2_matrix(x, X);
  tds_g2_matrix(y, Y);
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      P[i][j] = X[i][0] * Y[0][j] + X[i][1] * Y[1][j] + X[i][2] * Y[2][j] + X[i][3] * Y[3][j];
  double I[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  if (same(P, I)) return 0;
  for (int a = 0; a < 8; a++)
    for (int len = 1; len < 7; len++) {
      double Q[4][4];
      int32_t c = canon(a, a + len);
      tds_g2_matrix(c, Q);
      if (same(P, Q)) return c;
    }
  return TDS_SYM_OUTSIDE;
}

void tds_g2_apply(int32_t w, const double x[3], double out[3], double J[3][3], double T[3][3][3]) {
  double M[4][4];
  tds_g2_matrix(w, M);
  double y[4];
  for (int i = 0; i < 4; i++) y[i] = M[i][0] * x[0] + M[i][1] * x[1] + M[i][2] * x[2] + M[i][3];
  double f[3] = {y[0] / y[3], y[1] / y[3], y[2] / y[3]};
  if (J) /* J_ij = (M_ij - f_i M_3j) / w */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) J[i][j] = (M[i][j] - f[i] * M[3][j]) / y[3];
  if (J && T) /* d2 f_i / dx_j dx_k = -(M_3j J_ik + M_3k J_ij) / w */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++) T[i][j][k] = -(M[3][j] * J[i][k] + M[3][k] * J[i][j]) / y[3];
  memcpy(out, f, sizeof f);
}
