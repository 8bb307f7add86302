/*
** mobility.h: Evolver's area normalization (AREA_NORMALIZATION, the
** area_normalization toggle): g turns the force on a vertex into a
** velocity by dividing it by the area the vertex stands for, one third of
** the area of its facets, or in the string model one half of the length of
** its edges (Evolver's model.htm). Edges and facets are measured through
** the gather point, so wraps of the torus count; under KLEIN_METRIC the
** areas and lengths are hyperbolic (as Evolver's, measured).
*/
#ifndef TDS_MOBILITY_H
#define TDS_MOBILITY_H

#include "surf.h"

/* r[v] = 1 / sqrt(a_v) for every vertex slot (0 for a vertex with no
** edges or facets of positive size, or dead): iterate.c scales forces and
** constraint gradients by r before solving for the multipliers and the
** velocity by r after, so the velocity is M (force - sum lambda g) with
** M = 1/a_v and the multipliers are those of the M-weighted projection. */
void tds_area_norm_weights(const tds_surf *s, double *r);

#endif
