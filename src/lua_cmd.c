/* lua_cmd.c: command primitives (iterate, refine, equiangulate, average,
** scale, gravity, parameters, totals, checks). The prelude gives them
** their user names (g, r, u, V, ...). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "string_model.h"
#include "iterate.h"
#include "jiggle.h"
#include "lua_tds.h"
#include "symgroup.h"
#include "symmetry.h"
#include "recalc.h"
#include "topo.h"

static int check_rc(lua_State *L, tds_state *st, int rc) {
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc); /* EINTR: the hook stays armed */
  return 0;
}

static void print_counts(tds_state *st) {
  const tds_mesh *m = &st->s.m;
  int32_t nf = tds_surf_count(&st->s, TDS_FACET);
  tds_printf(&st->ctx, "Vertices: %d  Edges: %d  Facets: %d  Bodies: %d  Facetedges: %d\n",
             tds_mesh_count(m, TDS_VERTEX), tds_mesh_count(m, TDS_EDGE), nf,
             tds_mesh_count(m, TDS_BODY), 3 * nf);
}

/* tds.iterate(n) */
static int l_iterate(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  lua_Integer n = luaL_optinteger(L, 1, 1);
  luaL_argcheck(L, n >= 0 && n <= 1000000000, 1, "iteration count out of range");
  check_rc(L, st, tds_iterate(&st->ctx, &st->s, (int)n));
  return 0;
}

typedef int (*set_cmd)(tds_ctx *, tds_surf *, const uint8_t *, int32_t *);

/* Run a command on an optional element set (argument 1) and push the
** count it reports. */
static int32_t run_on_set(lua_State *L, tds_state *st, int kind, set_cmd fn) {
  uint8_t *sel = tds_lua_selection(L, st, 1, kind);
  int32_t n = 0;
  int rc = fn(&st->ctx, &st->s, sel, &n);
  free(sel);
  check_rc(L, st, rc);
  lua_pushinteger(L, n);
  return n;
}

/* tds.refine([edges]) -> number of edges split */
static int l_refine(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int32_t n = run_on_set(L, st, TDS_EDGE, tds_refine);
  if (lua_isnoneornil(L, 1))
    print_counts(st);
  else
    tds_printf(&st->ctx, "Edges refined: %d\n", n);
  return 1;
}

/* tds.equiangulate([edges [, repeat]]) -> flips: one pass as Evolver, or
** with repeat until no edge fails the test. */
static int l_equiangulate(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int rep = lua_toboolean(L, 2);
  int32_t n = run_on_set(L, st, TDS_EDGE, rep ? tds_equiangulate : tds_equiangulate_once);
  tds_printf(&st->ctx, "Edges switched in equiangulation: %d\n", n);
  return 1;
}

/* tds.vertex_average([vertices [, rule [, sequential]]]) -> vertices
** moved. rule: "V" (Evolver's V, the default), "raw" (rawv), "rawest"
** (rawestv) or "centroid" (tds's earlier rule); sequential moves each
** vertex before computing the next (Evolver's vertex_average). */
static int l_vertex_average(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  static const char *const rules[] = {"V", "raw", "rawest", "centroid", NULL};
  int mode = luaL_checkoption(L, 2, "V", rules);
  int seq = lua_toboolean(L, 3);
  uint8_t *sel = tds_lua_selection(L, st, 1, TDS_VERTEX);
  int32_t n = 0;
  int rc = tds_vertex_average_mode(&st->ctx, &st->s, sel, mode, seq, &n);
  free(sel);
  check_rc(L, st, rc);
  lua_pushinteger(L, n);
  tds_printf(&st->ctx, "Vertex averaging done.\n");
  return 1;
}

/* tds.jiggle([temperature [, vertices]]) -> vertices moved (jiggle.h);
** the temperature defaults to Evolver's jiggle_temperature, 0.05. */
static int l_jiggle(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  double t = luaL_optnumber(L, 1, 0.05);
  uint8_t *sel = tds_lua_selection(L, st, 2, TDS_VERTEX);
  int32_t n = 0;
  int rc = tds_jiggle(&st->ctx, &st->s, t, sel, &n);
  free(sel);
  check_rc(L, st, rc);
  lua_pushinteger(L, n);
  return 1;
}

/* tds.totals() -> energy, area (recomputed) */
static int l_totals(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  check_rc(L, st, tds_surf_update(&st->ctx, &st->s));
  lua_pushnumber(L, st->s.energy);
  lua_pushnumber(L, st->s.area);
  return 2;
}

/* tds.pressures(): recompute body pressures at the current shape. */
static int l_pressures(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  check_rc(L, st, tds_pressures(&st->ctx, &st->s));
  return 0;
}

