/*
** topo.h: topology-changing commands and the face builder.
**
** Each command checks and reserves everything it needs before mutating,
** and the refine, equiangulate and vertex-average commands also keep a
** snapshot (snap.h), so any failure (out of memory, a non-finite energy
** afterwards) leaves the surface exactly as it was. All of them bump
** topo_gen; ids of existing elements never change.
*/
#ifndef TDS_TOPO_H
#define TDS_TOPO_H

#include "surf.h"

/* Refine: split every selected edge at its midpoint (all live edges without
** TDS_NO_REFINE when sel is NULL; otherwise those with sel[e] != 0) and
** subdivide the facets around them: 3 split edges give 4 facets, 2 give 3,
** 1 gives 2. New vertices inherit fixed/constraints/boundary from their
** edge (boundary parameters by interpolation) and are projected onto their
** constraints; new edges inside a facet inherit the facet's fixed,
** no_refine and constraints; new facets inherit everything. Counts of new
** elements go to *nsplit (edges split) if not NULL. */
int tds_refine(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *nsplit);

/* Edge dst, split from src, takes its flags, constraints, boundary,
** tension, colour, datafile edge and user attributes (topo_refine.c). */
void tds_edge_inherit(tds_mesh *m, tds_id dst, tds_id src);
/* Facet dst, split from src, takes its flags, constraints, tension, colour,
** bodies, datafile face and user attributes (topo_refine.c). */
void tds_facet_inherit(tds_mesh *m, tds_id dst, tds_id src);

/* A new vertex at the midpoint of edge e, with the edge's fixed flag,
** constraints and boundary (its parameter found from the nearer end on
** it); the edge itself is not changed (topo_refine.c). Storage must be
** reserved. */
tds_id tds_edge_midpoint(tds_surf *s, tds_id e);

/* Equiangulate: flip every edge between exactly two facets whose angles
** opposite the edge sum to more than pi, until none is left (a work set,
** as in Delaunay flipping). Never flips fixed edges, edges on constraints
** or boundaries, edges of other than two facets, edges whose facets differ
** in tension, bodies, constraints or fixedness, or a flip that would
** duplicate an existing edge. sel as for tds_refine (NULL = all).
** *nflips gets the number of flips. */
int tds_equiangulate(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                     int32_t *nflips);

/* Evolver's u (the default of tds's u): one pass over the selected edges
** in id order, with the rules of tds_equiangulate but a margin: an edge is
** flipped when the cosines of its two opposite angles sum to less than
** -TDS_U_COS (cos a + cos b < 0 is the Delaunay test a + b > pi). Each
** edge is tested once, when its turn comes; edges made non-Delaunay by
** later flips wait for the next call. The margin is Evolver's as measured:
** on 12 perturbed cube, cat and mound states the flip counts of three
** successive u equal Evolver's for margins in (4.21e-4, 5.2e-4) and for
** no value outside (tests/evolver/uv.sh). */
#define TDS_U_COS 5e-4
int tds_equiangulate_once(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                          int32_t *nflips);

/* Whether edge e may be flipped by the local rules above (fixed,
** constrained, valence, facet attributes, orientation, c != d), and if so
** the two facets: f1 contains e forwards, f2 backwards. Whether the new
** edge already exists is the caller's check (tds_equiangulate keeps a set
** of vertex pairs for it). */
int tds_flip_ok(const tds_surf *s, tds_id e, tds_id *f1, tds_id *f2);

/* Flip edge e (tds_flip_ok must hold and the new edge must not exist). */
void tds_flip(tds_surf *s, tds_id e, tds_id f1, tds_id f2);

/* Vertex averaging. tds_vertex_average is Evolver's V (TDS_VAVG_V, the
** rule measured from Evolver 2.70 and described in topo_vavg_ev.c): every
** free vertex moves a quarter of the way to a weighted mean of its
** neighbours, minus the normal part of that move. TDS_VAVG_RAW (rawv)
** keeps the normal part; TDS_VAVG_RAWEST (rawestv) also ignores triple
** edges and constraints when choosing neighbours. TDS_VAVG_CENTROID is
** tds's earlier rule: the whole way to the area-weighted mean of the
** centroids of its facets minus the normal component (vertices on triple
** edges, or on constraints along border edges, averaged along those edges
** if they have exactly two such neighbours). Vertices on parametric
** boundaries never move; constrained ones are projected back.
** All new positions are computed before any move, unless seq (Evolver's
** vertex_average on a generator: one vertex after another, in id order).
** sel as for tds_refine but over vertices. *nmoved: vertices moved. */
enum { TDS_VAVG_V, TDS_VAVG_RAW, TDS_VAVG_RAWEST, TDS_VAVG_CENTROID };
int tds_vertex_average(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                       int32_t *nmoved);
int tds_vertex_average_mode(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                            int mode, int seq, int32_t *nmoved);

/* Where Evolver's rule (mode TDS_VAVG_V, _RAW or _RAWEST) moves vertex v
** of the soapfilm model, into out; g and ord are scratch for v's edge and
** facet counts. Returns 0 if v stays. Needs the mesh adjacency. */
int tds_vavg_target(const tds_surf *s, tds_id v, int mode, double *g,
                    int32_t *ord, double out[3]);

/* Attributes of a declared face, applied to every facet built from it. */
typedef struct tds_face_attr {
  uint32_t flags;      /* TDS_FIXED, TDS_NO_REFINE, TDS_NODISPLAY, ... */
  tds_cmask con;
  double tension;
  int16_t color;       /* Evolver colour number; 15 (white) is the default */
} tds_face_attr;

/* Build face `f` (0-based id) from a loop of n >= 3 oriented edges that
** chain head to tail. A triangle occupies slot f. A longer loop gets a new
** centre vertex at the mean of its vertices, n spoke edges (loop vertex ->
** centre) and n triangles, as Evolver splits faces: the triangle on the
** last loop edge occupies slot f, the others are appended. Every facet
** built records f as its original face (forig). TDS_OK, TDS_ERANGE (slot
** in use), TDS_ETOPO (edges do not chain) or TDS_ENOMEM. */
int tds_build_face(tds_ctx *ctx, tds_surf *s, tds_id f, int n,
                   const int32_t *oe, const tds_face_attr *attr);

/* Declarations (shared by .tds scripts and the datafile reader). Ids are
** 0-based slots; each checks its references and fails with a message
** naming the element (1-based ids) and TDS_ERANGE/TDS_ETOPO/TDS_ENOMEM. */

/* Vertex `v` at x, or on boundary slot bdry (>= 0) at parameters p (x is
** then computed). Projected onto its constraints, except when constraint
** formulas may read vertex attributes (xattr.h): then the caller sets the
** vertex's attributes and calls tds_decl_vertex_done, which projects
** (calling it in any case is harmless). */
int tds_decl_vertex(tds_ctx *ctx, tds_surf *s, tds_id v, const double x[3],
                    int32_t bdry, const double p[2], uint32_t flags,
                    tds_cmask con);
int tds_decl_vertex_done(tds_ctx *ctx, tds_surf *s, tds_id v);

/* Edge `e` from vertex t to h. */
int tds_decl_edge(tds_ctx *ctx, tds_surf *s, tds_id e, tds_id t, tds_id h,
                  uint32_t flags, tds_cmask con, int32_t bdry, double tension,
                  int16_t color);

/* Body `b` bounded by declared faces (signed 1-based face ids: + when the
** face's normal points out of the body). Every facet built from a listed
** face gets b as front (+) or back (-) body. */
int tds_decl_body(tds_ctx *ctx, tds_surf *s, tds_id b, int n,
                  const int32_t *faces);

#endif
