/*
** method.h: the method table. Every energy and constraint term of tds is a
** row of it (Evolver's method table): a name, the element kind it lives on,
** flags, and one kernel that gives the term's value on ONE element and, on
** request, its gradient and Hessian with respect to the element's corners.
**
** Kernels see only gathered local data (tds_mlocal): the corner positions
** in the element's orientation, the integrands, the parameter values. They
** know nothing about the mesh, bodies or tensions: which elements a row
** applies to, with which weight, and where the results go (the energy,
** a body's volume, a named quantity) is the assembly's business (eval.c:
** one loop gathers, calls the row, scatters). So a new term is a kernel
** plus a row here, and a unit test (tests/unit/test_methods.c) checks
** every row's gradient and Hessian by finite differences.
*/
#ifndef TDS_METHOD_H
#define TDS_METHOD_H

#include "expr.h"
#include "geom.h"

/* Element kinds; the value is the number of corners a kernel sees. */
enum { TDS_EL_EDGE = 2, TDS_EL_FACET = 3, TDS_EL_EPAIR = 4 };

/* How the assembly walks a row's elements (tds_method.iter). Rows other
** than TDS_IT_ELEMENT are assembled by eval_knot.c:
**   TDS_IT_ELEMENT  every live element of the row's kind
**   TDS_IT_VPAIR    every pair of live vertices (2 corners, counted in
**                   both orders, as Evolver's knot energies)
**   TDS_IT_VSTAR    every vertex with exactly two edges: corners the far
**                   end of the first edge, the vertex, the far end of the
**                   second (3 corners)
**   TDS_IT_EPAIR    every ordered pair of distinct live edges (4
**                   corners: tail, head of the first, tail, head of the
**                   second); a 4-corner kernel, gradient only
**   TDS_IT_EDGE_K   every live edge, with L.k and L.pw read per edge
**                   from parameters or an edge attribute (the Hooke rows) */
enum { TDS_IT_ELEMENT = 0, TDS_IT_VPAIR, TDS_IT_VSTAR, TDS_IT_EPAIR, TDS_IT_EDGE_K };

enum {                     /* row flags */
  TDS_MF_VECTOR = 1,       /* reads a vector integrand ig[0..2] (NULL = 0) */
  TDS_MF_SCALAR = 2,       /* reads a scalar integrand ig[0] (required) */
  TDS_MF_FORMULA = 4,      /* reads a level-set formula ig[0] and constant k */
  TDS_MF_USER = 8,         /* a named quantity may use it (METHOD name) */
  TDS_MF_HESS_FD = 16,     /* Hessian by central differences of the exact
                              gradient (the exact one needs third
                              derivatives of the formula) */
  TDS_MF_DENSITY = 32,     /* as a quantity method, weighted per facet by
                              the density of its front body minus its
                              back body's */
  TDS_MF_TIMES_G = 64,     /* ... and by G when gravity is on (0 if off) */
  TDS_MF_SINGULAR = 128,   /* infinite where two corners meet (knot energies) */
  TDS_MF_DISJOINT = 256,   /* TDS_IT_EPAIR: only pairs of edges without a
                              common vertex */
  TDS_MF_SYMPAIR = 512,    /* TDS_IT_EPAIR: the kernel is symmetric in its
                              two edges (each unordered pair once, doubled) */
  TDS_MF_METRIC = 1024     /* reads a metric tensor ig[0..8] (ig NULL: the
                              identity) */
};

