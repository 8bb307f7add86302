/*
** method_string.c: the rows of the string model (surface dimension 1),
** whose facets are plane cells bounded by edges (Evolver's model.htm):
**   edge_area           -int y dx along the edge, exact for a straight
**                       edge: -(y0 + y1)(x1 - x0)/2. Summed with the
**                       signs of a facet's edge loop it is the facet's
**                       area (Green), so a body's area is a sum of rows.
**   string_gravity      -int y^2/2 dx = -(x1 - x0)(y0^2 + y0 y1 + y1^2)/6:
**                       summed over a cell's loop, int int y dA (the
**                       gravitational moment, weighted by G density).
**   vertex_scalar_head  the scalar integrand at the head (tail) corner:
**   vertex_scalar_tail  a constraint's content in the string model, which
**                       Evolver evaluates at the vertices on the
**                       constraint where a cell's loop leaves or meets it.
**   edge_shift          x1[k] - x0[k] (k the row constant): in the torus a
**                       cell's edge seen from a lattice translate t of its
**                       stored tail has edge_area less t_y (x1 - x0), so a
**                       body's area is its edge_area rows plus this row
**                       weighted by -t_y per loop entry (string_model.h).
** Only x and y enter the first two, in 2-D and 3-D space alike (Evolver's
** string model measures areas in the x-y plane).
*/
#include "method.h"

#include <math.h>
#include <string.h>

void tds_mk_edge_area_hess(double (*h)[9]) {
  memset(h, 0, sizeof(double[9][9]));
  /* d2/dx0 dy0 = d2/dx0 dy1 = 1/2, d2/dx1 dy0 = d2/dx1 dy1 = -1/2 */
  h[0][1] = h[1][0] = h[0][4] = h[4][0] = 0.5;
  h[3][1] = h[1][3] = h[3][4] = h[4][3] = -0.5;
}

double tds_mk_string_gravity(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  const double *a = L->x[0], *b = L->x[1];
  double y0 = a[1], y1 = b[1], D = b[0] - a[0];
  double Q = y0 * y0 + y0 * y1 + y1 * y1;
  if (g) {
    memset(g, 0, sizeof(double[3][3]));
    g[0][0] = Q / 6;
    g[1][0] = -Q / 6;
    g[0][1] = -D * (2 * y0 + y1) / 6;
    g[1][1] = -D * (y0 + 2 * y1) / 6;
  }
  if (h) {
    memset(h, 0, sizeof(double[9][9]));
    double p = (2 * y0 + y1) / 6, q = (y0 + 2 * y1) / 6;
    h[0][1] = h[1][0] = p;   /* x0 y0 */
    h[0][4] = h[4][0] = q;   /* x0 y1 */
    h[3][1] = h[1][3] = -p;  /* x1 y0 */
    h[3][4] = h[4][3] = -q;  /* x1 y1 */
    h[1][1] = -2 * D / 6;
    h[4][4] = -2 * D / 6;
    h[1][4] = h[4][1] = -D / 6;
  }
  return -D * Q / 6;
}

/* The scalar integrand at corner c of the edge. */
static double at_corner(const tds_mlocal *L, int c, double g[3][3], double h[9][9]) {
  const double *x = L->x[c];
  double vars[TDS_NVARS] = {x[0], x[1], x[2], 0, 0, L->G};
  if (!g) return tds_expr_eval(L->ig[0], L->param, vars);
  double gr[TDS_NDIFF], H[TDS_NDIFF][TDS_NDIFF];
  double f = h ? tds_expr_eval_hess(L->ig[0], L->param, vars, gr, H)
               : tds_expr_eval_grad(L->ig[0], L->param, vars, gr);
  memset(g, 0, sizeof(double[3][3]));
  for (int i = 0; i < 3; i++) g[c][i] = gr[i];
  if (h) {
    memset(h, 0, sizeof(double[9][9]));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) h[3 * c + i][3 * c + j] = H[i][j];
  }
  return f;
}

double tds_mk_vertex_head(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  return at_corner(L, 1, g, h);
}

double tds_mk_vertex_tail(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  return at_corner(L, 0, g, h);
}

