/*
** test_oom.c: out-of-memory sweeps (SQLite's and Lua's OOM tests).
**
** The surfaces and contexts get an allocator hook (tds.h) that counts
** allocations and fails a chosen one. For each operation (a datafile
** load, refine r, iteration g, u, V, dump) on each input:
**  1. a run without failure gives the expected result, the number of
**     allocations the operation makes, and the call site of each (a key
**     hashed from the return addresses of the hook's three callers);
**  2. allocation N and every later one fail, for N up to DENSE (Lua's
**     test: the error paths get no memory either);
**  3. only allocation N fails, for every N up to DENSE, then the first
**     allocation of every site not failed yet, then about SPARSE more
**     evenly spaced up to the end, so every allocation site the operation
**     reaches fails at least once (checked: the sites failed cover the
**     sites of run 1);
**  4. after each failure: the status is TDS_ENOMEM with a message, the
**     mesh checker passes and the surface is bit for bit what it was
**     before (every column of every element slot, counts, body volumes,
**     targets and pressures, quantities, energy, scale, iteration count);
**     a load leaves the surface empty holding no memory; a dump leaves no
**     file. An operation that absorbs a failure and succeeds must give
**     exactly the expected result. The same surface is reused for the
**     next N (a failed command left it as before, so it must behave the
**     same), and at the end every block is released (the hook counts).
*/
#include <execinfo.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "torus.h"
#include "check.h"
#include "datafile.h"
#include "export.h"
#include "hess.h"
#include "helpers.h"
#include "iterate.h"
#include "newton.h"
#include "pg.h"
#include "topo.h"
#include "topo_edit.h"

#define EX "/usr/share/doc/evolver/examples/"
#define DENSE 600   /* every allocation up to this one is failed */
#define SPARSE 150  /* about this many more beyond DENSE */

/* ---- the failing allocator ---- */

typedef struct oom {
  long count;       /* allocations (not frees) so far */
  long fail_at;     /* fail the allocation with this count (0: none) */
  int persist;      /* and, with this, every allocation after it too */
  uint64_t fail_key; /* or the first allocation from this site (0: none) */
  int failed;       /* a failure was injected */
  uint64_t failed_key;
  long live;        /* blocks held */
  void *fr[16];     /* the stack of the injected failure (OOM_DEBUG) */
  int nfr;
  int record;       /* store each allocation's site key in keys[] */
  uint64_t *keys;
  long nkeys, capkeys;
} oom;

/* The site of an allocation: the return addresses in the helper of
** ctx.c that called the hook and in its caller (the hook's private
** dispatcher is always inlined into the helpers). */
__attribute__((noinline)) static uint64_t site_key(void) {
  void *fr[4];
  int n = backtrace(fr, 4);
  uint64_t h = 1469598103934665603ULL;
  for (int i = 2; i < n; i++) { /* skip site_key and the hook */
    h ^= (uint64_t)(uintptr_t)fr[i];
    h *= 1099511628211ULL;
  }
  return h ? h : 1;
}

static void *oom_fn(void *ud, void *p, size_t n) {
  oom *o = ud;
  if (n == 0) {
    if (p) o->live--;
    free(p);
    return NULL;
  }
  o->count++;
  uint64_t key = (o->record || o->fail_key || o->count == o->fail_at) ? site_key() : 0;
  if (o->record) {
    if (o->nkeys == o->capkeys) {
      o->capkeys = o->capkeys ? 2 * o->capkeys : 1024;
      o->keys = realloc(o->keys, (size_t)o->capkeys * sizeof *o->keys);
      if (!o->keys) abort();
    }
    o->keys[o->nkeys++] = key;
  }
  if (o->persist && o->failed && o->fail_at) return NULL; /* still out */
  if (!o->failed && (o->count == o->fail_at || (o->fail_key && key == o->fail_key))) {
    o->failed = 1;
    o->failed_key = key;
    o->nfr = backtrace(o->fr, 16);
    return NULL;
  }
  void *q = realloc(p, n);
  if (q && !p) o->live++;
  return q;
}

static oom O;

/* A quiet context and an empty surface, both on the hook. */
static void setup(tds_ctx *ctx, tds_surf *s) {
  h_setup(ctx, s);
  ctx->alloc.fn = oom_fn;
  ctx->alloc.ud = &O;
  s->m.alloc = ctx->alloc;
}

/* ---- inputs ---- */

