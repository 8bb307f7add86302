/*
** lua_surface.c: surfaces as Lua values, and the module `require "tds"`.
**
** A surface is a namespace table: its raw bindings (field `tds`, bound to
** its own tds_state) and the friendly names its prelude defines
** (vertices{}, g(), r(), vertex[i], total_area, parameters, ...). The
** prelude and the other embedded modules (the files of lua/) run with the
** namespace as their _ENV, so each surface has its own copy of them and
** no name of one surface reaches another.
**
**   tds.new([{ safe =, outdir =, quiet = }])  a fresh surface; a name it
**                does not define reads the Lua globals (a safe surface:
**                a sandboxed copy of them)
**   tds.globals()  the global table becomes the namespace of a surface
**                (once; later calls return it again): the tds program's
**                Evolver-style globals
**
** The module installs no global (luaopen_tds); the tds program calls
** tds.globals() (tds_lua_open). doc/embedding.md is the user's guide.
*/
#include <lualib.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lua_tds.h"
#include "prelude.inc"

#define STATES_KEY "tds.states"   /* registry: weak map st -> userdata */
#define GLOBALS_KEY "tds.globals" /* registry: the global surface's state */

static int state_gc(lua_State *L) {
  tds_state *st = lua_touserdata(L, 1);
  tds_lua_track(st, 0);
  tds_surf_free(&st->s);
  free(st->datafile);
  st->datafile = NULL;
  free(st->outdir);
  st->outdir = NULL;
  return 0;
}

/* Push the registry's weak map from state pointers to their userdata. */
static void push_states(lua_State *L) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, STATES_KEY) == LUA_TTABLE) return;
  lua_pop(L, 1);
  lua_newtable(L);
  lua_createtable(L, 0, 1);
  lua_pushliteral(L, "v");
  lua_setfield(L, -2, "__mode");
  lua_setmetatable(L, -2);
  lua_pushvalue(L, -1);
  lua_setfield(L, LUA_REGISTRYINDEX, STATES_KEY);
}

void tds_lua_push_state(lua_State *L, tds_state *st) {
  push_states(L);
  lua_rawgetp(L, -1, st);
  lua_remove(L, -2);
}

void tds_lua_keep(lua_State *L, tds_state *st, const char *name) {
  tds_lua_push_state(L, st);
  lua_getiuservalue(L, -1, TDS_UV_KEEP); /* v st keep */
  lua_rotate(L, -3, -1);                 /* st keep v */
  lua_setfield(L, -2, name);
  lua_pop(L, 2);
}

void tds_lua_kept(lua_State *L, tds_state *st, const char *name) {
  tds_lua_push_state(L, st);
  lua_getiuservalue(L, -1, TDS_UV_KEEP);
  lua_getfield(L, -1, name);
  lua_replace(L, -3);
  lua_pop(L, 1);
}

void tds_lua_push_lib(lua_State *L, tds_state *st) {
  tds_lua_push_state(L, st);
  lua_getiuservalue(L, -1, TDS_UV_LIB);
  lua_remove(L, -2);
}

/* Load embedded module i as a function whose _ENV is the table at index
** env (0: the global table). */
static int load_module(lua_State *L, int i, int env) {
  char chunk[64];
  snprintf(chunk, sizeof chunk, "=[tds %s]", lua_sources[i].name);
  int rc = luaL_loadbuffer(L, (const char *)lua_sources[i].data, lua_sources[i].size, chunk);
  if (rc == LUA_OK && env) {
    lua_pushvalue(L, env);
    lua_setupvalue(L, -2, 1);
  }
  return rc;
}

static int find_module(const char *name) {
  for (int i = 0; lua_sources[i].name; i++)
    if (!strcmp(lua_sources[i].name, name)) return i;
  return -1;
}

/* package.preload loader of the global surface (upvalue: the index). */
static int load_embedded(lua_State *L) {
  if (load_module(L, (int)lua_tointeger(L, lua_upvalueindex(1)), 0) != LUA_OK)
    return lua_error(L);
  lua_call(L, 0, 1);
  return 1;
}

