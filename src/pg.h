/*
** pg.h: the projected-gradient method of Ma, Zhou, Pan, Zhang (2016), with
** CVT (Lloyd) mesh quality, Delaunay flips, and Anderson acceleration.
**
** Each iteration moves every movable vertex by v_i = t_i d_i + r_i + s u_i:
**   d_i  the vertex normal n_i = sum_F N_F / |sum_F N_F| (the direction of
**        the volume gradient, independent of x_i on a closed star), mapped
**        into the vertex's motion space for constrained vertices;
**   t_i  the closed-form root of A_i'(t) = c_i for the star's (tension
**        weighted) area along d_i, where c_i carries every other energy term
**        from tds_eval (gravity, constraint integrals, quantities) and the
**        bodies' Lagrange multipliers (least squares over the normal
**        components);
**   r_i  the volume-restoring motion (Newton step onto the targets);
**   u_i  the tangential part of (G_i - x_i), G_i the centroid of the
**        restricted Voronoi cell of the vertex in its star; s = 2.
** All moves are computed from the same positions and applied together;
** non-Delaunay edges are flipped (Algorithm 1) at the start of each
** iteration, before the moves are computed. r = max_i |v_i|.
** The method is described in doc/method.md; the files in pg_int.h.
*/
#ifndef TDS_PG_H
#define TDS_PG_H

#include "surf.h"

typedef struct tds_pg_opts {
  int64_t iterations;     /* > 0: run exactly this many; 0: until converged */
  int64_t max_iterations; /* cap when running until converged (100000) */
  int nmax;               /* N_max of the termination criterion (200) */
  double s;               /* tangential over-relaxation (2) */
  int accel;              /* 1: Anderson acceleration (default); 0: plain */
  int depth;              /* Anderson history depth (20) */
  int flips;              /* 1: Delaunay edge flips every iteration (default) */
  int64_t every;          /* progress line period; 0: automatic; < 0: none */
  double rtol;            /* > 0: also stop once r < rtol * mean edge length */
  int threads;            /* threads of the facet pass: 1 (default) or 2;
                             the results do not depend on it */
  int newton;             /* 1: Newton-type preconditioning of the
                             accelerated run (default); 0: none */
  int probe;              /* 1: an accelerated run until converged checks
                             that its fixed point is stable under the plain
                             iteration before it stops (default); 0: no */
  int calm;               /* 1: an accelerated run meeting a flip 2-cycle
                             (a quadrilateral flipped back and forth
                             twice) takes plain steps until the flips
                             stop (default); 0: no */
  double momentum;        /* the accelerated run's plain (warm) steps after
                             a flip add this times the last move (a heavy-
                             ball step; 0.6 by default, 0: none;
                             doc/method.md, Acceleration) */
  int32_t momentum_size;  /* > 0: on more movable vertices n than this the
                             warm steps take 1 - (1 - momentum) sqrt(size / n),
                             at most 0.95, when that is larger (0 by
                             default: momentum as given; doc/method.md) */
} tds_pg_opts;

typedef struct tds_pg_result {
  int64_t iterations;     /* iterations done in this run */
  int64_t best_iteration; /* iteration whose mesh is kept (1-based) */
  int64_t flips;          /* edges flipped in this run */
  int64_t clamps;         /* normal steps skipped (c^2 >= b) or limited */
  int64_t restarts;       /* Anderson history resets (flips, safeguards) */
  int64_t reached;        /* first iteration with r < 1e-13 x mean edge */
  double r;               /* r of the kept mesh: max |v_i| */
  double r_last;          /* r of the last iteration */
  double lambda;          /* paper's lambda of the first body (= -pressure) */
  double energy;          /* total energy of the kept mesh */
  double mean_edge;       /* mean edge length (for r relative to it) */
  double seconds;         /* wall time of the run */
  double cpu_seconds;     /* processor time of the process during the run
                             (all threads) */
  int64_t threaded;       /* passes run on two threads */
  int32_t nfree;          /* movable vertices */
  int converged;          /* stopped by the termination criterion */
  int status;             /* how the run ended: TDS_PG_* below */
  int64_t window_flips;   /* TDS_PG_CYCLING: flips in the last windows */
  int64_t newton_builds;  /* Jacobians measured (Newton preconditioning) */
  int64_t calms;          /* flip 2-cycles met with plain steps */
  int64_t cycles;         /* flips that undid a flip back (2-cycles) */
  int64_t returns;        /* flips that re-created an edge removed by a
                             flip of the same watch window (doc/method.md,
                             Termination) */
  int64_t probes;         /* stability probes of a converged mesh */
  int64_t saddles;        /* probes that found it unstable (run went on) */
  int64_t momentum_steps; /* warm steps that took momentum */
  double momentum;        /* the warm steps' momentum used (momentum_size) */
  double hysteresis;      /* flip hysteresis at the end: 1e-3, widened
                             up to 0.1 while flips cycle (doc/method.md) */
  char message[640];      /* STALLED, CYCLING, MAX: what happened and what
                             to try (also printed by tds_warnf); else "" */
} tds_pg_result;

