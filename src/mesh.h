/*
** mesh.h: the element store of a soap-film surface.
**
** Struct-of-arrays per element kind, addressed by 0-based indices. Slots
** are never moved: a deleted element keeps its slot with TDS_DEAD set, so
** user ids (index + 1) stay stable. New elements are appended.
**
** Facet f has vertices fv[f][0..2] and oriented edges fe[f][0..2]; side
** s = 3f+k runs from fv[f][k] to fv[f][(k+1)%3] along edge fe[f][k].
** The sides on one edge form a circular ring through side_next[], entered
** at eside[e]; any number of facets may share an edge. The ring's order is
** Evolver's facet-edge loop order after loading and refining (ring.h),
** otherwise whatever the last change left.
**
** The primary arrays (x, ev, fv, fe, fb, side_next/eside) are the truth.
** Vertex stars are derived (mesh_adj.c), rebuilt when topo_gen moves.
*/
#ifndef TDS_MESH_H
#define TDS_MESH_H

#include "tds.h"

enum {                      /* element flags (any kind) */
  TDS_DEAD = 1u << 0,       /* slot unused */
  TDS_FIXED = 1u << 1,      /* does not move (vertex) / fixes descendants */
  TDS_NO_REFINE = 1u << 2,  /* edge or facet not subdivided by refine */
  TDS_BARE = 1u << 3,       /* vertex or edge expected to have no facets */
  TDS_NODISPLAY = 1u << 4,  /* facet hidden in graphics (kept for dumps) */
  TDS_TARGET = 1u << 5,     /* body volume is constrained to btarget */
  TDS_PRESSURE = 1u << 6,   /* body has a prescribed pressure */
  TDS_NONCONTENT = 1u << 7, /* facet or edge excluded from volumes */
  TDS_AXIAL = 1u << 8,      /* vertex on a symmetry group's axis (axial_point):
                               its facets' wraps need not multiply to 1 */
  TDS_VOLCONST = 1u << 9,   /* body has an explicit volconst */
  TDS_CONREV = 1u << 10     /* edge: constraint integrals run reversed */
};

enum { TDS_VERTEX = 0, TDS_EDGE, TDS_FACET, TDS_BODY, TDS_NKINDS };

typedef uint64_t tds_cmask; /* bit c set: on constraint slot c (0..63) */

struct tds_ucol;            /* a user attribute's column (attr.h) */

typedef struct tds_mesh {
  /* vertices */
  int32_t nv, capv;         /* slots used, capacity */
  double (*x)[3];           /* position */
  uint32_t *vflags;
  tds_cmask *vcon;          /* constraints the vertex is on */
  int32_t *vbdry;           /* parametric boundary index or TDS_NONE */
  double (*vp)[2];          /* boundary parameters */
  int32_t *vfile;           /* Evolver's `original`: the element's id in the
                               datafile (inherited by the parts of a split
                               element of the same kind), or 0 for one made
                               at run time (Evolver 2.70 prints 0; its manual
                               says -1); likewise efile, ffile, bfile */
  /* edges */
  int32_t ne, cape;
  tds_id (*ev)[2];          /* tail, head */
  uint32_t *eflags;
  tds_cmask *econ;
  int32_t *ebdry;
  double *eten;             /* edge tension (default 0 in the soapfilm model) */
  int16_t *ecolor;
  int32_t *eside;           /* one facet side on the edge or TDS_NONE */
  int32_t *efile;
  int32_t *ewrap;           /* torus model only (NULL otherwise): how the
                               edge crosses the unit cell, packed lattice
                               counts (torus.h); the true head is
                               x[head] + wrap . periods */
  /* facets */
  int32_t nf, capf;
  tds_id (*fv)[3];
  int32_t (*fe)[3];         /* oriented edge references */
  tds_id (*fb)[2];          /* [0] frontbody (listed +), [1] backbody (-) */
  uint32_t *fflags;
  tds_cmask *fcon;
  double *ften;             /* surface tension (default 1) */
  int16_t *fcolor;
  tds_id *forig;            /* facet of the datafile it descends from */
  int32_t *ffile;
  int32_t *side_next;       /* ring of sides around an edge, 3*capf */
  /* bodies */
  int32_t nb, capb;
  uint32_t *bflags;
  double *btarget;          /* target volume (TDS_TARGET) */
  double *bvolconst;        /* constant added to the computed volume */
  double *bdensity;         /* for gravity */
  double *bpressure;        /* Lagrange multiplier, or prescribed pressure */
  double *bvol;             /* actual volume, as last computed */
  int32_t *bfile;

  /* user attributes per kind (attr.h): grown, copied and freed with the
  ** element columns above */
  struct tds_ucol *ucol[TDS_NKINDS];
  int nucol[TDS_NKINDS];

  /* the torus model (torus.h): 0 none, 1 TORUS, 2 TORUS_FILLED; period[i]
  ** is the i-th period vector (rows of the datafile's PERIODS) */
  int torus;
  double period[3][3];
  /* a symmetry group (symgroup.h; SYMMETRY_GROUP): its TDS_SYM_* id, 0
  ** none; torus is then 1 too, so commands that do not handle wraps refuse.
  ** Beyond TDS_SYM_TORUS the wraps are group elements, not lattice counts
  ** (gather.h applies their isometries); symp: the group's parameters */
  int sym;
  double symp[2];
  /* how the torus surface is drawn, exported and detorused (torus.h:
  ** TDS_DRAW_RAW, _CONNECTED, _CLIPPED; Evolver's raw_cells, connected,
  ** clipped); the clip box is the cell with its lower corner at origin
  ** when has_origin is set (DISPLAY_ORIGIN), else at 0 */
  int draw;
  int has_origin;
  double origin[3];

  uint64_t topo_gen;        /* bumped by every topology change */
  uint64_t coord_gen;       /* bumped by every coordinate change */

  /* derived adjacency (mesh_adj.c), valid while adj_gen == topo_gen */
  uint64_t adj_gen;
  int32_t *vf_start, *vf;   /* facets around each vertex, CSR */
  int32_t *ve_start, *ve;   /* oriented edges leaving each vertex, CSR */
  int32_t adj_cap[4];        /* capacities of vf_start, ve_start, vf, ve */

  /* The allocator of every array above (tds.h); zero = the C library.
  ** Set it right after tds_mesh_init; tds_mesh_free keeps it. */
  tds_alloc alloc;
} tds_mesh;

