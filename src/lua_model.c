/* lua_model.c: constraint(), boundary(), quantity() declarations. */
#include "lua_tds.h"

void tds_open_model(lua_State *L, tds_state *st) {
  (void)L;
  (void)st;
}