/* tds.scale([s]) -> current scale; tds.scale(s) fixes it, tds.scale(nil)
** via tds.optimize() returns to optimizing mode. */
static int l_scale(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  if (!lua_isnoneornil(L, 1)) {
    double sc = tds_lua_checkfinite(L, 1, "scale");
    if (sc < 0) tds_lua_error(L, "scale must not be negative, not %f", sc);
    st->s.scale = sc;
    st->s.fixed_scale = 1;
  }
  lua_pushnumber(L, st->s.scale);
  lua_pushboolean(L, st->s.fixed_scale);
  return 2;
}

/* A scale limit: a positive normal number. Infinity, NaN, 0 and
** subnormals would make the line search loop forever (its smallest trial
** scale is 1e-12 times the limit). */
static double check_scale_limit(lua_State *L, int i) {
  double lim = tds_lua_checkfinite(L, i, "scale limit");
  if (!(lim > 0 && isnormal(lim)))
    tds_lua_error(L, "scale limit must be a positive normal number, not %f", lim);
  return lim;
}

/* tds.optimize([limit]): optimizing scale, with an optional upper bound. */
static int l_optimize(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  if (!lua_isnoneornil(L, 1)) {
    st->s.scale_limit = check_scale_limit(L, 1);
  }
  st->s.fixed_scale = 0;
  return 0;
}

/* tds.gravity([G [, on]]) -> G, on */
static int l_gravity(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  if (!lua_isnoneornil(L, 1)) st->s.gravity = tds_lua_checkfinite(L, 1, "gravity constant");
  if (!lua_isnoneornil(L, 2)) st->s.gravity_on = lua_toboolean(L, 2);
  lua_pushnumber(L, st->s.gravity);
  lua_pushboolean(L, st->s.gravity_on);
  return 2;
}

/* tds.check(): run the mesh checker; raises with the broken relation.
** Then warns about inconsistent bodies and zero-area facets. Returns true
** and the number of warnings. */
static int l_check(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  if (tds_mesh_adjacency(&st->s.m) != TDS_OK) return tds_lua_error(L, "out of memory");
  check_rc(L, st, tds_mesh_check(&st->ctx, &st->s.m));
  if (st->s.str) check_rc(L, st, tds_strings_check(&st->ctx, &st->s)); /* cells */
  lua_pushboolean(L, 1);
  lua_pushinteger(L, tds_mesh_body_warnings(&st->ctx, &st->s.m, ""));
  return 2;
}

/* tds.body_warnings(): only the warnings of check(), prefixed with the
** user's file and line (the prelude calls it after bodies{}). */
static int l_body_warnings(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_lua_where(L);
  lua_pushinteger(L, tds_mesh_body_warnings(&st->ctx, &st->s.m, lua_tostring(L, -1)));
  return 1;
}

/* tds.param(name [, value]) -> value or nil */
static int l_param(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  size_t len;
  const char *name = luaL_checklstring(L, 1, &len);
  if (!lua_isnoneornil(L, 2)) {
    lua_pushfstring(L, "parameter %s", name);
    double v = tds_lua_checkfinite(L, 2, lua_tostring(L, -1));
    lua_pop(L, 1);
    if (tds_surf_param_set(&st->s, name, v) < 0) return tds_lua_error(L, "out of memory");
    st->s.m.coord_gen++;
  }
  int i = tds_surf_param_find(&st->s, name, len);
  if (i < 0) return 0;
  lua_pushnumber(L, st->s.parval[i]);
  return 1;
}

/* tds.quiet([on]) -> previous setting */
static int l_quiet(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  lua_pushboolean(L, st->ctx.quiet);
  if (!lua_isnone(L, 1)) st->ctx.quiet = lua_toboolean(L, 1);
  return 1;
}

