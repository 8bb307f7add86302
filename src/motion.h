/*
** motion.h: how each vertex may move.
**
** A vertex's motion space: nothing if fixed; the tangent space of its
** active level-set constraints; or, on a parametric boundary, the
** parameter space (the first nparams components of a motion vector).
** Gradients (covectors) are mapped into motion space by tds_motion_project;
** positions are set from a base point plus a motion by tds_motion_apply,
** which also projects the vertex back onto its level sets.
*/
#ifndef TDS_MOTION_H
#define TDS_MOTION_H

#include "surf.h"

/* Map the covector w at vertex v into its motion space, in place. */
void tds_motion_project(const tds_surf *s, tds_id v, double w[3]);

/* Place vertex v at base position x0 (boundary parameters p0) moved by the
** motion-space vector d (may be NULL for no motion), then enforce its
** constraints. Returns TDS_OK, or TDS_ENUM if projection fails to converge
** (the vertex is left at the best point found). */
int tds_motion_apply(tds_surf *s, tds_id v, const double x0[3],
                     const double p0[2], const double d[3]);

/* Project vertex v onto its level-set constraints and, on a boundary,
** recompute its position from its parameters. TDS_OK or TDS_ENUM. */
int tds_motion_enforce(tds_surf *s, tds_id v);

/* Parameters of the point of boundary bd nearest to target, found as
** Evolver does when refining a boundary edge: five Gauss-Newton steps
** starting from pstart (the parameters of the edge's head vertex). */
void tds_boundary_param_toward(const tds_surf *s, int32_t bd,
                               const double target[3], const double pstart[2],
                               double p[2]);

/* The variables a constraint or boundary formula sees at position x with
** boundary parameters p (NULL: 0): x y z p1 p2 and G (0 with gravity off). */
void tds_motion_vars(const tds_surf *s, const double x[3], const double p[2],
                     double vars[TDS_NVARS]);

/* Nonzero if vertex v can move at all. */
static inline int tds_vertex_free(const tds_surf *s, tds_id v) {
  return !(s->m.vflags[v] & (TDS_FIXED | TDS_DEAD));
}

/* Nonzero if vertex v moves freely in space: not fixed or dead, on no
** boundary and no constraint. Its motion space is all of R^3 (the
** projection leaves w as it is) and tds_motion_apply puts it at x0 + d:
** the hot loops of g do that inline. */
static inline int tds_vertex_plain(const tds_surf *s, tds_id v) {
  const tds_mesh *m = &s->m;
  return !(m->vflags[v] & (TDS_FIXED | TDS_DEAD)) && m->vbdry[v] == TDS_NONE && !m->vcon[v];
}

#endif
