/*
** newton.h: Newton steps and Hessian eigenvalues (Evolver's hessian,
** hessian_seek, saddle, eigenprobe, ritz, move).
**
** The system. The Hessian of the Lagrangian (hess.h) restricted to the
** vertices' motion spaces (tds_hess_reduce) and, with `normal` on
** (Evolver's hessian_normal, the default), further to each vertex's
** normal space: a free or constrained vertex moves along its normal
** (Evolver's: the sum of its facets' area vectors, each signed to agree
** with the sum so far in Evolver's order, newton_int.h; the volume
** gradient on a smooth sheet), projected into its motion space and scaled to
** unit length in space; a vertex on one triple
** junction line (edges with three or more facets) moves in the plane
** perpendicular to the line; a vertex where several such lines meet, or
** with no facets, keeps its whole motion space. In the string model a
** vertex moves along its chord's normal (2-D space) or in the plane
** across its chord (3-D), a junction freely, and in 2-D space nothing
** moves off the plane (newton_strnorm.c). The unknowns w (sys.m of
** them) are the amounts of these unit motions. Volumes and FIXED
** quantities are held by a border: K = [H A; A^T 0] with A the
** quantities' gradients in the same unknowns.
**
** The metric M of the eigenvalue problems H w = lambda M w (on A^T w = 0):
** the identity, or with linear_metric the L2 product of the piecewise
** linear interpolation of the unit motions over the facets, as Evolver's
** linear_metric: mix x (consistent mass, area/12 (1 + [i = j]) per facet
** pair) + (1 - mix) x (lumped, area/3 on the diagonal), mix 0.5 by
** default, each facet's area weighted by its tension (as Evolver does:
** column.fe's solder, tension 460, shows it).
**
** Counts. Eigencounts are the inertia of H - c M on A^T w = 0: the
** inertia of the bordered K - c [M 0; 0 0] less nq from the negative and
** from the positive side (nq independent constraint gradients).
**
** Multipliers: those stored on the surface (the pressures of the last g
** or Newton step, as Evolver), computed here only when none ever was; a
** step stores the new ones from its solution.
**
** Singular systems: a step through a consistent singular system (rigid
** motions with hessian_normal off) leaves the null directions out; an
** inconsistent one is refused.
**
** Every command is all-or-nothing (snap.h): a singular system, a
** non-finite energy or any failure leaves the surface exactly as before.
** Core code: no Lua, no globals.
*/
#ifndef TDS_NEWTON_H
#define TDS_NEWTON_H

#include "la.h"
#include "surf.h"

typedef struct tds_newton_opts {
  int normal;           /* hessian_normal */
  int linear_metric;    /* M as above instead of the identity */
  double metric_mix;    /* linear_metric_mix, 0 .. 1 */
  int diff;             /* hessian_diff: H by central differences */
  int special_normal;   /* hessian_special_normal: the normal is the
                           datafile's HESSIAN_SPECIAL_NORMAL_VECTOR */
  int normal_one;       /* hessian_normal_one: with normal, every vertex
                           with facets moves along one direction, the
                           leading eigenvector of the sum of its facets'
                           n n^T (also on triple junctions) */
  int normal_perp;      /* hessian_normal_perp: linear_metric takes only
                           each unit motion's component along the facet's
                           normal */
  double epsilon;       /* hessian_epsilon: a pivot below epsilon x the
                           largest entry counts as zero (la.h); <= 0: 1e-10 */
  int general;          /* assemble through the xyz Hessian (hess.h) and
                           triplets, as hessian_diff does, instead of
                           straight into the unknowns (a check: the
                           same matrix, slower) */
} tds_newton_opts;

