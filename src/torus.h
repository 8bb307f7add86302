/*
** torus.h: the torus model (Evolver's TORUS and TORUS_FILLED).
**
** The domain is R^3 modulo the lattice of the three period vectors
** (m->period, rows of the datafile's PERIODS). Vertices keep their stored
** coordinates; each edge carries a wrap (wrap.h) saying which lattice
** translation takes its stored head to its true head. gather.h unwraps
** every element from its first corner, so lengths, areas, their gradients
** and Hessians need nothing else.
**
** Body volumes need more: a facet's own integral depends on where its
** corners are put, and the facets of a body, each unwrapped from its own
** first corner, do not form a closed surface. tds_torus_lifts finds, per
** body, a lattice translation of every facet of the body so that the
** translated facets join up edge to edge (a walk over the body's facets);
** for a body that is a closed cell in the torus (every foam cell) that is a
** closed polyhedron in space, whose volume is exact. eval.c adds each
** facet's translation as the facet_flux row (method_torus.c) weighted by
** the translation. A body that wraps round the torus itself (a layer) has
** no such lift; its volume is then right only up to whole cell volumes and
** to the fluxes through the cut, and tds warns at load.
**
** Volumes are defined up to whole cell volumes: at load each body's
** volconst gets the multiple of the cell volume that brings its volume
** nearest its target (or, without one, into [0, cell volume)), as
** Evolver adjusts volconst (tds_torus_settle).
*/
#ifndef TDS_TORUS_H
#define TDS_TORUS_H

#include "string_model.h"
#include "surf.h"
#include "wrap.h"

/* Volume of the unit cell: |det(period)|. */
double tds_torus_cell_volume(const tds_mesh *m);

/* Make s->tlift current for the mesh's topology (see above). Returns the
** number of bodies whose facets do not close up (wrap round the torus),
** or a negative status (-TDS_ENOMEM) after setting ctx's message. */
int tds_torus_lifts(tds_ctx *ctx, tds_surf *s);

/* One walk over the facet sides (2 f + j: facet f seen from its body
** fb[f][j]) of the body of side root, lifting each side (lift[side], a
** wrap) so that the body's facets join edge to edge; seen marks the sides
** reached and queue[0..*nq) lists them. Across each edge the walk goes to
** the facet bounding the same wedge about it: in angular order, or, if
** that does not close up, in the edge's ring (Evolver's facet-edge order,
** which it follows where flips have folded the surface so that the angles
** mislead). Returns whether the sides close up consistently. */
int tds_torus_walk(const tds_mesh *m, int32_t *lift, uint8_t *seen, int32_t *queue, int32_t root,
                   int32_t *nq);

/* Re-evaluate the PERIODS expressions (recalc). TDS_OK or TDS_ENUM (a
** period not finite, or a degenerate cell), the periods unchanged. */
int tds_torus_periods(tds_ctx *ctx, tds_surf *s);

/* Adjust every body's volconst by whole cell volumes (see above); the
** volumes must be current (tds_surf_update). */
void tds_torus_settle(tds_surf *s);

/* Check that the wraps of every live facet's edges add up to zero (a
** facet lies in one copy of the cell). TDS_OK or TDS_ETOPO with a message
** naming the facet. */
int tds_torus_check(tds_ctx *ctx, const tds_mesh *m);

/* The body whose volume constraint TORUS_FILLED drops (the first body with
** a target volume, as Evolver 2.70 does: its pressure stays 0), or
** TDS_NONE. */
tds_id tds_torus_dropped_body(const tds_mesh *m);

/* Position of corner k of facet f unwrapped from its first corner, into
** out (the same points tds_gather_facet gives). */
void tds_torus_facet_corner(const tds_mesh *m, tds_id f, int k, double out[3]);

/* Corners of facet f (in its orientation) in the frame of its corner k:
** out[k] is vertex fv[f][k]'s stored position and the others follow the
** facet's edges from there (through the inverse of corner k's wrap, which
** may rotate under a symmetry group). Without wraps, the stored
** positions. */
void tds_torus_facet_at(const tds_mesh *m, tds_id f, int k, double out[3][3]);

