/* lua_torus.c: Lua bindings of the torus model (torus.h):
**   tds.torus() -> 0 (none), 1 (TORUS) or 2 (TORUS_FILLED)
**   tds.symmetry_group() -> the SYMMETRY_GROUP's name, or nil
**   tds.wrap_compose(a, b) -> code   Evolver's wrap_compose: a first, then b
**   tds.wrap_inverse(a) -> code      Evolver's wrap_inverse
**   tds.periods() -> {{x, y, z}, {x, y, z}, {x, y, z}} or nil
**   tds.wrap_vertex(v, code)   Evolver's wrap_vertex (code: a wrap code)
**   tds.rewrap() -> n          vertices moved into the unit cell
**   tds.detorus()              the surface as drawn, no torus any more
**   tds.torus_display([mode]) -> mode   "raw", "connected" or "clipped"
**   tds.display_origin([{x, y, z} | false]) -> the previous {x, y, z} or nil */
#include "lua_tds.h"

#include <math.h>
#include <string.h>

#include "snap.h"
#include "gather.h"
#include "symgroup.h"
#include "torus.h"

static int l_torus(lua_State *L) {
  lua_pushinteger(L, TDS_STATE(L)->s.m.torus);
  return 1;
}

static int l_symmetry_group(lua_State *L) {
  int id = TDS_STATE(L)->s.m.sym;
  if (!id) return 0;
  lua_pushstring(L, tds_sym_name(id));
  return 1;
}

/* The internal wrap of Evolver code argument i of fn in the surface's
** group (the torus model's translations without SYMMETRY_GROUP). */
static int32_t check_wrap(lua_State *L, const tds_mesh *m, int i, const char *fn) {
  double code = tds_lua_checkfinite(L, i, "wrap code");
  int32_t w = 0;
  if (!m->torus) return tds_lua_error(L, "%s needs the torus model or a SYMMETRY_GROUP", fn);
  int rc = m->sym > TDS_SYM_TORUS ? tds_sym_from_code(m->sym, m->symp, code, &w)
                                  : tds_torus_wrap_from_code(code, &w);
  if (rc != TDS_OK) return tds_lua_error(L, "%s: %f is no wrap code of the surface's group", fn, code);
  return w;
}

static double code_of(const tds_mesh *m, int32_t w) {
  return m->sym > TDS_SYM_TORUS ? tds_sym_code(m->sym, w) : tds_torus_wrap_code(w);
}

static int l_wrap_compose(lua_State *L) {
  const tds_mesh *m = &TDS_STATE(L)->s.m;
  int32_t a = check_wrap(L, m, 1, "wrap_compose"), b = check_wrap(L, m, 2, "wrap_compose");
  if (!tds_mesh_rotates(m) && tds_wrap_overflows(a, b))
    return tds_lua_error(L, "wrap_compose: the sum leaves the range of wrap codes");
  /* a first, then b; genus2's runs compose as Evolver's do (measured:
  ** wrap_compose(0x10, 0x21) is 0x20, the run G_0 G_1, b first) */
  int32_t w = m->sym == TDS_SYM_GENUS2 ? tds_wrap_mul(m, a, b) : tds_wrap_mul(m, b, a);
  if (w == TDS_SYM_OUTSIDE)
    return tds_lua_error(L, "wrap_compose: the product of %f and %f is no wrap code of "
                      "SYMMETRY_GROUP \"genus2\" (its codes name runs G_a ... G_(b-1))",
                      code_of(m, a), code_of(m, b));
  lua_pushnumber(L, code_of(m, w));
  return 1;
}

static int l_wrap_inverse(lua_State *L) {
  const tds_mesh *m = &TDS_STATE(L)->s.m;
  lua_pushnumber(L, code_of(m, tds_wrap_inv(m, check_wrap(L, m, 1, "wrap_inverse"))));
  return 1;
}

