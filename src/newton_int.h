/* newton_int.h: the Newton system shared by newton.c and newton_eig.c
** (newton.h describes it). */
#ifndef TDS_NEWTON_INT_H
#define TDS_NEWTON_INT_H

#include "hess.h"
#include "newton.h"

typedef struct tds_nsys {
  tds_alloc alloc;      /* of the arrays (the ctx's) */
  int32_t m, nq;
  int32_t *vert;        /* unknown -> vertex slot */
  double (*mv)[3];      /* unknown -> motion-space vector of a unit amount */
  double (*dx)[3];      /* unknown -> displacement in space of a unit amount */
  tds_spmat H;          /* m x m upper */
  tds_spmat A;          /* m x nq */
  tds_spmat M;          /* m x m upper; empty (nrow 0) for the identity */
  double *grad;         /* m: gradient of the Lagrangian */
  double *value, *target; /* nq */
  double *mult;         /* nq: multipliers H was built with */
  double energy;
} tds_nsys;

/* The normal space of each vertex slot (hessian_normal, newton.h): the
** normal, the number of triple-junction edges at it and their direction
** (each signed to agree with the first).
**
** The normal is Evolver's (its vertex_normal attribute): the running sum
** of the facets' area vectors, each added with the sign that agrees with
** the sum so far, over the vertex's facets in Evolver's order (by their
** edges leaving the vertex: the lowest edge id first, then decreasing
** ids, the order of a surface Evolver has just read). On a smooth,
** consistently oriented surface this is the plain sum of the area
** vectors, the volume gradient, whatever the order; where the facets
** around a vertex fold over (a crumpled mesh) the signs, and so the
** normal, depend on the order. */
typedef struct vnorm {
  double an[3];
  double td[3];
  int nt, nf, bent;     /* bent: two triple edges not along one line */
  int full;             /* no normal space: the whole motion space (a
                           junction of the string model) */
  int flat;             /* 2-D space (the string model): every direction,
                           the normal's and the whole space's, lies in
                           the xy plane */
} vnorm;

/* vn: m->nv slots. TDS_OK or TDS_ENOMEM (then vn is incomplete). */
int tds_vertex_normals(const tds_alloc *al, const tds_mesh *m, vnorm *vn);

/* The string model's normal spaces (newton_strnorm.c has Evolver's rule):
** vn m->nv slots; normal_one: hessian_normal_one (2-D space only). TDS_OK
** or TDS_ENOMEM (message in ctx). */
int tds_string_normals(tds_ctx *ctx, tds_surf *s, int normal_one, vnorm *vn);
/* tds_vertex_normal_at in the string model: Evolver's vertex_normal
** attribute, the 2-D rule's normal in the xy plane in 3-D space too (as
** Evolver prints it); (1, 0, 0) at a junction. */
int tds_string_vertex_normal(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_id v,
                             double n[3]);

/* The normal spaces the Newton system uses with options o: the soap
** film's (tds_vertex_normals, then tds_normals_one, tds_special_normals
** as o asks) or the string model's. TDS_OK or a failure with its
** message (out of memory; hessian_normal_one in a 3-D string model;
** the special normal vector missing or not finite). */
int tds_hess_normals(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, vnorm *vn);

/* Vector c of facet f's (or edge e's, f TDS_NONE) gathered frame as its
** corner k sees it: under a symmetry group that rotates, the corner's
** element's rotation undone (symmetry.h), written to out; c itself
** otherwise. Returns the pointer to use. */
const double *tds_norm_seen_from(const tds_mesh *m, tds_id f, tds_id e, int k,
                                 const double c[3], double out[3]);