/* The packed lattice offset of corner k of facet f from its first corner
** (0, the wrap of the first edge, minus the wrap of the third). */
int32_t tds_torus_corner_wrap(const tds_mesh *m, tds_id f, int k);

/* Give the edge on side k of facet f the wrap that makes the facet's
** wraps add up to zero (a new edge inside a facet whose other two edges
** already have theirs). */
void tds_torus_close(tds_mesh *m, tds_id f, int k);

/* The product of facet f's edge wraps in order (tds_wrap_mul): 0 when
** the facet closes (in the torus: the lattice counts add up to zero). */
int32_t tds_facet_wrap(const tds_mesh *m, tds_id f);
/* Whether facet f has a vertex on a symmetry axis (axial_point): its
** wraps' product may then be any element fixing that vertex (Evolver's
** rule), and its corners gathered from any vertex are still the facet. */
int tds_facet_axial(const tds_mesh *m, tds_id f);

/* Evolver's wrap code of a packed wrap (the `wrap` edge attribute): 6 bits
** per period from the lowest, each count in 5-bit two's complement
** (+1 = 1, -1 = 31), so "* * +" is 4096. */
double tds_torus_wrap_code(int32_t w);
/* The packed wrap of an Evolver wrap code; TDS_ERANGE if it is not one. */
int tds_torus_wrap_from_code(double code, int32_t *w);
/* Set edge e's wrap from an Evolver code: the torus model only, and every
** facet on e must still close. All or nothing (ctx says what is wrong). */
int tds_torus_set_wrap(tds_ctx *ctx, tds_surf *s, tds_id e, double code);

/* "WHAT is not supported yet in the torus model" in ctx; TDS_ESYNTAX.
** Commands that would need wraps they do not maintain call it first. */
int tds_torus_unsupported(tds_ctx *ctx, const char *what);

/* Evolver's wrap_vertex: move vertex v by the lattice translation of wrap
** w and change the wraps of its edges so that the surface is the same
** (only the stored copy of v changes). TDS_ERANGE (no torus, no such
** vertex, a wrap out of range) leaves everything unchanged. */
int tds_torus_wrap_vertex(tds_ctx *ctx, tds_surf *s, tds_id v, int32_t w);

/* How a torus surface is drawn (m->draw): each facet from its first
** corner; each body's facets joined across the cell; or everything cut
** to the clip box. */
enum { TDS_DRAW_RAW = 0, TDS_DRAW_CONNECTED = 1, TDS_DRAW_CLIPPED = 2 };

/* Evolver's detorus on a mesh: the torus model ends and the mesh becomes
** what is drawn in m->draw's mode (Evolver's detorus likewise follows the
** display mode):
**   RAW: each facet where it is drawn from its first corner; vertices it
**     reaches across the cell get copies there, edges likewise.
**   CONNECTED: each body's facets edge-connected, the body moved by a
**     lattice vector so the mean of its facets' corners lies in the clip
**     box (translations only); a facet two bodies place apart is
**     repeated, each copy keeping one body; facets of no body as RAW.
**   CLIPPED (translations only): the RAW facets cut by the faces of the
**     clip box and of its translates, each piece moved into the box;
**     cut polygons are triangulated as fans.
** Attributes are inherited; elements no facet uses any more are removed
** (bare edges stay, unwrapped from their tail). Bodies keep their facets
** (open, except connected bodies that do not wrap). If src is not NULL,
** src[0] gets m->nv entries after the call, the vertex of the torus mesh
** each vertex is (a copy of), or -1 for a point where a cut crossed an
** edge, and src[1] m->nf entries, the facet each facet is drawn from (-1
** for dead slots); free both with tds_free(&m->alloc, ...). TDS_OK,
** TDS_ENOMEM or TDS_ERANGE (clipped under a group that rotates), with
** nothing changed. */
int tds_torus_detorus(tds_ctx *ctx, tds_mesh *m, int32_t *src[2]);

/* The CLIPPED case of tds_torus_detorus (torus_clip.c). */
int tds_torus_clip(tds_ctx *ctx, tds_mesh *m, int32_t *src[2]);