/* The libraries a safe surface may require (the sandboxed copies). */
static const char *const safe_libs[] = {"string", "table", "math", "utf8", "coroutine",
                                        "os", "io", NULL};

/* require(name) of a surface's namespace. Upvalues: 1 the namespace, 2
** its table of loaded modules, 3 the library require (nil in a safe
** surface), 4 the base library table. tds's own modules load into the
** namespace; anything else is the library's require (in a safe surface
** only the standard libraries above, sandboxed). */
static int surface_require(lua_State *L) {
  const char *name = luaL_checkstring(L, 1);
  lua_settop(L, 1);
  if (lua_getfield(L, lua_upvalueindex(2), name) != LUA_TNIL) return 1;
  lua_pop(L, 1);
  int i = find_module(name);
  if (i >= 0) {
    if (load_module(L, i, lua_upvalueindex(1)) != LUA_OK) return lua_error(L);
    lua_pushvalue(L, 1);
    lua_call(L, 1, 1);
    if (lua_isnil(L, -1)) {
      lua_pop(L, 1);
      lua_pushboolean(L, 1);
    }
    lua_pushvalue(L, -1);
    lua_setfield(L, lua_upvalueindex(2), name);
    return 1;
  }
  if (lua_isfunction(L, lua_upvalueindex(3))) {
    lua_pushvalue(L, lua_upvalueindex(3));
    lua_pushvalue(L, 1);
    lua_call(L, 1, 1);
    return 1;
  }
  for (int k = 0; safe_libs[k]; k++)
    if (!strcmp(safe_libs[k], name)) {
      lua_getfield(L, lua_upvalueindex(4), name);
      return 1;
    }
  return tds_lua_error(L, "safe mode: require '%s' is not allowed (only tds's own "
                       "modules and the standard libraries)", name);
}

/* Push a shallow copy of the table at index t. */
static void copy_table(lua_State *L, int t) {
  t = lua_absindex(L, t);
  lua_newtable(L);
  lua_pushnil(L);
  while (lua_next(L, t)) {
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_rawset(L, -4);
  }
}

/* What a safe surface's code sees of Lua's library (copies of the tables,
** then sandboxed): nothing of the host's own globals. */
static const char *const safe_names[] = {
    "assert", "error", "getmetatable", "ipairs", "next", "pairs", "pcall", "print",
    "rawequal", "rawget", "rawlen", "rawset", "select", "setmetatable", "tonumber",
    "tostring", "type", "xpcall", "warn", "collectgarbage", "_VERSION", "load",
    "loadfile", "dofile", NULL};

/* Push the library a private surface falls back to: the global table, or
** for a safe surface a sandboxed copy of the standard library. Returns 0
** with a message on the stack on failure. */
static int push_base(lua_State *L, tds_state *st, int env, int safe, const char *outdir) {
  lua_pushglobaltable(L);
  if (!safe) return 1;
  lua_newtable(L); /* G B */
  for (int k = 0; safe_names[k]; k++) {
    lua_getfield(L, -2, safe_names[k]);
    lua_setfield(L, -2, safe_names[k]);
  }
  for (int k = 0; safe_libs[k]; k++)
    if (lua_getfield(L, -2, safe_libs[k]) == LUA_TTABLE) {
      copy_table(L, -1);
      lua_setfield(L, -3, safe_libs[k]);
      lua_pop(L, 1);
    } else {
      lua_pop(L, 1);
    }
  lua_remove(L, -2); /* B */
  if (!tds_lua_sandbox(L, st, -1, env, outdir)) {
    lua_remove(L, -2);
    return 0;
  }
  return 1;
}

/* Run the prelude with the namespace at env (a private surface). */
static int run_private_prelude(lua_State *L, int env, int safe) {
  if (safe) { /* the runtime keeps debug for its error positions (evorun) */
    lua_getglobal(L, "debug");
    lua_setfield(L, env, "debug");
  }
  lua_getfield(L, env, "require");
  lua_pushliteral(L, "prelude");
  int rc = lua_pcall(L, 1, 0, 0);
  if (safe) {
    lua_pushnil(L);
    lua_setfield(L, env, "debug");
  }
  return rc == LUA_OK;
}

