/*
** surf.h: a surface = the mesh plus its model (parameters, constraints,
** boundaries, quantities, gravity) and iteration settings.
**
** Everything the commands need lives here, so two surfaces can coexist in
** one process. Commands take (tds_ctx *, tds_surf *) and return a status.
*/
#ifndef TDS_SURF_H
#define TDS_SURF_H

#include "mesh.h"
#include "method.h"

#define TDS_MAX_CON 64   /* constraint slots (bits of tds_cmask) */

enum {                   /* constraint flags */
  TDS_CON_NONNEG = 1,    /* one-sided: formula >= 0 allowed */
  TDS_CON_NONPOS = 2,    /* one-sided: formula <= 0 allowed */
  TDS_CON_CONVEX = 4,    /* gap energy for edges on it */
  TDS_CON_GLOBAL = 8     /* applies to every vertex */
};

typedef struct tds_constraint {
  int number;             /* user's id (1-based, as declared); 0 = unused */
  char name[32];          /* Evolver's named constraint (`constraint plane
                             formula ...`, numbered with the smallest free
                             number), lower case; "" if declared by number */
  int flags;
  tds_expr *formula;      /* level set: formula(x) = 0 */
  tds_expr *energy[3];    /* edge integrand (vector field), or NULL */
  tds_expr *content[3];   /* edge integrand added to body volumes */
  int npts[2];            /* Gauss points for energy, content (1 or 2) */
} tds_constraint;

typedef struct tds_boundary {
  int number;             /* user's id; 0 = unused */
  int nparams;            /* 1 (wire) or 2 (surface) */
  int flags;              /* TDS_CON_CONVEX */
  tds_expr *x[3];         /* position as functions of p1, p2 */
  tds_expr *energy[3];
  tds_expr *content[3];
  int npts[2];            /* Gauss points for energy, content (1 or 2) */
} tds_boundary;

enum { TDS_Q_ENERGY = 0, TDS_Q_FIXED, TDS_Q_INFO };

typedef struct tds_method_inst {
  int method;             /* TDS_M_* */
  double modulus;         /* multiplier of this instance */
  tds_expr *integrand[3]; /* vector integrand, or [0] scalar */
  int npts;               /* quadrature points (exact for its degree) */
} tds_method_inst;

typedef struct tds_quantity {
  char *name;
  int kind;               /* TDS_Q_ENERGY / FIXED / INFO */
  double modulus;         /* multiplies the value in the energy */
  double target;          /* for FIXED */
  double volconst;        /* added to the value */
  double value;           /* as last computed */
  double pressure;        /* Lagrange multiplier (FIXED) */
  int ninst;
  tds_method_inst *inst;  /* ninst instances (any number) */
} tds_quantity;

