/*
** fixq.h: constraints held by Lagrange multipliers (body volumes with a
** target, FIXED named quantities), Evolver's "fixed quantities".
**
** Each constrained quantity q has a value, a target and a gradient. The
** gradients are stored sparsely: for every vertex, the list of quantities
** it touches and dQ_q/dx_v (a vertex touches the bodies around it and every
** global quantity). The Gram matrix G[q][r] = sum_v <dQ_q, dQ_r> couples
** them; pressures (multipliers) come from a small dense solve.
*/
#ifndef TDS_FIXQ_H
#define TDS_FIXQ_H

#include "sparse.h"
#include "surf.h"

/* Above this many constrained quantities the Gram matrix is assembled
** sparse and factored by the sparse Cholesky (spchol.h), not dense: a 2-D foam of 10,000 cells would otherwise take 800 MB and
** a cubic-time solve. */
#define TDS_FIXQ_DENSE_MAX 400

typedef struct tds_fixq {
  int32_t nq;           /* number of constrained quantities */
  int32_t *qbody;       /* q -> body index, or TDS_NONE */
  int32_t *qquant;      /* q -> named quantity index, or -1 */
  int32_t *bq;          /* body -> q, or -1 (m.nb entries) */
  double *value;        /* current values */
  double *target;
  double *mult;         /* scratch: multipliers of the last solve */
  double *gram;         /* nq*nq, scratch; NULL when nq > TDS_FIXQ_DENSE_MAX
                           (then the Gram matrix is sparse: fixq.c) */
  int32_t (*gpair)[3];  /* the dense Gram matrix's entry pairs (fixq.c's
                           gram, lower triangle): entries i, j and the
                           index in gram, in the order the vertices list
                           them; made at the first use (NULL: not yet, or
                           no memory: then the pairs are searched) */
  int64_t ngpair;
  int32_t nv;           /* vertex slots covered by the pattern */
  int32_t *start;       /* per-vertex entry range, nv + 1 */
  int32_t *eq;          /* entry -> q */
  double (*g)[3];       /* entry -> gradient */
  int32_t nent;
  /* Where the assembly adds a body's gradient without searching the
  ** vertex's entries (eval.c): emap[emap_kind * slot + c] is the entry of
  ** corner c for slot `slot` (-1: the body holds no target). Facets
  ** (emap_kind 3): slot 2f + j for facet f's body on side j (fb[f][j]),
  ** corner c at fv[f][c]. The string model (emap_kind 2): slot k of the
  ** cells' edge index (string_model.h's eb_body[k] on the edge e with
  ** eb_start[e] <= k < eb_start[e + 1]), corner c at ev[e][c]; valid for
  ** that index only (emap_gen, emap_topo, emap_ne: its idx_gen, idx_topo,
  ** idx_ne at the build; eval.c sets emap_kind 0 if they differ). 0: none
  ** (no body holds a target, or out of memory: the assembly searches). */
  int32_t *emap;
  int emap_kind;
  uint64_t emap_gen, emap_topo;
  int32_t emap_ne;
  /* The sparse path's Gram matrix (fixq.c), made at its first solve and
  ** kept with the pattern: its upper triangle (CSC), where each vertex's
  ** entry pairs add (gmap), the values last factored (gold) and their
  ** factorisation (gf, analysed once). */
  tds_spmat gm;
  int32_t *gmap;
  double *gold;
  double *gwork;        /* 4 nq: conjugate gradients' vectors */
  double *glam;         /* nq: the last multipliers solved for on this
                           path, the next ones' first guess (glam_ok) */
  int glam_ok;
  struct tds_spchol *gf;
  int gfok;             /* gf holds the factors of gold */
  /* The relative residual tds_fixq_restore's sparse solve may leave
  ** (0: as exact as a direct solve). A caller that repeats the restoring
  ** move until the targets are met (a Newton iteration) may set it: the
  ** solve is then cheaper, and each move still shrinks the error by
  ** about this factor. */
  double restore_rtol;
  /* String model: bodies whose area targets are dependent by the foam's
  ** combinatorics (tds_fixq_dependent, at the build): the lowest such
  ** body and how many bodies its dependent set has (0: none found). The
  ** solves then refuse with a message naming them. */
  tds_id dep_first;
  int32_t dep_count;
  tds_alloc alloc;      /* the allocator of the arrays (the ctx's at build) */
} tds_fixq;

