/* attr_rows.c: the built-in attributes of vertices, edges, facets and
** bodies, one row each (attr.h). The order of the TDS_AT_FE rows is the
** order dump writes them in. Setters see values already checked against
** the row's type (tds_attr_check) and keep the rules of the attribute. */
#include <stddef.h>
#include <string.h>

#include "attr.h"
#include "gather.h"
#include "method.h"
#include "geom.h"
#include "motion.h"
#include "symgroup.h"
#include "torus.h"
#include "vec3.h"

#define UNUSED(x) (void)(x)
#define SETTER_ARGS tds_ctx *ctx, tds_surf *s, const tds_attr *a, tds_id id, \
                    const double *v, int n
#define GETTER_ARGS tds_ctx *ctx, tds_surf *s, const tds_attr *a, tds_id id, \
                    double *v, int *n

static uint32_t *flags_of(tds_mesh *m, int kind) {
  return kind == TDS_VERTEX ? m->vflags
         : kind == TDS_EDGE ? m->eflags
         : kind == TDS_FACET ? m->fflags : m->bflags;
}

static tds_cmask *cons_of(tds_mesh *m, int kind) {
  return kind == TDS_VERTEX ? m->vcon : kind == TDS_EDGE ? m->econ : m->fcon;
}

static int one(double *v, int *n, double x) {
  v[0] = x;
  *n = 1;
  return TDS_OK;
}

/* original (every kind): the id in the datafile, 0 for run-time elements */
static int get_original(GETTER_ARGS) {
  UNUSED(ctx);
  return one(v, n, tds_mesh_file_ids(&s->m, a->kind)[id]);
}
static int set_original(SETTER_ARGS) {
  UNUSED(n);
  if (!(v[0] >= 0 && v[0] <= INT32_MAX))
    return tds_seterr(ctx, TDS_ERANGE, "%s %d: original must be an element id or 0, not %g",
                      tds_kind_name[a->kind], id + 1, v[0]);
  tds_mesh_file_ids(&s->m, a->kind)[id] = (int32_t)v[0];
  return TDS_OK;
}
#define ORIGINAL(k) ROW(.name = "original", .kind = k, .type = TDS_AT_INT, .size = 1, \
                        .get = get_original, .set = set_original)

/* Rows whose value is one element of a mesh column (a->off: its offset in
** tds_mesh) of doubles or of int16_t (colours). */
static int get_dcol(GETTER_ARGS) {
  UNUSED(ctx);
  return one(v, n, (*(double **)((char *)&s->m + a->off))[id]);
}
static int get_scol(GETTER_ARGS) {
  UNUSED(ctx);
  return one(v, n, (*(int16_t **)((char *)&s->m + a->off))[id]);
}

/* ---- generic kinds of rows ---- */

static int get_flag(GETTER_ARGS) {
  UNUSED(ctx);
  return one(v, n, (flags_of(&s->m, a->kind)[id] & a->flag) != 0);
}

static int set_flag(SETTER_ARGS) {
  UNUSED(ctx);
  uint32_t *fl = flags_of(&s->m, a->kind);
  if (n && v[0] != 0) fl[id] |= a->flag;
  else fl[id] &= ~a->flag;
  if (a->kind == TDS_FACET || a->flag == TDS_NONCONTENT) s->m.topo_gen++;
  return TDS_OK;
}

static int get_cons(GETTER_ARGS) {
  UNUSED(ctx);
  tds_cmask mask = cons_of(&s->m, a->kind)[id];
  *n = 0;
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (mask & ((tds_cmask)1 << c)) v[(*n)++] = s->con[c].number;
  return TDS_OK;
}

/* The mask of the constraint numbers v[0..n) (signs ignored), or raise. */
static int cons_mask(tds_ctx *ctx, const tds_surf *s, const tds_attr *a, tds_id id,
                     const double *v, int n, tds_cmask *mask) {
  *mask = 0;
  for (int i = 0; i < n; i++) {
    double c = v[i] < 0 ? -v[i] : v[i];
    int slot = c >= 1 && c <= 1e9 ? tds_surf_con_slot(s, (int)c) : -1;
    if (slot < 0)
      return tds_seterr(ctx, TDS_ERANGE, "%s %d: constraint %g is not defined",
                        tds_kind_name[a->kind], (int)id + 1, v[i]);
    *mask |= (tds_cmask)1 << slot;
  }
  return TDS_OK;
}