static int l_periods(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  if (!st->s.m.torus || st->s.m.sym > TDS_SYM_TORUS) return 0; /* no periods */
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; i++) {
    lua_createtable(L, 3, 0);
    for (int j = 0; j < 3; j++) {
      lua_pushnumber(L, st->s.m.period[i][j]);
      lua_rawseti(L, -2, j + 1);
    }
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

static int l_wrap_vertex(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_id v = lua_isnumber(L, 1) ? (tds_id)(luaL_checknumber(L, 1) - 1)
                                : tds_check_elem(L, st, 1, TDS_VERTEX, NULL);
  double code = tds_lua_checkfinite(L, 2, "wrap code");
  int32_t w;
  if (tds_torus_wrap_from_code(code, &w) != TDS_OK)
    return tds_lua_error(L, "wrap_vertex: %f is not a wrap code (6 bits per period)", code);
  int rc = tds_torus_wrap_vertex(&st->ctx, &st->s, v, w);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_surf_update(&st->ctx, &st->s);
  return 0;
}

static int l_rewrap(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_snap sn;
  int rc = tds_snap_take(&st->ctx, &st->s, &sn);
  int32_t n = 0;
  if (rc == TDS_OK) rc = tds_snap_end(&st->ctx, &st->s, &sn, tds_torus_rewrap(&st->ctx, &st->s, &n));
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_surf_update(&st->ctx, &st->s);
  lua_pushinteger(L, n);
  return 1;
}

static int l_detorus(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int draw = st->s.m.draw;
  if (st->s.str && st->s.m.torus && draw != TDS_DRAW_RAW) { /* films only, so far */
    tds_warnf(&st->ctx, "detorus: %s mode is not supported yet in the string model: "
                        "raw cells (each cell as drawn from its first vertex)\n",
              draw == TDS_DRAW_CLIPPED ? "clipped" : "connected");
    st->s.m.draw = TDS_DRAW_RAW;
  }
  int rc = tds_torus_detorus(&st->ctx, &st->s.m, NULL);
  st->s.m.draw = draw;
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_surf_update(&st->ctx, &st->s);
  return 0;
}

static const char *const draw_names[] = {"raw", "connected", "clipped", NULL};

static int l_torus_display(lua_State *L) {
  tds_mesh *m = &TDS_STATE(L)->s.m;
  int was = m->draw;
  if (!lua_isnoneornil(L, 1)) {
    const char *want = lua_type(L, 1) == LUA_TSTRING ? lua_tostring(L, 1) : NULL;
    int d = 0;
    while (draw_names[d] && (!want || strcmp(draw_names[d], want))) d++;
    if (!draw_names[d])
      return tds_lua_error(L, "torus_display: the mode is \"raw\", \"connected\" or \"clipped\", not %s",
                           want ? want : luaL_typename(L, 1));
    if (d == TDS_DRAW_CLIPPED && tds_mesh_rotates(m))
      return tds_lua_error(L, "clipped: SYMMETRY_GROUP \"%s\" has no unit cell to clip to "
                              "(use raw_cells or connected)", tds_sym_name(m->sym));
    m->draw = d;
  }
  lua_pushstring(L, draw_names[was]);
  return 1;
}

static int l_display_origin(lua_State *L) {
  tds_mesh *m = &TDS_STATE(L)->s.m;
  int had = m->has_origin;
  double was[3];
  memcpy(was, m->origin, sizeof was);
  if (lua_istable(L, 1)) {
    double o[3];
    for (int i = 0; i < 3; i++) {
      lua_geti(L, 1, i + 1);
      if (!lua_isnumber(L, -1)) return tds_lua_error(L, "display_origin: {x, y, z} of numbers");
      o[i] = lua_tonumber(L, -1);
      if (!isfinite(o[i])) return tds_lua_error(L, "display_origin: coordinate %d is not finite", i + 1);
      lua_pop(L, 1);
    }
    memcpy(m->origin, o, sizeof o);
    m->has_origin = 1;
  } else if (lua_isboolean(L, 1) && !lua_toboolean(L, 1)) {
    m->has_origin = 0;
  } else if (!lua_isnoneornil(L, 1)) {
    return tds_lua_error(L, "display_origin: {x, y, z} or false, not %s", luaL_typename(L, 1));
  }
  if (!had) return 0;
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; i++) {
    lua_pushnumber(L, was[i]);
    lua_seti(L, -2, i + 1);
  }
  return 1;
}

void tds_open_torus(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"torus", l_torus},
                                 {"periods", l_periods},
                                 {"symmetry_group", l_symmetry_group},
                                 {"wrap_compose", l_wrap_compose},
                                 {"wrap_inverse", l_wrap_inverse},
                                 {"wrap_vertex", l_wrap_vertex},
                                 {"rewrap", l_rewrap},
                                 {"detorus", l_detorus},
                                 {"torus_display", l_torus_display},
                                 {"display_origin", l_display_origin},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