/* Two unit cubes sharing the face x = 1: 12 vertices, 20 edges, 11 faces
** (quadrilaterals, split by the reader), two bodies of volume 1. With
** `perturb`, every vertex moves by a seeded random amount up to 0.15 in
** each coordinate, and the text uses a macro and a parameter. */
static char *double_bubble(int perturb, unsigned seed) {
  static char buf[16384];
  int ev[20][2], ne = 0;
  size_t n = 0;
  uint64_t rng = seed * 0x9e3779b97f4a7c15ULL + 1;
#define OUT(...) (n += (size_t)snprintf(buf + n, sizeof buf - n, __VA_ARGS__))
  if (perturb) OUT("#define VOL 1.0\nparameter wobble = 0.15\n");
  OUT("vertices\n");
  for (int k = 0; k < 2; k++)
    for (int j = 0; j < 2; j++)
      for (int i = 0; i < 3; i++) {
        double d[3] = {0, 0, 0};
        for (int c = 0; perturb && c < 3; c++) d[c] = h_uniform(&rng, -0.15, 0.15);
        OUT("%d %.17g %.17g %.17g\n", 1 + i + 3 * (j + 2 * k), i + d[0], j + d[1], k + d[2]);
      }
#define VID(i, j, k) (1 + (i) + 3 * ((j) + 2 * (k)))
  for (int k = 0; k < 2; k++)
    for (int j = 0; j < 2; j++)
      for (int i = 0; i < 2; i++) ev[ne][0] = VID(i, j, k), ev[ne][1] = VID(i + 1, j, k), ne++;
  for (int k = 0; k < 2; k++)
    for (int i = 0; i < 3; i++) ev[ne][0] = VID(i, 0, k), ev[ne][1] = VID(i, 1, k), ne++;
  for (int j = 0; j < 2; j++)
    for (int i = 0; i < 3; i++) ev[ne][0] = VID(i, j, 0), ev[ne][1] = VID(i, j, 1), ne++;
  OUT("edges\n");
  for (int e = 0; e < ne; e++) OUT("%d %d %d\n", e + 1, ev[e][0], ev[e][1]);
  OUT("faces\n");
  /* a face: axis d, at integer coordinate c along d, cell offset (x of
  ** the cell for faces normal to y or z), outward sign sg */
  int nf = 0, wall = 0, body[2][8], nb[2] = {0, 0};
  for (int cell = 0; cell < 2; cell++)
    for (int d = 0; d < 3; d++)
      for (int side = 0; side < 2; side++) {
        int c = d == 0 ? cell + side : side;
        if (d == 0 && cell == 1 && side == 0) { /* the wall, made by cell 0 */
          body[1][nb[1]++] = -wall;
          continue;
        }
        int u = (d + 1) % 3, w = (d + 2) % 3;
        int corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        int vid[4];
        for (int q = 0; q < 4; q++) {
          int p[3];
          p[d] = c;
          p[u] = corner[q][0] + (u == 0 ? cell : 0);
          p[w] = corner[q][1] + (w == 0 ? cell : 0);
          vid[q] = VID(p[0], p[1], p[2]);
        }
        if (!side) { /* outward is -d: reverse the loop */
          int t = vid[1];
          vid[1] = vid[3];
          vid[3] = t;
        }
        OUT("%d", ++nf);
        for (int q = 0; q < 4; q++) {
          int a = vid[q], b = vid[(q + 1) % 4], id = 0;
          for (int e = 0; e < ne && !id; e++)
            id = ev[e][0] == a && ev[e][1] == b ? e + 1 : ev[e][0] == b && ev[e][1] == a ? -(e + 1) : 0;
          OUT(" %d", id);
        }
        OUT("\n");
        body[cell][nb[cell]++] = nf;
        if (d == 0 && cell == 0 && side == 1) wall = nf;
      }
  OUT("bodies\n");
  for (int b = 0; b < 2; b++) {
    OUT("%d", b + 1);
    for (int i = 0; i < nb[b]; i++) OUT(" %d", body[b][i]);
    OUT(perturb ? " volume VOL\n" : " volume 1\n");
  }
#undef VID
#undef OUT
  return buf;
}

static char bubble_path[64], pbubble_path[64], dump_path[64], prism_path[64];

/* The cone over a triangular prism frame (pop_to_edge, pop_to_face). */
static const char prism_fe[] =
    "vertices\n1 1 0 0 fixed\n2 -0.5 0.8660254 0 fixed\n3 -0.5 -0.8660254 0 fixed\n"
    "4 1 0 0.6 fixed\n5 -0.5 0.8660254 0.6 fixed\n6 -0.5 -0.8660254 0.6 fixed\n"
    "7 0.01 0.02 0.31\nedges\n1 1 2 fixed\n2 2 3 fixed\n3 3 1 fixed\n4 4 5 fixed\n"
    "5 5 6 fixed\n6 6 4 fixed\n7 1 4 fixed\n8 2 5 fixed\n9 3 6 fixed\n10 7 1\n"
    "11 7 2\n12 7 3\n13 7 4\n14 7 5\n15 7 6\nfaces\n1 10 1 -11\n2 11 2 -12\n"
    "3 12 3 -10\n4 13 4 -14\n5 14 5 -15\n6 15 6 -13\n7 10 7 -13\n8 11 8 -14\n"
    "9 12 9 -15\n";

static int write_text(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  fputs(text, f);
  return fclose(f);
}

/* ---- comparing surfaces bit for bit ---- */

static char why[256];

