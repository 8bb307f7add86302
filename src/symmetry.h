/*
** symmetry.h: a mesh in the quotient of space by a symmetry group
** (SYMMETRY_GROUP; the groups themselves are in symgroup.h).
**
** The mesh is in the torus model's machinery (m->torus is 1, so commands
** that do not maintain wraps refuse) with m->sym naming the group. Wraps
** compose with tds_wrap_mul / tds_wrap_inv (gather.h), in order: for
** groups that rotate (tds_mesh_rotates) the product does not commute, and
** code that handles wraps as translations (lattice sums, period vectors)
** must refuse those groups with tds_sym_unsupported.
**
** The gather point (gather.h) applies each corner's group element; for
** groups that rotate, a kernel's gradient with respect to the moved
** corner g(x) = R x + t is pulled back to the stored vertex by R^T (and
** Hessian blocks by R_c^T H R_d): tds_sym_pullback, called by the
** assembly. Bodies get Evolver's Euclidean volumes: each facet's integral
** where its corners are gathered, no lifts (Evolver 2.70 does the same:
** its manual asks for named quantities where that is not the volume
** wanted). SYMMETRIC_CONTENT: the facets gathered the same way, except
** under the torus group, where Evolver takes the stored positions
** (eval.c).
*/
#ifndef TDS_SYMMETRY_H
#define TDS_SYMMETRY_H

#include "surf.h"

/* Pull a kernel's gradient g (and Hessian h when not NULL) of element el
** (kind TDS_EL_FACET or TDS_EL_EDGE) back from its gathered corners to
** its stored vertices. */
void tds_sym_pullback(const tds_mesh *m, int kind, tds_id el, double g[3][3], double h[9][9]);

/* Read the group's parameters (rotation_order ...) from the surface's
** global parameters into m->symp (Evolver's defaults where not defined);
** TDS_OK, or TDS_ERANGE with a message naming the parameter when they are
** unusable (m->symp unchanged). */
int tds_sym_read_params(tds_ctx *ctx, tds_surf *s);

/* TDS_ESYNTAX with "WHAT is not supported yet with SYMMETRY_GROUP "name""
** in ctx when the mesh's group rotates (tds_mesh_rotates), else TDS_OK:
** commands that treat wraps as translations call it first. */
int tds_sym_unsupported(tds_ctx *ctx, const tds_mesh *m, const char *what);


#endif