/* tds.setting(name [, value]): model switches and iteration state. */
static int l_setting(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  static const char *const names[] = {"symmetric_content", "scale_limit",
                                      "constraint_tolerance", "gap_constant",
                                      "iterations", "conj_grad", "view_transforms",
                                      "check_increase", "random_seed",
                                      "evolver_line_search", "autopop",
                                      "immediate_autopop", "autochop",
                                      "autochop_length", "area_normalization", "pop_to_edge",
                                      "pop_to_face", "pop_enjoin", NULL};
  int which = luaL_checkoption(L, 1, NULL, names);
  tds_surf *s = &st->s;
  int set = !lua_isnone(L, 2);
  /* the switches take true or false: 0, "off" or 5 is an error, not on */
  static const char is_switch[] = {1, 0, 0, 0, 0, 1, 0, 1, 0, 1, 1, 1, 1, 0, 1, 1, 1, 1};
  if (set && is_switch[which] && !lua_isboolean(L, 2))
    return tds_lua_error(L, "tds.setting: %s is true or false, not %s", names[which],
                         luaL_typename(L, 2));
  switch (which) {
  case 0:
    if (set) s->symmetric_content = lua_toboolean(L, 2);
    lua_pushboolean(L, s->symmetric_content);
    break;
  case 1:
    if (set) s->scale_limit = check_scale_limit(L, 2);
    lua_pushnumber(L, s->scale_limit);
    break;
  case 2:
    if (set) {
      double tol = tds_lua_checkfinite(L, 2, "constraint tolerance");
      if (!(tol > 0)) tds_lua_error(L, "constraint tolerance must be positive, not %f", tol);
      s->constraint_tol = tol;
    }
    lua_pushnumber(L, s->constraint_tol);
    break;
  case 3:
    if (set) s->gap_constant = tds_lua_checkfinite(L, 2, "gap constant");
    lua_pushnumber(L, s->gap_constant);
    break;
  case 4:
    lua_pushinteger(L, (lua_Integer)s->iterations);
    break;
  case 6: /* read-only: Evolver's transform_count - 1 (lua_view.c) */
    lua_pushinteger(L, s->view_transforms > 1 ? s->view_transforms - 1 : 0);
    break;
  case 7:
    if (set) s->check_increase = lua_toboolean(L, 2);
    lua_pushboolean(L, s->check_increase);
    break;
  case 9:
    if (set) s->evolver_ls = lua_toboolean(L, 2);
    lua_pushboolean(L, s->evolver_ls);
    break;
  case 10:
    if (set) s->autopop = lua_toboolean(L, 2);
    lua_pushboolean(L, s->autopop);
    break;
  case 11:
    if (set) s->immediate_autopop = lua_toboolean(L, 2);
    lua_pushboolean(L, s->immediate_autopop);
    break;
  case 12:
    if (set) s->autochop = lua_toboolean(L, 2);
    lua_pushboolean(L, s->autochop);
    break;
  case 13:
    if (set) {
      double len = tds_lua_checkfinite(L, 2, "autochop length");
      if (len < 0) tds_lua_error(L, "autochop length must not be negative, not %f", len);
      s->autochop_length = len;
    }
    lua_pushnumber(L, s->autochop_length);
    break;
  case 14:
    if (set) s->area_normalization = lua_toboolean(L, 2);
    lua_pushboolean(L, s->area_normalization);
    break;
  case 15: /* Evolver's pop_to_edge and pop_to_face exclude each other */
  case 16: {
    int *mine = which == 15 ? &s->pop_to_edge : &s->pop_to_face;
    if (set) {
      *mine = lua_toboolean(L, 2);
      if (*mine) *(which == 15 ? &s->pop_to_face : &s->pop_to_edge) = 0;
    }
    lua_pushboolean(L, *mine);
    break;
  }
  case 17:
    if (set) s->pop_enjoin = lua_toboolean(L, 2);
    lua_pushboolean(L, s->pop_enjoin);
    break;
  case 8: /* the jiggle's generator state (jiggle.h) */
    if (set) s->rng = (uint64_t)luaL_checkinteger(L, 2);
    lua_pushinteger(L, (lua_Integer)s->rng);
    break;
  default:
    if (set) {
      s->conj_grad = lua_toboolean(L, 2);
      s->cg_norm2 = 0; /* a fresh history */
    }
    lua_pushboolean(L, s->conj_grad);
  }
  return 1;
}

/* tds.recalc(): re-place vertices from the parameters (recalc.h). */
static int l_recalc(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  check_rc(L, st, tds_recalc(&st->ctx, &st->s));
  return 0;
}

/* tds.memory() -> bytes held by the mesh store */
static int l_memory(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  lua_pushinteger(L, (lua_Integer)tds_mesh_bytes(&st->s.m));
  return 1;
}

void tds_open_cmd(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {
      {"iterate", l_iterate},   {"refine", l_refine},
      {"equiangulate", l_equiangulate}, {"vertex_average", l_vertex_average},
      {"jiggle", l_jiggle},
      {"totals", l_totals},     {"pressures", l_pressures},
      {"scale", l_scale},       {"optimize", l_optimize},
      {"gravity", l_gravity},   {"check", l_check},
      {"param", l_param},       {"quiet", l_quiet},
      {"setting", l_setting},   {"memory", l_memory},
      {"recalc", l_recalc},     {"body_warnings", l_body_warnings},
      {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
