/* lua_export.c: the Lua face of export (src/export.h; doc/output.md).
**
**   export(path [, opts])   write the surface for other tools; returns the
**                           list of files written. opts: format, encoding,
**                           appended, version, facets, vertex_fields,
**                           facet_fields, per_body, caps. Errors are raised at the
**                           caller's line and name the option.
**   mark()                  record every vertex position now, for the
**                           vertex field "displacement"
**   tds.vertex_gauss_curvature(v)  angle defect over mixed area, or nil
**                           (the attribute v.gauss_curvature)
*/
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export.h"
#include "lua_tds.h"
#include "metrics.h"


typedef struct mark {
  int32_t n;
  double (*x)[3];
} mark;

static int mark_gc(lua_State *L) {
  mark *mk = lua_touserdata(L, 1);
  free(mk->x);
  mk->x = NULL;
  return 0;
}

/* mark(): positions of every vertex slot now (NaN for dead slots). */
static int l_mark(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const tds_mesh *m = &st->s.m;
  double (*x)[3] = malloc((size_t)(m->nv > 0 ? m->nv : 1) * sizeof *x);
  if (!x) return tds_lua_error(L, "out of memory");
  for (tds_id v = 0; v < m->nv; v++)
    for (int c = 0; c < 3; c++) x[v][c] = tds_alive(m->vflags, v) ? m->x[v][c] : (double)NAN;
  mark *mk = lua_newuserdatauv(L, sizeof *mk, 0);
  mk->n = m->nv;
  mk->x = x;
  lua_newtable(L);
  lua_pushcfunction(L, mark_gc);
  lua_setfield(L, -2, "__gc");
  lua_setmetatable(L, -2);
  tds_lua_keep(L, st, "mark"); /* the surface's own mark */
  return 0;
}

/* tds.vertex_gauss_curvature(v) -> number or nil (not measured) */
static int l_vertex_gauss_curvature(lua_State *L) {
  return tds_lua_vertex_measure(L, tds_vertex_gauss_curvature);
}

