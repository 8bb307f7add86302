/*
** lua_check.c: primitives of the check mode (lua/check.lua, TDS_CHECK=1):
**
**   tds.check_snapshot() -> snap   copy of the surface's changeable state
**   tds.check_same(snap) -> true | false, msg
**                                  the surface equals the snapshot bit for
**                                  bit (what a failed command must leave)
**   tds.check_finite([derived]) -> true | false, msg
**                                  every coordinate, parameter, pressure
**                                  (with derived: energy, area, volume,
**                                  quantity value) is finite (snap.h)
**   tds.check_restore(snap)        put the surface back as in the snapshot
**                                  (atomic declarations, lua/prelude.lua)
** The snapshot is freed by the garbage collector (or at once by
** tds.check_release(snap) or tds.check_restore(snap)).
*/
#include <string.h>

#include "lua_tds.h"
#include "snap.h"

#define SNAP_META "tds.snapshot"

static int snap_gc(lua_State *L) {
  tds_snap *sn = luaL_checkudata(L, 1, SNAP_META);
  tds_snap_free(sn);
  return 0;
}

static int l_check_snapshot(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_snap *sn = lua_newuserdatauv(L, sizeof *sn, 0);
  memset(sn, 0, sizeof *sn);
  luaL_setmetatable(L, SNAP_META);
  if (tds_snap_take(&st->ctx, &st->s, sn) != TDS_OK) return tds_lua_fail(L, st, TDS_ENOMEM);
  return 1;
}

static int l_check_same(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_snap *sn = luaL_checkudata(L, 1, SNAP_META);
  tds_ctx ctx = st->ctx; /* leave the command's message alone */
  int rc = sn->taken ? tds_snap_same(&ctx, &st->s, sn) : TDS_OK;
  lua_pushboolean(L, rc == TDS_OK);
  if (rc == TDS_OK) return 1;
  lua_pushstring(L, ctx.errmsg);
  return 2;
}

static int l_check_finite(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_ctx ctx = st->ctx;
  int rc = tds_surf_all_finite(&ctx, &st->s, lua_toboolean(L, 1));
  lua_pushboolean(L, rc == TDS_OK);
  if (rc == TDS_OK) return 1;
  lua_pushstring(L, ctx.errmsg);
  return 2;
}

static int l_check_release(lua_State *L) {
  tds_snap_free(luaL_checkudata(L, 1, SNAP_META));
  return 0;
}

static int l_check_restore(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_snap *sn = luaL_checkudata(L, 1, SNAP_META);
  if (sn->taken) tds_snap_restore(&st->s, sn);
  return 0;
}

void tds_open_check(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"check_snapshot", l_check_snapshot},
                                 {"check_same", l_check_same},
                                 {"check_finite", l_check_finite},
                                 {"check_release", l_check_release},
                                 {"check_restore", l_check_restore},
                                 {NULL, NULL}};
  if (luaL_newmetatable(L, SNAP_META)) {
    lua_pushcfunction(L, snap_gc);
    lua_setfield(L, -2, "__gc");
  }
  lua_pop(L, 1);
  tds_lua_register(L, st, fns);
}