tds_state *tds_lua_surface_new(lua_State *L, int env, int safe, const char *outdir) {
  env = lua_absindex(L, env);
  lua_pushglobaltable(L);
  int global = lua_rawequal(L, -1, env);
  lua_pop(L, 1);
  tds_state *st = lua_newuserdatauv(L, sizeof *st, TDS_STATE_NUV);
  memset(st, 0, sizeof *st);
  tds_ctx_init(&st->ctx);
  tds_surf_init(&st->s);
  if (luaL_newmetatable(L, "tds.state")) {
    lua_pushcfunction(L, state_gc);
    lua_setfield(L, -2, "__gc");
  }
  lua_setmetatable(L, -2);
  tds_lua_track(st, 1); /* untracked by state_gc */
  int sti = lua_gettop(L);
  push_states(L);
  lua_pushvalue(L, sti);
  lua_rawsetp(L, -2, st);
  lua_pop(L, 1);
  lua_newtable(L); /* the interned handles */
  lua_createtable(L, 0, 1);
  lua_pushliteral(L, "v");
  lua_setfield(L, -2, "__mode");
  lua_setmetatable(L, -2);
  lua_setiuservalue(L, sti, TDS_UV_HANDLES);
  lua_newtable(L);
  lua_setiuservalue(L, sti, TDS_UV_KEEP);

  lua_newtable(L); /* the raw library */
  lua_pushvalue(L, -1);
  lua_setiuservalue(L, sti, TDS_UV_LIB);
  tds_open_elem(L, st);
  tds_open_decl(L, st);
  tds_open_cmd(L, st);
  tds_open_model(L, st);
  tds_open_datafile(L, st);
  tds_open_pg(L, st);
  tds_open_export(L, st);
  tds_open_live(L, st);
  tds_open_render(L, st);
  tds_open_check(L, st);
  tds_open_out(L, st);
  tds_open_newton(L, st);
  tds_open_string(L, st);
  tds_open_topo(L, st);
  tds_open_view(L, st);
  lua_pushvalue(L, -1);
  lua_setfield(L, env, "tds"); /* st lib */

  if (global) {
    lua_getglobal(L, "package");
    lua_getfield(L, -1, "preload");
    for (int i = 0; lua_sources[i].name; i++) {
      lua_pushinteger(L, i);
      lua_pushcclosure(L, load_embedded, 1);
      lua_setfield(L, -2, lua_sources[i].name);
    }
    lua_pop(L, 2);
    lua_getglobal(L, "require");
    lua_pushliteral(L, "prelude");
    if (lua_pcall(L, 1, 0, 0) != LUA_OK) return NULL;
    lua_pop(L, 2);
    return st;
  }
  lua_pushvalue(L, env); /* chunks the surface loads run in it (tds.load_chunk) */
  tds_lua_keep(L, st, "env");
  if (!push_base(L, st, env, safe, outdir)) return NULL; /* st lib base */
  lua_pushvalue(L, -1);
  lua_setfield(L, -3, "env_base"); /* names the surface lacks (prelude) */
  lua_pushvalue(L, env);
  lua_setfield(L, env, "_G");
  lua_pushvalue(L, env);
  lua_newtable(L); /* its loaded modules */
  if (safe) lua_pushnil(L);
  else lua_getglobal(L, "require");
  lua_pushvalue(L, -4);
  lua_pushcclosure(L, surface_require, 4);
  lua_setfield(L, env, "require");
  lua_createtable(L, 0, 1);
  lua_pushvalue(L, -2);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, env); /* until the prelude sets its own */
  if (!run_private_prelude(L, env, safe)) return NULL;
  lua_pop(L, 3);
  return st;
}

static int l_globals_fn(lua_State *L);