typedef struct tds_surf {
  tds_mesh m;

  /* parameters: live values read by compiled expressions through slots */
  int npar, cappar;
  char **parname;         /* lower-case names */
  double *parval;         /* npar values; the xcap doubles before parval[0]
                             (parval[-1-j]) are the element attribute slots
                             of xattr.h, one block with them */
  int xcap;               /* attribute slots room in front of parval */
  int nxa;                /* attribute slots in use (xa[0..nxa)) */
  struct tds_xattr *xa;   /* what each slot reads (xattr.h) */
  int nxa_kind[4];        /* slots per element kind (TDS_VERTEX..TDS_BODY) */
  uint64_t param_gen;     /* counts parameter assignments */
  uint64_t placed_gen;    /* param_gen at the last recalc (recalc.h) */

  tds_constraint con[TDS_MAX_CON];
  int nbdry;
  tds_boundary *bdry;     /* nbdry slots */
  int nquant;
  tds_quantity *quant;

  /* model */
  double gravity;         /* G */
  int gravity_on;         /* gravity energy active */
  int symmetric_content;  /* volume via (x,y,z)/3 . dS */
  int view_transforms;    /* Evolver's transform_count: matrices in view[];
                             0 = none given (the identity alone) */
  double (*view)[16];     /* the view transforms, 4x4 row-major (display
                             and scripts only; the datafile's VIEW_TRANSFORMS
                             after the identity, or transform_expr's) */
  uint8_t *view_swap;     /* per view transform: SWAP_COLORS (or NULL) */
  int nvgen;              /* VIEW_TRANSFORM_GENERATORS */
  double (*vgen)[16];
  uint8_t *vgen_swap;
  double gap_constant;    /* spring constant for convex constraints */
  tds_expr *metric[9];    /* Riemannian metric G[i][j] = metric[3i+j] (NULL
                             entries 0), string model only; metric_on says
                             whether one was declared (METRIC) */
  int metric_on;
  int klein;              /* KLEIN_METRIC (string model): edge lengths are
                             hyperbolic distances in the Klein model */
  double constraint_tol;  /* level-set projection tolerance */

  /* iteration settings and state */
  double scale;           /* last scale factor */
  double scale_limit;     /* upper bound of the optimizing scale */
  int fixed_scale;        /* nonzero: use `scale` as given (m command) */
  int64_t iterations;     /* iterations done since load */
  int conj_grad;          /* conjugate gradient directions (Evolver's U) */
  double (*cg_dir)[3];    /* CG history: last search direction per vertex */
  double (*cg_prev)[3];   /* and the last velocity (for Polak-Ribiere) */
  double cg_norm2;        /* |velocity|^2 of the last step (0: restart) */
  int32_t cg_nv;          /* vertex slots cg_dir covers */
  uint64_t cg_topo;       /* topo_gen the history belongs to */
  int32_t stall_facet;    /* facet slot + 1 of g's last stall warning; 0 none */
  int check_increase;     /* undo a g step that raises the energy, stop g */
  int evolver_ls;         /* g's line search: Evolver's bracketing (iterate.c) */
  int autopop;            /* g deletes edges and facets about to vanish, pops */
  int immediate_autopop;  /* ... each as soon as it is found (autopop.h) */
  int pop_to_edge;        /* o pops a prism cone to an edge (tds_pop_prism) */
  int pop_to_face;        /* ... or to a triangle (at most one of the two on) */
  int pop_enjoin;         /* o widens two cones at a vertex into a neck (tds_pop_neck) */
  int autochop;           /* g bisects edges about to grow past autochop_length */
  double autochop_length;
  int area_normalization; /* g divides each vertex's force by its share of
                             the edge lengths (facet areas): iterate.c */
  uint64_t rng;           /* state of the jiggle's random numbers (jiggle.h) */

  char *read_text;        /* a datafile's read section, kept verbatim */
  struct tds_expr *special_normal[3]; /* HESSIAN_SPECIAL_NORMAL_VECTOR c1..c3
                              (Newton steps' normals with
                              hessian_special_normal), or NULL */

  struct tds_strings *str; /* the string model's cells (string_model.h),
                              NULL in the soapfilm model */

  /* the torus model (torus.h; the periods and wraps are in the mesh) */
  struct tds_expr *period_expr[3][3]; /* PERIODS as given, re-evaluated by
                                         recalc; NULL: a constant */
  int32_t *tlift;         /* per facet side 2f+j (j 0 front body, 1 back):
                             the packed lattice translation that makes the
                             body's facets one closed surface */
  int32_t tlift_cap;
  uint64_t tlift_gen;     /* topo_gen tlift was built for (0: never) */
  struct tds_tplan *tplan; /* the wraps of the facet pass (eval_torus.c) */

  /* derived: facets of each declared face (CSR by forig), for bodies */
  int32_t *orig_start, *orig_facets;
  uint64_t orig_gen;      /* topo_gen the index was built for */

  /* last computed totals */
  double energy, area;
} tds_surf;

/* Initialise an empty surface with Evolver's defaults. Its allocator is
** s->m.alloc (zero: the C library); set it before anything is added, to
** the hook of the contexts the surface will be used with (tds.h). */
void tds_surf_init(tds_surf *s);
/* Release everything the surface owns; it is empty afterwards and keeps
** its allocator. */
void tds_surf_free(tds_surf *s);

/* Recompute energy, area and body volumes (fills s->energy, s->area,
** m.bvol and quantity values). TDS_OK, or TDS_ENUM if not finite. */
int tds_surf_update(tds_ctx *ctx, tds_surf *s);

/* Parameter table. tds_surf_param_find returns the slot or -1;
** tds_surf_param_set creates the parameter if needed and returns its slot,
** or -1 when out of memory. Names are matched case-insensitively.
** Changing a value counts in param_gen: positions follow at the next
** recalc (recalc.h). */
int tds_surf_param_find(const tds_surf *s, const char *name, size_t len);
int tds_surf_param_set(tds_surf *s, const char *name, double value);
/* Make room for xcap attribute slots (xattr.h) and cap parameters, moving
** the values: TDS_OK or TDS_ENOMEM (nothing changed). */
int tds_surf_param_room(tds_surf *s, int xcap, int cap);

/* Constraint slot for a user number, or -1 if not declared. */
int tds_surf_con_slot(const tds_surf *s, int number);
/* Constraint slot of a named constraint (name[0..len), any case), or -1. */
int tds_surf_con_named(const tds_surf *s, const char *name, size_t len);
/* The smallest constraint number not declared (what a named one gets). */
int tds_surf_con_free_number(const tds_surf *s);

/* Replace the view transforms (n matrices, 4x4 row-major; n = 0: the
** identity alone) or, with gen, the view transform generators, by copies
** of m[0..n) and their SWAP_COLORS flags swap[0..n) (NULL: none). All or
** nothing: TDS_ERANGE if a value is not finite or n is beyond
** TDS_MAX_VIEW, TDS_ENOMEM. */
#define TDS_MAX_VIEW 100000
int tds_surf_set_view(tds_ctx *ctx, tds_surf *s, int gen, int n, const double (*m)[16],
                      const uint8_t *swap);

/* The constraints declared GLOBAL: every vertex is on them, also vertices
** made later by refining or splitting faces. */
tds_cmask tds_surf_global_cons(const tds_surf *s);

#endif
