/* method.c: the method table and its geometric rows (area, length,
** volumes, gravity moment) with their Hessians.
**
** Values and gradients are geom.h's (the same bits as before the table).
** Hessians use that the facet normal N = (x1-x0) x (x2-x0)
** = x0 x x1 + x1 x x2 + x2 x x0 is bilinear in the corners:
**   dN/dx[c][i] = u[c][i] = E_i x d_c,  d_c = x[c+1] - x[c+2],
**   d2N/dx[c][i]dx[d][j] = sigma(c,d) E_i x E_j,
** with sigma = +1 when d = c+1, -1 when d = c+2, 0 when d = c (mod 3).
*/
#include "method.h"

#include <string.h>
#include <strings.h>


/* sigma(c, d) above. */
static double sigma(int c, int d) { return d == (c + 1) % 3 ? 1 : d == (c + 2) % 3 ? -1 : 0; }

/* eps_ijm, the Levi-Civita symbol. */
static double eps(int i, int j, int m) {
  if (i == j || j == m || i == m) return 0;
  return ((j - i + 3) % 3 == 1) ? 1 : -1;
}

void tds_mk_normal_derivs(const double *const *x, double u[3][3][3]) {
  for (int c = 0; c < 3; c++) {
    double d[3];
    v3_sub(d, x[(c + 1) % 3], x[(c + 2) % 3]);
    for (int i = 0; i < 3; i++) {
      double e[3] = {0, 0, 0};
      e[i] = 1;
      v3_cross(u[c][i], e, d);
    }
  }
}

/* eps_ijm n_m: the matrix of n x. */
static void cross_matrix(const double n[3], double E[3][3]) {
  E[0][0] = E[1][1] = E[2][2] = 0;
  E[0][1] = n[2], E[0][2] = -n[1];
  E[1][0] = -n[2], E[1][2] = n[0];
  E[2][0] = n[1], E[2][1] = -n[0];
}

void tds_mk_area_hess(const double *const *x, double (*h)[9]) {
  double ab[3], ac[3], N[3];
  v3_sub(ab, x[1], x[0]);
  v3_sub(ac, x[2], x[0]);
  v3_cross(N, ab, ac);
  double len = v3_norm(N);
  if (!(len > 0)) { /* not differentiable: a degenerate facet */
    memset(h, 0, sizeof(double[9][9]));
    return;
  }
  double n[3] = {N[0] / len, N[1] / len, N[2] / len};
  /* A = |N|/2: d2A = (u.u' - (n.u)(n.u'))/(2|N|) + n . d2N / 2, where
  ** u[c][i].u[d][j] = delta_ij d_c.d_d - (d_d)_i (d_c)_j and
  ** n.u[c][i] = (d_c x n)_i */
  double d[3][3], mc[3][3], dd[3][3], E[3][3];
  for (int c = 0; c < 3; c++) {
    v3_sub(d[c], x[(c + 1) % 3], x[(c + 2) % 3]);
    v3_cross(mc[c], d[c], n);
  }
  for (int c = 0; c < 3; c++)
    for (int e = 0; e < 3; e++) dd[c][e] = v3_dot(d[c], d[e]);
  cross_matrix(n, E);
  double il = 0.5 / len;
  for (int c = 0; c < 3; c++)
    for (int e = 0; e < 3; e++) {
      double s = 0.5 * sigma(c, e);
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          h[3 * c + i][3 * e + j] =
              il * ((i == j ? dd[c][e] : 0) - d[e][i] * d[c][j] - mc[c][i] * mc[e][j]) +
              s * E[i][j];
    }
}

void tds_mk_length_hess(const double t[3], double len, double (*h)[9]) {
  static const double s[2] = {-1, 1};
  for (int c = 0; c < 2; c++)
    for (int i = 0; i < 3; i++)
      for (int e = 0; e < 2; e++)
        for (int j = 0; j < 3; j++)
          h[3 * c + i][3 * e + j] = len > 0 ? s[c] * s[e] * ((i == j) - t[i] * t[j]) / len : 0;
}

