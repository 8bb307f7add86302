/* lua_attr.c: element attributes in Lua, by iterating the registry
** (attr.h): values to and from Lua, user attribute declarations
** (attribute{...}, tds.define_attribute) and tds.attributes(kind). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "attr.h"
#include "lua_attr.h"

/* A scratch buffer for one attribute's values: `small` (TDS_MAX_CON
** doubles on the C stack) when it fits, else a userdata pushed on the Lua
** stack (so a raised error cannot leak it); *pushed says which. */
static double *values_buf(lua_State *L, const tds_attr *a, double *small, int *pushed) {
  *pushed = a->size > TDS_MAX_CON;
  if (!*pushed) return small;
  return lua_newuserdatauv(L, sizeof(double) * (size_t)a->size, 0);
}

static void push_number(lua_State *L, const tds_attr *a, double x) {
  if (a->type == TDS_AT_REAL) {
    lua_pushnumber(L, x);
  } else if (a->type == TDS_AT_FLAG) {
    lua_pushboolean(L, x != 0);
  } else if (a->type == TDS_AT_VERTEX) {
    tds_push_elem(L, TDS_VERTEX, (tds_id)x - 1);
  } else if (a->type == TDS_AT_BODY) {
    tds_push_elem(L, TDS_BODY, (tds_id)x - 1);
  } else {
    lua_pushinteger(L, (lua_Integer)x);
  }
}

/* Nested tables of dims dim[d..ndim) from v, advancing *k. */
static void push_array(lua_State *L, const tds_attr *a, const double *v, int *k, int d) {
  int n = a->ndim ? (int)a->dim[d] : a->size;
  lua_createtable(L, n, 0);
  for (int i = 0; i < n; i++) {
    if (a->ndim && d + 1 < a->ndim) push_array(L, a, v, k, d + 1);
    else push_number(L, a, v[(*k)++]);
    lua_rawseti(L, -2, i + 1);
  }
}

void tds_lua_attr_push(lua_State *L, tds_state *st, const tds_attr *a, tds_id id) {
  if (a->ndim > 0) { /* a user array: a proxy that reads and writes the element */
    tds_lua_attr_push_array(L, a, id);
    return;
  }
  double small[TDS_MAX_CON];
  int pushed;
  double *v = values_buf(L, a, small, &pushed);
  int n = 0;
  int rc = tds_attr_read(&st->ctx, &st->s, a, id, v, &n);
  if (rc != TDS_OK) tds_lua_fail(L, st, rc);
  if (a->type == TDS_AT_CONS) {
    lua_createtable(L, n, 0);
    for (int i = 0; i < n; i++) {
      lua_pushinteger(L, (lua_Integer)v[i]);
      lua_rawseti(L, -2, i + 1);
    }
  } else if (n == 0) {
    lua_pushnil(L);
  } else if (a->size == 1) {
    push_number(L, a, v[0]);
  } else {
    int k = 0;
    push_array(L, a, v, &k, 0);
  }
  if (pushed) lua_remove(L, -2); /* the buffer */
}

static const char *lua_kind(lua_State *L, int i) { return luaL_typename(L, i); }

/* One number from the value at index i into v[*n] ("a number" wanted). */
static int one_value(lua_State *L, const tds_attr *a, int i, double *v, int *n,
                     const char *what) {
  int t = lua_type(L, i);
  if (a->type == TDS_AT_FLAG) {
    if (t != LUA_TBOOLEAN && t != LUA_TNIL) {
      lua_pushfstring(L, "%s: %s must be a boolean (true or false), not a %s", what, a->name,
                      lua_kind(L, i));
      return 0;
    }
    v[(*n)++] = lua_toboolean(L, i);
    return 1;
  }
  if (a->type == TDS_AT_BODY) {
    if (t == LUA_TUSERDATA && lua_getmetatable(L, i)) {
      lua_getfield(L, -1, "__tds_kind");
      int k = (int)lua_tointeger(L, -1);
      lua_pop(L, 2);
      if (k == TDS_BODY) { /* a live body of this surface, or an error */
        v[(*n)++] = (double)tds_check_elem(L, TDS_STATE(L), i, TDS_BODY, NULL) + 1;
        return 1;
      }
    }
    if (t != LUA_TNUMBER) {
      lua_pushfstring(L, "%s: %s must be a body or a body id, not a %s", what, a->name,
                      lua_kind(L, i));
      return 0;
    }
  }
  if (t != LUA_TNUMBER) {
    lua_pushfstring(L, "%s: %s must be a number, not a %s", what, a->name, lua_kind(L, i));
    return 0;
  }
  v[(*n)++] = lua_tonumber(L, i);
  return 1;
}

