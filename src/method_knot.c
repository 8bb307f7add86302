/*
** method_knot.c: knot energies, the string model's squared curvature and
** Hooke springs (Evolver's named methods of knotty.fe). Formulas as
** evolver-nox-d 2.70 computes them, measured on an irregular pentagon and
** on single corners (tests/evolver/knot.sh compares whole files):
**   knot_energy         vertex pair:  1/|x0 - x1|^p            (p knot_power)
**   edge_knot_energy    edge pair:    L1 L2 / |m1 - m2|^p      (midpoints m)
**   buck_knot_energy    edge pair without a common vertex:
**                       1 / (sum of the 4 end-to-end distances - 2(L1 + L2))^p
**   proj_knot_energy    ordered edge pair: 2 L1 L2 cos^p(th) / |r|^p,
**                       r = m1 - m2, th the angle between r and the normal
**                       plane of edge 1: |r|^2 cos^2 = |r|^2 - (r.t1)^2
**   circle_knot_energy  edge pair: L1 L2 (1 - cos a) / |r|^2 with
**                       cos a = 2 (t1.r)(t2.r)/|r|^2 - t1.t2 (power 2 only)
**   sqcurve_string      vertex between edges a = x1 - x0, b = x2 - x1, of
**                       lengths s1, s2, c = a.b / (s1 s2):
**                       (4 (1 - c) + 2/3 (1 - c)^2) / (s1 + s2)
**                       (the manual's 4 (1 - cos t)/(s1 + s2) plus the next
**                       term of the series of 2 t^2 / (s1 + s2); measured)
**   hooke_energy        edge: |L - L0|^p, p = 0: -log |L - L0|
** Every pair sum runs over ordered pairs (each unordered pair twice), the
** assembly's business (eval_knot.c). The 4-corner kernels give their
** gradient by complex-step differentiation of one complex formula: exact
** to rounding (no difference quotient), one evaluation per coordinate.
*/
#include "method.h"

#include <complex.h>
#include <math.h>
#include <string.h>

#include "vec3.h"

/* ---- knot_energy: 1/|r|^p, r = x0 - x1 ---- */

double tds_mk_knot(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double r[3];
  v3_sub(r, L->x[0], L->x[1]);
  double s = v3_dot(r, r), p = L->pw;
  if (!(s > 0)) {
    if (g) memset(g, 0, sizeof(double[3][3]));
    if (h) memset(h, 0, sizeof(double[9][9]));
    return HUGE_VAL;
  }
  double v = p == 2 ? 1 / s : pow(s, -p / 2);
  if (g) {
    memset(g, 0, sizeof(double[3][3]));
    double a = -p * v / s; /* dv/dr = a r */
    for (int i = 0; i < 3; i++) g[0][i] = a * r[i], g[1][i] = -a * r[i];
    if (h) {
      double b = p * (p + 2) * v / (s * s); /* d2v/dr2 = a I + b r r^T */
      memset(h, 0, sizeof(double[9][9]));
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          double d = (i == j ? a : 0) + b * r[i] * r[j];
          h[i][j] = h[3 + i][3 + j] = d;
          h[i][3 + j] = h[3 + i][j] = -d;
        }
    }
  }
  return v;
}

/* ---- hooke_energy, hooke2_energy: f(L) = |L - k|^pw ---- */

double tds_mk_hooke(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double d[3];
  v3_sub(d, L->x[1], L->x[0]);
  double len = v3_norm(d), u = len - L->k, au = fabs(u), p = L->pw;
  double f, f1, f2; /* f(L), f'(L), f''(L) */
  if (p == 0) {
    f = -log(au), f1 = -1 / u, f2 = 1 / (u * u);
  } else if (p == 2) {
    f = u * u, f1 = 2 * u, f2 = 2;
  } else {
    f = pow(au, p);
    f1 = au > 0 ? p * f / u : 0;
    f2 = au > 0 ? p * (p - 1) * f / (u * u) : 0;
  }
  if (g) {
    memset(g, 0, sizeof(double[3][3]));
    double t[3] = {0, 0, 0};
    if (len > 0) t[0] = d[0] / len, t[1] = d[1] / len, t[2] = d[2] / len;
    for (int i = 0; i < 3; i++) g[1][i] = f1 * t[i], g[0][i] = -f1 * t[i];
    if (h) {
      memset(h, 0, sizeof(double[9][9]));
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          double M = f2 * t[i] * t[j] +
                     (len > 0 ? f1 / len * ((i == j) - t[i] * t[j]) : 0);
          h[i][j] = h[3 + i][3 + j] = M;
          h[i][3 + j] = h[3 + i][j] = -M;
        }
    }
  }
  return f;
}