/* Hessian of Nz * P / den, P a polynomial in the corner heights with
** gradient dP[c] (along z) and Hessian ddP[c][d] (z, z): shared by the
** z-volume (P = z0 + z1 + z2) and the gravity moment. */
static void nz_poly_hess(const double *const *x, double P, const double *dP,
                         const double (*ddP)[3], double den, double (*h)[9]) {
  /* u[c][j][2] = (E_j x d_c)_z: (d_c)_y for j = 0, -(d_c)_x for j = 1, 0 */
  double uz[3][3];
  for (int c = 0; c < 3; c++) {
    const double *p = x[(c + 1) % 3], *q = x[(c + 2) % 3];
    uz[c][0] = p[1] - q[1];
    uz[c][1] = -(p[0] - q[0]);
    uz[c][2] = 0;
  }
  double Nz = (x[1][0] - x[0][0]) * (x[2][1] - x[0][1]) -
              (x[1][1] - x[0][1]) * (x[2][0] - x[0][0]);
  double id = 1 / den;
  for (int c = 0; c < 3; c++)
    for (int d = 0; d < 3; d++) {
      double ps = P * sigma(c, d);
      double *r0 = h[3 * c], *r1 = h[3 * c + 1], *r2 = h[3 * c + 2];
      /* eps(i, j, 2): +1 for (0, 1), -1 for (1, 0) */
      r0[3 * d] = 0, r0[3 * d + 1] = ps, r0[3 * d + 2] = dP[d] * uz[c][0];
      r1[3 * d] = -ps, r1[3 * d + 1] = 0, r1[3 * d + 2] = dP[d] * uz[c][1];
      r2[3 * d] = dP[c] * uz[d][0], r2[3 * d + 1] = dP[c] * uz[d][1];
      r2[3 * d + 2] = Nz * ddP[c][d];
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) h[3 * c + i][3 * d + j] *= id;
    }
}

void tds_mk_volume_hess(const double *const *x, double (*h)[9]) {
  static const double dP[3] = {1, 1, 1}, ddP[3][3] = {{0}};
  nz_poly_hess(x, x[0][2] + x[1][2] + x[2][2], dP, ddP, 6, h);
}

static double k_zmoment(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double W = geom_zmoment(L->x[0], L->x[1], L->x[2], g);
  if (h) {
    double z[3] = {L->x[0][2], L->x[1][2], L->x[2][2]}, zs = z[0] + z[1] + z[2];
    double S = z[0] * z[0] + z[1] * z[1] + z[2] * z[2] + z[0] * z[1] + z[1] * z[2] +
               z[2] * z[0];
    double dS[3] = {z[0] + zs, z[1] + zs, z[2] + zs};
    double ddS[3][3] = {{2, 1, 1}, {1, 2, 1}, {1, 1, 2}};
    nz_poly_hess(L->x, S, dS, (const double(*)[3])ddS, 24, h);
  }
  return W;
}

/* V = det(x0, x1, x2)/6 is trilinear. */
void tds_mk_volume_sym_hess(const double *const *x, double (*h)[9]) {
  for (int c = 0; c < 3; c++)
    for (int i = 0; i < 3; i++)
      for (int d = 0; d < 3; d++)
        for (int j = 0; j < 3; j++) {
          double v = 0;
          if (c != d) {
            const double *t = x[3 - c - d];
            for (int m = 0; m < 3; m++) v += eps(i, j, m) * t[m];
            v *= sigma(c, d);
          }
          h[3 * c + i][3 * d + j] = v / 6;
        }
}

