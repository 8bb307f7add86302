/* method_integral.c: the rows with expression integrands (edge and facet,
** vector and scalar) and the gap energy of a convex constraint.
**
** Integrals use the quadrature rules of quadrature.h; at a quadrature point
** p = sum_c b_c x_c (edge: b = (1-t, t)) the expression compiler gives the
** integrand's exact gradient and Hessian in x, y, z, and the chain rule
** through p and through the element's geometry (edge vector d, facet
** normal N, area, length) gives the kernel's. Notation: F_j the vector
** field, J[j][k] = dF_j/dx_k, H[j][k][l] its second derivatives.
*/
#include <math.h>
#include <string.h>

#include "quadrature.h"
#include "geom.h"
#include "method.h"

/* Integrand components 0..n-1 at p: values f, with J its Jacobian, with H
** also its Hessians (missing components are 0). */
static void field(const tds_mlocal *L, int n, const double *p, double *f,
                  double (*J)[3], double (*H)[3][3]) {
  double vars[TDS_NVARS] = {p[0], p[1], p[2], 0, 0, L->G};
  for (int j = 0; j < n; j++) {
    const tds_expr *e = L->ig[j];
    if (J) memset(J[j], 0, sizeof J[j]);
    if (H) memset(H[j], 0, sizeof H[j]);
    if (!e) {
      f[j] = 0;
    } else if (H) {
      double gr[TDS_NDIFF], hs[TDS_NDIFF][TDS_NDIFF];
      f[j] = tds_expr_eval_hess(e, L->param, vars, gr, hs);
      for (int k = 0; k < 3; k++) {
        J[j][k] = gr[k];
        for (int l = 0; l < 3; l++) H[j][k][l] = hs[k][l];
      }
    } else if (J) {
      double gr[TDS_NDIFF];
      f[j] = tds_expr_eval_grad(e, L->param, vars, gr);
      for (int k = 0; k < 3; k++) J[j][k] = gr[k];
    } else {
      f[j] = tds_expr_eval(e, L->param, vars);
    }
  }
}

static void clear(int n, double g[3][3], double h[9][9]) {
  if (g) memset(g, 0, sizeof(double[3][3]));
  if (h) memset(h, 0, sizeof(double[9][9]));
  (void)n;
}

/* int over the edge of F . ds = sum_q w F(p_q) . d, d = x1 - x0. */
double tds_mk_edge_vint(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  const tds_rule *R = tds_edge_rule(L->npts);
  static const double s[2] = {-1, 1}; /* dd/dx0 = -I, dd/dx1 = I */
  double d[3], sum = 0;
  v3_sub(d, L->x[1], L->x[0]);
  clear(2, g, h);
  for (int q = 0; q < R->n; q++) {
    double t = R->t[q], w = R->w[q], p[3], f[3], J[3][3], H[3][3][3];
    for (int k = 0; k < 3; k++) p[k] = L->x[0][k] + t * d[k];
    field(L, 3, p, f, g ? J : NULL, h ? H : NULL);
    sum += w * v3_dot(f, d);
    if (!g) continue;
    const double c[2] = {1 - t, t};
    double Jd[3];
    for (int k = 0; k < 3; k++) Jd[k] = J[0][k] * d[0] + J[1][k] * d[1] + J[2][k] * d[2];
    for (int P = 0; P < 2; P++)
      for (int k = 0; k < 3; k++) g[P][k] += w * (c[P] * Jd[k] + s[P] * f[k]);
    if (!h) continue;
    for (int k = 0; k < 3; k++)
      for (int l = 0; l < 3; l++) {
        double Hd = H[0][k][l] * d[0] + H[1][k][l] * d[1] + H[2][k][l] * d[2];
        for (int P = 0; P < 2; P++)
          for (int Q = 0; Q < 2; Q++)
            h[3 * P + k][3 * Q + l] +=
                w * (c[P] * c[Q] * Hd + c[P] * s[Q] * J[l][k] + s[P] * c[Q] * J[k][l]);
      }
  }
  return sum;
}

