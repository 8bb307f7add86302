/*
** pg_int.h: internals shared by the files of the projected-gradient method.
**
**   pg.c        the driver: work arrays, the iteration loop, termination
**   pg_kernel.c per-facet and per-star kernels (Voronoi cells, the star
**               model, the closed-form normal root); exported in pg.h
**   pg_pass.c   the fused evaluation pass over the facets (energy, its
**               gradient, volume gradients, Voronoi moments, star model,
**               cotangents) and the non-facet energy terms
**   pg_step.c   motion frames, directions, multipliers, the move of every
**               vertex, rigid-motion gauge, applying moves, state vectors
**   pg_flip.c   Delaunay edge flips (Algorithm 1)
**   pg_accel.c  Anderson acceleration with its safeguards
**
** One iteration: pg_pass() at the current positions; pg_flip_check() on
** the cotangents of that pass (flip, then pass again when anything
** flipped); pg_step() computes every move; the driver applies them
** (pg_apply()) and mixes with the history (pg_accel_mix()).
*/
#ifndef TDS_PG_INT_H
#define TDS_PG_INT_H

#include "fixq.h"
#include "pairset.h"
#include "pg.h"

/* Vertex kinds: how a vertex moves. */
enum { VK_FIXED = 0, VK_FREE, VK_LEVEL, VK_BDRY, VK_JUNCTION };

/* Per-vertex sums of one pass (array of structures: one vertex's sums are
** adjacent in memory, the facet loop adds into three of them, four
** doubles at a time: keep the layout). */
typedef struct pg_acc {
  double N[3];   /* sum of facet area vectors (tension facets) */
  double A0;     /* tension-weighted star area */
  double ga[3];  /* gradient of the tension-weighted star area */
  double area;   /* restricted Voronoi area */
  double H[6];   /* Hessian of the star area in x_v: xx yy zz xy xz yz */
  double mom[3]; /* Voronoi moment: sum area * (centroid - x_v) */
  double pad_;
  double vg[3];  /* one-body facets: gradient of the body's volume (for
                    the vertex's fixq entry pgw.vent) */
  double gg[3];  /* one-body facets: gradient of gravity (into grad) */
} pg_acc;        /* 24 doubles: three cache lines */
_Static_assert(sizeof(pg_acc) == 24 * sizeof(double), "pg_acc: three cache lines");

/* The pass's plan (pg_pass.c): the facets in processing order, split in
** two halves by a plane (so that few vertices have facets in both), and
** where each facet corner adds its sums. The halves may run on two
** threads; the results do not depend on it, to the last bit. */
typedef struct pg_half {
  int32_t i0, i1;         /* range of pgw.forder */
  double energy, area;
  double *bvol;           /* per body: this half's volume sums */
} pg_half;

/* Anderson history (pg_accel.c). */
typedef struct pg_accel {
  int depth;              /* history depth m */
  int hist, head;         /* columns held, next column to write */
  int32_t N;              /* state length (3 per movable vertex) */
  double *X, *G;          /* state before / after the plain move */
  double *Fprev, *Gprev;  /* last residual and plain image */
  double *dF, *dG;        /* N x m columns */
  double *M;              /* m x m Gram matrix of the dF columns */
  double *Ms, *gam, *sc;  /* scratch for the solve */
  int have_prev;
  double fbest;           /* smallest |F|^2 since the last restart */
  double fref;            /* |F|^2 at the last progress (halving) */
  int64_t kbest;          /* step of the last progress */
  int64_t steps;          /* steps in this run */
  int64_t cool;           /* plain steps left after a stagnation */
  int64_t cooldown;       /* length of the next such plain phase */
  int64_t restarts;       /* resets by safeguards */
  int isa;                /* as pgw.isa: 0 generic code, 1 the widest */
  tds_alloc al;           /* of the arrays */
} pg_accel;

/* Newton-type preconditioner (pg_newton.c); the multipliers' dependence
** on the positions is in it for up to PG_NT_NQ constraints. */
#define PG_NT_NQ 4
typedef struct tds_la tds_la;
typedef struct pg_newton {
  int32_t *inv;           /* per vertex: movable index, or -1 */
  int32_t *nbp, *nbi;     /* closed neighbourhoods (CSR, movable indices) */
  int32_t *nbn;           /* scratch: neighbours found so far */
  int32_t *color, ncolor; /* distance-2 colouring */
  double *X0, *F0, *Xp, *Fp, *b;
  double (*xs)[3], (*ps)[2];
  int32_t *mark;
  double *R0, *Rp, *dR, *S0, *Sp, *dS; /* multipliers' parts (pg_newton.c) */
  tds_la *lu;             /* the factored bordered Jacobian, or NULL */
  int64_t builds;         /* Jacobians measured in this run */
  int free;               /* a free surface: all six rigid motions are
                             null vectors of J (set by the driver) */
  tds_alloc al;
} pg_newton;