/* Lattice coordinates c of point x (x = sum_i c_i period[i]). */
void tds_torus_to_lattice(const tds_mesh *m, const double x[3], double c[3]);
/* The clip box's lower corner in lattice coordinates (the box is lo to
** lo + 1): at DISPLAY_ORIGIN, else at 0. (Evolver's manual calls the
** origin the box's centre; Evolver 2.70 puts the corner there.) */
void tds_torus_box(const tds_mesh *m, double lo[3]);

/* Move every vertex into the unit cell (lattice coordinates in [0, 1))
** with tds_torus_wrap_vertex (Evolver's rewrap.cmd); *n gets how many
** moved. The volumes do not change (tds needs no volconst adjustment). */
int tds_torus_rewrap(tds_ctx *ctx, tds_surf *s, int32_t *n);

/* The lattice counts k that move point x into the unit cell (lattice
** coordinates in [0, 1)): x + k . periods is inside. Translations only. */
void tds_torus_cell_offset(const tds_mesh *m, const double x[3], int k[3]);

/* A neighbourhood unwrapped into one frame, so that a mesh change written
** for ordinary surfaces (the pops) can run on it unchanged: the vertices
** joined by an edge to the seeds, and the seeds, are translated (as
** wrap_vertex does: the surface stays the same) into the frame of seed[0],
** so every edge at a seed, and every edge of a facet at a seed, has no
** wrap. New elements the change makes among them then need none either.
** tds_torus_local_end translates the vertices back (new edges' wraps
** follow; new vertices stay in seed[0]'s frame; a vertex the change did
** not move gets its stored coordinates back bitwise). begin returns 0
** (nothing to do without a torus), or -1, the mesh unchanged, when the
** neighbourhood wraps round the torus (a vertex seen at two places), a
** seed is not joined to seed[0] through seeds, it has more than
** TDS_TORUS_LOCAL_MAX vertices, or the group rotates. */
#define TDS_TORUS_LOCAL_MAX 256
typedef struct tds_torus_local {
  int n, nmoved;
  tds_id v[TDS_TORUS_LOCAL_MAX];
  int32_t w[TDS_TORUS_LOCAL_MAX];
  double x0[TDS_TORUS_LOCAL_MAX][3];
} tds_torus_local;
int tds_torus_local_begin(tds_mesh *m, const tds_id *seed, int nseed, tds_torus_local *L);
void tds_torus_local_end(tds_mesh *m, tds_torus_local *L);
/* The error of an edge pop whose neighbourhood could not be unwrapped:
** "CMD: edge N: ..." naming the group when it rotates. */
int tds_torus_pop_refused(tds_ctx *ctx, const tds_mesh *m, const char *cmd, tds_id e);

/* For exports and pictures: the surface as drawn. s is a shallow copy of
** the surface (sharing its model: parameters, constraints, quantities)
** whose mesh is a detorused deep copy (tds_torus_detorus in the mesh's
** draw mode), so no edge crosses the cell; vsrc and fsrc give, for each
** vertex and facet slot of s.m, the vertex and facet of the surface it is
** drawn from (vsrc -1 for a point made by clipping). In the string
** model only the clipped mode has a view (the others are drawn edge by
** edge from the surface itself): its edges cut into the box, and no cells
** (str, a copy of the surface's with none). */
typedef struct tds_torus_drawn {
  tds_surf s;
  int32_t *vsrc, *fsrc;
  struct tds_strings str;
} tds_torus_drawn;
/* TDS_OK, TDS_ENOMEM or TDS_ERANGE; release with tds_torus_view_free
** (never tds_surf_free). Also brings s's vertex stars up to date (for
** tds_torus_drawn_curvature). */
int tds_torus_view(tds_ctx *ctx, tds_surf *s, tds_torus_drawn *view);
void tds_torus_view_free(tds_torus_drawn *view);
/* The mean curvature (tds_vertex_mean_curvature) of orig's vertex that
** drawn vertex v is drawn from; NaN for a point made by clipping. */
double tds_torus_drawn_curvature(const tds_torus_drawn *view, tds_surf *orig, tds_id v);

#endif
