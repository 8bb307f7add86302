/*
** recalc.h: make positions agree with the parameters again (Evolver's
** `recalc`).
**
** Assigning a parameter changes the formulas at once but moves nothing, as
** in Evolver. tds_recalc re-places every boundary vertex from its boundary
** parameters and projects every constrained vertex onto its level sets,
** then recomputes energy, area and volumes. g, r and pg call
** tds_recalc_if_stale first, so a parameter change takes effect on the
** whole surface before they act (Evolver does the same).
*/
#ifndef TDS_RECALC_H
#define TDS_RECALC_H

#include "surf.h"

/* All or nothing: if some vertex cannot be placed (its boundary formula is
** not finite there, or projection does not converge), every vertex is put
** back as it was and TDS_ENUM is returned with a message naming it.
** TDS_ENOMEM leaves the surface unchanged too. */
int tds_recalc(tds_ctx *ctx, tds_surf *s);

/* tds_recalc if a parameter has been set since the last recalc (or since
** load), else TDS_OK at once. */
int tds_recalc_if_stale(tds_ctx *ctx, tds_surf *s);

#endif
