/*
** string_model.h: the string model (Evolver's STRING / SURFACE_DIMENSION
** 1): the surface is a network of edges carrying tension, and a facet is a
** plane cell given by a list of oriented boundary edges of any length (the
** list need not close: a cell may be partly bounded by a constraint whose
** content integrand closes it). A body's "volume" is the area of its cells.
**
** The mesh (mesh.h) keeps the vertices, edges and bodies as in the
** soapfilm model but no triangles (m.nf stays 0); the cells live here, in
** s->str (NULL in the soapfilm model). Cell f's loop is the oriented edges
** oe[start[f] .. start[f+1]); front body fb[f][0] counts the cell's area
** +, back body fb[f][1] counts it -. Slots never move; a dead cell keeps
** an empty loop. Energies and areas are rows of the method table
** (method_string.c) assembled in eval.c from the per-edge body weights
** below.
*/
#ifndef TDS_STRING_MODEL_H
#define TDS_STRING_MODEL_H

#include "surf.h"

typedef struct tds_strings {
  int space_dim;            /* 2 or 3: coordinates the dump writes */
  int32_t nf, capf;         /* cell slots */
  uint32_t *flags;          /* TDS_DEAD, TDS_FIXED, TDS_NONCONTENT, ... */
  tds_id (*fb)[2];          /* front (+) and back (-) body, or TDS_NONE */
  int16_t *color;
  int32_t *start;           /* capf + 1 entries */
  int32_t *oe;              /* loops, concatenated */
  int32_t noe, capoe;
  uint64_t gen;             /* counts changes of loops and bodies */
  /* derived: per edge, the bodies its edge_area goes to and the weights
  ** (sum over the cells of the loop sign times +1 front / -1 back) */
  uint64_t idx_gen, idx_topo;
  int32_t idx_ne;
  int32_t *eb_start;        /* idx_ne + 1 */
  tds_id *eb_body;
  double *eb_w;
  double *eb_lift;          /* torus: sum over the same entries of the weight
                               times t_y, t the lattice translate of the
                               edge's tail in the cell's loop unwrapped from
                               its first edge (edge_shift, method_string.c);
                               NULL without a torus */
  tds_alloc alloc;
} tds_strings;

/* Switch s (empty, soapfilm) to the string model in `space_dim` (2 or 3)
** dimensions. TDS_OK or TDS_ENOMEM. */
int tds_strings_enable(tds_ctx *ctx, tds_surf *s, int space_dim);
/* Release s->str (if any) and set it NULL. */
void tds_strings_free(tds_surf *s);
/* A deep copy of src (NULL gives NULL) into *dst. TDS_OK or TDS_ENOMEM. */
int tds_strings_copy(const tds_alloc *a, const tds_strings *src, tds_strings **dst);

/* Append cell slot f (>= nf; slots in between are dead) with loop oe[0..n),
** checked: edges exist and consecutive ones chain head to tail. TDS_OK,
** TDS_ERANGE, TDS_ETOPO (message in ctx) or TDS_ENOMEM. */
int tds_strings_add(tds_ctx *ctx, tds_surf *s, tds_id f, int n, const int32_t *oe,
                    uint32_t flags, int16_t color);
/* Room for nf cell slots and noe loop entries. TDS_OK or TDS_ENOMEM. */
int tds_strings_room(tds_strings *st, int32_t nf, int32_t noe);

/* The refusal of a soap-film command in the string model, as Evolver's
** ("Can only do area weed on soapfilm model."): TDS_ERANGE. */
int tds_string_unsupported(tds_ctx *ctx, const char *what);

/* Live cell count. */
int32_t tds_strings_count(const tds_strings *st);
/* Live element count of kind in s: cells for facets in the string model. */
int32_t tds_surf_count(const tds_surf *s, int kind);

/* Refine: every edge e with split[e] != TDS_NONE was cut into e (tail to
** the new vertex) and split[e] (new vertex to head); put the new pieces
** into the loops. TDS_OK or TDS_ENOMEM (then nothing changed). */
int tds_strings_split(tds_strings *st, const tds_id *split, int32_t ne);

