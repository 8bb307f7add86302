/* lua_newton.c: Newton steps and eigenvalues (newton.h) for Lua:
** tds.hessian, tds.hessian_seek, tds.saddle, tds.eigenprobe, tds.ritz,
** tds.move, tds.eigenvector, tds.vertex_normal, tds.hessian_setting. The settings and the
** last ritz eigenvector live in a userdata in the registry (no globals). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lua_tds.h"
#include "newton.h"


typedef struct nstate {
  tds_newton_opts o;
  double (*vec)[3];   /* eigenvector of the last ritz, per vertex slot */
  int32_t nv;
  uint64_t topo;      /* topo_gen it belongs to */
  double last;        /* the first eigenvalue of the last ritz (Evolver's
                         last_eigenvalue), 0 before any */
  tds_inertia counts; /* of the last hessian, hessian_seek, eigenprobe or
                         ritz (Evolver's eigenneg, eigenzero, eigenpos),
                         0 before any */
  double scale;       /* the step of the last hessian_seek or saddle, 1
                         after hessian (Evolver's last_hessian_scale), 0
                         before any */
} nstate;

static int ns_gc(lua_State *L) {
  nstate *ns = lua_touserdata(L, 1);
  free(ns->vec);
  ns->vec = NULL;
  return 0;
}

/* The surface's own settings and eigenvector (anchored to its state). */
static nstate *get_ns(lua_State *L) {
  tds_lua_kept(L, TDS_STATE(L), "newton");
  nstate *ns = lua_touserdata(L, -1);
  lua_pop(L, 1);
  return ns;
}

static int check_rc(lua_State *L, tds_state *st, int rc) {
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  return 0;
}

/* tds.hessian() -> energy */
static int l_hessian(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  nstate *ns = get_ns(L);
  tds_inertia in = {0};
  check_rc(L, st, tds_newton_step(&st->ctx, &st->s, &ns->o, 0, &in, NULL));
  ns->counts = in;
  ns->scale = 1; /* Evolver's last_hessian_scale after hessian (measured) */
  lua_pushnumber(L, st->s.energy);
  lua_pushinteger(L, in.neg);
  return 2;
}

/* tds.hessian_seek([maxscale = 10]) -> energy, scale, index (Evolver's
** manual says the default is 1; evolver-nox-d 2.70 seeks up to 10 without
** one: on the cube's g; r; hessian_seek it tries 1.6; newton.c's seek) */
static int l_hessian_seek(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  nstate *ns = get_ns(L);
  double mx = lua_isnoneornil(L, 1) ? 10 : tds_lua_checkfinite(L, 1, "hessian_seek scale");
  if (!(mx > 0)) return tds_lua_error(L, "hessian_seek: the largest scale must be positive, not %f", mx);
  tds_inertia in = {0};
  double t = 0;
  check_rc(L, st, tds_newton_step(&st->ctx, &st->s, &ns->o, mx, &in, &t));
  ns->counts = in;
  ns->scale = t;
  lua_pushnumber(L, st->s.energy);
  lua_pushnumber(L, t);
  lua_pushinteger(L, in.neg);
  return 3;
}

/* tds.saddle([maxscale]) -> lowest eigenvalue, moved, step */
static int l_saddle(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  nstate *ns = get_ns(L);
  double mx = lua_isnoneornil(L, 1) ? 0 : tds_lua_checkfinite(L, 1, "saddle scale");
  if (mx < 0) return tds_lua_error(L, "saddle: the largest scale must not be negative, not %f", mx);
  double low = 0, step = 0;
  check_rc(L, st, tds_newton_saddle(&st->ctx, &st->s, &ns->o, mx, &low, &step));
  ns->scale = step;
  ns->last = low; /* Evolver's last_eigenvalue after saddle too */
  lua_pushnumber(L, low);
  lua_pushboolean(L, step != 0);
  lua_pushnumber(L, step);
  return 3;
}

static void print_counts(tds_state *st, nstate *ns, tds_inertia in) {
  ns->counts = in;
  tds_printf(&st->ctx, "Eigencounts:    %d <,  %d ==,  %d > \n", (int)in.neg, (int)in.zero,
             (int)in.pos);
}

