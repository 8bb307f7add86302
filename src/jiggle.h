/*
** jiggle.h: Evolver's j (jiggle): a random displacement of every vertex,
** for simulated annealing or to shake a surface out of a rut.
**
** Each free vertex (not fixed, not on a parametric boundary) moves by an
** independent Gaussian vector whose components have standard deviation
** temperature x the mean length of the live edges, then is projected back
** onto its level-set constraints. Volumes are not restored (the next g
** does that). The random numbers come from a generator seeded by the
** surface (s->rng, which every jiggle advances), so the same script gives
** the same surface on every run and every machine; set the seed to
** repeat or vary a run. Not Evolver's random numbers: the same statistics,
** not the same draws.
*/
#ifndef TDS_JIGGLE_H
#define TDS_JIGGLE_H

#include "surf.h"

/* Jiggle the selected vertices (sel NULL: all; else sel[v] != 0) at the
** given temperature (finite, >= 0). *nmoved: vertices moved. All or
** nothing: a non-finite energy afterwards, a failed projection or a bad
** temperature leave the surface (and the seed) as they were. TDS_OK,
** TDS_ERANGE, TDS_ENUM, TDS_ENOMEM. */
int tds_jiggle(tds_ctx *ctx, tds_surf *s, double temperature, const uint8_t *sel,
               int32_t *nmoved);

/* The next number of the surface's generator, uniform in [0, 1). */
double tds_rng_uniform(uint64_t *state);

#endif