/* The pieces of tds_vertex_normals that tds_vertex_normal_at
** (newton_vnorm.c) shares. A facet at a vertex with its place in
** Evolver's order there: key INT32_MIN for the facet whose leading edge
** (the side leaving the vertex) is the vertex's lowest edge, else minus
** that edge's index. tds_evolver_sum sorts a[0..n) by key (then facet)
** and sets S to the running sum of their area vectors, each signed to
** agree with the sum so far. */
typedef struct tds_fkey {
  int32_t key, f;
  int32_t k; /* the vertex's corner in f (0 will do without a symmetry
             ** group that rotates: the facet's vector is seen from it) */
} tds_fkey;
void tds_evolver_sum(const tds_mesh *m, tds_fkey *a, int32_t n, double S[3]);
/* P (upper: xx xy xz yy yz zz) += c c^T / |c|^2 (nothing when c = 0). */
void tds_unit_nnt(const double c[3], double P[6]);
/* e = the unit eigenvector of P's largest eigenvalue, signed to agree
** with ref; 0 when that eigenvalue is not positive (e untouched). */
int tds_lead_eig(const double P[6], const double ref[3], double e[3]);
/* The HESSIAN_SPECIAL_NORMAL_VECTOR at vertex v. TDS_OK or TDS_ENUM. */
int tds_special_at(tds_ctx *ctx, const tds_surf *s, tds_id v, double an[3]);

/* hessian_normal_one: every vertex with facets gets a one-dimensional
** normal space, the leading eigenvector of sum n n^T over its facets'
** unit normals (signed to agree with its normal from
** tds_vertex_normals), also on triple junctions. TDS_OK or TDS_ENOMEM
** (vn unchanged). */
int tds_normals_one(const tds_alloc *al, const tds_mesh *m, vnorm *vn);

/* hessian_special_normal: the normal of every vertex off triple
** junctions becomes the datafile's HESSIAN_SPECIAL_NORMAL_VECTOR there
** (a function of the coordinates and parameters). TDS_OK, TDS_ERANGE
** (no such vector), TDS_ENUM (not finite). */
int tds_special_normals(tds_ctx *ctx, const tds_surf *s, vnorm *vn);

/* Columns W (d x c) of the unknowns of a vertex with motion basis B
** (3 x d, dx = B u): the normal space's directions pulled back into u
** (least squares) and made orthonormal in space (|B w| = 1); with full,
** or when the vertex has no normal space, its whole motion space (c = d,
** each coordinate scaled to unit length in space; for a flat vertex the
** part of it in the xy plane, made orthonormal, c <= 2, 0 when that is
** empty). Returns c. */
int tds_normal_columns(const vnorm *vn, const double B[3][3], int d, int full, double W[3][3]);

/* Build at the current positions (multipliers recomputed first). */
int tds_nsys_build(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_nsys *out);
void tds_nsys_free(tds_nsys *n);

/* The linear_metric matrix out->M (out->m, out->dx set; over the facets,
** or the edges in the string model): vk maps a vertex
** slot to its movable index (or -1), ustart a movable index to its first
** unknown. TDS_OK or TDS_ENOMEM. */
int tds_nsys_build_metric(tds_ctx *ctx, const tds_surf *s, double mix, int perp,
                          const int32_t *vk, const int32_t *ustart, tds_nsys *out);

/* tds_nsys_build's fast path (newton_asm.c): the same system assembled
** straight into the unknowns on a pattern from the edges. *miss set (and
** out empty, TDS_OK) when an element couples vertices with no edge
** between them: then use the general path. Multipliers as stored. */
int tds_nsys_assemble(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_nsys *out,
                      int *miss);

/* The bordered K - c [M 0; 0 0] (upper CSC). */
int tds_nsys_kkt(tds_ctx *ctx, const tds_nsys *n, double c, tds_spmat *K);

/* hessian_diff: replace h->H's values by central differences of the
** Lagrangian's gradient (multipliers h->mult), keeping its pattern
** (newton_diff.c). The positions are restored exactly. */
int tds_hess_diff(tds_ctx *ctx, tds_surf *s, tds_hess *h);

/* y = M x (the identity when M is empty). */
void tds_nsys_metric(const tds_nsys *n, const double *x, double *y);

#endif