/* Edge deletion (Evolver's t and delete edge in the string model; the
** mesh side is topo_collapse.c's): drop every reference to edge e from the
** loops (its ends have merged, so the loops still chain), or make every
** reference to edge `from` one to `to` (two edges merged; flip: they ran
** opposite ways). In place, no allocation. */
void tds_strings_drop_edge(tds_strings *st, const tds_mesh *m, tds_id e);
void tds_strings_rename_edge(tds_strings *st, tds_id from, tds_id to, int flip);
/* After merges: cells whose loop is empty or only runs edges out and back
** (zero area) die, as Evolver's do. Their bodies stay. */
void tds_strings_prune(tds_strings *st);

/* Bring the per-edge body weights up to date. TDS_OK or TDS_ENOMEM. */
int tds_strings_index(tds_ctx *ctx, tds_surf *s);

/* Area of cell f at the current positions: the edge_area rows of its loop
** plus the content of constraints at its open ends. */
double tds_strings_area(const tds_surf *s, tds_id f);

/* Bodies (with targets, per fixq's bq) a vertex touches through its edges:
** written to out[0..max), returns how many (at most max). */
int tds_strings_vertex_bodies(tds_surf *s, tds_id v, tds_id *out, int max);

/* Check the cells: loops chain, edges alive, bodies alive, and in the
** torus a closed loop's wraps add up to zero (the cell lies in one copy of
** the unit cell). TDS_OK or TDS_ETOPO with a message. */
int tds_strings_check(tds_ctx *ctx, const tds_surf *s);

/* Evolver's V for one vertex of the string model: a vertex on no
** constraint or boundary, with exactly two edges (on no constraint),
** moves by a quarter of the component of (a + c)/2 - b along c - a (a, c
** its neighbours, b itself): along the chord, so the triangle a b c keeps
** its area. New position in out; 0 if v does not move. Needs current
** adjacency. (Measured on evolver-nox-d; vertices on constraints, at
** junctions or ends stay.) */
int tds_strings_vavg(const tds_surf *s, tds_id v, double out[3]);
/* Evolver's rawv and rawestv for strings (measured on evolver-nox-d
** 2.70): a vertex on no constraint or boundary with two or more edges
** (junctions too) moves a quarter of the way to the mean of its edges'
** far ends, each edge counted once (wraps followed). New position in
** out; 0 if v does not move. Needs current adjacency. */
int tds_strings_rawv(const tds_surf *s, tds_id v, double out[3]);

/* Evolver's o (pop) for strings (string_topo.c): every vertex (sel NULL) or
** selected vertex (sel[v] != 0) with four or
** more edges, not fixed and on no constraint or boundary, is split until
** three edges meet at each of its pieces. *npopped: splits made. All or
** nothing. TDS_OK, TDS_ERANGE (not the string model), TDS_ENOMEM,
** TDS_ENUM. */
int tds_strings_pop(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *npopped);

/* tds_strings_pop on every vertex without a snapshot (autopop inside g,
** which holds one): on failure the surface may be half changed. */
int tds_strings_pop_raw(tds_ctx *ctx, tds_surf *s, int32_t *npopped);

/* Evolver's t1_edgeswap (string_topo.c), in 2-D space: every selected edge
** (sel[e] != 0; sel NULL: all) joining two triple points, not fixed and
** on no constraint or boundary, with ends that are free, turns a quarter
** about its midpoint and reconnects its four neighbours (the 2-D foam T1);
** other edges are skipped. In 3-D space nothing is done. *nflip: edges
** flipped. All or nothing. */
int tds_strings_t1(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *nflip);

/* Evolver's facet_crosscut (string_topo.c): split cell f (closed edge
** list) by a new edge from corner tv to corner hv (tension 0, as
** Evolver's); f keeps the new edge and the corners from hv round to tv, a
** new cell (same bodies) the rest. *newedge: the new edge. All or
** nothing; TDS_ERANGE (no such cell or corners) with a message. */
int tds_strings_crosscut(tds_ctx *ctx, tds_surf *s, tds_id f, tds_id tv, tds_id hv,
                         tds_id *newedge);
#endif