/* One Newton step (Evolver's hessian): solve K [w; y] = [-grad; target -
** value], move every vertex by its w (projecting onto its constraints),
** bring the quantities back to their targets, print Evolver's line
** "  1. area: ... energy: ..." and, when H on the constraints is not
** positive definite, "WARNING 1825: Hessian not positive definite.
** Index: n" (Evolver's words and number).
** With seek > 0 (hessian_seek), the step is scaled by the t in (0, seek]
** that Evolver's line search finds along it (newton.c's seek: trials
** from 0.01 seek, doubling, then a parabola), or in [-seek, 0) when no
** forward t down to 1e-6 seek lowers the energy (Evolver looks both
** ways; t = 0, no move, when neither does), and the line shows the scale. *inertia (if not
** NULL) gets the inertia of H on the constraints at the start (neg is the
** index), *scale (if not NULL) the step's multiple of the Newton step (1
** for hessian). */
int tds_newton_step(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double seek,
                    tds_inertia *inertia, double *scale);

/* Inertia of H - c M on the constraints (eigenprobe c), and the number of
** unknowns. Prints nothing. */
int tds_newton_probe(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double c,
                     tds_inertia *in);

/* The n eigenvalues of H w = lambda M w (on A^T w = 0) nearest shift (a
** NaN shift: the lowest ones, the shift put below them), by
** subspace iteration with (H - shift M)^-1 (shift-invert) and
** Rayleigh-Ritz, to 1e-12 relative change; vals sorted by distance from
** the shift as Evolver lists them. in: the inertia at the shift. With
** vec (nv slots x 3, zeroed) not NULL, the eigenvector of vals[0] as
** a displacement per vertex (unit M-norm in the unknowns; 0 for fixed
** vertices). *got: how many were found (fewer than n when there are
** fewer unknowns). *iters: iterations done; *change (if not NULL): the
** total change of the n values in the last iteration. */
int tds_newton_ritz(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double shift,
                    int32_t n, double *vals, int32_t *got, tds_inertia *in, double (*vec)[3],
                    int *iters, double *change);

/* eigenprobe(c, maxit): the counts at c (as tds_newton_probe, printed as
** Evolver's "Eigencounts:" line), then
** inverse iteration with (H - c M)^-1 (on the constraints; c moved off an
** eigenvalue a little) from a seeded start, towards the eigenvalue
** nearest c: at most maxit iterations after the first estimate, stopping
** when the estimate x'Mx / x'M(H - cM)^-1 Mx + c changes by 1e-13
** relative; prints "k  ev = value" at k = 0, every 10th and the last (as
** Evolver). *val: the estimate; vec (nv slots x 3, zeroed; may be NULL):
** the eigenvector as a displacement per vertex (unit M-norm), signed to
** go downhill in energy when the gradient is not zero (Evolver's rule).
** With maxit 0 only the counts. */
int tds_newton_invit(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double c, int maxit,
                     double *val, tds_inertia *in, double (*vec)[3], int *iters);

/* Move every vertex by t times vec (a displacement per vertex slot, as
** tds_newton_ritz gives), projecting onto its constraints and then the
** quantities onto their targets (in the unknowns of o: the part of vec
** in each vertex's normal space). The new energy is in s->energy. */
int tds_newton_move(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, const double (*vec)[3],
                    int32_t nv, double t);

/* saddle: if the lowest eigenvalue is negative, move along its
** eigenvector (signed downhill to first order, of Evolver's length: its
** largest unknown 0.1 of the largest distance of a vertex from the
** origin) by hessian_seek's line search with the largest step maxscale
** (maxscale <= 0: Evolver's default, 100, whose first trial is 1);
** prints what Evolver prints.
** *lowest gets the lowest eigenvalue; *step the step taken (0: no move;
** negative: backwards). */
int tds_newton_saddle(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double maxscale,
                      double *lowest, double *step);

/* Evolver's vertex_normal of live vertex v: the unit direction
** hessian_normal moves it along (newton_int.h's rule, with o's
** normal_one and special_normal), on a triple junction line the first
** direction of its normal plane, where several lines meet (1, 0, 0);
** (0, 0, 0) for a vertex with no facets. TDS_OK, TDS_ENOMEM, TDS_ERANGE
** or TDS_ENUM (the special normal vector missing or not finite). */
int tds_vertex_normal_at(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_id v,
                         double n[3]);

#endif