/* Build the quantity list and sparsity pattern for the surface as it is
** now (call after any topology or constraint-set change). Needs current
** adjacency. TDS_OK or TDS_ENOMEM. */
int tds_fixq_build(tds_ctx *ctx, tds_surf *s, tds_fixq *fq);
void tds_fixq_free(tds_fixq *fq);
/* String model (fixq_dep.c): a set of bodies with targets in fq whose
** signed areas add up to a constant whatever the free vertices do (all
** cells of a torus foam; cells closed in by fixed edges): *first its
** lowest body, *count its size; 0 and TDS_NONE when the combinatorics
** show none (the targets may still be dependent by coincidence of the
** positions: the numerical solve finds those). TDS_OK or TDS_ENOMEM. */
int tds_fixq_dependent(tds_ctx *ctx, const tds_surf *s, const tds_fixq *fq, tds_id *first,
                       int32_t *count);

/* The quantities' values (fq->value) from an evaluation made without fq
** (the bodies' volumes in m.bvol, the named quantities' values): the
** same numbers an evaluation with fq stores, without the gradients. */
void tds_fixq_values(const tds_surf *s, tds_fixq *fq);

/* Zero all entry gradients. */
void tds_fixq_clear(tds_fixq *fq);
/* Add gv to the gradient of quantity q at vertex v (entry must exist in the
** pattern, which holds by construction). Inline: the assembly calls it
** for every corner of every facet of a constrained body. */
static inline void tds_fixq_add(tds_fixq *fq, tds_id v, int32_t q, const double gv[3]) {
  TDS_ASSERT(v >= 0 && v < fq->nv && q >= 0 && q < fq->nq);
  for (int32_t i = fq->start[v]; i < fq->start[v + 1]; i++)
    if (fq->eq[i] == q) {
      fq->g[i][0] += gv[0];
      fq->g[i][1] += gv[1];
      fq->g[i][2] += gv[2];
      return;
    }
  TDS_ASSERT(!"the pattern holds (v, q)");
}

/* Add gv to the entry e of quantity q (an emap entry). */
static inline void tds_fixq_add_at(tds_fixq *fq, int32_t e, int32_t q, const double gv[3]) {
  TDS_ASSERT(e >= 0 && e < fq->nent && fq->eq[e] == q);
  (void)q;
  fq->g[e][0] += gv[0];
  fq->g[e][1] += gv[1];
  fq->g[e][2] += gv[2];
}

/* Restoring motion dx = sum_q mu_q g_q with G mu = target - value (dx, of
** nv >= fq->nv rows, is overwritten). TDS_OK or TDS_ENUM. */
int tds_fixq_restore(tds_ctx *ctx, tds_fixq *fq, int32_t nv, double (*dx)[3]);

/* Multipliers of the gradient of energy: lambda = G^-1 <g, grad E>, so that
** grad E - sum lambda g is orthogonal to every g. These are Evolver's
** pressures. Stored in fq->mult. TDS_OK or TDS_ENUM. */
int tds_fixq_multipliers(tds_ctx *ctx, tds_fixq *fq, double (*gradE)[3]);

/* Solve the dense symmetric system A x = b (n x n, row-major) in place by
** Gaussian elimination with partial pivoting; b becomes x. A is destroyed.
** Returns 0, or -1 when singular. */
int tds_dense_solve(int n, double *A, double *b);

#endif