/* Set up an empty mesh. */
void tds_mesh_init(tds_mesh *m);
/* Release all storage; the mesh is empty and reusable afterwards (with the
** same allocator). */
void tds_mesh_free(tds_mesh *m);
/* Deep copy of src into an initialised empty dst, which takes src's
** allocator. TDS_OK or TDS_ENOMEM. */
int tds_mesh_copy(tds_mesh *dst, const tds_mesh *src);

/* Contracts of the functions below (checked by TDS_ASSERT in checked
** builds, tds.h): kind is TDS_VERTEX..TDS_BODY; ids are in the slot range
** of their kind; elements referred to are alive. */

/* Make room for at least n slots of `kind` (all columns grow together).
** TDS_OK or TDS_ENOMEM; on failure nothing observable changes. */
int tds_mesh_reserve(tds_mesh *m, int kind, int32_t n);

/* Like tds_mesh_reserve, but grows by at least half the capacity, so
** that many small requests cost amortised constant time. */
int tds_mesh_room(tds_mesh *m, int kind, int32_t n);
/* Turn the torus model on (1 TORUS, 2 TORUS_FILLED) or off (0): allocates
** ewrap (all wraps 0) or frees it. TDS_ENOMEM leaves the mesh unchanged. */
int tds_mesh_set_torus(tds_mesh *m, int torus);

/* Append a vertex at x; returns its index or TDS_NONE (out of memory). */
tds_id tds_mesh_add_vertex(tds_mesh *m, const double x[3]);
/* Append an edge from v0 to v1; index or TDS_NONE. Vertices must exist. */
tds_id tds_mesh_add_edge(tds_mesh *m, tds_id v0, tds_id v1);
/* Append a facet bounded by three oriented edges that chain head to tail;
** links its sides into the edge rings. Index or TDS_NONE. The caller
** checks the chain (tds_mesh_edges_chain). */
tds_id tds_mesh_add_facet(tds_mesh *m, const int32_t oe[3]);
/* Append a body with no facets; index or TDS_NONE. */
tds_id tds_mesh_add_body(tds_mesh *m);
/* Extend the slot range of `kind` to n slots, the new ones dead (used to
** honour explicit ids with gaps). TDS_OK or TDS_ENOMEM. */
int tds_mesh_extend_dead(tds_mesh *m, int kind, int32_t n);

/* Bring dead slot `id` of `kind` to life with default attributes,
** extending the slot range as needed (explicit ids). A claimed facet has no
** edges yet: give it some with tds_mesh_set_facet. TDS_OK, TDS_ENOMEM, or
** TDS_ERANGE if the slot is already in use. */
int tds_mesh_claim(tds_mesh *m, int kind, tds_id id);