/* tds.eigenprobe(c [, iterations]) -> below, equal, above [, eigenvalue]
** (prints Eigencounts; with iterations, inverse iteration towards the
** eigenvalue nearest c, which becomes last_eigenvalue and the eigenvector
** move follows) */
static int l_eigenprobe(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  nstate *ns = get_ns(L);
  double c = lua_isnoneornil(L, 1) ? 0 : tds_lua_checkfinite(L, 1, "eigenprobe value");
  tds_inertia in;
  if (lua_isnoneornil(L, 2)) {
    check_rc(L, st, tds_newton_probe(&st->ctx, &st->s, &ns->o, c, &in));
    print_counts(st, ns, in);
    lua_pushinteger(L, in.neg);
    lua_pushinteger(L, in.zero);
    lua_pushinteger(L, in.pos);
    return 3;
  }
  lua_Integer n = luaL_checkinteger(L, 2);
  if (n < 0 || n > 1000000)
    return tds_lua_error(L, "eigenprobe: the iteration count %d is out of range", (int)n);
  tds_surf *s = &st->s;
  double (*vec)[3] = calloc((size_t)s->m.nv + 1, sizeof *vec);
  if (!vec) return tds_lua_error(L, "out of memory");
  double val = NAN;
  int iters = 0;
  int rc = tds_newton_invit(&st->ctx, s, &ns->o, c, (int)n, &val, &in, vec, &iters);
  if (rc != TDS_OK) {
    free(vec);
    return tds_lua_fail(L, st, rc);
  }
  ns->counts = in;
  lua_pushinteger(L, in.neg);
  lua_pushinteger(L, in.zero);
  lua_pushinteger(L, in.pos);
  if (isnan(val)) { /* no iteration (n = 0, or nothing can move) */
    free(vec);
    return 3;
  }
  ns->last = val;
  free(ns->vec);
  ns->vec = vec;
  ns->nv = s->m.nv;
  ns->topo = s->m.topo_gen;
  lua_pushnumber(L, val);
  return 4;
}

/* tds.ritz(shift, n) -> {eigenvalues nearest shift}, below, equal, above */
static int l_ritz(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  nstate *ns = get_ns(L);
  double shift = tds_lua_checkfinite(L, 1, "ritz shift");
  lua_Integer n = luaL_optinteger(L, 2, 5);
  if (n < 0 || n > 100000) return tds_lua_error(L, "ritz: the count %d is out of range", (int)n);
  tds_surf *s = &st->s;
  double *vals = malloc(((size_t)n + 1) * sizeof *vals);
  double (*vec)[3] = calloc((size_t)s->m.nv + 1, sizeof *vec);
  if (!vals || !vec) {
    free(vals);
    free(vec);
    return tds_lua_error(L, "out of memory");
  }
  int32_t got = 0;
  int iters = 0;
  tds_inertia in = {0};
  double change = 0;
  int rc = tds_newton_ritz(&st->ctx, s, &ns->o, shift, (int32_t)n, vals, &got, &in, vec, &iters,
                           &change);
  if (rc != TDS_OK) {
    free(vals);
    free(vec);
    return tds_lua_fail(L, st, rc);
  }
  print_counts(st, ns, in);
  lua_createtable(L, got, 0);
  for (int32_t i = 0; i < got; i++) {
    tds_printf(&st->ctx, "%3d.    %.15g\n", (int)i + 1, vals[i]);
    lua_pushnumber(L, vals[i]);
    lua_rawseti(L, -2, i + 1);
  }
  if (got)
    tds_printf(&st->ctx, "Iterations: %d. Total eigenvalue changes in last iteration: %.8g\n",
               iters, change);
  if (got) ns->last = vals[0];
  free(ns->vec);
  ns->vec = got ? vec : NULL;
  ns->nv = got ? s->m.nv : 0;
  ns->topo = s->m.topo_gen;
  if (!got) free(vec);
  free(vals);
  lua_pushinteger(L, in.neg);
  lua_pushinteger(L, in.zero);
  lua_pushinteger(L, in.pos);
  return 4;
}

static int have_vec(const nstate *ns, const tds_surf *s) {
  return ns->vec && ns->nv == s->m.nv && ns->topo == s->m.topo_gen;
}

/* tds.move(t): move t times along the last ritz eigenvector */
static int l_move(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  nstate *ns = get_ns(L);
  double t = tds_lua_checkfinite(L, 1, "move step");
  if (!have_vec(ns, &st->s))
    return tds_lua_error(L, "move: there is no eigenvector of this surface "
                            "(run ritz first; the surface's topology has changed since)");
  check_rc(L, st, tds_newton_move(&st->ctx, &st->s, &ns->o, (const double(*)[3])ns->vec,
                                  ns->nv, t));
  lua_pushnumber(L, st->s.energy);
  return 1;
}

/* tds.eigenvector(vertex) -> x, y, z of the last ritz eigenvector there */
static int l_eigenvector(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  nstate *ns = get_ns(L);
  tds_id v = tds_check_elem(L, st, 1, TDS_VERTEX, NULL);
  if (!have_vec(ns, &st->s))
    return tds_lua_nilmsg(L, "no eigenvector: run ritz first (or the surface changed since)");
  for (int i = 0; i < 3; i++) lua_pushnumber(L, ns->vec[v][i]);
  return 3;
}

