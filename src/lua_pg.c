/* lua_pg.c: the projected-gradient method and mesh metrics. */
#include "lua_tds.h"

void tds_open_pg(lua_State *L, tds_state *st) {
  (void)L;
  (void)st;
}