static int get_bdry(GETTER_ARGS) {
  UNUSED(ctx);
  int32_t b = a->kind == TDS_VERTEX ? s->m.vbdry[id] : s->m.ebdry[id];
  *n = 0;
  if (b != TDS_NONE) one(v, n, s->bdry[b].number);
  return TDS_OK;
}

/* Evolver's `unset vertices boundary 1`: an element can leave its
** boundary (a vertex keeps its position, now free); putting one on a
** boundary needs its parameters, which only the datafile gives. */
static int set_bdry(SETTER_ARGS) {
  UNUSED(v);
  if (n) return tds_seterr(ctx, TDS_ERANGE,
                           "%s %d: boundary can only be unset (boundaries are given in the "
                           "datafile)", tds_kind_name[a->kind], id + 1);
  if (a->kind == TDS_VERTEX) s->m.vbdry[id] = TDS_NONE;
  else s->m.ebdry[id] = TDS_NONE;
  s->m.coord_gen++;
  return TDS_OK;
}

/* ---- vertices ---- */

static int vx_get(GETTER_ARGS) {
  UNUSED(ctx);
  return one(v, n, s->m.x[id][a->name[0] - 'x']);
}
static int vx_set(SETTER_ARGS) {
  UNUSED(ctx);
  if (!n) return tds_seterr(ctx, TDS_ERANGE, "vertex %d: %s cannot be unset", id + 1, a->name);
  if (s->klein) { /* the Klein model is the open unit ball: outside, no length */
    double p[3] = {s->m.x[id][0], s->m.x[id][1], s->m.x[id][2]};
    p[a->name[0] - 'x'] = v[0];
    if (!(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] < 1))
      return tds_seterr(ctx, TDS_ERANGE,
                        "vertex %d: %s = %.15g puts it at (%.15g, %.15g), not inside the unit "
                        "disk, the Klein model of KLEIN_METRIC",
                        id + 1, a->name, v[0], p[0], p[1]);
  }
  s->m.x[id][a->name[0] - 'x'] = v[0];
  s->m.coord_gen++;
  return TDS_OK;
}

static int vp_get(GETTER_ARGS) {
  UNUSED(ctx);
  return one(v, n, s->m.vp[id][a->name[1] - '1']);
}

/* p1/p2 = value: move a boundary vertex along its boundary; where the
** boundary formula is not finite, nothing moves. */
static int vp_set(SETTER_ARGS) {
  tds_mesh *m = &s->m;
  int k = a->name[1] - '1';
  if (m->vbdry[id] == TDS_NONE)
    return tds_seterr(ctx, TDS_ERANGE, "vertex %d is not on a boundary, so it has no p%d",
                      id + 1, k + 1);
  if (!n) return tds_seterr(ctx, TDS_ERANGE, "vertex %d: p%d cannot be unset", id + 1, k + 1);
  if (k >= s->bdry[m->vbdry[id]].nparams)
    return tds_seterr(ctx, TDS_ERANGE, "vertex %d: boundary %d has only p1", id + 1,
                      s->bdry[m->vbdry[id]].number);
  double x0[3], p0 = m->vp[id][k];
  v3_copy(x0, m->x[id]);
  m->vp[id][k] = v[0];
  if (tds_motion_enforce(s, id) != TDS_OK) {
    m->vp[id][k] = p0;
    v3_copy(m->x[id], x0);
    return tds_seterr(ctx, TDS_ERANGE, "vertex %d: boundary %d is not defined at p%d = %g",
                      id + 1, s->bdry[m->vbdry[id]].number, k + 1, v[0]);
  }
  m->coord_gen++;
  return TDS_OK;
}

/* constraints = list: all or nothing, a failed projection leaves the
** vertex as it was. */
static int vcon_set(SETTER_ARGS) {
  tds_mesh *m = &s->m;
  tds_cmask mask;
  int rc = cons_mask(ctx, s, a, id, v, n, &mask);
  if (rc) return rc;
  tds_cmask old = m->vcon[id];
  double x[3], p[2] = {m->vp[id][0], m->vp[id][1]};
  v3_copy(x, m->x[id]);
  m->vcon[id] = mask;
  m->coord_gen++;
  if (tds_motion_enforce(s, id) != TDS_OK) {
    m->vcon[id] = old;
    v3_copy(m->x[id], x);
    memcpy(m->vp[id], p, sizeof p);
    return tds_seterr(ctx, TDS_ENUM, "vertex %d could not be projected onto its constraints",
                      id + 1);
  }
  return TDS_OK;
}