/* How a run ended. CONVERGED: the paper's criterion with r at most 1e-6 x
** the mean edge. STALLED: the same criterion (no new best r for 5 N_max
** iterations, no flips) with r above that: not converged. CYCLING: a
** window of 5 N_max iterations is stuck when it flipped edges, at least
** half of them re-created an edge removed in the window (returns), and r
** never went below half its best before the window; each stuck window widens the
** flip hysteresis tenfold up to 0.1, and three stuck windows running at
** 0.1 stop the run (the triangulation keeps changing without progress;
** not converged). MAX:
** the iteration cap. COUNT: a fixed number of iterations was asked. */
enum { TDS_PG_COUNT = 0, TDS_PG_CONVERGED, TDS_PG_STALLED, TDS_PG_CYCLING,
       TDS_PG_MAX };

/* Defaults: until converged, N_max 200, s = 2, accelerated (depth 20),
** flips on, Newton preconditioning, the stability probe and the calm
** after flip 2-cycles on, momentum 0.6 in the warm steps after a flip. */
void tds_pg_defaults(tds_pg_opts *o);

/* Run the method. Allocates its work arrays once; the loop allocates
** nothing. On return the surface holds the kept mesh (the one with the
** best r since the last flip when running until converged, else the last
** one), body pressures (Evolver's sign: -lambda) and s->energy. Polls
** ctx->interrupt: TDS_EINTR leaves the last completed iteration. TDS_OK,
** TDS_ENOMEM, TDS_ENUM (non-finite values), TDS_EINTR. Any failure but
** an interruption leaves the surface exactly as before the call (snap.h). */
int tds_pg_run(tds_ctx *ctx, tds_surf *s, const tds_pg_opts *o,
               tds_pg_result *res);

/* The curvature polish (pg_polish.c, doc/method.md): `steps` steps of
** steepest descent of Phi = sum (|grad V_i| / A_mixed,i - 1)^2 over the
** measured vertices, moving the vertices free of constraints and
** boundaries along their tangent planes; no step takes a facet's smallest
** angle below floor_deg (degrees). Stops early when a step cannot lower
** Phi, or only by taking the mean of the measured facets' smallest
** angles (quality()) below mean_floor_deg. *phi0, *phi1: Phi before and
** after; *nmoved: vertices it may move.
** The normal equilibrium is left to the caller (pg{ s = 0 }). TDS_OK,
** TDS_ENOMEM, TDS_ERANGE (string model), torus: unsupported. */
int tds_pg_polish(tds_ctx *ctx, tds_surf *s, int steps, double floor_deg,
                  double mean_floor_deg, double *phi0, double *phi1, int32_t *nmoved);

/* Kernels, exposed for the unit tests and the metrics. --------------- */

/* Sum of the area vectors N_F = (b - a) x (c - a) of the live facets
** around v with nonzero tension, normalised into n; returns its length
** (0 leaves n zero). Needs current adjacency. */
double tds_pg_vertex_normal(const tds_mesh *m, tds_id v, double n[3]);

/* Tension-weighted area of v's star with v moved to x_v + t d: A(t). */
double tds_pg_star_area(const tds_mesh *m, tds_id v, const double d[3],
                        double t);
/* A(0), A'(0), A''(0) of the same function. Needs current adjacency. */
void tds_pg_star_model(const tds_mesh *m, tds_id v, const double d[3],
                       double *A0, double *A1, double *A2);

/* The closed-form root of A'(t) = c for the model sqrt(a + b (s0 + t)^2)
** fitted to A0, A1, A2 (method.md, section 3). When c^2 >= b (no root)
** returns 0 and sets *clamped to 1 (else 0). */
double tds_pg_normal_root(double A0, double A1, double A2, double c,
                          int *clamped);

/* Restricted Voronoi cells of the corners of triangle p[0..2]: cell k is
** the part of the triangle closer to p[k] than to the other corners (exact
** for obtuse triangles). area[k] and centroid cen[k] (absolute). */
void tds_pg_voronoi(const double p[3][3], double area[3], double cen[3][3]);

/* Delaunay flips over the whole surface (Algorithm 1): flip every
** flippable edge (tds_flip_ok, the new edge not already present) whose
** opposite angles sum to more than pi, checking the quadrilateral's edges
** again after each flip. *nflips gets the count. TDS_OK or TDS_ENOMEM. */
int tds_pg_flip_all(tds_ctx *ctx, tds_surf *s, int32_t *nflips);

/* The bodies' multipliers as the method computes them: least squares of
** the energy gradient against the volume gradients over the normal
** components of the movable vertices. mult[b] (m.nb entries; 0 for bodies
** without a target) in Evolver's sign (pressure = -lambda of the paper).
** TDS_OK, TDS_ENOMEM, TDS_ENUM. */
int tds_pg_multipliers(tds_ctx *ctx, tds_surf *s, double *mult);

/* One evaluation of the method at the current positions, moving nothing
** (for the tests): the total energy and, for every movable vertex, the
** energy gradient grad[v], the direction of its normal move dir[v] and
** the star model model[v] = A0, A1, A2 along it (dir and model are zero
** rows for fixed vertices; grad is then incomplete), all from the fused pass (pg_pass.c). TDS_OK,
** TDS_ENOMEM, TDS_ENUM. */
int tds_pg_probe(tds_ctx *ctx, tds_surf *s, double *energy, double (*grad)[3],
                 double (*dir)[3], double (*model)[3]);

#endif