/* Rows. The first TDS_M_COUNT are the named quantity methods, in the
** order dumps and datafiles have always used; the rest are built-in terms
** that only the assembly uses. */
enum {
  TDS_M_FACET_AREA = 0, TDS_M_EDGE_LENGTH, TDS_M_FACET_VECTOR_INTEGRAL,
  TDS_M_EDGE_VECTOR_INTEGRAL, TDS_M_FACET_SCALAR_INTEGRAL,
  TDS_M_EDGE_SCALAR_INTEGRAL, TDS_M_GRAVITY, TDS_M_FULL_GRAVITY,
  TDS_M_KNOT, TDS_M_EDGE_KNOT, TDS_M_BUCK_KNOT, TDS_M_PROJ_KNOT,
  TDS_M_CIRCLE_KNOT, TDS_M_SQCURVE_STRING, TDS_M_HOOKE, TDS_M_HOOKE2,
  TDS_M_FACET_VOLUME,               /* int z dx dy: body content, and
                                       Evolver's facet_volume method */
  TDS_M_KLEIN_LENGTH,               /* KLEIN_METRIC: hyperbolic length in the
                                       Klein model (method_klein.c); also
                                       Evolver's klein_length method */
  TDS_M_KLEIN_AREA,                 /* KLEIN_METRIC on films: hyperbolic
                                       area of the flat (geodesic) triangle;
                                       also Evolver's klein_area method */
  TDS_M_COUNT,
  TDS_M_FACET_VOLUME_SYM = TDS_M_COUNT, /* symmetric content (x,y,z)/3 . dS */
  TDS_M_EDGE_GAP,                   /* gap energy on a convex constraint */
  TDS_M_EDGE_AREA,                  /* string model: -int y dx (body area) */
  TDS_M_STRING_GRAVITY,             /* string model: -int y^2/2 dx */
  TDS_M_VERTEX_HEAD,                /* string model: scalar ig[0] at the head */
  TDS_M_VERTEX_TAIL,                /* ... and at the tail */
  TDS_M_METRIC_LENGTH,              /* string model: edge length in a
                                       Riemannian metric ig[0..8] */
  TDS_M_FACET_FLUX,                 /* torus: (N . e_k) / 2, k the row
                                       constant (method_torus.c) */
  TDS_M_EDGE_SHIFT,                 /* string torus: x1[k] - x0[k], k the row
                                       constant (method_string.c) */
  TDS_M_NROWS
};

/* Gathered local data of one element. */
typedef struct tds_mlocal {
  const double *x[3];      /* corners in the element's orientation (edge:
                              tail, head): pointers into the mesh, or into
                              the gatherer's scratch */
  tds_expr *const *ig;     /* integrand(s), as the row's flags say */
  int npts;                /* quadrature points (tds_edge_rule/facet_rule) */
  double k;                /* row constant: TDS_M_EDGE_GAP's gap constant,
                              the Hooke rows' equilibrium length */
  double pw;               /* row power: knot_power, hooke_power ... */
  const double *param;     /* parameter values the expressions read */
  double G;                /* the expressions' G (gravity constant) */
} tds_mlocal;

/* Value of the term on one element. With g not NULL also the gradient,
** g[c][i] = dE/dx[c][i]; with h not NULL (then g is not NULL either) the
** Hessian, h[3c+i][3d+j] = d2E/dx[c][i]dx[d][j] (full and symmetric; only
** the first 3*kind rows and columns are written). Pure: no allocation, no
** state, safe from several threads. */
typedef double (*tds_mkernel)(const tds_mlocal *L, double g[3][3], double h[9][9]);

/* A 4-corner kernel (TDS_EL_EPAIR): corners y[0..3], power pw; with g not
** NULL also the gradient g[c][i]. No Hessian. Pure. */
typedef double (*tds_mkernel4)(const double *const y[4], double pw, double g[4][3]);

typedef struct tds_method {
  const char *name;        /* Evolver's name where it has one */
  int kind;                /* TDS_EL_* */
  int flags;               /* TDS_MF_* */
  tds_mkernel eval;        /* NULL for TDS_EL_EPAIR rows */
  int iter;                /* TDS_IT_* */
  tds_mkernel4 eval4;      /* TDS_EL_EPAIR rows only */
} tds_method;

extern const tds_method tds_methods[TDS_M_NROWS];

/* Row of a named quantity method ("facet_vector_integral", also Evolver's
** aliases facet_tension and edge_tension), case-insensitive, or -1. */
int tds_method_by_name(const char *name);

