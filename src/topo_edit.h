/*
** topo_edit.h: mesh-maintenance commands beyond r, u and V (Evolver's t,
** w, l, K, n, delete, edgeswap, o, pop_edge_to_tri, pop_tri_to_edge,
** dissolve, reverse_orientation).
**
** Every command here is all or nothing (a snapshot, snap.h): it checks
** what it needs, and any failure (out of memory, a non-finite energy
** afterwards) leaves the surface exactly as it was. Selections `sel` are
** per-slot flags over the kind the command acts on (NULL: all live
** elements); elements are visited in id order, as Evolver's generators do.
** Each command stores the number of elements it acted on in *n (the count
** Evolver prints). Ids of surviving elements never change.
*/
#ifndef TDS_TOPO_EDIT_H
#define TDS_TOPO_EDIT_H

#include "surf.h"

/* Edge collapse (Evolver's delete edge). Edge e shrinks to a point: its
** facets vanish, and on each of them the two other edges become one. An
** end is pinned when it is fixed or its constraints or boundary differ
** from the edge's; a pinned end stays where it is and the other joins it;
** with neither pinned the tail survives at the midpoint (projected back
** onto the edge's constraints). Refused (returns 0, nothing changes) when
** the edge is dead or fixed, both ends are pinned, or another edge joins
** the same two vertices. Edges that come to join the same two vertices are
** merged (the one from the removed end survives unless the other is
** fixed or on more constraints or a boundary); two facets that come to
** share all three edges are both removed; edges and vertices left without
** facets or edges by that are removed. Returns 1 when the edge collapsed.
** Not a command by itself: no snapshot, no energy update. */
int tds_collapse_edge(tds_surf *s, tds_id e);
/* autopop's collapse: the same, but end 0 (tail) or 1 (head) stays where
** it is (unless an end is pinned; end -1: the midpoint), and in the string
** model, of two edges that merge the one from the removed end survives
** (Evolver's autopop; its t keeps the higher id). */
int tds_collapse_edge_at(tds_surf *s, tds_id e, int end);

