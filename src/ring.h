/*
** ring.h: the order of the facets around an edge (the edge's ring of
** facet sides, mesh.h), kept as Surface Evolver keeps its facet-edge
** loops, so that the command language's `ee.facet`, `ee.facet[k]` and a
** facetedge's `nextfacet` list them in Evolver's order (measured with
** evolver-nox-d on cube, mound and a double bubble, after loading and
** after `r`):
**  * after loading a datafile, an edge's ring starts at the facet of the
**    first face (in file order) that uses the edge; a spoke of a split
**    face (an edge from a loop vertex to the face's centre) starts at the
**    facet that keeps the face's id; an edge of three or more facets is
**    ordered by angle around the edge, right-handed about its direction,
**    from that first facet;
**  * refining keeps the cyclic order: the first half of a split edge
**    starts at the child of the facet its parent started at, the second
**    half at the child of the facet before it in the ring.
** Other commands keep the rings in whatever order they leave them.
*/
#ifndef TDS_RING_H
#define TDS_RING_H

#include "mesh.h"

/* Make the ring of edge e the sides sides[0..n) in that order, starting at
** sides[0]. They must be exactly the sides on e (n its valence). */
void tds_ring_set(tds_mesh *m, tds_id e, const int32_t *sides, int n);

/* Order the ring of every live edge e >= from with three or more facets by
** angle about the edge, keeping its first side first. Edges of more than
** TDS_RING_MAX facets are left as they are. */
#define TDS_RING_MAX 64
void tds_ring_sort_angular(tds_mesh *m, tds_id from);

#endif
