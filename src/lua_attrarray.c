/* lua_attrarray.c: array attributes (user attributes with dimensions) in
** Lua as proxies, so that `facet[1].flags[2] = 9` and `f.mat[2][1] = x`
** change the element, as reading `f.flags[2]` reads it. A proxy is an
** empty table whose metatable holds the element's handle, the attribute's
** name and the indices taken so far (`path`); every access reads the
** element's values afresh through the registry (attr.h), and a write sets
** them through the row's setter (type checks, file:line errors). */
#include <stdio.h>
#include <string.h>

#include "attr.h"
#include "lua_attr.h"

typedef struct where {
  tds_state *st;
  tds_attr a;
  tds_id id;
  int depth;                      /* indices in path */
  int32_t path[TDS_ATTR_MAXDIM];  /* 1-based */
} where;

/* The proxy at index 1: its element (alive), attribute and path. */
static void locate(lua_State *L, where *w) {
  w->st = TDS_STATE(L);
  lua_getmetatable(L, 1);
  int mt = lua_gettop(L);
  lua_getfield(L, mt, "elem");
  int kind;
  w->id = tds_check_elem(L, w->st, -1, -1, &kind);
  lua_getfield(L, mt, "name");
  if (!tds_attr_find(&w->st->s.m, kind, lua_tostring(L, -1), &w->a) || w->a.ndim < 1)
    tds_lua_error(L, "attribute %s no longer exists", lua_tostring(L, -1));
  lua_getfield(L, mt, "path");
  w->depth = (int)luaL_len(L, -1);
  for (int i = 0; i < w->depth && i < TDS_ATTR_MAXDIM; i++) {
    lua_rawgeti(L, -1, i + 1);
    w->path[i] = (int32_t)lua_tointeger(L, -1);
    lua_pop(L, 1);
  }
  lua_settop(L, mt - 1);
}

/* Key at index 2 as an index of dimension w->depth: 1..dim, else 0. */
static int32_t key(lua_State *L, const where *w) {
  int isint;
  lua_Integer k = lua_tointegerx(L, 2, &isint);
  if (!isint && lua_type(L, 2) == LUA_TNUMBER) { /* 2.0 indexes as 2 */
    lua_Number x = lua_tonumber(L, 2);
    if (x == (lua_Number)(lua_Integer)x) k = (lua_Integer)x, isint = 1;
  }
  return isint && k >= 1 && k <= w->a.dim[w->depth] ? (int32_t)k : 0;
}

/* The row-major offset of path + k (a full index). */
static size_t offset(const where *w, int32_t k) {
  size_t off = 0;
  for (int i = 0; i < w->a.ndim; i++) {
    int32_t p = i < w->depth ? w->path[i] : k;
    off = off * (size_t)w->a.dim[i] + (size_t)(p - 1);
  }
  return off;
}

static double *read_all(lua_State *L, where *w) {
  double *v = lua_newuserdatauv(L, sizeof(double) * (size_t)w->a.size, 0);
  int n;
  int rc = tds_attr_read(&w->st->ctx, &w->st->s, &w->a, w->id, v, &n);
  if (rc != TDS_OK) tds_lua_fail(L, w->st, rc);
  return v;
}

static void push_proxy(lua_State *L, int st_index, int kind, tds_id id, const char *name,
                       const int32_t *path, int depth);

static int proxy_index(lua_State *L) {
  where w;
  locate(L, &w);
  int32_t k = key(L, &w);
  if (!k) return 0; /* nil, as a table has nothing there */
  if (w.depth + 1 < w.a.ndim) {
    int32_t path[TDS_ATTR_MAXDIM];
    memcpy(path, w.path, sizeof path);
    path[w.depth] = k;
    push_proxy(L, lua_upvalueindex(1), w.a.kind, w.id, w.a.name, path, w.depth + 1);
    return 1;
  }
  double x = read_all(L, &w)[offset(&w, k)];
  if (w.a.type == TDS_AT_INT) lua_pushinteger(L, (lua_Integer)x);
  else lua_pushnumber(L, x);
  return 1;
}