#define COLS(a, b, field, n)                                                   \
  do {                                                                         \
    if ((n) > 0 && memcmp((a)->field, (b)->field, (size_t)(n) * sizeof *(a)->field)) { \
      snprintf(why, sizeof why, "column %s differs", #field);                 \
      return 0;                                                                \
    }                                                                          \
  } while (0)

static int same_mesh(const tds_mesh *a, const tds_mesh *b) {
  if (a->nv != b->nv || a->ne != b->ne || a->nf != b->nf || a->nb != b->nb) {
    snprintf(why, sizeof why, "counts %d %d %d %d, expected %d %d %d %d", a->nv, a->ne,
             a->nf, a->nb, b->nv, b->ne, b->nf, b->nb);
    return 0;
  }
  COLS(a, b, x, a->nv);
  COLS(a, b, vflags, a->nv);
  COLS(a, b, vcon, a->nv);
  COLS(a, b, vbdry, a->nv);
  COLS(a, b, vp, a->nv);
  COLS(a, b, ev, a->ne);
  COLS(a, b, eflags, a->ne);
  COLS(a, b, econ, a->ne);
  COLS(a, b, ebdry, a->ne);
  COLS(a, b, eten, a->ne);
  COLS(a, b, ecolor, a->ne);
  COLS(a, b, eside, a->ne);
  COLS(a, b, fv, a->nf);
  COLS(a, b, fe, a->nf);
  COLS(a, b, fb, a->nf);
  COLS(a, b, fflags, a->nf);
  COLS(a, b, fcon, a->nf);
  COLS(a, b, ften, a->nf);
  COLS(a, b, fcolor, a->nf);
  COLS(a, b, forig, a->nf);
  COLS(a, b, side_next, 3 * a->nf);
  COLS(a, b, bflags, a->nb);
  COLS(a, b, btarget, a->nb);
  COLS(a, b, bvolconst, a->nb);
  COLS(a, b, bdensity, a->nb);
  COLS(a, b, bpressure, a->nb);
  COLS(a, b, bvol, a->nb);
  return 1;
}

static int same_surf(const tds_surf *a, const tds_surf *b) {
  if (!same_mesh(&a->m, &b->m)) return 0;
  double sa[4] = {a->energy, a->area, a->scale, a->gravity};
  double sb[4] = {b->energy, b->area, b->scale, b->gravity};
  if (memcmp(sa, sb, sizeof sa) || a->iterations != b->iterations) {
    snprintf(why, sizeof why, "energy %.17g area %.17g scale %g iterations %lld, expected "
             "%.17g %.17g %g %lld", a->energy, a->area, a->scale, (long long)a->iterations,
             b->energy, b->area, b->scale, (long long)b->iterations);
    return 0;
  }
  if (a->view_transforms != b->view_transforms || a->nvgen != b->nvgen) {
    snprintf(why, sizeof why, "view transforms differ");
    return 0;
  }
  if (a->npar != b->npar || a->nquant != b->nquant || a->nbdry != b->nbdry ||
      (a->npar && memcmp(a->parval, b->parval, (size_t)a->npar * sizeof *a->parval))) {
    snprintf(why, sizeof why, "parameters, quantities or boundaries differ");
    return 0;
  }
  for (int i = 0; i < a->nquant; i++)
    if (memcmp(&a->quant[i].value, &b->quant[i].value, sizeof(double)) ||
        memcmp(&a->quant[i].pressure, &b->quant[i].pressure, sizeof(double)) ||
        a->quant[i].ninst != b->quant[i].ninst) {
      snprintf(why, sizeof why, "quantity %s differs", a->quant[i].name);
      return 0;
    }
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (a->con[c].number != b->con[c].number) {
      snprintf(why, sizeof why, "constraint slot %d differs", c);
      return 0;
    }
  if (!a->read_text != !b->read_text || (a->read_text && strcmp(a->read_text, b->read_text))) {
    snprintf(why, sizeof why, "read section differs");
    return 0;
  }
  return 1;
}

/* ---- operations ---- */

typedef struct opcase {
  const char *file;  /* datafile loaded by the set-up (or by the op) */
  int refine, steps; /* set-up after the load: r's, then g steps */
  char op;           /* 'L' load, 'r', 'g', 'u', 'V', 'd' dump, 'p' pg,
                        'h' Hessian (assembly, KKT, reduction), 'x' export, 'O' pop edges, 'o' pop edges and vertices, 'E'/'F' o with pop_to_edge/pop_to_face, 'Q' pop_quad_to_quad, 'J' o with pop_enjoin, 'N' renumber_all, 'B' rebody,
                        'q' and 'c' run-time define of a quantity and of a
                        global constraint with an energy integrand, 'n' a
                        Newton step (hessian), 's' hessian_seek, 'e'
                        eigenvalues (ritz: 3 lowest), 'S' saddle, 'i'
                        inverse iteration (eigenprobe(0.5, 20)), 'A'
                        addload of the same file, 'R' replace_load, 'T'
                        replacing the view transforms, 'D' detorus ('K'
                        connected, 'C' clipped), 'G'
                        g with Evolver's line search, 'W' every vertex's
                        vertex_normal (hessian_normal_one), 'P' pg's
                        curvature polish (tds_pg_polish) */
} opcase;

static int prepare(tds_ctx *ctx, tds_surf *s, const opcase *c) {
  if (c->op == 'L') return TDS_OK;
  int rc = tds_datafile_load(ctx, s, c->file);
  if (rc == TDS_OK && tds_surf_param_set(s, "wob", 0.5) < 0) rc = TDS_ENOMEM;
  if (rc == TDS_OK) rc = tds_surf_update(ctx, s);
  s->evolver_ls = c->op == 'G';
  for (int i = 0; i < c->refine && rc == TDS_OK; i++) rc = tds_refine(ctx, s, NULL, NULL);
  if (rc == TDS_OK && c->steps) rc = tds_iterate(ctx, s, c->steps);
  return rc;
}

/* The Hessian, its KKT matrix and its reduction, all released. */
static int hessian(tds_ctx *ctx, tds_surf *s) {
  tds_hess h;
  tds_hess_red red;
  tds_spmat K;
  int rc = tds_hess_assemble(ctx, s, NULL, &h);
  if (rc != TDS_OK) return rc;
  rc = tds_hess_kkt(ctx, &h, &K);
  if (rc == TDS_OK) {
    tds_spmat_free(&K);
    rc = tds_hess_reduce(ctx, s, &h, &red);
    if (rc == TDS_OK) tds_hess_red_free(&red);
  }
  tds_hess_free(&h);
  return rc;
}

static int run_op(tds_ctx *ctx, tds_surf *s, const opcase *c) {
  int32_t n;
  tds_pg_opts po;
  tds_pg_result pr;
  tds_export_opts xo = {.format = TDS_FMT_VTU, .encoding = TDS_ENC_BASE64,
                        .vfields = 1u << TDS_VF_MEAN_CURVATURE,
                        .ffields = (1u << TDS_FF_MIN_ANGLE) | (1u << TDS_FF_FRONTBODY)};
  if (s->str) /* the string model exports its edges, to obj or vtk */
    xo = (tds_export_opts){.format = TDS_FMT_VTK, .encoding = TDS_ENC_ASCII};
  switch (c->op) {
  case 'p':
    tds_pg_defaults(&po);
    po.max_iterations = 3; /* until converged (its arrays: the probe's too), capped */
    po.every = -1;
    return tds_pg_run(ctx, s, &po, &pr);
  case 'P': {
    double p0, p1;
    return tds_pg_polish(ctx, s, 2, 0, 0, &p0, &p1, &n);
  }
  case 'h': return hessian(ctx, s);
  case 'n':
  case 's': {
    tds_newton_opts no = {.normal = 1, .metric_mix = 0.5};
    return tds_newton_step(ctx, s, &no, c->op == 's' ? 2 : 0, NULL, NULL);
  }
  case 'e': {
    tds_newton_opts no = {.normal = 1, .linear_metric = 1, .metric_mix = 0.5};
    double vals[3];
    int32_t got;
    int iters;
    tds_inertia in;
    return tds_newton_ritz(ctx, s, &no, NAN, 3, vals, &got, &in, NULL, &iters, NULL);
  }
  case 'W': {
    tds_newton_opts no = {.normal = 1, .normal_one = 1};
    for (tds_id v = 0; v < s->m.nv; v++) {
      if (s->m.vflags[v] & TDS_DEAD) continue;
      double nv3[3];
      int rc = tds_vertex_normal_at(ctx, s, &no, v, nv3);
      if (rc != TDS_OK) return rc;
    }
    return TDS_OK;
  }
  case 'i': { /* also hessian_normal_one and hessian_normal_perp */
    tds_newton_opts no = {.normal = 1, .normal_one = 1, .normal_perp = 1, .linear_metric = 1,
                          .metric_mix = 0.5};
    double val;
    int iters;
    tds_inertia in;
    return tds_newton_invit(ctx, s, &no, 0.5, 20, &val, &in, NULL, &iters);
  }
  case 'S': {
    tds_newton_opts no = {.normal = 1, .metric_mix = 0.5};
    double lowest, step;
    return tds_newton_saddle(ctx, s, &no, 0, &lowest, &step);
  }
  case 'q': {
    static const char q[] = "quantity qq energy modulus 2 method facet_vector_integral global\n"
                            "vector_integrand:\nq1: 0\nq2: 0\nq3: z*wob\n"
                            "method edge_length global";
    return tds_datafile_define(ctx, s, "(define)", 1, q, sizeof q - 1);
  }
  case 'c': {
    static const char k[] = "constraint 9 global nonnegative\nformula: z + 5 = 0\n"
                            "energy:\ne1: 0\ne2: -x*wob\ne3: 0";
    return tds_datafile_define(ctx, s, "(define)", 1, k, sizeof k - 1);
  }
  case 'x': return tds_export(ctx, s, dump_path, &xo);
  case 'L': return tds_datafile_load(ctx, s, c->file);
  case 'A': return tds_datafile_addload(ctx, s, c->file);
  case 'T': {
    static const double mm[2][16] = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                                     {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    static const uint8_t sw[2] = {0, 1};
    return tds_surf_set_view(ctx, s, 0, 2, mm, sw);
  }
  case 'R': return tds_datafile_replace_load(ctx, s, c->file);
  case 'r': return tds_refine(ctx, s, NULL, &n);
  case 'g':
  case 'G': return tds_iterate(ctx, s, 2);
  case 'u': return tds_equiangulate(ctx, s, NULL, &n);
  case 'V': return tds_vertex_average(ctx, s, NULL, &n);
  case 'O': return tds_pop_edges(ctx, s, NULL, &n);
  case 'Q': return tds_pop_quad_to_quad(ctx, s, NULL, &n);
  case 'J': { /* o with pop_enjoin: a neck */
    int32_t nv;
    s->pop_enjoin = 1;
    return tds_pop(ctx, s, &n, &nv);
  }
  case 'N': return tds_renumber_all(ctx, s, &n);
  case 'B': return tds_rebody(ctx, s, &n);
  case 'o': {
    int32_t nv;
    return tds_pop(ctx, s, &n, &nv);
  }
  case 'E': /* o on a prism cone with pop_to_edge, then pop_to_face */
  case 'F': {
    int32_t nv;
    s->pop_to_edge = c->op == 'E';
    s->pop_to_face = c->op == 'F';
    return tds_pop(ctx, s, &n, &nv);
  }
  case 'C': /* detorus as drawn clipped, or connected */
  case 'K': s->m.draw = c->op == 'C' ? TDS_DRAW_CLIPPED : TDS_DRAW_CONNECTED; /* fall through */
  case 'D': return tds_torus_detorus(ctx, &s->m, NULL);
  default: return tds_datafile_dump(ctx, s, dump_path);
  }
}

static int key_seen(const uint64_t *k, long n, uint64_t key) {
  for (long i = 0; i < n; i++)
    if (k[i] == key) return 1;
  return 0;
}

/* Set S up again after an operation succeeded on it. */
static void restart(tds_ctx *ctx, tds_surf *S, const opcase *c) {
  tds_surf_free(S);
  CHECK(prepare(ctx, S, c) == TDS_OK);
  if (c->op == 'd' || c->op == 'x') unlink(dump_path);
}

/* Totals over all sweeps, for the summary line. */
static long total_trials, total_allocs, total_sites, total_absorbed;

/* One trial: fail allocation `at` (counted from now) or the first from
** site `key`. Returns 1 if the operation succeeded without a failure
** being injected (the sweep is over), else 0. */
static int trial(tds_ctx *ctx, tds_surf *S, tds_surf *R, tds_surf *E, const opcase *c,
                 long at, uint64_t key, uint64_t *failed, long *nfailed) {
  if (c->op == 'L') tds_surf_free(S); /* so that S holds nothing */
  long live0 = O.live;
  O.failed = 0;
  O.fail_at = at ? O.count + at : 0;
  O.fail_key = key;
  ctx->errmsg[0] = 0;
  int rc = run_op(ctx, S, c);
  O.fail_at = 0;
  O.fail_key = 0;
  total_trials++;
  if (!O.failed) {
    if (!key) { /* every allocation was made: the end of the sweep */
      CHECK(rc == TDS_OK);
      CHECK(same_surf(S, E));
    }
    restart(ctx, S, c); /* a site not reached this time: also changed */
    return !key;
  }
  if (!key_seen(failed, *nfailed, O.failed_key)) failed[(*nfailed)++] = O.failed_key;
  if (rc == TDS_OK) { /* absorbed: the result must be the normal one */
    total_absorbed++;
    if (getenv("OOM_DEBUG")) {
      printf("  absorbed: %s %c allocation %ld: %s\n", c->file, c->op, at, ctx->errmsg);
      fflush(stdout);
      backtrace_symbols_fd(O.fr, O.nfr, 1);
    }
    if (!same_surf(S, E)) {
      CHECK(!"an absorbed allocation failure changed the result");
      printf("  %s %c, allocation %ld: %s\n", c->file, c->op, at, why);
    }
    restart(ctx, S, c);
    return 0;
  }
  /* a failed load holds nothing (checked before the checker builds the
  ** adjacency) */
  int ok_live = c->op != 'L' || O.live == live0;
  int ok_rc = rc == TDS_ENOMEM, ok_msg = strstr(ctx->errmsg, "memory") != NULL;
  int ok_mesh = h_check(ctx, &S->m) == TDS_OK;
  int ok_same = same_surf(S, R);
  int ok_file = (c->op != 'd' && c->op != 'x') || access(dump_path, F_OK) != 0;
  CHECK(ok_rc && ok_msg && ok_mesh && ok_same && ok_file && ok_live);
  if (!(ok_rc && ok_msg && ok_mesh && ok_same && ok_file && ok_live))
    printf("  %s %c, allocation %ld%s: rc %d '%s' mesh %d same %d (%s) file %d live %ld->%ld\n",
           c->file, c->op, at, key ? " (by site)" : "", rc, ctx->errmsg, ok_mesh, ok_same,
           ok_same ? "" : why, ok_file, live0, O.live);
  return 0;
}

static void sweep(const opcase *c) {
  tds_ctx ctx;
  tds_surf S, R, E;
  memset(&O, 0, sizeof O);
  setup(&ctx, &E);
  setup(&ctx, &S);
  setup(&ctx, &R);
  /* 1. the expected result, the count and the sites */
  REQUIRE_OK(&ctx, prepare(&ctx, &E, c));
  REQUIRE_OK(&ctx, prepare(&ctx, &R, c));
  REQUIRE_OK(&ctx, prepare(&ctx, &S, c));
  O.record = 1;
  O.nkeys = 0;
  int rc0 = run_op(&ctx, &E, c);
  O.record = 0;
  if (rc0 != TDS_OK && strchr("pnseSP", c->op)) { /* not every model */
    fprintf(stderr, "test_oom: %s: %c refuses it (%s)\n", c->file, c->op, ctx.errmsg);
    tds_surf_free(&S);
    tds_surf_free(&R);
    tds_surf_free(&E);
    free(O.keys);
    memset(&O, 0, sizeof O);
    return;
  }
  REQUIRE_OK(&ctx, rc0);
  if (c->op == 'd' || c->op == 'x') unlink(dump_path);
  long total = O.nkeys;
  uint64_t *sites = calloc((size_t)total + 1, sizeof *sites);
  uint64_t *failed = calloc((size_t)total + 1, sizeof *failed);
  long nsites = 0, nfailed = 0;
  for (long i = 0; i < total; i++)
    if (!key_seen(sites, nsites, O.keys[i])) sites[nsites++] = O.keys[i];
  CHECK(total > 0);
  /* 2. persistent failures (Lua's OOM test: once memory runs out, every
  ** later request fails too, also those of the error paths) from every
  ** allocation up to DENSE */
  O.persist = 1;
  for (long at = 1; at <= DENSE && at <= total && !check_failed_; at++)
    trial(&ctx, &S, &R, &E, c, at, 0, failed, &nfailed);
  O.persist = 0;
  nfailed = 0;
  /* 3. one failure: dense, by site, sparse, until it succeeds */
  long at = 1;
  int done = 0;
  for (; at <= DENSE && !done && !check_failed_; at++)
    done = trial(&ctx, &S, &R, &E, c, at, 0, failed, &nfailed);
  /* A failed command leaves the surface as it was but not its caches
  ** (adjacency, the CG history), so a later run may take other paths:
  ** each site not failed yet is tried on a fresh set-up, as run 1 was. */
  for (long i = 0; i < nsites && !check_failed_; i++)
    if (!key_seen(failed, nfailed, sites[i])) {
      restart(&ctx, &S, c);
      trial(&ctx, &S, &R, &E, c, 0, sites[i], failed, &nfailed);
    }
  long step = total > DENSE ? (total - DENSE) / SPARSE + 1 : 1;
  for (; !done && !check_failed_; at += step)
    done = trial(&ctx, &S, &R, &E, c, at, 0, failed, &nfailed);
  for (long i = 0; i < nsites; i++)
    if (!key_seen(failed, nfailed, sites[i])) {
      CHECK(!"an allocation site was never failed");
      printf("  %s %c: site %ld of %ld never failed\n", c->file, c->op, i, nsites);
      if (getenv("OOM_DEBUG")) {
        for (long k = 0; k < total; k++) printf("   alloc %ld key %llx\n", k + 1, (unsigned long long)O.keys[k]);
        for (long k = 0; k < nfailed; k++) printf("   failed %llx\n", (unsigned long long)failed[k]);
      }
      break;
    }
  total_allocs += total;
  total_sites += nsites;
  free(sites);
  free(failed);
  tds_surf_free(&S);
  tds_surf_free(&R);
  tds_surf_free(&E);
  CHECK(O.live == 0); /* nothing leaked */
  if (O.live) printf("  %s %c: %ld blocks not released\n", c->file, c->op, O.live);
  free(O.keys);
  memset(&O, 0, sizeof O);
}

static void sweep_all(char op, int refine, int steps) {
  const char *files[] = {EX "cube.fe", EX "mound.fe", bubble_path, pbubble_path,
                         "tests/datafile/good/features.fe", "tests/datafile/good/lexical.fe"};
  for (size_t i = 0; i < sizeof files / sizeof *files && !check_failed_; i++) {
    if (op != 'L' && i == 5) continue; /* lexical.fe is for the reader */
    opcase c = {files[i], refine, steps, op};
    sweep(&c);
  }
}

/* The string model's knot, curvature and Hooke rows (eval_knot.c), its
** Riemannian metric, and its torus with autochop, autopop and area
** normalization (100grain.fe): load, g, dump. */
static void oom_strings(void) {
  const char *files[] = {"tests/evolver/knot/knots.fe", EX "metric.fe", EX "100grain.fe"};
  const char ops[] = {'L', 'g', 'd'};
  for (size_t i = 0; i < 3 && !check_failed_; i++)
    for (size_t k = 0; k < 3 && !check_failed_; k++) {
      opcase c = {files[i], 0, 0, ops[k]};
      sweep(&c);
    }
}

/* The Newton commands in the string model (the normals of newton_strnorm.c
** and the edges' linear metric): a 2-D foam of junctions (Newton step,
** ritz with linear_metric, inverse iteration with hessian_normal_one;
** vertex_normal allocates nothing there) and a 3-D string with a
** junction (step, ritz). */
static void oom_string_newton(void) {
  const char *flower = "tests/evolver/data/flower5.fe", *string3 = "tests/evolver/data/string3_junction.fe";
  const opcase cases[] = {{flower, 1, 4, 'n'}, {flower, 1, 4, 'e'}, {flower, 1, 4, 'i'},
                          {string3, 0, 2, 'n'}, {string3, 0, 2, 'e'}};
  for (size_t i = 0; i < sizeof cases / sizeof *cases && !check_failed_; i++) sweep(&cases[i]);
}

/* 100grain.fe stepped to just before the string autopop's rarer cases
** (without failures, once) and dumped: g then merges two junctions at a
** midpoint and pops in the moved positions (steps 245-246), or moves a
** chop's new vertex after a collapse (steps 818-819; autopop.h). */
static void oom_autopop_string(void) {
  const int upto[] = {244, 817};
  for (size_t i = 0; i < 2 && !check_failed_; i++) {
    char path[64];
    snprintf(path, sizeof path, "/tmp/tds_oom_%d_grain%d.fe", (int)getpid(), upto[i]);
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    int rc = tds_datafile_load(&ctx, &s, EX "100grain.fe");
    if (rc == TDS_OK) rc = tds_iterate(&ctx, &s, upto[i]);
    if (rc == TDS_OK) rc = tds_datafile_dump(&ctx, &s, path);
    tds_surf_free(&s);
    CHECK(rc == TDS_OK);
    if (rc != TDS_OK) return;
    opcase c = {path, 0, 0, 'g'};
    sweep(&c);
    unlink(path);
  }
}

/* A 2-D foam of 21 x 20 square cells, each a body of area 1, the inner
** junctions moved by up to 0.1 (seeded), the four corners fixed (fixing
** the whole rim would fix the total area: dependent targets): more bodies
** than the dense Gram matrix takes (fixq.h), so g solves for the pressures
** with the sparse Cholesky (spchol.c). */
static char foam_path[64];
static int write_foam(const char *path) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  enum { NX = 21, NY = 20 };
  unsigned seed = 99;
  fprintf(f, "STRING\nSPACE_DIMENSION 2\nvertices\n");
  for (int j = 0; j <= NY; j++)
    for (int i = 0; i <= NX; i++) {
      int edge = i == 0 || j == 0 || i == NX || j == NY;
      int corner = (i == 0 || i == NX) && (j == 0 || j == NY);
      double d[2];
      for (int k = 0; k < 2; k++) {
        seed = seed * 1103515245u + 12345u;
        d[k] = edge ? 0 : 0.2 * ((double)(seed >> 8) / (1 << 24) - 0.5);
      }
      fprintf(f, "%d %.17g %.17g%s\n", j * (NX + 1) + i + 1, i + d[0], j + d[1],
              corner ? " fixed" : "");
    }
  fprintf(f, "edges\n"); /* horizontal (i, j): 1 + j NX + i; vertical: H + 1 + j (NX+1) + i */
  const int H = NX * (NY + 1);
  for (int j = 0; j <= NY; j++)
    for (int i = 0; i < NX; i++)
      fprintf(f, "%d %d %d\n", 1 + j * NX + i, j * (NX + 1) + i + 1, j * (NX + 1) + i + 2);
  for (int j = 0; j < NY; j++)
    for (int i = 0; i <= NX; i++)
      fprintf(f, "%d %d %d\n", H + 1 + j * (NX + 1) + i, j * (NX + 1) + i + 1,
              (j + 1) * (NX + 1) + i + 1);
  fprintf(f, "faces\n");
  for (int j = 0; j < NY; j++)
    for (int i = 0; i < NX; i++)
      fprintf(f, "%d %d %d %d %d\n", 1 + j * NX + i, 1 + j * NX + i,
              H + 1 + j * (NX + 1) + i + 1, -(1 + (j + 1) * NX + i), -(H + 1 + j * (NX + 1) + i));
  fprintf(f, "bodies\n");
  for (int c = 1; c <= NX * NY; c++) fprintf(f, "%d %d volume 1\n", c, c);
  return fclose(f);
}

/* The foam: g (the sparse Gram path) and export (its edges as lines). */
static void oom_foam(void) {
  const char ops[] = {'g', 'x'};
  for (size_t k = 0; k < 2 && !check_failed_; k++) {
    opcase c = {foam_path, 0, 0, ops[k]};
    sweep(&c);
  }
}

static void oom_load(void) { sweep_all('L', 0, 0); }
static void oom_refine(void) { sweep_all('r', 0, 0); }
static void oom_iterate(void) {
  sweep_all('g', 1, 0);
  sweep_all('G', 1, 0);
}
static void oom_equiangulate(void) { sweep_all('u', 1, 2); }
static void oom_vertex_average(void) { sweep_all('V', 1, 2); }
static void oom_dump(void) { sweep_all('d', 1, 2); }
static void oom_pg(void) {
  sweep_all('p', 1, 0);
  sweep_all('P', 1, 0);
}
static void oom_hessian(void) { sweep_all('h', 1, 2); }
static void oom_export(void) { sweep_all('x', 1, 0); }
static void oom_newton(void) {
  sweep_all('n', 1, 5);
  sweep_all('s', 1, 5);
  sweep_all('e', 1, 5);
  sweep_all('S', 1, 5);
  sweep_all('i', 1, 5);
  sweep_all('W', 1, 0);
}
/* O on octa.fe (six runs of one edge: split, then pulled) and refined
** once (runs of two edges). */
static void oom_pop_edges(void) {
  for (int r = 0; r < 2 && !check_failed_; r++) {
    opcase c = {EX "octa.fe", r, 0, 'O'};
    sweep(&c);
    opcase c2 = {EX "octa.fe", r, 0, 'o'}; /* and the sphere at the centre */
    sweep(&c2);
  }
  /* renumber_all and rebody on a double bubble (two bodies, ids dense) */
  opcase c3 = {bubble_path, 1, 0, 'N'};
  sweep(&c3);
  opcase c4 = {bubble_path, 1, 0, 'B'};
  sweep(&c4);
  /* the prism cone (refined once: fans of two facets) popped to an edge and to a triangle */
  opcase c5 = {prism_path, 1, 0, 'E'};
  sweep(&c5);
  opcase c6 = {prism_path, 1, 0, 'F'};
  sweep(&c6);
  /* pop_quad_to_quad on every facet of six bubbles round a quadrilateral */
  opcase c7 = {"tests/evolver/data/quadfoam.fe", 0, 0, 'Q'};
  sweep(&c7);
  /* pop_enjoin on two cones meeting at a vertex */
  opcase c8 = {"tests/evolver/data/doublecone.fe", 0, 0, 'J'};
  sweep(&c8);
}
/* Element attributes in formulas and integrands (xattr.h): their slots
** are allocated as the expressions are compiled (load), and read by g
** and refining. */
static void oom_xattr(void) {
  const char ops[] = {'L', 'g', 'r'};
  for (size_t k = 0; k < 3 && !check_failed_; k++) {
    opcase c = {"tests/datafile/good/xattr.fe", 0, 0, ops[k]};
    sweep(&c);
  }
}
static void oom_addload(void) {
  sweep_all('A', 1, 0);
  sweep_all('R', 0, 1);
  sweep_all('T', 0, 0);
}
/* The torus model: twointor.fe (wraps, lifts of the volumes, TORUS_FILLED)
** through load, r, g, u, V, dump, the Hessian, export and detorus (raw,
** clipped, connected). */
static void oom_torus(void) {
  const char ops[] = "LrguVdhxDCK";
  for (int i = 0; ops[i] && !check_failed_; i++) {
    opcase c = {EX "twointor.fe", ops[i] == 'L' || ops[i] == 'r' ? 0 : 1,
                ops[i] == 'u' || ops[i] == 'V' ? 2 : 0, ops[i]};
    sweep(&c);
  }
}
static void oom_define(void) {
  sweep_all('q', 0, 0);
  sweep_all('c', 0, 0);
}

/* The double bubble is what it claims: two bodies of volume 1 sharing a
** wall, every facet on one or two bodies, and its perturbed twin loads
** to the same topology. */
static void oom_inputs(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, bubble_path));
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK(tds_mesh_count(&s.m, TDS_BODY) == 2);
  CHECK_NEAR(s.m.bvol[0], 1, 1e-12);
  CHECK_NEAR(s.m.bvol[1], 1, 1e-12);
  CHECK_NEAR(s.area, 11, 1e-12); /* 10 outer squares and the wall */
  CHECK_MESH(&ctx, &s.m);
  int32_t nf = s.m.nf;
  tds_surf_free(&s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, pbubble_path));
  CHECK(s.m.nf == nf);
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);
}