/* The numbers of a (nested) table at index i, in order, into v. */
static int table_values(lua_State *L, const tds_attr *a, int i, double *v, int *n, int cap,
                        const char *what) {
  i = lua_absindex(L, i);
  lua_Integer len = luaL_len(L, i);
  for (lua_Integer k = 1; k <= len; k++) {
    lua_geti(L, i, k); /* not raw: arrays read from elements are proxies */
    int ok;
    if (lua_istable(L, -1)) {
      ok = table_values(L, a, -1, v, n, cap, what);
    } else if (*n >= cap) {
      lua_pushfstring(L, "%s: %s takes %d value%s, got more", what, a->name, cap,
                      cap == 1 ? "" : "s");
      ok = 0;
    } else {
      ok = one_value(L, a, -1, v, n, what);
    }
    if (!ok) {
      lua_remove(L, -2);
      return 0;
    }
    lua_pop(L, 1);
  }
  return 1;
}

int tds_lua_attr_values(lua_State *L, const tds_attr *a, int i, const char *what, double *v,
                        int *n) {
  *n = 0;
  int cap = a->type == TDS_AT_CONS ? TDS_MAX_CON : a->size;
  if (lua_isnil(L, i) && a->type != TDS_AT_FLAG) return 1;
  if (a->type == TDS_AT_CONS && lua_isboolean(L, i) && !lua_toboolean(L, i)) return 1;
  if (lua_istable(L, i) && (cap > 1 || a->type == TDS_AT_CONS)) {
    if (!table_values(L, a, i, v, n, cap, what)) return 0;
    if (a->type != TDS_AT_CONS && *n != cap) {
      lua_pushfstring(L, "%s: %s takes %d values, got %d", what, a->name, cap, *n);
      return 0;
    }
    return 1;
  }
  if (cap > 1 && a->type != TDS_AT_CONS) {
    lua_pushfstring(L, "%s: %s must be a table of %d numbers, not a %s", what, a->name, cap,
                    lua_kind(L, i));
    return 0;
  }
  return one_value(L, a, i, v, n, what);
}

void tds_lua_attr_set(lua_State *L, tds_state *st, const tds_attr *a, tds_id id, int i) {
  char what[64];
  snprintf(what, sizeof what, "%s %d", tds_kind_name[a->kind], (int)id + 1);
  if (!a->set) tds_lua_error(L, "%s: %s cannot be set", what, a->name);
  i = lua_absindex(L, i);
  double small[TDS_MAX_CON];
  int pushed;
  double *v = values_buf(L, a, small, &pushed);
  int n;
  if (!tds_lua_attr_values(L, a, i, what, v, &n)) tds_lua_error(L, "%s", lua_tostring(L, -1));
  int rc = tds_attr_write(&st->ctx, &st->s, a, id, v, n);
  if (rc != TDS_OK) tds_lua_error(L, "%s", st->ctx.errmsg);
  if (pushed) lua_pop(L, 1);
}

/* ---- declarations of user attributes ---- */