/* delete edge (sel over edges): collapse each selected live edge. */
int tds_delete_edges(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* t / edgeweed: collapse, in id order, each live edge shorter than len at
** the time it is reached. */
int tds_edgeweed(tds_ctx *ctx, tds_surf *s, double len, int32_t *n);

/* delete facet (sel over facets): for each selected live facet, collapse
** the first of its edges that can be collapsed, shortest first. */
int tds_delete_facets(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* w / areaweed: delete facet on each live facet whose area is below
** `area` when it is reached. */
int tds_areaweed(tds_ctx *ctx, tds_surf *s, double area, int32_t *n);

/* l / edge_divide: split every live edge longer than len at its midpoint
** (new edges are not split again), subdividing its facets as r does; it
** ignores no_refine, as Evolver's l does. */
int tds_edge_divide(tds_ctx *ctx, tds_surf *s, double len, int32_t *n);

/* The same on the selected edges (Evolver's `refine edges ...`: each edge
** in id order splits its facets in two, so a facet with two of them is
** cut as the splits fall, not along its shorter diagonal as r cuts it).
** In the torus and string models, tds_refine on the set. */
int tds_edge_divide_set(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* K: split the longest edge of every facet whose smallest angle is below
** `angle` (radians). */
int tds_skinny(tds_ctx *ctx, tds_surf *s, double angle, int32_t *n);

/* n / notch: for every edge between exactly two facets whose normals make
** an angle above `angle` (radians), split both facets into three at their
** centroids. *n: edges notched. */
int tds_notch(tds_ctx *ctx, tds_surf *s, double angle, int32_t *n);

/* edgeswap (sel over edges): flip each selected edge that can be flipped
** (tds_flip_ok, and the new edge must not exist yet), whatever the angles. */
int tds_edgeswap(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* o / pop on vertices (sel over vertices): each live vertex that is not
** fixed, on a constraint or on a boundary, whose edges all have two or more
** facets, and whose facets form separate cones (joined only at the vertex,
** as a neck pinched by t) is split into one vertex per cone, at the same
** place; the cone of its lowest facet keeps the vertex. A vertex whose
** star is one cone that is not minimal (plane, triple line, tetrahedral
** point) makes the command fail with "not supported yet for vertex N"
** (Evolver's general sphere construction is not done), the surface as
** before. *n: vertices split. */
int tds_pop_vertices(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* Pop vertex v whose star is one cone that is not minimal by Evolver's
** sphere construction (topo_popcone.c): no snapshot, no energy update.
** *done = 0 (nothing changed) when its regions do not make simple cells.
** TDS_OK or TDS_ENOMEM (then half changed: callers run under a snapshot). */
int tds_pop_cone(tds_surf *s, tds_id v, int *done);

/* Pop vertex v if its star is the cone over a triangular prism frame
** (six triple edges, nine films joining them as a prism's edges): to an
** edge joining the two triangles' sides (to_face 0, Evolver's pop_to_edge)
** or to a triangle between the two triangles' regions (to_face 1,
** pop_to_face), or (to_face -1) as Evolver chooses with neither toggle
** on (topo_t1.c). No snapshot, no energy update; adjacency
** must be current and is stale after. 1 done, 0 not such a cone, or
** -status. */
int tds_pop_prism(tds_surf *s, tds_id v, int to_face);

/* O / pop on edges (sel over edges, NULL: all; topo_popedge.c): each
** selected live edge with more than three facets, not fixed, on no
** constraint (beyond global ones) or boundary, is split into two chains
** as Evolver splits it: the two neighbouring facets with the smallest
** angle between them (the wedge) are pulled 1% of an edge length apart
** from the others along the whole run of such edges (through free
** vertices where only facets fin between the two edges of the run), and
** new triangles join the two runs; a run with no vertex inside is first
** split at its midpoint. Edges are visited in id order; *n gets the
** number of vertices pulled apart (Evolver's "Edges popped"). */
int tds_pop_edges(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* Pop one edge (no snapshot, no energy update): *npulled as above, 0 when
** the edge is not poppable. TDS_OK, or TDS_ENOMEM/TDS_ETOPO (the surface
** is then half changed: callers run under a snapshot). */
int tds_pop_one_edge(tds_surf *s, tds_id e, int32_t *npulled);

/* o: pop every edge (tds_pop_edges), then every vertex (tds_pop_vertices),
** all or nothing; the two counts in *nedges, *nverts. */
int tds_pop(tds_ctx *ctx, tds_surf *s, int32_t *nedges, int32_t *nverts);

/* Widen vertex v, where two cones of facets meet, into a neck (Evolver's
** pop_enjoin; topo_popneck.c). fl[0..nf-1] are v's facets, lab their
** cone labels (lab[0] one cone). *done 0 when the cones do not fit (edges
** at v of other than two facets, rims of different lengths): nothing
** changed then. TDS_OK or TDS_ENOMEM. Needs the mesh adjacency. */
int tds_pop_neck(tds_surf *s, tds_id v, const tds_id *fl, const int *lab, int nf, int *done);

/* The same without a snapshot (for autopop inside g, which has one). */
int tds_pop_raw(tds_ctx *ctx, tds_surf *s, int32_t *nedges, int32_t *nverts);

/* Raw pieces (no snapshot, no energy update; storage is reserved inside):
** split edge e at its midpoint as l does (TDS_OK or TDS_ENOMEM), delete
** facet f as `delete facet` does (1 done, 0 nothing collapsible, -1 out
** of memory). */
int tds_split_edge_raw(tds_surf *s, tds_id e);
int tds_delete_facet_raw(tds_surf *s, tds_id f);


/* pop_edge_to_tri (sel over edges): each edge of valence 3 between two
** free tetrahedral points (four triple edges each, all other edges of
** valence 2), whose other triple edges have no common far ends, becomes a
** small triangle between the bodies beyond its ends (a foam T1 move):
** the edge collapses, and the point becomes three vertices a quarter of
** the edge's length from it, joined by three new triple edges and the
** new facet. *n: edges transformed. Volumes change by the swept amount;
** g brings bodies with targets back. */
int tds_pop_edge_to_tri(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* pop_tri_to_edge (sel over facets): the inverse: a facet whose edges are
** triple edges and whose corners are free tetrahedral points, between two
** different bodies, collapses to a point that opens into a short triple
** edge across, joining the two bodies' sides. *n: facets transformed. */
int tds_pop_tri_to_edge(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* pop_quad_to_quad (sel over facets; topo_quad.c): the film of each
** selected facet, between two bodies and bounded by four triple edges
** whose corners are free tetrahedral points, becomes the quadrilateral
** across, between the two bodies beyond its long sides (Evolver's rules,
** described in topo_quad.c). Facets without a triple edge are skipped
** silently; others that do not fit are skipped with a line saying why
** (for a selection). *n: quadrilaterals popped. */
int tds_pop_quad_to_quad(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);

/* renumber_all (topo_renumber.c): the live elements of each kind get ids
** 1, 2, ... in their present order, every reference following; dead slots
** are dropped. *n: elements whose id changed. Refused in the string model
** (its cells are not renumbered yet). */
int tds_renumber_all(tds_ctx *ctx, tds_surf *s, int32_t *n);

/* vertex_merge (0-based ids): vertex v2 joins v1 (which stays where it
** is): every edge and facet at v2 now has v1, and v2 goes. Refused (the
** surface as before) when the two are joined by an edge or have a
** neighbour in common (the merge would lay two edges side by side), as
** Evolver's manual asks. */
int tds_vertex_merge(tds_ctx *ctx, tds_surf *s, tds_id v1, tds_id v2);

/* rebody: the facets of each body are divided into edge-connected sets
** (a body cut in two by a pinched neck); the set with the lowest facet
** keeps the body, each other set gets a new body with the same attributes
** (as Evolver's rebody). Bodies with target volumes: every piece's target
** becomes its actual volume. *n: new bodies. */
int tds_rebody(tds_ctx *ctx, tds_surf *s, int32_t *n);

/* dissolve (kind, sel): remove elements without closing the gap, as if
** their lines were erased from the datafile: only vertices without edges,
** edges without facets, facets on at most one body (or the same body on
** both sides; the body is left open) and bodies no facet refers to.
** Others are skipped silently, as in Evolver. *n: elements removed. */
int tds_dissolve(tds_ctx *ctx, tds_surf *s, int kind, const uint8_t *sel, int32_t *n);

/* reverse_orientation (edges or facets): a facet runs the other way round
** and swaps its front and back bodies (volumes unchanged); an edge swaps
** its ends, its facets' references follow, and its constraint integrals
** keep their value. *n: elements reversed. */
int tds_reverse_orientation(tds_ctx *ctx, tds_surf *s, int kind, const uint8_t *sel,
                            int32_t *n);

#endif