/* Raise "file:line: message" at the caller's line (never returns). */
static int fail(lua_State *L, tds_state *st, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int fail(lua_State *L, tds_state *st, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(st->ctx.errmsg, sizeof st->ctx.errmsg, fmt, ap);
  va_end(ap);
  return tds_lua_fail(L, st, TDS_ERANGE);
}

static void want(lua_State *L, tds_state *st, int idx, int type, const char *key) {
  if (lua_type(L, idx) != type)
    fail(L, st, "export: option '%s' must be a %s", key,
         type == LUA_TSTRING ? "string" : type == LUA_TBOOLEAN ? "boolean" : "table");
}

static int lookup(const char *const *names, int n, const char *s) {
  for (int i = 0; i < n; i++)
    if (!strcmp(names[i], s)) return i;
  return -1;
}

/* A list of field names -> bit mask. */
static unsigned field_mask(lua_State *L, tds_state *st, int idx, const char *key,
                           const char *const *names, int n) {
  want(L, st, idx, LUA_TTABLE, key);
  unsigned mask = 0;
  lua_Integer len = luaL_len(L, idx);
  for (lua_Integer i = 1; i <= len; i++) {
    lua_rawgeti(L, idx, i);
    const char *s = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
    int bit = s ? lookup(names, n, s) : -1;
    if (bit < 0) {
      char list[256] = "";
      for (int j = 0; j < n; j++) {
        strncat(list, j ? ", " : "", sizeof list - strlen(list) - 1);
        strncat(list, names[j], sizeof list - strlen(list) - 1);
      }
      if (!s) fail(L, st, "export: option '%s' must list field names (%s)", key, list);
      fail(L, st, "export: option '%s': unknown field '%s' (known: %s)", key, s, list);
    }
    mask |= 1u << bit;
    lua_pop(L, 1);
  }
  return mask;
}

/* The facet id of the value on top (a facet handle or a positive id), or
** -1. */
static lua_Integer facet_id(lua_State *L) {
  if (lua_isinteger(L, -1)) return lua_tointeger(L, -1);
  if (!lua_getmetatable(L, -1)) return -1;
  lua_getfield(L, -1, "__tds_kind");
  int kind = lua_isinteger(L, -1) ? (int)lua_tointeger(L, -1) : -1;
  lua_pop(L, 2);
  if (kind != TDS_FACET) return -1;
  lua_getfield(L, -1, "id");
  lua_Integer id = lua_isinteger(L, -1) ? lua_tointeger(L, -1) : -1;
  lua_pop(L, 1);
  return id;
}

static void select_one(lua_State *L, tds_state *st, uint8_t *sel, int32_t nf,
                       const char *where) {
  lua_Integer id = facet_id(L);
  const tds_mesh *m = &st->s.m;
  if (id < 1 || id > nf || id > m->nf || !tds_alive(m->fflags, (tds_id)id - 1))
    fail(L, st, "export: option 'facets': %s is not a live facet", where);
  sel[id - 1] = 1;
}

/* opts.facets at idx: a filter f -> bool (one parameter), an iterator
** such as facets(filter) (no parameters), or a list of facets or ids.
** The selection lives in a userdata left on the stack. */
static uint8_t *facet_selection(lua_State *L, tds_state *st, int idx) {
  const tds_mesh *m = &st->s.m;
  size_t n = (size_t)(m->nf > 0 ? m->nf : 1);
  uint8_t *sel = lua_newuserdatauv(L, n, 0);
  memset(sel, 0, n);
  int top = lua_gettop(L);
  char where[48];
  uint64_t gen = m->topo_gen;
  int32_t nf = m->nf;
  if (lua_isfunction(L, idx)) {
    lua_Debug ar;
    lua_pushvalue(L, idx);
    lua_getinfo(L, ">u", &ar);
    if (ar.nparams >= 1) { /* filter */
      for (tds_id f = 0; f < nf && m->topo_gen == gen; f++) {
        if (!tds_alive(m->fflags, f)) continue;
        lua_pushvalue(L, idx);
        tds_push_elem(L, TDS_FACET, f);
        lua_call(L, 1, 1);
        if (lua_toboolean(L, -1)) sel[f] = 1;
        lua_settop(L, top);
      }
    } else { /* iterator */
      for (int k = 1;; k++) {
        lua_pushvalue(L, idx);
        lua_call(L, 0, 1);
        if (lua_isnil(L, -1)) break;
        snprintf(where, sizeof where, "value %d of the iterator", k);
        select_one(L, st, sel, nf, where);
        lua_settop(L, top);
      }
    }
  } else if (lua_istable(L, idx)) {
    lua_Integer len = luaL_len(L, idx);
    for (lua_Integer i = 1; i <= len; i++) {
      lua_rawgeti(L, idx, i);
      snprintf(where, sizeof where, "entry %d", (int)i);
      select_one(L, st, sel, nf, where);
      lua_settop(L, top);
    }
  } else {
    fail(L, st, "export: option '%s' must be a filter function, an iterator or a list",
         "facets");
  }
  if (m->topo_gen != gen || m->nf != nf)
    fail(L, st, "export: option '%s' changed the surface while choosing facets", "facets");
  lua_settop(L, top);
  return sel;
}

static void written(void *ud, const char *path) {
  lua_State *L = ud;
  lua_pushstring(L, path);
  lua_rawseti(L, -2, (lua_Integer)luaL_len(L, -2) + 1);
}

static const char *const option_names[] = {"format", "encoding", "version", "facets",
                                           "vertex_fields", "facet_fields", "per_body",
                                           "caps", "appended", NULL};

/* export(path [, opts]) -> { files written } */
static int l_export(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  if (lua_type(L, 1) != LUA_TSTRING)
    fail(L, st, "export(path [, options]): path must be a string");
  const char *path = lua_tostring(L, 1);
  if (!tds_lua_may_write(L, st, path)) /* safe mode: only in its folder */
    return tds_lua_error(L, "%s", lua_tostring(L, -1));
  if (!lua_isnoneornil(L, 2) && !lua_istable(L, 2))
    fail(L, st, "export(path [, options]): options must be a table");
  lua_settop(L, 2);
  if (lua_isnil(L, 2)) {
    lua_newtable(L);
    lua_replace(L, 2);
  }
  /* unknown keys first */
  lua_pushnil(L);
  while (lua_next(L, 2)) {
    lua_pop(L, 1);
    const char *k = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
    if (!k || lookup(option_names, 9, k) < 0) {
      const char *shown = k ? k : luaL_tolstring(L, -1, NULL);
      fail(L, st, "export: unknown option '%s' (options: format, encoding, version, "
           "appended, facets, vertex_fields, facet_fields, per_body, caps)", shown);
    }
  }
  tds_export_opts o;
  memset(&o, 0, sizeof o);
  o.msh_version = 41;
  o.caps = 1;
  o.format = tds_export_format_of(path);
  lua_getfield(L, 2, "format"); /* 3 */
  if (!lua_isnil(L, 3)) {
    want(L, st, 3, LUA_TSTRING, "format");
    o.format = lookup(tds_export_formats, TDS_FMT_COUNT, lua_tostring(L, 3));
    if (o.format < 0)
      fail(L, st, "export: option 'format': unknown format '%s' (obj, off, ply, stl, vtu, "
           "vtk, msh)", lua_tostring(L, 3));
  } else if (o.format < 0) {
    fail(L, st, "export: cannot tell the format of '%s' from its extension; give "
         "format = \"obj\" | \"off\" | \"ply\" | \"stl\" | \"vtu\" | \"vtk\" | \"msh\"",
         path);
  }
  int binary_ok = o.format != TDS_FMT_OBJ && o.format != TDS_FMT_OFF;
  o.encoding = binary_ok ? TDS_ENC_BINARY : TDS_ENC_ASCII;
  lua_getfield(L, 2, "encoding"); /* 4 */
  if (!lua_isnil(L, 4)) {
    static const char *const encs[] = {"ascii", "binary", "base64"};
    want(L, st, 4, LUA_TSTRING, "encoding");
    o.encoding = lookup(encs, 3, lua_tostring(L, 4));
    if (o.encoding < 0)
      fail(L, st, "export: option 'encoding': unknown encoding '%s' (ascii, binary, "
           "base64)", lua_tostring(L, 4));
  }
  lua_getfield(L, 2, "appended"); /* 5 */
  o.appended = o.format == TDS_FMT_VTU && o.encoding == TDS_ENC_BINARY;
  if (!lua_isnil(L, 5)) {
    want(L, st, 5, LUA_TBOOLEAN, "appended");
    o.appended = lua_toboolean(L, 5);
  }
  lua_pop(L, 1);
  lua_getfield(L, 2, "version"); /* 5 */
  if (!lua_isnil(L, 5)) {
    if (o.format != TDS_FMT_MSH)
      fail(L, st, "export: option 'version' is only for msh, not %s",
           tds_export_formats[o.format]);
    const char *v = lua_type(L, 5) == LUA_TSTRING || lua_type(L, 5) == LUA_TNUMBER
                        ? lua_tostring(L, 5) : NULL;
    if (!v || (strcmp(v, "2.2") && strcmp(v, "4.1")))
      fail(L, st, "export: option 'version' must be \"2.2\" or \"4.1\"");
    o.msh_version = v[0] == '2' ? 22 : 41;
  }
  lua_getfield(L, 2, "facets"); /* 6 */
  if (!lua_isnil(L, 6)) o.facets = facet_selection(L, st, 6);
  else lua_pushnil(L);
  /* 7: selection userdata or nil */
  lua_getfield(L, 2, "vertex_fields"); /* 8 */
  if (!lua_isnil(L, 8))
    o.vfields = field_mask(L, st, 8, "vertex_fields", tds_export_vfields, TDS_VF_COUNT);
  lua_getfield(L, 2, "facet_fields"); /* 9 */
  if (!lua_isnil(L, 9))
    o.ffields = field_mask(L, st, 9, "facet_fields", tds_export_ffields, TDS_FF_COUNT);
  lua_getfield(L, 2, "per_body"); /* 10 */
  if (!lua_isnil(L, 10)) {
    want(L, st, 10, LUA_TBOOLEAN, "per_body");
    o.per_body = lua_toboolean(L, 10);
  }
  lua_getfield(L, 2, "caps"); /* 11 */
  if (!lua_isnil(L, 11)) {
    want(L, st, 11, LUA_TBOOLEAN, "caps");
    o.caps = lua_toboolean(L, 11);
    if (!o.per_body) fail(L, st, "export: option 'caps' needs per_body = true");
  }
  tds_lua_kept(L, st, "mark"); /* 12 */
  if (!lua_isnil(L, 12)) {
    mark *mk = lua_touserdata(L, 12);
    o.mark = (const double (*)[3])mk->x;
    o.nmark = mk->n;
  }
  lua_newtable(L); /* 13: the files written */
  o.written = written;
  o.ud = L;
  int rc = tds_export(&st->ctx, &st->s, path, &o);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  return 1;
}

void tds_open_export(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"export", l_export}, {"mark", l_mark},
                                 {"vertex_gauss_curvature", l_vertex_gauss_curvature},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