/* ---- edge length in a Riemannian metric (METRIC) ----
** L = sum over Evolver's 2-point Gauss rule (measured: its edge length
** equals this rule to 1e-16 on metric.fe's metric) of w sqrt(d^T G(x) d),
** d = x1 - x0, x = x0 + t d; G[i][j] = ig[3i+j] (NULL: 0; ig NULL: the
** identity, Euclidean length). The Hessian is
** a central difference of the exact gradient. */

static double metric_len(const tds_mlocal *L, const double *x0, const double *x1,
                         double g[3][3]) {
  static const double T[2] = {0.21132486540518711775, 0.78867513459481288225};
  double d[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]}, len = 0;
  if (g) memset(g, 0, sizeof(double[3][3]));
  for (int q = 0; q < 2; q++) {
    double vars[TDS_NVARS] = {x0[0] + T[q] * d[0], x0[1] + T[q] * d[1],
                              x0[2] + T[q] * d[2], 0, 0, L->G};
    double G[3][3], dG[3][3][3] = {{{0}}}; /* dG[k][i][j] = dG_ij/dx_k */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        const tds_expr *e = L->ig ? L->ig[3 * i + j] : NULL;
        if (!e) { /* no metric: the identity (a test's Euclidean case) */
          G[i][j] = L->ig ? 0 : i == j;
          continue;
        }
        if (g) {
          double gr[TDS_NDIFF];
          G[i][j] = tds_expr_eval_grad(e, L->param, vars, gr);
          for (int k = 0; k < 3; k++) dG[k][i][j] = gr[k];
        } else {
          G[i][j] = tds_expr_eval(e, L->param, vars);
        }
      }
    double Gd[3], S = 0;
    for (int i = 0; i < 3; i++) {
      Gd[i] = 0;
      for (int j = 0; j < 3; j++) Gd[i] += 0.5 * (G[i][j] + G[j][i]) * d[j];
      S += d[i] * Gd[i];
    }
    double r = S > 0 ? sqrt(S) : 0;
    len += 0.5 * r;
    if (!g || !(r > 0)) continue;
    for (int k = 0; k < 3; k++) {
      double dd = 0; /* d^T dG/dx_k d */
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) dd += d[i] * dG[k][i][j] * d[j];
      double c = 0.5 / (2 * r); /* w / (2 sqrt S) */
      g[0][k] += c * (-2 * Gd[k] + (1 - T[q]) * dd);
      g[1][k] += c * (2 * Gd[k] + T[q] * dd);
    }
  }
  return len;
}

double tds_mk_metric_length(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double v = metric_len(L, L->x[0], L->x[1], g);
  if (!h) return v;
  memset(h, 0, sizeof(double[9][9]));
  double d[3] = {L->x[1][0] - L->x[0][0], L->x[1][1] - L->x[0][1], L->x[1][2] - L->x[0][2]};
  double step = 1e-5 * sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(step > 0)) return v;
  double xs[2][3];
  memcpy(xs[0], L->x[0], sizeof xs[0]);
  memcpy(xs[1], L->x[1], sizeof xs[1]);
  for (int c = 0; c < 2; c++)
    for (int i = 0; i < 3; i++) {
      double gp[3][3], gm[3][3], keep = xs[c][i];
      xs[c][i] = keep + step;
      metric_len(L, xs[0], xs[1], gp);
      xs[c][i] = keep - step;
      metric_len(L, xs[0], xs[1], gm);
      xs[c][i] = keep;
      for (int e = 0; e < 2; e++)
        for (int j = 0; j < 3; j++) h[3 * e + j][3 * c + i] = (gp[e][j] - gm[e][j]) / (2 * step);
    }
  for (int k = 0; k < 6; k++)
    for (int j = 0; j < k; j++) h[k][j] = h[j][k] = (h[k][j] + h[j][k]) / 2;
  return v;
}

double tds_mk_edge_shift(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  int k = (int)L->k;
  if (k < 0) k = 0;
  if (k > 2) k = 2;
  if (g) {
    memset(g, 0, sizeof(double[3][3]));
    g[0][k] = -1;
    g[1][k] = 1;
  }
  if (h) memset(h, 0, sizeof(double[9][9]));
  return L->x[1][k] - L->x[0][k];
}
