/* lua_datafile.c: loading and writing Surface Evolver datafiles. */
#include "lua_tds.h"

void tds_open_datafile(lua_State *L, tds_state *st) {
  (void)L;
  (void)st;
}