static int v_valence(GETTER_ARGS) {
  UNUSED(a);
  if (tds_mesh_adjacency(&s->m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  return one(v, n, s->m.ve_start[id + 1] - s->m.ve_start[id]);
}

/* A row: fields not given are 0/NULL (no alias, not in datafiles, no
** setter, dumped when not the default). */
#define ROW(...) {.col = -1, __VA_ARGS__}
#define FLAGROW(k, nm, al, fal, bit, io_)                                          \
  ROW(.name = nm, .alias = al, .fe_alias = fal, .kind = k, .type = TDS_AT_FLAG, .size = 1, \
      .io = io_, .flag = bit, .get = get_flag, .set = set_flag)
#define RO(k, nm, ty, sz, fn) ROW(.name = nm, .kind = k, .type = ty, .size = sz, .get = fn)
#define FE_DECL (TDS_AT_FE | TDS_AT_DECL)
#define OFF(field) offsetof(tds_mesh, field)

static const tds_attr vertex_rows[] = {
    ROW(.name = "x", .kind = TDS_VERTEX, .type = TDS_AT_REAL, .size = 1, .get = vx_get,
        .set = vx_set),
    ROW(.name = "y", .kind = TDS_VERTEX, .type = TDS_AT_REAL, .size = 1, .get = vx_get,
        .set = vx_set),
    ROW(.name = "z", .kind = TDS_VERTEX, .type = TDS_AT_REAL, .size = 1, .get = vx_get,
        .set = vx_set),
    ROW(.name = "p1", .kind = TDS_VERTEX, .type = TDS_AT_REAL, .size = 1, .get = vp_get,
        .set = vp_set),
    ROW(.name = "p2", .kind = TDS_VERTEX, .type = TDS_AT_REAL, .size = 1, .get = vp_get,
        .set = vp_set),
    ROW(.name = "boundary", .kind = TDS_VERTEX, .type = TDS_AT_BDRY, .size = 1, .io = FE_DECL,
        .get = get_bdry, .set = set_bdry),
    ROW(.name = "constraints", .alias = "constraint", .fe_alias = "constraint",
        .kind = TDS_VERTEX, .type = TDS_AT_CONS, .size = TDS_MAX_CON, .io = FE_DECL,
        .get = get_cons, .set = vcon_set),
    FLAGROW(TDS_VERTEX, "fixed", NULL, NULL, TDS_FIXED, FE_DECL),
    FLAGROW(TDS_VERTEX, "bare", NULL, NULL, TDS_BARE, FE_DECL),
    FLAGROW(TDS_VERTEX, "axial_point", NULL, NULL, TDS_AXIAL, FE_DECL),
    RO(TDS_VERTEX, "valence", TDS_AT_INT, 1, v_valence),
    ORIGINAL(TDS_VERTEX),
};

/* ---- edges ---- */

static int e_length(GETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  if (s->klein) { /* KLEIN_METRIC: the hyperbolic length */
    tds_corners C;
    tds_gather_edge(&s->m, TDS_OREF(id, 0), &C);
    return one(v, n, tds_klein_dist(C.x[0], C.x[1]));
  }
  if (s->metric_on) { /* METRIC: the length in the metric */
    tds_corners C;
    tds_gather_edge(&s->m, TDS_OREF(id, 0), &C);
    tds_mlocal L = {.x = {C.x[0], C.x[1]}, .ig = s->metric, .param = s->parval,
                    .G = s->gravity_on ? s->gravity : 0};
    return one(v, n, tds_methods[TDS_M_METRIC_LENGTH].eval(&L, NULL, NULL));
  }
  double d[3];
  tds_edge_vec(&s->m, TDS_OREF(id, 0), d);
  return one(v, n, v3_norm(d));
}
static int e_end(GETTER_ARGS) {
  UNUSED(ctx);
  return one(v, n, s->m.ev[id][a->name[0] == 'h'] + 1);
}
static int e_valence(GETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  return one(v, n, tds_edge_valence(&s->m, id));
}
static int e_tension_set(SETTER_ARGS) {
  UNUSED(a);
  if (!n) return tds_seterr(ctx, TDS_ERANGE, "edge %d: tension cannot be unset", id + 1);
  s->m.eten[id] = v[0];
  return TDS_OK;
}
static int e_color_set(SETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  s->m.ecolor[id] = n ? (int16_t)v[0] : 0;
  return TDS_OK;
}
/* Edge constraints carry no projection (the vertices have their own). */
static int econ_set(SETTER_ARGS) {
  tds_cmask mask;
  int rc = cons_mask(ctx, s, a, id, v, n, &mask);
  if (rc) return rc;
  s->m.econ[id] = mask;
  return TDS_OK;
}

/* wrap (torus model, torus.h): Evolver's wrap code. Dumps write wraps as
** * + - signs after the vertices; the word only for counts beyond 1, and
** for every wrap of a SYMMETRY_GROUP (as Evolver writes them). */
static int e_wrap_get(GETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  if (!s->m.ewrap) return one(v, n, 0);
  if (s->m.sym > TDS_SYM_TORUS) return one(v, n, tds_sym_code(s->m.sym, s->m.ewrap[id]));
  return one(v, n, tds_torus_wrap_code(s->m.ewrap[id]));
}
static int e_wrap_set(SETTER_ARGS) {
  UNUSED(a);
  if (!n) return tds_seterr(ctx, TDS_ERANGE, "edge %d: wrap cannot be unset", id + 1);
  return tds_torus_set_wrap(ctx, s, id, v[0]);
}
static int e_wrap_dumped(const tds_surf *s, tds_id id) {
  int k[3];
  if (!s->m.ewrap) return 0;
  if (s->m.sym) return s->m.ewrap[id] != 0;
  tds_wrap_unpack(s->m.ewrap[id], k);
  return k[0] * k[0] > 1 || k[1] * k[1] > 1 || k[2] * k[2] > 1;
}

/* A string model's edge defaults to tension 1 when read (a film's to 0),
** so there every tension is written, 0 too. */
static int e_tension_dumped(const tds_surf *s, tds_id id) {
  return s->str || s->m.eten[id] != 0;
}

static const tds_attr edge_rows[] = {
    RO(TDS_EDGE, "length", TDS_AT_REAL, 1, e_length),
    ORIGINAL(TDS_EDGE),
    RO(TDS_EDGE, "tail", TDS_AT_VERTEX, 1, e_end),
    RO(TDS_EDGE, "head", TDS_AT_VERTEX, 1, e_end),
    RO(TDS_EDGE, "valence", TDS_AT_INT, 1, e_valence),
    ROW(.name = "constraints", .alias = "constraint", .fe_alias = "constraint",
        .kind = TDS_EDGE,
        .type = TDS_AT_CONS, .size = TDS_MAX_CON, .io = FE_DECL, .get = get_cons,
        .set = econ_set),
    ROW(.name = "boundary", .kind = TDS_EDGE, .type = TDS_AT_BDRY, .size = 1, .io = FE_DECL,
        .get = get_bdry, .set = set_bdry),
    FLAGROW(TDS_EDGE, "fixed", NULL, NULL, TDS_FIXED, FE_DECL),
    FLAGROW(TDS_EDGE, "no_refine", NULL, "norefine", TDS_NO_REFINE, FE_DECL),
    FLAGROW(TDS_EDGE, "bare", NULL, NULL, TDS_BARE, FE_DECL),
    FLAGROW(TDS_EDGE, "noncontent", NULL, NULL, TDS_NONCONTENT, FE_DECL),
    ROW(.name = "tension", .alias = "density", .fe_alias = "density", .kind = TDS_EDGE,
        .type = TDS_AT_REAL, .size = 1, .io = FE_DECL, .get = get_dcol, .set = e_tension_set,
        .dumped = e_tension_dumped, .off = OFF(eten)),
    ROW(.name = "color", .fe_alias = "colour", .kind = TDS_EDGE, .type = TDS_AT_COLOR,
        .size = 1,
        .io = FE_DECL, .get = get_scol, .set = e_color_set, .off = OFF(ecolor)),
    ROW(.name = "wrap", .kind = TDS_EDGE, .type = TDS_AT_INT, .size = 1, .io = FE_DECL,
        .get = e_wrap_get, .set = e_wrap_set, .dumped = e_wrap_dumped),
};

/* ---- facets ---- */

static int f_area(GETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  tds_corners C;
  tds_gather_facet(&s->m, id, &C);
  if (s->klein) /* KLEIN_METRIC: the hyperbolic area */
    return one(v, n, tds_klein_area(C.x[0], C.x[1], C.x[2]));
  return one(v, n, geom_area(C.x[0], C.x[1], C.x[2], NULL));
}
static int f_tension_set(SETTER_ARGS) {
  UNUSED(a);
  if (!n) return tds_seterr(ctx, TDS_ERANGE, "facet %d: tension cannot be unset", id + 1);
  s->m.ften[id] = v[0];
  s->m.topo_gen++; /* equiangulation and pg compare facet tensions */
  return TDS_OK;
}
static int f_color_set(SETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  s->m.fcolor[id] = n ? (int16_t)v[0] : 15;
  return TDS_OK;
}
static int f_body_get(GETTER_ARGS) {
  UNUSED(ctx);
  tds_id b = s->m.fb[id][a->name[0] == 'b'];
  *n = 0;
  if (b != TDS_NONE) one(v, n, b + 1);
  return TDS_OK;
}
static int f_body_set(SETTER_ARGS) {
  tds_mesh *m = &s->m;
  tds_id b = n && v[0] != 0 ? (tds_id)v[0] - 1 : TDS_NONE;
  if (b != TDS_NONE && (b < 0 || b >= m->nb || !tds_alive(m->bflags, b)))
    return tds_seterr(ctx, TDS_ERANGE, "facet %d: body %g does not exist", id + 1, v[0]);
  m->fb[id][a->name[0] == 'b'] = b;
  m->topo_gen++; /* bodies feed derived data */
  return TDS_OK;
}
static int f_vertices(GETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  for (int k = 0; k < 3; k++) v[k] = s->m.fv[id][k] + 1;
  *n = 3;
  return TDS_OK;
}
static int f_edges(GETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  for (int k = 0; k < 3; k++) {
    int32_t r = s->m.fe[id][k];
    v[k] = (TDS_OID(r) + 1) * (TDS_OREV(r) ? -1 : 1);
  }
  *n = 3;
  return TDS_OK;
}
static int fcon_set(SETTER_ARGS) {
  tds_cmask mask;
  int rc = cons_mask(ctx, s, a, id, v, n, &mask);
  if (rc) return rc;
  s->m.fcon[id] = mask;
  s->m.topo_gen++;
  return TDS_OK;
}

static const tds_attr facet_rows[] = {
    RO(TDS_FACET, "area", TDS_AT_REAL, 1, f_area),
    ORIGINAL(TDS_FACET),
    RO(TDS_FACET, "vertices", TDS_AT_VERTEX, 3, f_vertices),
    RO(TDS_FACET, "edges", TDS_AT_INT, 3, f_edges),
    ROW(.name = "frontbody", .kind = TDS_FACET, .type = TDS_AT_BODY, .size = 1,
        .get = f_body_get, .set = f_body_set),
    ROW(.name = "backbody", .kind = TDS_FACET, .type = TDS_AT_BODY, .size = 1,
        .get = f_body_get,
        .set = f_body_set),
    ROW(.name = "constraints", .alias = "constraint", .fe_alias = "constraint",
        .kind = TDS_FACET, .type = TDS_AT_CONS, .size = TDS_MAX_CON, .io = FE_DECL,
        .get = get_cons, .set = fcon_set),
    FLAGROW(TDS_FACET, "fixed", NULL, NULL, TDS_FIXED, FE_DECL),
    FLAGROW(TDS_FACET, "no_refine", NULL, "norefine", TDS_NO_REFINE, FE_DECL),
    FLAGROW(TDS_FACET, "nodisplay", "no_display", "no_display", TDS_NODISPLAY, FE_DECL),
    FLAGROW(TDS_FACET, "noncontent", NULL, NULL, TDS_NONCONTENT, FE_DECL),
    ROW(.name = "tension", .alias = "density", .fe_alias = "density", .kind = TDS_FACET,
        .type = TDS_AT_REAL, .size = 1, .io = FE_DECL, .dflt = 1, .get = get_dcol,
        .set = f_tension_set, .off = OFF(ften)),
    ROW(.name = "color", .fe_alias = "colour frontcolor", .kind = TDS_FACET,
        .type = TDS_AT_COLOR, .size = 1, .io = FE_DECL, .dflt = 15, .get = get_scol,
        .set = f_color_set, .off = OFF(fcolor)),
};

/* ---- bodies ----
** A body has a target volume (TDS_TARGET, bpressure then its Lagrange
** multiplier) or a prescribed pressure (TDS_PRESSURE), never both. */

static int b_volume(GETTER_ARGS) {
  UNUSED(a);
  int rc = tds_surf_update(ctx, s);
  return rc ? rc : one(v, n, s->m.bvol[id]);
}
static int b_target_get(GETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  *n = 0;
  if (s->m.bflags[id] & TDS_TARGET) one(v, n, s->m.btarget[id]);
  return TDS_OK;
}
static int b_target_set(SETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  tds_mesh *m = &s->m;
  if (!n) {
    m->bflags[id] &= ~TDS_TARGET;
  } else {
    m->btarget[id] = v[0];
    m->bflags[id] = (m->bflags[id] | TDS_TARGET) & ~TDS_PRESSURE;
  }
  return TDS_OK;
}
static int b_pressure_set(SETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  tds_mesh *m = &s->m;
  if (!n) {
    m->bflags[id] &= ~TDS_PRESSURE;
  } else {
    m->bpressure[id] = v[0];
    m->bflags[id] = (m->bflags[id] | TDS_PRESSURE) & ~TDS_TARGET;
  }
  return TDS_OK;
}
static int b_pressure_dumped(const tds_surf *s, tds_id id) {
  return (s->m.bflags[id] & (TDS_PRESSURE | TDS_TARGET)) == TDS_PRESSURE;
}
static int b_lagrange_set(SETTER_ARGS) {
  UNUSED(a);
  if (!n) return tds_seterr(ctx, TDS_ERANGE, "body %d: lagrange_multiplier cannot be unset",
                            id + 1);
  s->m.bpressure[id] = v[0];
  return TDS_OK;
}
static int b_target_dumped(const tds_surf *s, tds_id id) {
  return (s->m.bflags[id] & TDS_TARGET) != 0;
}
static int b_volconst_set(SETTER_ARGS) {
  UNUSED(ctx);
  UNUSED(a);
  tds_mesh *m = &s->m;
  m->bvolconst[id] = n ? v[0] : 0;
  if (n) m->bflags[id] |= TDS_VOLCONST;
  else m->bflags[id] &= ~TDS_VOLCONST;
  return TDS_OK;
}
static int b_volconst_dumped(const tds_surf *s, tds_id id) {
  return (s->m.bflags[id] & TDS_VOLCONST) || s->m.bvolconst[id] != 0;
}
/* Evolver: declaring any density, even 0, turns gravity on. */
static int b_density_set(SETTER_ARGS) {
  UNUSED(a);
  if (!n) return tds_seterr(ctx, TDS_ERANGE, "body %d: density cannot be unset", id + 1);
  s->m.bdensity[id] = v[0];
  s->gravity_on = 1;
  return TDS_OK;
}
static int b_density_dumped(const tds_surf *s, tds_id id) {
  return s->m.bdensity[id] != 0 || s->gravity_on;
}

static const tds_attr body_rows[] = {
    ORIGINAL(TDS_BODY),
    ROW(.name = "volume", .excl = "pressure", .kind = TDS_BODY, .type = TDS_AT_REAL, .size = 1,
        .io = TDS_AT_DECL,
        .get = b_volume, .set = b_target_set),
    ROW(.name = "target", .excl = "pressure", .fe = "volume", .kind = TDS_BODY,
        .type = TDS_AT_REAL, .size = 1,
        .io = TDS_AT_FE, .get = b_target_get, .set = b_target_set, .dumped = b_target_dumped),
    ROW(.name = "lagrange_multiplier", .kind = TDS_BODY, .type = TDS_AT_REAL, .size = 1,
        .io = TDS_AT_FE, .get = get_dcol, .set = b_lagrange_set, .dumped = b_target_dumped,
        .off = OFF(bpressure)),
    ROW(.name = "pressure", .excl = "target volume", .kind = TDS_BODY, .type = TDS_AT_REAL,
        .size = 1, .io = FE_DECL,
        .get = get_dcol, .set = b_pressure_set, .dumped = b_pressure_dumped,
        .off = OFF(bpressure)),
    ROW(.name = "volconst", .kind = TDS_BODY, .type = TDS_AT_REAL, .size = 1, .io = FE_DECL,
        .get = get_dcol, .set = b_volconst_set, .dumped = b_volconst_dumped,
        .off = OFF(bvolconst)),
    ROW(.name = "density", .kind = TDS_BODY, .type = TDS_AT_REAL, .size = 1, .io = FE_DECL,
        .get = get_dcol, .set = b_density_set, .dumped = b_density_dumped,
        .off = OFF(bdensity)),
};

#define N(a) ((int)(sizeof a / sizeof *a))
const tds_attr *const tds_attr_rows[TDS_NKINDS] = {vertex_rows, edge_rows, facet_rows,
                                                   body_rows};
const int tds_attr_nrows[TDS_NKINDS] = {N(vertex_rows), N(edge_rows), N(facet_rows),
                                        N(body_rows)};
