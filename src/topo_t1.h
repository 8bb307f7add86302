/* topo_t1.h: pieces of the foam T1 moves (topo_t1.c) shared with
** pop_quad_to_quad (topo_quad.c). Core only: no Lua. */
#ifndef TDS_TOPO_T1_H
#define TDS_TOPO_T1_H

#include "surf.h"

/* Expand vertex v: triple edge te[i] goes to vertex tv[i] (new vertices,
** or v itself, which then stays); conn are the edges among them. The fans
** of facets at v (joined through its edges not listed in te) follow the
** vertex of one of their two bounding triple edges: the first found, the
** other with flip, `follow` when it is one of the two (TDS_NONE: no
** preference), or, with axis given, the end counterclockwise after the
** other about axis; a fan whose ends part gains a facet (P, u, Q) on the edge
** P-Q, u the far end of the triple edge at Q. TDS_OK, or TDS_ETOPO when
** the star is not fans bounded by two listed triple edges each (nothing
** changed then). Room for nt new edges and facets must be reserved. */
int tds_t1_expand(tds_mesh *m, tds_id v, int nt, const tds_id *te, const tds_id *tv,
                  const tds_id *conn, int nc, int flip, const double *axis, tds_id follow);

/* The triple edges at v other than `not` into t3 (up to 4), when v is a
** tetrahedral point: four triple edges, every other edge of valence 2. */
int tds_t1_tetra(const tds_mesh *m, tds_id v, tds_id not, tds_id *t3);

/* Not fixed, on no constraint other than global ones, on no boundary. */
int tds_t1_free_vertex(const tds_surf *s, tds_id v);

/* Whether body b (TDS_NONE: the outside) is on a facet around edge e. */
int tds_t1_around_has(const tds_mesh *m, tds_id e, tds_id b);

/* The distinct bodies on the facets around e (up to 8) into out; count. */
int tds_t1_bodies_around(const tds_mesh *m, tds_id e, tds_id *out);

#endif