/* tds.new([options]) -> a new surface (its namespace table) */
static int l_new(lua_State *L) {
  int safe = 0, quiet = 0;
  const char *outdir = NULL;
  if (!lua_isnoneornil(L, 1)) {
    if (!lua_istable(L, 1))
      return tds_lua_error(L, "tds.new(options): options must be a table, not a %s",
                           luaL_typename(L, 1));
    lua_pushnil(L);
    while (lua_next(L, 1)) {
      const char *k = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : "";
      int t = lua_type(L, -1);
      if (!strcmp(k, "safe") && t == LUA_TBOOLEAN) safe = lua_toboolean(L, -1);
      else if (!strcmp(k, "quiet") && t == LUA_TBOOLEAN) quiet = lua_toboolean(L, -1);
      else if (!strcmp(k, "outdir") && t == LUA_TSTRING) outdir = lua_tostring(L, -1);
      else if (!strcmp(k, "safe") || !strcmp(k, "quiet") || !strcmp(k, "outdir"))
        return tds_lua_error(L, "tds.new: %s must be a %s, not a %s", k,
                             k[0] == 'o' ? "string" : "boolean", luaL_typename(L, -1));
      else
        return tds_lua_error(L, "tds.new: unknown key '%s' (known: outdir, quiet, safe)",
                             lua_type(L, -2) == LUA_TSTRING ? k : luaL_typename(L, -2));
      lua_pop(L, 1);
    }
    if (outdir && !safe)
      return tds_lua_error(L, "tds.new: outdir is the output folder of a safe surface; "
                           "give safe = true too");
  }
  /* In a safe session (tds --safe) every surface is safe, with its folder. */
  if (lua_getfield(L, LUA_REGISTRYINDEX, GLOBALS_KEY) == LUA_TUSERDATA) {
    const tds_state *g = lua_touserdata(L, -1);
    if (g->safe) {
      if (outdir)
        return tds_lua_error(L, "tds.new: in safe mode a surface's outdir is the "
                             "session's output folder");
      safe = 1;
      outdir = g->outdir;
    }
  }
  lua_pop(L, 1);
  lua_settop(L, 1);
  lua_newtable(L); /* 2: the namespace */
  tds_state *st = tds_lua_surface_new(L, 2, safe, outdir);
  if (!st) {
    tds_lua_where(L);
    lua_insert(L, -2);
    lua_concat(L, 2);
    return lua_error(L);
  }
  st->ctx.quiet = quiet;
  lua_settop(L, 2);
  return 1;
}

/* The global surface's state, creating it (with the global table as its
** namespace) on first use; NULL with a message on the stack on failure. */
static tds_state *global_surface(lua_State *L) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, GLOBALS_KEY) == LUA_TUSERDATA) {
    tds_state *st = lua_touserdata(L, -1);
    lua_pop(L, 1);
    return st;
  }
  lua_pop(L, 1);
  lua_pushglobaltable(L);
  tds_state *st = tds_lua_surface_new(L, -1, 0, NULL);
  if (!st) return NULL;
  lua_pop(L, 1);
  tds_lua_push_state(L, st);
  lua_setfield(L, LUA_REGISTRYINDEX, GLOBALS_KEY);
  /* The global `tds` is the surface's raw library; it also offers the
  ** module's functions, so scripts of the program can make surfaces. */
  lua_getglobal(L, "tds");
  lua_pushcfunction(L, l_new);
  lua_setfield(L, -2, "new");
  lua_pushcfunction(L, l_globals_fn);
  lua_setfield(L, -2, "globals");
  lua_pop(L, 1);
  return st;
}

/* tds.globals() -> the global table, the namespace of the global surface */
static int l_globals_fn(lua_State *L) {
  if (!global_surface(L)) return lua_error(L);
  lua_pushglobaltable(L);
  return 1;
}

int luaopen_tds(lua_State *L) {
  static const luaL_Reg fns[] = {{"new", l_new}, {"globals", l_globals_fn}, {NULL, NULL}};
  luaL_newlib(L, fns);
  lua_pushliteral(L, TDS_VERSION);
  lua_setfield(L, -2, "version");
  return 1;
}

tds_state *tds_lua_open(lua_State *L) {
  luaL_openlibs(L);
  luaL_requiref(L, "tds", luaopen_tds, 0);
  lua_pop(L, 1);
  return global_surface(L);
}
