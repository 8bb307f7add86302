/*
** lua_attr.h: element attributes in Lua through the registry (attr.h).
*/
#ifndef TDS_LUA_ATTR_H
#define TDS_LUA_ATTR_H

#include "attr.h"
#include "lua_tds.h"

/* Push attribute a of live element id: a boolean, number, integer,
** handle, nil (no value), a table (built-in lists: constraints, a facet's
** vertices) or a proxy (user arrays, tds_lua_attr_push_array). Raises the
** core's message on failure. Upvalue 1 must be the tds state. */
void tds_lua_attr_push(lua_State *L, tds_state *st, const tds_attr *a, tds_id id);

/* Set attribute a of element id from the value at index i (nil unsets),
** through the row's setter; raises "file:line: kind N: ..." on a wrong
** type or a refused value, leaving the element unchanged. */
void tds_lua_attr_set(lua_State *L, tds_state *st, const tds_attr *a, tds_id id, int i);

/* Convert the Lua value at index i to a's values in v (room for
** max(a->size, TDS_MAX_CON)): 1 with *n set (0 for nil), or 0 with a
** message "what: ..." pushed. Types only; values are checked by the
** core (tds_attr_check). */
int tds_lua_attr_values(lua_State *L, const tds_attr *a, int i, const char *what, double *v,
                        int *n);

/* Push a proxy for the array attribute a (a->ndim > 0) of element id:
** indexing reads the element's values, assigning one sets it through the
** registry, # gives the dimension, tostring "{1, 2, 3}". The caller's
** upvalue 1 must be the tds state (lua_attrarray.c). */
void tds_lua_attr_push_array(lua_State *L, const tds_attr *a, tds_id id);

/* Register tds.define_attribute and tds.attributes. */
void tds_open_attr(lua_State *L, tds_state *st);

#endif