/* Kernels the assembly calls directly (declared for the table). */
double tds_mk_facet_vint(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_facet_sint(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_edge_vint(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_edge_sint(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_edge_gap(const tds_mlocal *L, double g[3][3], double h[9][9]);
/* String-model rows (method_string.c). */
double tds_mk_string_gravity(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_vertex_head(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_vertex_tail(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_metric_length(const tds_mlocal *L, double g[3][3], double h[9][9]);
/* KLEIN_METRIC (method_klein.c): the hyperbolic distance of a and b in the
** Klein model (+infinity unless both are inside the unit ball), and the
** edge row's kernel (exact gradient and Hessian). */
double tds_klein_dist(const double a[3], const double b[3]);
double tds_mk_klein_length(const tds_mlocal *L, double g[3][3], double h[9][9]);
/* The hyperbolic area of the flat triangle a, b, c of the Klein ball
** (+infinity unless all are inside), and the facet row's kernel (exact
** gradient, Hessian by differences of it: TDS_MF_HESS_FD). */
double tds_klein_area(const double a[3], const double b[3], const double c[3]);
double tds_mk_klein_area(const tds_mlocal *L, double g[3][3], double h[9][9]);
/* The torus model's row (method_torus.c). */
double tds_mk_facet_flux(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_edge_shift(const tds_mlocal *L, double g[3][3], double h[9][9]);

/* Knot, curvature and Hooke rows (method_knot.c). */
double tds_mk_knot(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_sqcurve(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_hooke(const tds_mlocal *L, double g[3][3], double h[9][9]);
double tds_mk_edge_knot(const double *const y[4], double pw, double g[4][3]);
double tds_mk_buck_knot(const double *const y[4], double pw, double g[4][3]);
double tds_mk_proj_knot(const double *const y[4], double pw, double g[4][3]);
double tds_mk_circle_knot(const double *const y[4], double pw, double g[4][3]);

/* Derivatives of a facet's normal N = (x1-x0) x (x2-x0):
** u[c][i] = dN/dx[c][i] = E_i x (x[c+1] - x[c+2]) (indices mod 3). */
void tds_mk_normal_derivs(const double *const *x, double u[3][3][3]);

/* Hessians of the facet area, z-volume and symmetric volume at corners x
** (h as for kernels). */
void tds_mk_area_hess(const double *const *x, double (*h)[9]);
void tds_mk_volume_hess(const double *const *x, double (*h)[9]);
void tds_mk_volume_sym_hess(const double *const *x, double (*h)[9]);

/* The kernels of facet_area, facet_volume and facet_volume_symmetric,
** inline so that the assembly's fused facet pass (eval.c) compiles them
** into its loop; the table points at these same functions. */
static inline __attribute__((always_inline)) double
tds_mk_area(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double A = geom_area(L->x[0], L->x[1], L->x[2], g);
  if (h) tds_mk_area_hess(L->x, h);
  return A;
}
static inline __attribute__((always_inline)) double
tds_mk_volume(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double V = geom_volume_z(L->x[0], L->x[1], L->x[2], g);
  if (h) tds_mk_volume_hess(L->x, h);
  return V;
}
/* facet_volume of the facet translated by L->k along z (the torus's
** lifted volumes, eval.c); no row of its own. */
static inline __attribute__((always_inline)) double
tds_mk_volume_zshift(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double V = geom_volume_zshift(L->x[0], L->x[1], L->x[2], L->k, g);
  if (h) {
    double y[3][3];
    const double *yp[3] = {y[0], y[1], y[2]};
    for (int c = 0; c < 3; c++) {
      y[c][0] = L->x[c][0];
      y[c][1] = L->x[c][1];
      y[c][2] = L->x[c][2] + L->k;
    }
    tds_mk_volume_hess(yp, h);
  }
  return V;
}
/* The kernels of edge_length and the string model's edge_area, inline
** for the string model's fused edge pass (eval.c); their Hessians out of
** line (t the unit tangent). */
void tds_mk_length_hess(const double t[3], double len, double (*h)[9]);
void tds_mk_edge_area_hess(double (*h)[9]);
static inline __attribute__((always_inline)) double
tds_mk_length(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double d[3];
  v3_sub(d, L->x[1], L->x[0]);
  double len = v3_norm(d);
  if (g) {
    double t[3] = {0, 0, 0};
    if (len > 0) t[0] = d[0] / len, t[1] = d[1] / len, t[2] = d[2] / len;
    for (int i = 0; i < 3; i++) g[1][i] = t[i], g[0][i] = -t[i];
    if (h) tds_mk_length_hess(t, len, h);
  }
  return len;
}
/* edge_area: -(y0 + y1)(x1 - x0)/2, the edge's part of its cells' areas */
static inline __attribute__((always_inline)) double
tds_mk_edge_area(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  const double *a = L->x[0], *b = L->x[1];
  double sy = a[1] + b[1], dx = b[0] - a[0];
  if (g) {
    g[0][2] = g[1][2] = g[2][0] = g[2][1] = g[2][2] = 0;
    g[0][0] = sy / 2;
    g[1][0] = -sy / 2;
    g[0][1] = g[1][1] = -dx / 2;
  }
  if (h) tds_mk_edge_area_hess(h);
  return -sy * dx / 2;
}
static inline __attribute__((always_inline)) double
tds_mk_volume_sym(const tds_mlocal *L, double g[3][3], double h[9][9]) {
  double V = geom_volume_sym(L->x[0], L->x[1], L->x[2], g);
  if (h) tds_mk_volume_sym_hess(L->x, h);
  return V;
}

#endif