/* ---- sqcurve_string ---- */

/* Value and gradient (g[0..2], may be NULL) at corners x. */
static double sqcurve(const double *const x[3], double g[3][3]) {
  double a[3], b[3];
  v3_sub(a, x[1], x[0]);
  v3_sub(b, x[2], x[1]);
  double s1 = v3_norm(a), s2 = v3_norm(b);
  if (g) memset(g, 0, sizeof(double[3][3]));
  if (!(s1 > 0 && s2 > 0)) return 0;
  double c = v3_dot(a, b) / (s1 * s2), S = s1 + s2, w = 1 - c;
  double K = 4 * w + 2.0 / 3.0 * w * w;
  if (g) {
    double dK = -4 - 4.0 / 3.0 * w; /* dK/dc */
    for (int i = 0; i < 3; i++) {
      double dca = b[i] / (s1 * s2) - c * a[i] / (s1 * s1);
      double dcb = a[i] / (s1 * s2) - c * b[i] / (s2 * s2);
      double da = dK * dca / S - K / (S * S) * a[i] / s1;
      double db = dK * dcb / S - K / (S * S) * b[i] / s2;
      g[0][i] = -da;
      g[1][i] = da - db;
      g[2][i] = db;
    }
  }
  return K / S;
}

/* The Hessian is a central difference of the exact gradient (step 1e-4
** of the shorter edge: truncation ~1e-8, rounding ~1e-12 relative). */
double tds_mk_sqcurve(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double v = sqcurve(L->x, g);
  if (!h) return v;
  memset(h, 0, sizeof(double[9][9]));
  double a[3], b[3];
  v3_sub(a, L->x[1], L->x[0]);
  v3_sub(b, L->x[2], L->x[1]);
  double step = 1e-4 * fmin(v3_norm(a), v3_norm(b));
  if (!(step > 0)) return v;
  double xs[3][3];
  const double *xp[3] = {xs[0], xs[1], xs[2]};
  for (int c = 0; c < 3; c++) memcpy(xs[c], L->x[c], sizeof xs[c]);
  for (int c = 0; c < 3; c++)
    for (int i = 0; i < 3; i++) {
      double gp[3][3], gm[3][3], keep = xs[c][i];
      xs[c][i] = keep + step;
      sqcurve(xp, gp);
      xs[c][i] = keep - step;
      sqcurve(xp, gm);
      xs[c][i] = keep;
      for (int d = 0; d < 3; d++)
        for (int j = 0; j < 3; j++)
          h[3 * d + j][3 * c + i] = (gp[d][j] - gm[d][j]) / (2 * step);
    }
  for (int k = 0; k < 9; k++) /* symmetrise the rounding away */
    for (int j = 0; j < k; j++) h[k][j] = h[j][k] = (h[k][j] + h[j][k]) / 2;
  return v;
}

/* ---- edge pairs: one complex formula each ---- */

typedef double complex cplx;
typedef cplx (*pairfn)(const cplx y[4][3], double pw);

