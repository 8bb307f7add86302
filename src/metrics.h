/*
** metrics.h: the paper's measures of a result (doc/metrics.md).
**
** Mesh quality: the smallest angle of every measured facet (live, not
** fixed, nonzero tension), in degrees: minimum, mean, standard deviation,
** percentages above 30/40/50/55 degrees and a 5-degree histogram.
**
** Mean curvature: Meyer, Desbrun, Schroeder, Barr (2003): at every measured
** vertex (movable, every incident edge between exactly two facets),
** K = (1 / 2 A_mixed) sum_j (cot a_ij + cot b_ij)(x_i - x_j); the curvature
** sum k1 + k2 is estimated as |K| with the sign of K . n_i (Meyer's, the
** paper's) or as K . n_i, n_i the vertex normal of the method (sum of facet
** area vectors). Its error against a target: a number, the
** bodies' multipliers ("lambda": -lambda of the paper, the pressure for
** unit tension), or the local pressure jump including gravity
** ("pressure": p - G rho z per body on each side).
*/
#ifndef TDS_METRICS_H
#define TDS_METRICS_H

#include "surf.h"

typedef struct tds_quality_out {
  int32_t n;                 /* facets measured */
  double min, mean, std;     /* smallest angle, degrees */
  double above[4];           /* % of facets above 30, 40, 50, 55 degrees */
  int32_t hist[12];          /* counts per 5-degree bin, [0,5) .. [55,60] */
  tds_id worst;              /* facet with the smallest angle, or TDS_NONE */
} tds_quality_out;

/* Smallest interior angle of facet f, in degrees (0 if degenerate). */
double tds_facet_min_angle(const tds_mesh *m, tds_id f);

/* Nonzero when facet f counts in the quality statistics (inline: the
** stall scan asks for every facet after each step of g). */
static inline int tds_facet_measured(const tds_mesh *m, tds_id f) {
  return !(m->fflags[f] & (TDS_DEAD | TDS_FIXED)) && m->ften[f] != 0;
}

/* Quality statistics over the measured facets. */
void tds_quality(const tds_surf *s, tds_quality_out *q);

enum { TDS_CURV_VALUE = 0, TDS_CURV_LAMBDA, TDS_CURV_PRESSURE };

typedef struct tds_curv_stats {
  double max, mean, rms;     /* of |h - target| */
  double hmean;              /* mean of h */
  tds_id worst;              /* vertex of the largest error, or TDS_NONE */
} tds_curv_stats;

typedef struct tds_curv_out {
  int32_t n;                 /* vertices measured */
  tds_curv_stats meyer;      /* h = Meyer's |K| with the sign of K . n */
  tds_curv_stats normal;     /* h = K . n */
} tds_curv_out;

/* Curvature sum k1 + k2 at vertex v (Meyer et al.), or NAN when v is not
** measured (fixed, on an edge of other than two facets, degenerate). Needs
** current adjacency. */
double tds_vertex_mean_curvature(const tds_surf *s, tds_id v);

/* Whether vertex v is measured: it can move and every edge at it lies
** between exactly two facets (a closed manifold star). */
int tds_vertex_measured(const tds_surf *s, tds_id v);

/* Sums over the star of measured vertex v: the cotangent vector K, the
** facet area-vector sum S (twice the areas), Meyer's mixed area and the
** facet angles at v; K and angle may be NULL. Returns 0 when a star facet
** is degenerate or the mixed area is not positive. */
int tds_vertex_star_sums(const tds_surf *s, tds_id v, double K[3], double S[3],
                         double *amix, double *angle);

/* Meyer's full estimate at vertex v: |K| (the length of the mean-curvature
** normal K = grad A / A_mixed, tangential part included) with the sign of
** K . n; NAN where tds_vertex_mean_curvature is NAN. Equal to it when K is
** along the normal. Needs current adjacency. */
double tds_vertex_meyer_curvature(const tds_surf *s, tds_id v);

/* Gaussian curvature k1 k2 at vertex v: the angle defect 2 pi - (sum of
** the facet angles at v) over Meyer's mixed area; NAN where the mean
** curvature is NAN. Needs current adjacency. */
double tds_vertex_gauss_curvature(const tds_surf *s, tds_id v);

/* Curvature and its error at every measured vertex, by both measures
** (Meyer's signed |K| and K . n). mode TDS_CURV_*; value is the target for
** TDS_CURV_VALUE. h, hn and target (m.nv entries each, may be NULL)
** receive the signed |K|, K . n and the target (NAN where not measured).
** Computes the multipliers (tds_pg_multipliers) for the other modes.
** TDS_OK, TDS_ENOMEM, TDS_ENUM. */
int tds_curvature(tds_ctx *ctx, tds_surf *s, int mode, double value,
                  double *h, double *hn, double *target, tds_curv_out *out);

#endif
