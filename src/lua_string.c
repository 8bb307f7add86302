/* lua_string.c: Lua bindings of the string model's own commands
** (string_model.h):
**   tds.string_pop([vertices [, quiet_none]]) -> n   Evolver's o (and pop
**                           vertex ...) for strings: split the vertices
**                           (all if none) where four or more edges meet;
**                           prints "Vertices popped: n" as Evolver does
**                           (with quiet_none, only when n > 0: its pop).
**   tds.string_t1([edges]) -> n   Evolver's t1_edgeswap: the 2-D foam T1 on
**                           the given edges (all if none).
**   tds.facet_crosscut(f, t, h) -> edge id   Evolver's facet_crosscut.
**   tds.dimensions() -> surface, space   1 and 2 or 3 in the string model,
**                           2 and 3 otherwise (Evolver's surface_dimension
**                           and space_dimension). */
#include <stdlib.h>

#include "lua_tds.h"
#include "string_model.h"

static int l_string_pop(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  uint8_t *sel = tds_lua_selection(L, st, 1, TDS_VERTEX);
  int32_t n = 0;
  int rc = tds_strings_pop(&st->ctx, &st->s, sel, &n);
  free(sel);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  if (n > 0 || !lua_toboolean(L, 2)) tds_printf(&st->ctx, "Vertices popped: %d\n", n);
  lua_pushinteger(L, n);
  return 1;
}

static int l_string_t1(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  uint8_t *sel = tds_lua_selection(L, st, 1, TDS_EDGE);
  int32_t n = 0;
  int rc = tds_strings_t1(&st->ctx, &st->s, sel, &n);
  free(sel);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  lua_pushinteger(L, n);
  return 1;
}

/* tds.facet_crosscut(facet, tail, head) -> new edge id (ids or handles) */
static tds_id id_arg(lua_State *L, tds_state *st, int i, int kind) {
  if (lua_isinteger(L, i)) return (tds_id)(luaL_checkinteger(L, i) - 1);
  if (lua_isnumber(L, i)) return (tds_id)(lua_tonumber(L, i) - 1);
  return tds_check_elem(L, st, i, kind, NULL);
}

static int l_facet_crosscut(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_id f = id_arg(L, st, 1, TDS_FACET), t = id_arg(L, st, 2, TDS_VERTEX),
         h = id_arg(L, st, 3, TDS_VERTEX);
  if (t < 0 || t >= st->s.m.nv || !tds_alive(st->s.m.vflags, t) || h < 0 ||
      h >= st->s.m.nv || !tds_alive(st->s.m.vflags, h))
    return tds_lua_error(L, "facet_crosscut: no such vertex");
  tds_id e = TDS_NONE;
  int rc = tds_strings_crosscut(&st->ctx, &st->s, f, t, h, &e);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  lua_pushinteger(L, e + 1);
  return 1;
}

static int l_dimensions(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  lua_pushinteger(L, st->s.str ? 1 : 2);
  lua_pushinteger(L, st->s.str ? st->s.str->space_dim : 3);
  return 2;
}

void tds_open_string(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"string_pop", l_string_pop},
                                 {"string_t1", l_string_t1},
                                 {"facet_crosscut", l_facet_crosscut},
                                 {"dimensions", l_dimensions},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