/* int over the edge of f ds = |d| sum_q w f(p_q). */
double tds_mk_edge_sint(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  const tds_rule *R = tds_edge_rule(L->npts);
  static const double s[2] = {-1, 1};
  double d[3];
  v3_sub(d, L->x[1], L->x[0]);
  double len = v3_norm(d), avg = 0, ga[2][3] = {{0}}, ha[6][6] = {{0}};
  clear(2, g, h);
  for (int q = 0; q < R->n; q++) {
    double t = R->t[q], w = R->w[q], p[3], f, J[1][3], H[1][3][3];
    for (int k = 0; k < 3; k++) p[k] = L->x[0][k] + t * d[k];
    field(L, 1, p, &f, g ? J : NULL, h ? H : NULL);
    avg += w * f;
    if (!g) continue;
    const double c[2] = {1 - t, t};
    for (int P = 0; P < 2; P++)
      for (int k = 0; k < 3; k++) {
        ga[P][k] += w * c[P] * J[0][k];
        if (h)
          for (int Q = 0; Q < 2; Q++)
            for (int l = 0; l < 3; l++) ha[3 * P + k][3 * Q + l] += w * c[P] * c[Q] * H[0][k][l];
      }
  }
  if (!g || !(len > 0)) return len * avg; /* no derivative at zero length */
  double tt[3] = {d[0] / len, d[1] / len, d[2] / len};
  for (int P = 0; P < 2; P++)
    for (int k = 0; k < 3; k++) g[P][k] = s[P] * tt[k] * avg + len * ga[P][k];
  if (h)
    for (int P = 0; P < 2; P++)
      for (int k = 0; k < 3; k++)
        for (int Q = 0; Q < 2; Q++)
          for (int l = 0; l < 3; l++)
            h[3 * P + k][3 * Q + l] =
                s[P] * s[Q] * ((k == l) - tt[k] * tt[l]) / len * avg +
                s[P] * tt[k] * ga[Q][l] + s[Q] * tt[l] * ga[P][k] +
                len * ha[3 * P + k][3 * Q + l];
  return len * avg;
}

/* int over the facet of F . n dA = sum_q w F(p_q) . N / 2. */
double tds_mk_facet_vint(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  const tds_rule *R = tds_facet_rule(L->npts);
  const double *const *x = L->x;
  double N[3], ab[3], ac[3], u[3][3][3], sum = 0;
  v3_sub(ab, x[1], x[0]);
  v3_sub(ac, x[2], x[0]);
  v3_cross(N, ab, ac);
  clear(3, g, h);
  if (g) tds_mk_normal_derivs(x, u);
  for (int q = 0; q < R->n; q++) {
    double p[3] = {0, 0, 0}, f[3], J[3][3], H[3][3][3], w = R->w[q] / 2;
    const double *b = R->b[q];
    for (int c = 0; c < 3; c++) v3_axpy(p, b[c], x[c]);
    field(L, 3, p, f, g ? J : NULL, h ? H : NULL);
    sum += w * v3_dot(f, N);
    if (!g) continue;
    double JN[3], JU[3][3][3]; /* JN_i = sum_j J[j][i] N_j; JU[c][i][l] = sum_j J[j][l] u[c][i]_j */
    for (int i = 0; i < 3; i++) JN[i] = J[0][i] * N[0] + J[1][i] * N[1] + J[2][i] * N[2];
    for (int c = 0; c < 3; c++)
      for (int i = 0; i < 3; i++) g[c][i] += w * (b[c] * JN[i] + v3_dot(f, u[c][i]));
    if (!h) continue;
    for (int c = 0; c < 3; c++)
      for (int i = 0; i < 3; i++)
        for (int l = 0; l < 3; l++)
          JU[c][i][l] = J[0][l] * u[c][i][0] + J[1][l] * u[c][i][1] + J[2][l] * u[c][i][2];
    for (int c = 0; c < 3; c++)
      for (int i = 0; i < 3; i++)
        for (int d = 0; d < 3; d++)
          for (int l = 0; l < 3; l++) {
            double HN = H[0][i][l] * N[0] + H[1][i][l] * N[1] + H[2][i][l] * N[2];
            double v = b[c] * b[d] * HN + b[c] * JU[d][l][i] + b[d] * JU[c][i][l];
            /* f . d2N = sigma(c,d) f . (E_i x E_l) */
            int m = 3 - i - l;
            if (i != l && d != c) {
              double sg = d == (c + 1) % 3 ? 1 : -1;
              double e = (l - i + 3) % 3 == 1 ? 1 : -1; /* eps_{i l m} */
              v += sg * e * f[m];
            }
            h[3 * c + i][3 * d + l] += w * v;
          }
  }
  return sum;
}