/* Work arrays of one run; allocated once (pg.c). */
typedef struct pgw {
  int32_t nv, ne, nf, nmov;
  int rigid;              /* no fixed vertex: rigid gauge (pg_step.c) */
  int frozen;             /* pg_step keeps the multipliers, restoring
                             coefficients and gauge motion of its last
                             unfrozen call */
  double gxc[3], gT[3], gR[3]; /* the gauge's last rigid motion (centre,
                             translation, rotation) */
  int nrig;               /* rigid motions in the gauge (<= 6) */
  int rig[6];             /* their indices: 0-2 translations, 3-5 rotations */
  uint8_t *kind;          /* per vertex slot: VK_* */
  int32_t (*bnb)[2];      /* constrained vertex: its two neighbours along
                             the film's border, or -1 */
  int32_t *mov;           /* movable vertex ids */
  pg_acc *acc;            /* per vertex slot: sums of the pass (2 nv
                             slots: nv + i holds the second half's sums
                             at shared vertex i until they are added) */
  double (*grad)[3];      /* (2 nv slots, as acc) gradient of the energies other than the
                             tension-weighted area (gravity, constraint
                             integrals, quantities, pressures, edges) */
  double *fcot;           /* per facet side: cot of the angle at corner k
                             of facet forder[i] at 3 i + k (the pass
                             writes it in its order) */
  double (*d)[3];         /* direction of the normal move (unit) */
  double (*nrm)[3];       /* unit vertex normal */
  double (*model)[3];     /* A0, A1, A2 along d */
  double (*vel)[3];       /* the move v_i */
  double (*rest)[3];      /* restoring motion */
  double (*tan)[3];       /* tangential (mesh-quality) part of the move */
  double (*P)[9];         /* motion-space projector (constrained vertices) */
  double (*Jinv)[6];      /* boundary: dp = Jinv v (2 x 3) */
  double (*xbest)[3];
  double (*pbest)[2];
  tds_fixq fq;
  double *an;             /* normal component of each fq entry */
  double *gram, *rhs, *mult;
  /* flips (pg_flip.c) */
  tds_pairset ps;         /* the mesh's edges as vertex pairs */
  double flip_tol;        /* flip when sin(a + b) < -flip_tol */
  int32_t *stack, *cand, ncand;
  int32_t recent[16][5];  /* the last flips: a, b (removed), c, d
                             (created), and how many flips of that
                             quadrilateral back and forth led to it */
  int recent_head;
  int64_t cycles;         /* flips that undid a flip back (2-cycles) */
  tds_pairset gone;       /* edges removed by flips since the driver last
                             cleared it (pg_flip_forget), at most gone_max */
  int32_t ngone, gone_max;
  int64_t returns;        /* flips that created an edge of gone (a return
                             to an earlier connectivity) */
  int32_t (*copp)[2];     /* per candidate: the two opposite facet sides */
  uint8_t *queued;
  uint64_t cand_gen;
  uint64_t cot_gen;       /* m->coord_gen of the positions of fcot */
  pg_accel aa;
  /* the pass's plan (pg_pass.c); slots and entries are rebuilt when the
  ** topology changes */
  uint64_t plan_gen;
  int32_t norder, *forder;/* the facets the pass visits, in order */
  int32_t *fpos;          /* per facet: its position in forder */
  int32_t *vent;          /* per vertex: the fixq entry its one-body
                             facets' volume gradients go to (acc.vg), or -1 */
  uint8_t *fmode;         /* per facet: what the pass computes */
  int32_t (*fslot)[3];    /* per facet corner: its slot in acc and grad */
  int32_t (*fent)[6];     /* per facet: fixq sum of side j, corner k, as
                             2 i (fq->g[i]) or 2 i + 1 (fgbuf[i]), or -1 */
  int32_t nshared, *shared; /* vertices with facets in both halves */
  int32_t *sbase;         /* per shared vertex: its first fgbuf entry */
  double (*fgbuf)[3];     /* second half's fixq sums at shared vertices */
  uint8_t *side;          /* per vertex: scratch */
  pg_half half[2];
  int threads;            /* threads of the pass (1: none) */
  int64_t threaded;       /* passes run on two threads */
  int isa;                /* vector unit of the pass: 0 generic, 1 AVX2
                             (pg_pass_isa); the same results either way */
  tds_alloc al;           /* the ctx's allocator, of every array here */
} pgw;