static cplx cdot(const cplx *a, const cplx *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void csub(cplx *d, const cplx *a, const cplx *b) {
  for (int i = 0; i < 3; i++) d[i] = a[i] - b[i];
}
/* x^(pw/2) for x = |.|^2 (real part positive) */
static cplx chalfpow(cplx x, double pw) {
  return pw == 2 ? x : pw == 1 ? csqrt(x) : cpow(x, pw / 2);
}

/* Shared pieces: edge vectors d1, d2, lengths, r = m1 - m2. */
typedef struct pairgeo {
  cplx d1[3], d2[3], r[3], L1, L2, rr;
} pairgeo;

static void geo(const cplx y[4][3], pairgeo *G) {
  csub(G->d1, y[1], y[0]);
  csub(G->d2, y[3], y[2]);
  for (int i = 0; i < 3; i++) G->r[i] = (y[0][i] + y[1][i] - y[2][i] - y[3][i]) / 2;
  G->L1 = csqrt(cdot(G->d1, G->d1));
  G->L2 = csqrt(cdot(G->d2, G->d2));
  G->rr = cdot(G->r, G->r);
}

static cplx f_edge_knot(const cplx y[4][3], double pw) {
  pairgeo G;
  geo(y, &G);
  return G.L1 * G.L2 / chalfpow(G.rr, pw);
}

static cplx f_buck(const cplx y[4][3], double pw) {
  pairgeo G;
  geo(y, &G);
  cplx D = 0, t[3];
  for (int a = 0; a < 2; a++)
    for (int b = 2; b < 4; b++) {
      csub(t, y[a], y[b]);
      D += csqrt(cdot(t, t));
    }
  cplx den = D - 2 * (G.L1 + G.L2);
  return 1 / chalfpow(den * den, pw);
}

static cplx f_proj(const cplx y[4][3], double pw) {
  pairgeo G;
  geo(y, &G);
  cplx rt = cdot(G.r, G.d1) / G.L1;
  return 2 * G.L1 * G.L2 * chalfpow(G.rr - rt * rt, pw) / chalfpow(G.rr * G.rr, pw);
}

static cplx f_circle(const cplx y[4][3], double pw) {
  (void)pw; /* power 2 only, as Evolver */
  pairgeo G;
  geo(y, &G);
  cplx num = G.L1 * G.L2 + cdot(G.d1, G.d2) -
             2 * cdot(G.d1, G.r) * cdot(G.d2, G.r) / G.rr;
  return num / G.rr;
}

/* Value (real formula: zero imaginary parts) and, with g, the gradient:
** dF/dy = Im F(y + i h e) / h exactly up to rounding for h tiny. */
static double pair_eval(pairfn f, const double *const y[4], double pw, double g[4][3]) {
  cplx z[4][3];
  for (int c = 0; c < 4; c++)
    for (int i = 0; i < 3; i++) z[c][i] = y[c][i];
  double v = creal(f((const cplx(*)[3])z, pw));
  if (g) {
    const double h = 1e-30;
    for (int c = 0; c < 4; c++)
      for (int i = 0; i < 3; i++) {
        ((double *)&z[c][i])[1] = h; /* y + i h (C11 6.2.5: a complex is an array of two
                                        reals; clang's headers lack CMPLX) */
        g[c][i] = cimag(f((const cplx(*)[3])z, pw)) / h;
        z[c][i] = y[c][i];
      }
  }
  return v;
}

double tds_mk_edge_knot(const double *const y[4], double pw, double g[4][3]) {
  return pair_eval(f_edge_knot, y, pw, g);
}
/* A non-positive denominator (edges long for their distance) has no
** energy: HUGE_VAL, which the assembly reports (Evolver stops too). */
double tds_mk_buck_knot(const double *const y[4], double pw, double g[4][3]) {
  double D = 0, L1 = 0, L2 = 0, t[3];
  for (int a = 0; a < 2; a++)
    for (int b = 2; b < 4; b++) {
      v3_sub(t, y[a], y[b]);
      D += v3_norm(t);
    }
  v3_sub(t, y[1], y[0]);
  L1 = v3_norm(t);
  v3_sub(t, y[3], y[2]);
  L2 = v3_norm(t);
  if (!(D - 2 * (L1 + L2) > 0)) {
    if (g) memset(g, 0, sizeof(double[4][3]));
    return HUGE_VAL;
  }
  return pair_eval(f_buck, y, pw, g);
}
double tds_mk_proj_knot(const double *const y[4], double pw, double g[4][3]) {
  return pair_eval(f_proj, y, pw, g);
}
double tds_mk_circle_knot(const double *const y[4], double pw, double g[4][3]) {
  return pair_eval(f_circle, y, pw, g);
}