/* Give facet f new oriented edges (vertices follow), relinking its sides in
** the edge rings. The chain must be valid. Bumps topo_gen. */
void tds_mesh_set_facet(tds_mesh *m, tds_id f, const int32_t oe[3]);
/* Mark an element dead; a facet is unlinked from its edges first. */
void tds_mesh_kill(tds_mesh *m, int kind, tds_id id);

/* Tail and head vertex of an oriented edge reference. */
static inline tds_id tds_oe_tail(const tds_mesh *m, int32_t oe) {
  TDS_ASSERT(oe >= 0 && TDS_OID(oe) < m->ne);
  return m->ev[TDS_OID(oe)][TDS_OREV(oe)];
}
static inline tds_id tds_oe_head(const tds_mesh *m, int32_t oe) {
  TDS_ASSERT(oe >= 0 && TDS_OID(oe) < m->ne);
  return m->ev[TDS_OID(oe)][!TDS_OREV(oe)];
}
/* Nonzero when the three oriented edges exist and chain head to tail. */
int tds_mesh_edges_chain(const tds_mesh *m, const int32_t oe[3]);

/* Number of facet sides on edge e (0 for a bare edge). */
int tds_edge_valence(const tds_mesh *m, tds_id e);

static inline int tds_alive(const uint32_t *flags, tds_id i) {
  return !(flags[i] & TDS_DEAD);
}
/* Live element counts. */
int32_t tds_mesh_count(const tds_mesh *m, int kind);

/* Rebuild derived adjacency if stale. TDS_OK or TDS_ENOMEM. */
int tds_mesh_adjacency(tds_mesh *m);

/* The corner (0, 1 or 2) at which facet f has vertex v (2 if not 0 or 1). */
static inline int tds_facet_corner(const tds_mesh *m, tds_id f, tds_id v) {
  return m->fv[f][0] == v ? 0 : m->fv[f][1] == v ? 1 : 2;
}

/* Evolver's order of the facets around a vertex v (as measured for its V
** and vertex_normal on surfaces loaded from a file): by the edge on which
** each facet leaves v (the facet's edge k, from its corner k = v), v's
** lowest-numbered edge emin first, then the others from the highest id
** down; ties by facet id. tds_star_key is that order's key. */
static inline int32_t tds_star_key(const tds_mesh *m, tds_id f, int k, tds_id emin) {
  tds_id e = TDS_OID(m->fe[f][k]);
  return e == emin ? INT32_MIN : -e;
}
/* v's lowest edge id (adjacency current), or INT32_MAX without edges. */
tds_id tds_vertex_min_edge(const tds_mesh *m, tds_id v);

/* Validate every invariant of the store (links, rings, orientation, body
** references, derived adjacency if current). Returns TDS_OK or TDS_ETOPO
** with a message naming the broken relation in ctx. */
int tds_mesh_check(tds_ctx *ctx, tds_mesh *m);

/* Warn (tds_warnf, each line prefixed by `where`) about bodies that are
** inconsistent on an edge — a body on the same side of two facets there,
** so some facet is listed in the body with the wrong sign (Evolver's
** WARNING 8745) — and about facets of zero area. Returns how many such
** edges and facets there are; changes nothing. */
int32_t tds_mesh_body_warnings(tds_ctx *ctx, const tds_mesh *m, const char *where);

/* The `original` column of a kind (vfile, efile, ffile or bfile). */
static inline int32_t *tds_mesh_file_ids(const tds_mesh *m, int kind) {
  return kind == TDS_VERTEX ? m->vfile : kind == TDS_EDGE ? m->efile
         : kind == TDS_FACET ? m->ffile : m->bfile;
}

/* Copy the user attribute values and the datafile id (`original`) of
** element src to dst (same kind): an element split from another inherits
** them, as in Evolver. */
void tds_mesh_inherit(tds_mesh *m, int kind, tds_id dst, tds_id src);

/* Copy every column (and user attribute) of slot src of `kind` over slot
** dst, references unchanged (renumber_all compacts with it). */
void tds_mesh_move_slot(tds_mesh *m, int kind, tds_id dst, tds_id src);
/* Shrink the slot range of `kind` to n (slots beyond are forgotten). */
void tds_mesh_truncate(tds_mesh *m, int kind, int32_t n);

/* Bytes of storage held by the mesh per live facet (for the benchmark). */
size_t tds_mesh_bytes(const tds_mesh *m);

#endif
