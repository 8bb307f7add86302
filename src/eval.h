/*
** eval.h: total energy, its gradient, and the constrained quantities.
**
** One pass gathers each facet's corners, runs the facet kernels (area with
** tension, body volume, gravity moment) and scatter-adds the results; edge
** and quantity terms follow. Energy terms:
**   sum_f tension_f area_f                       (surface tension)
**   G sum_b density_b int_b z dV                 (gravity, when on)
**   - sum_b pressure_b V_b                       (bodies with a prescribed pressure)
**   sum_e tension_e length_e                     (edges with a tension)
** plus constraint/boundary edge integrals and named energy quantities.
*/
#ifndef TDS_EVAL_H
#define TDS_EVAL_H

#include "fixq.h"

typedef struct tds_eval_out {
  double energy;        /* total energy */
  double area;          /* total facet area (all facets, any tension) */
  double (*grad)[3];    /* if not NULL: dE/dx per vertex slot (overwritten) */
  tds_fixq *fq;         /* if not NULL: values and gradients of the
                           constrained quantities (pattern must be built) */
} tds_eval_out;

/* Evaluate at the current positions. Also stores body volumes in m.bvol
** and named quantity values. TDS_OK, or TDS_ENUM when a value is not
** finite (the message names the first bad element). */
int tds_eval(tds_ctx *ctx, tds_surf *s, tds_eval_out *out);

#endif