/* Results of one pg_step. */
typedef struct pg_stepinfo {
  double r, energy, lambda0;
  int64_t clamps;
} pg_stepinfo;

/* pg.c: allocate and fill the work arrays of a run on s (depth > 0: also
** the Anderson history), and free them. TDS_OK or TDS_ENOMEM. */
int pg_work_init(tds_ctx *ctx, tds_surf *s, pgw *w, int depth);
void pg_work_free(pgw *w);

/* pg_pass.c: evaluate at the current positions. Fills w->acc, w->grad,
** w->fcot, the constrained quantities w->fq (values and gradients), body
** volumes, s->energy and s->area; *energy gets the total energy. Facets
** without a movable vertex contribute only to energy and volumes. The
** energy, gradient and quantities equal tds_eval's (eval.c: the facet
** terms are mirrored here, the edge and quantity terms are eval.c's own).
** TDS_OK or TDS_ENUM (energy not finite). */
int pg_pass(tds_ctx *ctx, tds_surf *s, pgw *w, double *energy);
/* The pass's plan and chunk buffers: TDS_OK or TDS_ENOMEM. */
int pg_plan_init(tds_surf *s, pgw *w);
void pg_plan_free(pgw *w);
/* The pass's vector unit: want 0 for the generic code, else the widest
** available (AVX2 on x86-64 when the processor has it). */
int pg_pass_isa(int want);

/* pg_step.c: from a pass, the move of every movable vertex (w->vel), the
** multipliers (w->mult) and r = max |v_i|. TDS_OK, TDS_ENUM. */
int pg_step(tds_ctx *ctx, tds_surf *s, pgw *w, double sfac, pg_stepinfo *si);
/* Choose the rigid motions of the gauge (after classification). */
void pg_gauge_init(const tds_surf *s, pgw *w);
/* Apply the moves w->vel: every vertex at once, constraints enforced.
** Returns nonzero if a vertex could not be projected. */
int pg_apply(tds_surf *s, pgw *w);
/* State vector of the movable vertices (x, or boundary parameters), and
** setting it (constraints enforced; nonzero if a projection failed). */
void pg_get_state(const tds_surf *s, const pgw *w, double *X);
int pg_set_state(tds_surf *s, const pgw *w, const double *X);
/* Store the multipliers as body / quantity pressures. */
void pg_store_pressures(tds_surf *s, const pgw *w);

/* pg_flip.c */
int pg_flip_init(tds_surf *s, pgw *w);   /* TDS_OK or TDS_ENOMEM */
void pg_flip_free(pgw *w);
/* Nonzero when some candidate edge is not Delaunay by the cotangents of
** the last pass (w->fcot). */
int pg_flip_needed(tds_surf *s, pgw *w);
/* Flip every non-Delaunay edge at the current positions (work set,
** Algorithm 1). Returns the number of flips. */
int32_t pg_flip_pass(tds_surf *s, pgw *w);
/* Forget the edges removed so far (w->gone): later flips that create one
** of them again count in w->returns only from here on. */
void pg_flip_forget(pgw *w);

/* pg_accel.c */
int pg_accel_init(pg_accel *a, const tds_alloc *al, int32_t nstate, int depth); /* TDS_OK/ENOMEM */
void pg_accel_free(pg_accel *a);
void pg_accel_reset(pg_accel *a);
/* Given a->X (state before) and a->G (after the plain move), write the
** next state into a->X. Returns 1 if the history was used (a->X differs
** from a->G), 0 for a plain step. lim2: largest squared distance of a
** vertex's mixed position from its plain one. */
int pg_accel_mix(pg_accel *a, double lim2);

/* pg_newton.c */
int pg_newton_init(pg_newton *nt, const tds_alloc *al, const pgw *w); /* TDS_OK/ENOMEM */
void pg_newton_free(pg_newton *nt);
void pg_newton_drop(pg_newton *nt);  /* forget the factorisation */
/* Measure and factor the Jacobian at state X (finite differences of step
** h); the surface is left as it was. TDS_OK (nt->lu NULL when the mesh
** has a facet with an angle below about 10 degrees: not built), TDS_ENOMEM,
** TDS_ENUM (singular: no factorisation). */
int pg_newton_build(tds_ctx *ctx, tds_surf *s, pgw *w, pg_newton *nt, const double *X,
                    double sfac, double h);
/* Nonzero when a facet at a movable vertex has an angle below about 10
** degrees: no Newton preconditioning then. */
int pg_newton_sliver(const tds_surf *s, const pgw *w);
/* G (the plain image of X) becomes X + dX, dX the preconditioned move. */
int pg_newton_apply(tds_ctx *ctx, pg_newton *nt, const pgw *w, const double *X, double *G);

#endif