const tds_method tds_methods[TDS_M_NROWS] = {
    [TDS_M_FACET_AREA] = {"facet_area", TDS_EL_FACET, TDS_MF_USER, tds_mk_area},
    [TDS_M_EDGE_LENGTH] = {"edge_length", TDS_EL_EDGE, TDS_MF_USER, tds_mk_length},
    [TDS_M_FACET_VECTOR_INTEGRAL] = {"facet_vector_integral", TDS_EL_FACET,
                                     TDS_MF_USER | TDS_MF_VECTOR, tds_mk_facet_vint},
    [TDS_M_EDGE_VECTOR_INTEGRAL] = {"edge_vector_integral", TDS_EL_EDGE,
                                    TDS_MF_USER | TDS_MF_VECTOR, tds_mk_edge_vint},
    [TDS_M_FACET_SCALAR_INTEGRAL] = {"facet_scalar_integral", TDS_EL_FACET,
                                     TDS_MF_USER | TDS_MF_SCALAR, tds_mk_facet_sint},
    [TDS_M_EDGE_SCALAR_INTEGRAL] = {"edge_scalar_integral", TDS_EL_EDGE,
                                    TDS_MF_USER | TDS_MF_SCALAR, tds_mk_edge_sint},
    /* The two gravity methods share the moment kernel; they differ in the
    ** weight the assembly gives each facet (density, or G * density). */
    [TDS_M_GRAVITY] = {"gravity_method", TDS_EL_FACET, TDS_MF_USER | TDS_MF_DENSITY,
                       k_zmoment},
    [TDS_M_FULL_GRAVITY] = {"full_gravity_method", TDS_EL_FACET,
                            TDS_MF_USER | TDS_MF_DENSITY | TDS_MF_TIMES_G, k_zmoment},
    /* Knot energies, string curvature and Hooke springs (method_knot.c),
    ** formulas measured against evolver-nox-d (doc/string.md). */
    [TDS_M_KNOT] = {"knot_energy", TDS_EL_EDGE, TDS_MF_USER | TDS_MF_SINGULAR, tds_mk_knot,
                    TDS_IT_VPAIR, NULL},
    [TDS_M_EDGE_KNOT] = {"edge_knot_energy", TDS_EL_EPAIR,
                         TDS_MF_USER | TDS_MF_SINGULAR | TDS_MF_SYMPAIR, NULL, TDS_IT_EPAIR,
                         tds_mk_edge_knot},
    [TDS_M_BUCK_KNOT] = {"buck_knot_energy", TDS_EL_EPAIR,
                         TDS_MF_USER | TDS_MF_SINGULAR | TDS_MF_DISJOINT | TDS_MF_SYMPAIR,
                         NULL, TDS_IT_EPAIR, tds_mk_buck_knot},
    [TDS_M_PROJ_KNOT] = {"proj_knot_energy", TDS_EL_EPAIR, TDS_MF_USER | TDS_MF_SINGULAR,
                         NULL, TDS_IT_EPAIR, tds_mk_proj_knot},
    [TDS_M_CIRCLE_KNOT] = {"circle_knot_energy", TDS_EL_EPAIR,
                           TDS_MF_USER | TDS_MF_SINGULAR | TDS_MF_SYMPAIR, NULL,
                           TDS_IT_EPAIR, tds_mk_circle_knot},
    [TDS_M_SQCURVE_STRING] = {"sqcurve_string", TDS_EL_FACET, TDS_MF_USER | TDS_MF_HESS_FD,
                              tds_mk_sqcurve, TDS_IT_VSTAR, NULL},
    [TDS_M_HOOKE] = {"hooke_energy", TDS_EL_EDGE, TDS_MF_USER, tds_mk_hooke, TDS_IT_EDGE_K,
                     NULL},
    [TDS_M_HOOKE2] = {"hooke2_energy", TDS_EL_EDGE, TDS_MF_USER, tds_mk_hooke, TDS_IT_EDGE_K,
                      NULL},
    [TDS_M_FACET_VOLUME] = {"facet_volume", TDS_EL_FACET, TDS_MF_USER, tds_mk_volume},
    [TDS_M_FACET_VOLUME_SYM] = {"facet_volume_symmetric", TDS_EL_FACET, 0, tds_mk_volume_sym},
    [TDS_M_EDGE_GAP] = {"edge_gap", TDS_EL_EDGE, TDS_MF_FORMULA | TDS_MF_HESS_FD,
                        tds_mk_edge_gap},
    [TDS_M_EDGE_AREA] = {"edge_area", TDS_EL_EDGE, 0, tds_mk_edge_area},
    [TDS_M_STRING_GRAVITY] = {"string_gravity", TDS_EL_EDGE, 0, tds_mk_string_gravity},
    [TDS_M_VERTEX_HEAD] = {"vertex_scalar_head", TDS_EL_EDGE, TDS_MF_SCALAR, tds_mk_vertex_head},
    [TDS_M_VERTEX_TAIL] = {"vertex_scalar_tail", TDS_EL_EDGE, TDS_MF_SCALAR, tds_mk_vertex_tail},
    [TDS_M_METRIC_LENGTH] = {"metric_edge_length", TDS_EL_EDGE, TDS_MF_HESS_FD | TDS_MF_METRIC,
                             tds_mk_metric_length},
    [TDS_M_FACET_FLUX] = {"facet_flux", TDS_EL_FACET, 0, tds_mk_facet_flux},
    [TDS_M_EDGE_SHIFT] = {"edge_shift", TDS_EL_EDGE, 0, tds_mk_edge_shift},
    [TDS_M_KLEIN_LENGTH] = {"klein_length", TDS_EL_EDGE, TDS_MF_USER, tds_mk_klein_length},
    [TDS_M_KLEIN_AREA] = {"klein_area", TDS_EL_FACET, TDS_MF_USER | TDS_MF_HESS_FD,
                          tds_mk_klein_area},
};

int tds_method_by_name(const char *name) {
  for (int i = 0; i < TDS_M_NROWS; i++)
    if ((tds_methods[i].flags & TDS_MF_USER) && !strcasecmp(name, tds_methods[i].name))
      return i;
  if (!strcasecmp(name, "facet_tension")) return TDS_M_FACET_AREA;
  if (!strcasecmp(name, "edge_tension")) return TDS_M_EDGE_LENGTH;
  if (!strcasecmp(name, "edge_edge_knot_energy")) return TDS_M_EDGE_KNOT;
  return -1;
}