/* "real", "integer", "real[3]", "integer[2][2]" -> type, dims; 0 if bad. */
static int parse_type(const char *s, int *type, int *ndim, int32_t *dim) {
  size_t k = strcspn(s, "[");
  if (k == 4 && !strncmp(s, "real", 4)) *type = TDS_AT_REAL;
  else if (k == 7 && !strncmp(s, "integer", 7)) *type = TDS_AT_INT;
  else return 0;
  *ndim = 0;
  s += k;
  while (*s == '[') {
    char *end;
    long d = strtol(s + 1, &end, 10);
    if (end == s + 1 || *end != ']' || *ndim == TDS_ATTR_MAXDIM || d < 1 || d > TDS_ATTR_MAXSIZE)
      return 0;
    dim[(*ndim)++] = (int32_t)d;
    s = end + 1;
  }
  return *s == 0;
}

/* tds.define_attribute(kind, name, type): type as parse_type, or a type
** name and a list of dimensions (the Evolver translator). Raises. */
static int l_define_attribute(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *kn = luaL_checkstring(L, 1);
  const char *name = luaL_checkstring(L, 2);
  const char *ty = luaL_checkstring(L, 3);
  int kind = tds_kind_find(kn);
  if (kind < 0)
    return tds_lua_error(L, "attribute %s: '%s' is not an element kind (vertex, edge, facet, "
                         "body)", name, kn);
  int type, ndim;
  int32_t dim[TDS_ATTR_MAXDIM];
  int ok = parse_type(ty, &type, &ndim, dim);
  if (ok && lua_istable(L, 4)) {
    lua_Integer nd = luaL_len(L, 4);
    for (lua_Integer i = 1; ok && i <= nd; i++) {
      lua_rawgeti(L, 4, i);
      int isnum;
      lua_Number d = lua_tonumberx(L, -1, &isnum);
      lua_pop(L, 1);
      ok = isnum && ndim < TDS_ATTR_MAXDIM && d >= 1 && d <= TDS_ATTR_MAXSIZE && d == floor(d);
      if (ok) dim[ndim++] = (int32_t)d;
      else
        return tds_lua_error(L, "%s attribute %s: dimension %d must be a whole number from 1 "
                             "to %d", tds_kind_name[kind], name, (int)i, TDS_ATTR_MAXSIZE);
    }
  }
  if (!ok)
    return tds_lua_error(L, "%s attribute %s: type '%s' is not real or integer (with "
                         "dimensions such as real[3])", tds_kind_name[kind], name, ty);
  int rc = tds_attr_define(&st->ctx, &st->s.m, kind, name, type, ndim, dim);
  if (rc != TDS_OK) return tds_lua_error(L, "%s", st->ctx.errmsg);
  return 0;
}

/* tds.attributes(kind): a list of { name =, type =, settable =, user =,
** alias = (other spellings, blank-separated), dims = {...} (arrays) } in
** registry order. */
static int l_attributes(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = (int)luaL_checkinteger(L, 1);
  luaL_argcheck(L, kind >= 0 && kind < TDS_NKINDS, 1, "bad element kind");
  int n = tds_attr_count(&st->s.m, kind);
  lua_createtable(L, n, 0);
  for (int i = 0; i < n; i++) {
    tds_attr a;
    tds_attr_at(&st->s.m, kind, i, &a);
    lua_createtable(L, 0, 5);
    lua_pushstring(L, a.name);
    lua_setfield(L, -2, "name");
    lua_pushstring(L, tds_attr_type_name(a.type));
    lua_setfield(L, -2, "type");
    lua_pushboolean(L, a.set != NULL);
    lua_setfield(L, -2, "settable");
    lua_pushboolean(L, (a.io & TDS_AT_USER) != 0);
    lua_setfield(L, -2, "user");
    if (a.alias) {
      lua_pushstring(L, a.alias);
      lua_setfield(L, -2, "alias");
    }
    if (a.ndim) {
      lua_createtable(L, a.ndim, 0);
      for (int d = 0; d < a.ndim; d++) {
        lua_pushinteger(L, a.dim[d]);
        lua_rawseti(L, -2, d + 1);
      }
      lua_setfield(L, -2, "dims");
    }
    lua_rawseti(L, -2, i + 1);
  }
  return 1;
}

void tds_open_attr(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"define_attribute", l_define_attribute},
                                 {"attributes", l_attributes},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
