/*
** stall.h: noticing when `g` stalls (doc/commands.md, "When g stalls").
**
** Two symptoms: a facet degenerates (its smallest angle or its area falls
** below a tolerance), or the optimizing scale collapses while the force is
** not small (the line search finds no lower energy along a real descent
** direction, typically because a facet has folded to a line). tds_iterate
** checks after every step and warns once per command, naming the worst
** facet and the remedies (u, V, t, autopop).
*/
#ifndef TDS_STALL_H
#define TDS_STALL_H

#include "surf.h"

/* A facet counts as degenerate below this smallest angle (degrees) ... */
#define TDS_STALL_ANGLE 1e-3
/* ... or below this fraction of the mean area of the measured facets. */
#define TDS_STALL_AREA 1e-9

typedef struct tds_stall_out {
  tds_id worst;     /* measured facet with the smallest angle, or TDS_NONE */
  double angle;     /* its smallest angle, degrees */
  double area;      /* its area */
  double mean_area; /* mean area of the measured facets */
  tds_id tiny;      /* measured facet of smallest area, or TDS_NONE */
  double tiny_area; /* its area */
  int degenerate;   /* worst or tiny is below the tolerances */
} tds_stall_out;

/* Scan the measured facets (metrics.h: live, not fixed, nonzero tension)
** for the smallest angle and the smallest area. One pass, no allocation:
** cheap next to one energy evaluation. */
void tds_stall_scan(const tds_surf *s, tds_stall_out *o);

/* 1 when tds_stall_scan would surely find no degenerate facet, from a
** pass without square roots or divisions (a third of the scan's time):
** every measured facet's (2A)^2 at least sin^2 of TDS_STALL_ANGLE times
** the product of its two longer sides squared, and the smallest (2A)^2
** at least TDS_STALL_AREA^2 times their mean; a margin of 1e-6 on both.
** 0 when it cannot tell: then scan. */
int tds_stall_clear(const tds_surf *s);

/* Nonzero when a step of the optimizing scale has collapsed: its scale is
** below 1e-6 of the scale limit although the squared force |vel|^2 (minus
** the slope of the line search) is above 1e-8 per unit of energy, i.e. the
** surface is not converged. */
int tds_stall_collapsed(const tds_surf *s, double slope, double energy);

/* The facet the warning names (slot), or TDS_NONE. */
tds_id tds_stall_facet(const tds_stall_out *o);

/* Print the one warning: which symptom, the worst facet, the remedies. */
void tds_stall_warn(tds_ctx *ctx, const tds_surf *s, const tds_stall_out *o,
                    int collapsed);

#endif