int main(void) {
  snprintf(bubble_path, sizeof bubble_path, "/tmp/tds_oom_%d_bubble.fe", (int)getpid());
  snprintf(pbubble_path, sizeof pbubble_path, "/tmp/tds_oom_%d_pbubble.fe", (int)getpid());
  snprintf(dump_path, sizeof dump_path, "/tmp/tds_oom_%d.dmp", (int)getpid());
  snprintf(foam_path, sizeof foam_path, "/tmp/tds_oom_%d_foam.fe", (int)getpid());
  snprintf(prism_path, sizeof prism_path, "/tmp/tds_oom_%d_prism.fe", (int)getpid());
  if (write_text(bubble_path, double_bubble(0, 0)) || write_text(prism_path, prism_fe) ||
      write_text(pbubble_path, double_bubble(1, 7)) || write_foam(foam_path)) {
    printf("FAIL oom_inputs: cannot write /tmp\n");
    return 1;
  }
  RUN(oom_inputs);
  RUN(oom_load);
  RUN(oom_strings);
  RUN(oom_autopop_string);
  RUN(oom_string_newton);
  RUN(oom_refine);
  RUN(oom_iterate);
  RUN(oom_equiangulate);
  RUN(oom_vertex_average);
  RUN(oom_dump);
  RUN(oom_pg);
  RUN(oom_hessian);
  RUN(oom_export);
  RUN(oom_define);
  RUN(oom_pop_edges);
  RUN(oom_addload);
  RUN(oom_xattr);
  RUN(oom_newton);
  RUN(oom_torus);
  RUN(oom_foam);
  unlink(foam_path);
  unlink(bubble_path);
  unlink(pbubble_path);
  unlink(dump_path);
  unlink(prism_path);
  fprintf(stderr, "test_oom: %ld trials over %ld allocations at %ld sites, %ld absorbed\n",
          total_trials, total_allocs, total_sites, total_absorbed);
  return check_done();
}
