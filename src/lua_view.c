/* lua_view.c: view transforms (Evolver's VIEW_TRANSFORMS,
** VIEW_TRANSFORM_GENERATORS, transform_expr; lua/evoview.lua).
**
**   tds.view_transforms() -> { m1, m2, ... }, { swap1, ... }  the view
**                           transforms, each a 4x4 table m[i][j] (row i,
**                           column j), and their SWAP_COLORS flags
**                           (booleans); the identity alone when none are set
**   tds.view_transforms(list [, swaps])  replace them (all or nothing:
**                           every entry a finite number, at most TDS_MAX_VIEW)
**   tds.view_generators() -> { g1, g2, ... }, { swap1, ... }  the
**                           datafile's generators
*/
#include <string.h>

#include "lua_tds.h"

static void push_swaps(lua_State *L, int n, const uint8_t *sw) {
  lua_createtable(L, n, 0);
  for (int t = 0; t < n; t++) {
    lua_pushboolean(L, sw && sw[t]);
    lua_rawseti(L, -2, t + 1);
  }
}

static void push_list(lua_State *L, int n, const double (*m)[16]) {
  lua_createtable(L, n, 0);
  for (int t = 0; t < n; t++) {
    lua_createtable(L, 4, 0);
    for (int i = 0; i < 4; i++) {
      lua_createtable(L, 4, 0);
      for (int j = 0; j < 4; j++) {
        lua_pushnumber(L, m[t][4 * i + j]);
        lua_rawseti(L, -2, j + 1);
      }
      lua_rawseti(L, -2, i + 1);
    }
    lua_rawseti(L, -2, t + 1);
  }
}

static int l_view_transforms(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_surf *s = &st->s;
  if (lua_isnoneornil(L, 1)) {
    static const double id[1][16] = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    if (s->view_transforms && s->view) {
      push_list(L, s->view_transforms, (const double (*)[16])s->view);
      push_swaps(L, s->view_transforms, s->view_swap);
    } else {
      push_list(L, 1, id);
      push_swaps(L, 1, NULL);
    }
    return 2;
  }
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_Integer n = luaL_len(L, 1);
  if (n < 0 || n > TDS_MAX_VIEW) return tds_lua_error(L, "view_transforms: %d matrices, at most %d", (int)n, TDS_MAX_VIEW);
  double (*m)[16] = lua_newuserdatauv(L, (size_t)(n ? n : 1) * sizeof *m, 0);
  uint8_t *sw = lua_newuserdatauv(L, (size_t)(n ? n : 1), 0);
  int has_swaps = lua_istable(L, 2);
  for (lua_Integer t = 1; t <= n; t++) {
    sw[t - 1] = 0;
    if (has_swaps) {
      lua_rawgeti(L, 2, t);
      sw[t - 1] = (uint8_t)lua_toboolean(L, -1);
      lua_pop(L, 1);
    }
  }
  for (lua_Integer t = 1; t <= n; t++) {
    if (lua_rawgeti(L, 1, t) != LUA_TTABLE) return tds_lua_error(L, "view_transforms: matrix %d is not a table", (int)t);
    for (int i = 0; i < 4; i++) {
      if (lua_rawgeti(L, -1, i + 1) != LUA_TTABLE)
        return tds_lua_error(L, "view_transforms: matrix %d: row %d is not a table", (int)t, i + 1);
      for (int j = 0; j < 4; j++) {
        lua_rawgeti(L, -1, j + 1);
        int ok;
        m[t - 1][4 * i + j] = lua_tonumberx(L, -1, &ok);
        if (!ok) return tds_lua_error(L, "view_transforms: matrix %d: entry [%d][%d] is not a number", (int)t, i + 1, j + 1);
        lua_pop(L, 1);
      }
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  if (tds_surf_set_view(&st->ctx, s, 0, (int)n, (const double (*)[16])m, sw) != TDS_OK)
    return tds_lua_error(L, "view_transforms: %s", st->ctx.errmsg);
  return 0;
}

static int l_view_generators(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  push_list(L, st->s.nvgen, (const double (*)[16])st->s.vgen);
  push_swaps(L, st->s.nvgen, st->s.vgen_swap);
  return 2;
}

void tds_open_view(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"view_transforms", l_view_transforms},
                                 {"view_generators", l_view_generators},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