/* tds.vertex_normal(v) -> x, y, z: Evolver's vertex_normal (newton.h,
** tds_vertex_normal_at) with the current hessian settings */
static int l_vertex_normal(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  nstate *ns = get_ns(L);
  tds_id v = tds_check_elem(L, st, 1, TDS_VERTEX, NULL);
  double n[3];
  check_rc(L, st, tds_vertex_normal_at(&st->ctx, &st->s, &ns->o, v, n));
  for (int i = 0; i < 3; i++) lua_pushnumber(L, n[i]);
  return 3;
}

/* tds.hessian_setting(name [, value]) -> value: hessian_normal,
** linear_metric, linear_metric_mix, hessian_diff, hessian_epsilon,
** hessian_special_normal, hessian_normal_one, hessian_normal_perp;
** last_eigenvalue, eigenneg, eigenzero, eigenpos, last_hessian_scale (read) */
static int l_setting(lua_State *L) {
  static const char *const names[] = {"hessian_normal", "linear_metric", "linear_metric_mix",
                                      "hessian_diff", "last_eigenvalue", "hessian_epsilon",
                                      "hessian_special_normal", "hessian_normal_one",
                                      "hessian_normal_perp", "eigenneg", "eigenzero",
                                      "eigenpos", "last_hessian_scale", NULL};
  nstate *ns = get_ns(L);
  int which = luaL_checkoption(L, 1, NULL, names);
  int set = !lua_isnone(L, 2);
  switch (which) {
  case 0:
    if (set) ns->o.normal = lua_toboolean(L, 2);
    lua_pushboolean(L, ns->o.normal);
    break;
  case 1:
    if (set) ns->o.linear_metric = lua_toboolean(L, 2);
    lua_pushboolean(L, ns->o.linear_metric);
    break;
  case 3:
    if (set) ns->o.diff = lua_toboolean(L, 2);
    lua_pushboolean(L, ns->o.diff);
    break;
  case 5:
    if (set) {
      double x = tds_lua_checkfinite(L, 2, "hessian_epsilon");
      if (!(x > 0)) return tds_lua_error(L, "hessian_epsilon must be positive, not %f", x);
      ns->o.epsilon = x;
    }
    lua_pushnumber(L, ns->o.epsilon);
    break;
  case 6:
    if (set) ns->o.special_normal = lua_toboolean(L, 2);
    lua_pushboolean(L, ns->o.special_normal);
    break;
  case 7:
    if (set) ns->o.normal_one = lua_toboolean(L, 2);
    lua_pushboolean(L, ns->o.normal_one);
    break;
  case 8:
    if (set) ns->o.normal_perp = lua_toboolean(L, 2);
    lua_pushboolean(L, ns->o.normal_perp);
    break;
  case 4: /* read-only */
    if (set) return tds_lua_error(L, "last_eigenvalue is read-only");
    lua_pushnumber(L, ns->last);
    break;
  case 12:
    if (set) return tds_lua_error(L, "last_hessian_scale is read-only");
    lua_pushnumber(L, ns->scale);
    break;
  case 9:
  case 10:
  case 11: {
    if (set) return tds_lua_error(L, "%s is read-only", names[which]);
    tds_inertia c = ns->counts;
    lua_pushinteger(L, which == 9 ? c.neg : which == 10 ? c.zero : c.pos);
    break;
  }
  default:
    if (set) {
      double x = tds_lua_checkfinite(L, 2, "linear_metric_mix");
      if (x < 0 || x > 1) return tds_lua_error(L, "linear_metric_mix must be in [0, 1], not %f", x);
      ns->o.metric_mix = x;
    }
    lua_pushnumber(L, ns->o.metric_mix);
  }
  return 1;
}

void tds_open_newton(lua_State *L, tds_state *st) {
  nstate *ns = lua_newuserdatauv(L, sizeof *ns, 0);
  memset(ns, 0, sizeof *ns);
  ns->o.normal = 1;       /* Evolver's defaults */
  ns->o.metric_mix = 0.5;
  ns->o.epsilon = 1e-10;
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, ns_gc);
  lua_setfield(L, -2, "__gc");
  lua_setmetatable(L, -2);
  tds_lua_keep(L, st, "newton");
  static const luaL_Reg fns[] = {
      {"hessian", l_hessian},       {"hessian_seek", l_hessian_seek},
      {"saddle", l_saddle},         {"eigenprobe", l_eigenprobe},
      {"ritz", l_ritz},             {"move", l_move},
      {"eigenvector", l_eigenvector}, {"hessian_setting", l_setting},
      {"vertex_normal", l_vertex_normal},
      {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