static int proxy_newindex(lua_State *L) {
  where w;
  locate(L, &w);
  char what[96];
  snprintf(what, sizeof what, "%s %d: %s", tds_kind_name[w.a.kind], (int)w.id + 1, w.a.name);
  for (int i = 0; i < w.depth; i++) {
    size_t len = strlen(what);
    snprintf(what + len, sizeof what - len, "[%d]", (int)w.path[i]);
  }
  int32_t k = key(L, &w);
  if (!k)
    return tds_lua_error(L, "%s: index %s is out of range (1 to %d)", what,
                         luaL_tolstring(L, 2, NULL), (int)w.a.dim[w.depth]);
  if (w.depth + 1 < w.a.ndim)
    return tds_lua_error(L, "%s[%d] is an array: set its elements or the whole %s", what,
                         (int)k, w.a.name);
  if (lua_type(L, 3) != LUA_TNUMBER)
    return tds_lua_error(L, "%s[%d] must be a number, not a %s", what, (int)k,
                         luaL_typename(L, 3));
  double *v = read_all(L, &w);
  v[offset(&w, k)] = lua_tonumber(L, 3);
  int rc = tds_attr_write(&w.st->ctx, &w.st->s, &w.a, w.id, v, w.a.size);
  if (rc != TDS_OK) return tds_lua_error(L, "%s", w.st->ctx.errmsg);
  return 0;
}

static int proxy_len(lua_State *L) {
  where w;
  locate(L, &w);
  lua_pushinteger(L, w.a.dim[w.depth]);
  return 1;
}

/* "{1, 2, 3}", nested braces for more dimensions. */
static void text(luaL_Buffer *b, const where *w, const double *v, size_t *k, int d) {
  luaL_addchar(b, '{');
  for (int32_t i = 0; i < w->a.dim[d]; i++) {
    if (i) luaL_addstring(b, ", ");
    if (d + 1 < w->a.ndim) {
      text(b, w, v, k, d + 1);
    } else {
      char num[32];
      snprintf(num, sizeof num, "%.14g", v[(*k)++]);
      luaL_addstring(b, num);
    }
  }
  luaL_addchar(b, '}');
}

static int proxy_tostring(lua_State *L) {
  where w;
  locate(L, &w);
  double *v = read_all(L, &w);
  size_t k = offset(&w, 1); /* the first value of this (sub-)array */
  luaL_Buffer b;
  luaL_buffinit(L, &b);
  text(&b, &w, v, &k, w.depth);
  luaL_pushresult(&b);
  return 1;
}

/* Push a proxy for attribute `name` of element (kind, id) at `path`; the
** tds state is the value at st_index (the closures' upvalue). */
static void push_proxy(lua_State *L, int st_index, int kind, tds_id id, const char *name,
                       const int32_t *path, int depth) {
  static const luaL_Reg meta[] = {{"__index", proxy_index},
                                  {"__newindex", proxy_newindex},
                                  {"__len", proxy_len},
                                  {"__tostring", proxy_tostring},
                                  {NULL, NULL}};
  st_index = lua_absindex(L, st_index);
  lua_newtable(L);                      /* the proxy */
  lua_createtable(L, 0, 8);             /* its metatable */
  for (int i = 0; meta[i].name; i++) {
    lua_pushvalue(L, st_index);
    lua_pushcclosure(L, meta[i].func, 1);
    lua_setfield(L, -2, meta[i].name);
  }
  lua_pushliteral(L, "tds.array");
  lua_setfield(L, -2, "__name");
  tds_push_elem(L, kind, id);
  lua_setfield(L, -2, "elem");
  lua_pushstring(L, name);
  lua_setfield(L, -2, "name");
  lua_createtable(L, depth, 0);
  for (int i = 0; i < depth; i++) {
    lua_pushinteger(L, path[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "path");
  lua_setmetatable(L, -2);
}

void tds_lua_attr_push_array(lua_State *L, const tds_attr *a, tds_id id) {
  push_proxy(L, lua_upvalueindex(1), a->kind, id, a->name, NULL, 0);
}
