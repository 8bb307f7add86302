/*
** autopop.h: Evolver's autopop and autochop, run by g before each step
** (toggle.htm). dt is the scale, vel[v] the motion direction of vertex v
** for the first nvel vertex slots (the step moves v by dt * vel[v]); a
** vertex made meanwhile counts as still. Both work without a snapshot
** (g holds one) and leave the surface updated when they change it.
*/
#ifndef TDS_AUTOPOP_H
#define TDS_AUTOPOP_H

#include "surf.h"

/* autopop: every edge that the move would shorten to below L = sqrt(2 dt)
** is collapsed (as t does; in the string model its end with the lower id
** stays where it is, as Evolver's), then every facet that the move would shrink
** to an area below L * perimeter / 2 is deleted (as `delete facet`
** does); all are found first, then removed, or with s->immediate_autopop
** each as soon as it is found. If any went, edges and vertices are popped
** as o does. Prints Evolver's lines ("Edges popped: n", "Autopopped n
** edges, m vertices.": n the edges and facets removed) and sets *changed. These are the rules of Evolver's manual; its own choices
** differ on the states we measured (doc/commands.md). */
int tds_autopop(tds_ctx *ctx, tds_surf *s, const double (*vel)[3], int32_t nvel,
                double dt, int *changed);

/* autochop: every edge whose length after twice the move would exceed
** `len` is split at its midpoint as l does (new edges are not tested
** again): Evolver's choice, measured (autopop.c).
** Prints "Autochopped n edges." and sets *changed when there were any;
** then *ends (to free with the mesh's allocator) holds the two ends of
** the edge each new vertex split, in the order the new vertices were
** made (the step moves a new vertex with the mean of its ends' motions,
** as Evolver does). */
int tds_autochop(tds_ctx *ctx, tds_surf *s, const double (*vel)[3], int32_t nvel,
                 double dt, double len, int32_t **ends, int *changed);

#endif
