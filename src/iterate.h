/*
** iterate.h: Evolver's gradient descent step (the `g` command).
**
** One step: evaluate the energy gradient and the constrained quantities;
** map the force into each vertex's motion space; remove the components
** along the constraint gradients (the multipliers are the body pressures);
** then move by scale * velocity, with the scale either fixed or chosen by a
** line search (bracket by halving/doubling, then quadratic interpolation;
** upper bound scale_limit). Every trial position is brought back to the
** volume and quantity targets by Newton steps along the constraint
** gradients (the restoring motion), so energies are compared at the right
** volumes.
*/
#ifndef TDS_ITERATE_H
#define TDS_ITERATE_H

#include "fixq.h"

/* Run n steps, printing one Evolver-style line per step unless quiet.
** Polls ctx->interrupt between steps: on interrupt returns TDS_EINTR with
** the surface at the last completed step. On any other failure (TDS_ENUM
** for a non-finite energy, a refused scale limit) the surface is exactly
** as before the call, all n steps undone (snap.h). */
int tds_iterate(tds_ctx *ctx, tds_surf *s, int n);

/* Body pressures (Lagrange multipliers) at the current positions, stored
** in m.bpressure for bodies with targets, without moving anything. */
int tds_pressures(tds_ctx *ctx, tds_surf *s);

#endif
