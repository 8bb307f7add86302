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
** is collapsed (as t does; in the string model as Evolver's: an end where
** two edges meet goes if the other is not such an end, the other staying
** where it is; else the tail stays at the midpoint), then every
** facet that the move would shrink to an area below L * perimeter / 2 is
** deleted (as `delete facet` does); all are found first, then removed, or
** with s->immediate_autopop each as soon as it is found. If any went,
** edges and vertices are popped as o does, and Evolver's lines are
** printed ("Edges popped: n", "Autopopped n edges, m vertices.": n the
** edges and facets removed); *changed is set. These are the rules of
** Evolver's manual; its own choices differ on the states we measured
** (doc/commands.md). In the string model the popping waits for the
** step's move: *deferred is then the number of edges removed, for
** tds_autopop_pop after the move (Evolver pops in the moved positions,
** measured on 100grain.fe).
** *mix (to free with the mesh's allocator; NULL if none) holds *nmix
** rules (dst, a, b), to apply in order: the step moves vertex dst with
** the mean of a's and b's motions (a junction merged at a midpoint). */
int tds_autopop(tds_ctx *ctx, tds_surf *s, const double (*vel)[3], int32_t nvel,
                double dt, int32_t **mix, int32_t *nmix, int32_t *deferred, int *changed);

/* The string model's popping after the move: vertices where four or more
** edges meet are popped (tds_strings_pop_raw) and "Autopopped cnt edges,
** m vertices." printed. */
int tds_autopop_pop(tds_ctx *ctx, tds_surf *s, int32_t cnt);

/* autochop: every edge whose length after the move by dt would exceed
** `len` is split at its midpoint as l does (new edges are not tested
** again). g passes twice the step's dt: Evolver looks two steps ahead
** (measured on 100grain.fe; tests/evolver/autochop.sh's soap films agree
** with either).
** Prints "Autochopped n edges." and sets *changed when there were any;
** then *ends (to free with the mesh's allocator) holds the two ends of
** the edge each new vertex split, in the order the new vertices were
** made (the step moves a new vertex with the mean of its ends' motions,
** as Evolver does). */
int tds_autochop(tds_ctx *ctx, tds_surf *s, const double (*vel)[3], int32_t nvel,
                 double dt, double len, int32_t **ends, int *changed);

#endif