/* int over the facet of f dA = A sum_q w f(p_q). */
double tds_mk_facet_sint(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  const tds_rule *R = tds_facet_rule(L->npts);
  const double *const *x = L->x;
  double gA[3][3];
  double A = geom_area(x[0], x[1], x[2], g ? gA : NULL);
  double avg = 0, ga[3][3] = {{0}}, ha[9][9] = {{0}};
  clear(3, g, h);
  for (int q = 0; q < R->n; q++) {
    double p[3] = {0, 0, 0}, f, J[1][3], H[1][3][3], w = R->w[q];
    const double *b = R->b[q];
    for (int c = 0; c < 3; c++) v3_axpy(p, b[c], x[c]);
    field(L, 1, p, &f, g ? J : NULL, h ? H : NULL);
    avg += w * f;
    if (!g) continue;
    for (int c = 0; c < 3; c++)
      for (int i = 0; i < 3; i++) {
        ga[c][i] += w * b[c] * J[0][i];
        if (h)
          for (int d = 0; d < 3; d++)
            for (int l = 0; l < 3; l++) ha[3 * c + i][3 * d + l] += w * b[c] * b[d] * H[0][i][l];
      }
  }
  if (!g) return A * avg;
  for (int c = 0; c < 3; c++)
    for (int i = 0; i < 3; i++) g[c][i] = A * ga[c][i] + avg * gA[c][i];
  if (h) {
    tds_mk_area_hess(L->x, h);
    for (int r = 0; r < 9; r++)
      for (int k = 0; k < 9; k++)
        h[r][k] = avg * h[r][k] + A * ha[r][k] + gA[r / 3][r % 3] * ga[k / 3][k % 3] +
                  ga[r / 3][r % 3] * gA[k / 3][k % 3];
  }
  return A * avg;
}

/* Gap energy of an edge on a convex constraint: k |S| |S.n| / 6, with S
** the edge vector and n the unit normal of the constraint at the tail
** (L->k is the gap constant): |S.n| is the height of the head above the
** tail's tangent plane, and |S||S.n|/6 the area between a chord and a
** circular wall to leading order (2/3 chord x sagitta). This is what
** evolver-nox-d computes (measured on skew edges); its manual's |S x Q|
** formula agrees only to leading order. */
static double gap_grad(const tds_mlocal *L, const double xt[3], const double xh[3],
                       double g[3][3]) {
  double S[3], vars[TDS_NVARS] = {xt[0], xt[1], xt[2], 0, 0, L->G};
  double gr[TDS_NDIFF], H[TDS_NDIFF][TDS_NDIFF];
  v3_sub(S, xh, xt);
  tds_expr_eval_hess(L->ig[0], L->param, vars, gr, H);
  double ulen = sqrt(gr[0] * gr[0] + gr[1] * gr[1] + gr[2] * gr[2]);
  double len = v3_norm(S);
  if (g) memset(g, 0, sizeof(double[3][3]));
  if (!(ulen > 0) || !(len > 0)) return 0;
  double n[3] = {gr[0] / ulen, gr[1] / ulen, gr[2] / ulen};
  double a = v3_dot(S, n), k = L->k / 6;
  if (!g) return k * len * fabs(a);
  double sa = a > 0 ? 1 : a < 0 ? -1 : 0;
  double dS[3], dn[3];
  for (int i = 0; i < 3; i++) {
    dS[i] = k * (fabs(a) * S[i] / len + len * sa * n[i]);
    dn[i] = k * len * sa * S[i]; /* dE/dn with |n| held */
  }
  /* dn/dx_t = (I - n n^T) H / |u|: chain rule through the tail's normal. */
  double pn = v3_dot(dn, n), tang[3];
  for (int i = 0; i < 3; i++) tang[i] = (dn[i] - pn * n[i]) / ulen;
  for (int i = 0; i < 3; i++) {
    double hn = 0;
    for (int j = 0; j < 3; j++) hn += H[j][i] * tang[j];
    g[0][i] = -dS[i] + hn;
    g[1][i] = dS[i];
  }
  return k * len * fabs(a);
}

double tds_mk_edge_gap(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double E = gap_grad(L, L->x[0], L->x[1], g);
  if (!h) return E;
  /* Central differences of the exact gradient, step relative to the
  ** edge's size, symmetrised. */
  double x[2][3];
  memcpy(x[0], L->x[0], sizeof x[0]);
  memcpy(x[1], L->x[1], sizeof x[1]);
  double scale = 1 + fabs(x[0][0]) + fabs(x[0][1]) + fabs(x[0][2]);
  double st = 1e-6 * scale;
  memset(h, 0, sizeof(double[9][9]));
  for (int c = 0; c < 2; c++)
    for (int j = 0; j < 3; j++) {
      double gp[3][3], gm[3][3], keep = x[c][j];
      x[c][j] = keep + st;
      gap_grad(L, x[0], x[1], gp);
      x[c][j] = keep - st;
      gap_grad(L, x[0], x[1], gm);
      x[c][j] = keep;
      for (int e = 0; e < 2; e++)
        for (int i = 0; i < 3; i++) h[3 * e + i][3 * c + j] = (gp[e][i] - gm[e][i]) / (2 * st);
    }
  for (int r = 0; r < 6; r++)
    for (int k = r + 1; k < 6; k++) h[r][k] = h[k][r] = (h[r][k] + h[k][r]) / 2;
  return E;
}
