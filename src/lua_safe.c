/*
** lua_safe.c: safe mode, for running files from others (`tds --safe`).
**
** What is refused, each with a clear "safe mode: ..." error:
**   processes      os.execute, io.popen
**   native code    package.loadlib, C modules through require (the C
**                  searchers are removed, package.cpath is emptied)
**   bytecode       load, loadfile, dofile and require read text only
**                  (mode "t"), so no precompiled (string.dump) chunk runs
**   file writes    io.open in a writing mode, io.output(name), os.remove,
**                  os.rename, os.tmpname, io.tmpfile, dump, write_fe and
**                  tds.write_text: only inside the output folder
**   introspection  the debug library is removed (its getupvalue and
**                  getregistry would reach the original functions)
** Reading files is allowed. The output folder is resolved once (symlinks
** followed); a path is inside it when its resolved folder is, and, if it
** exists, the file it resolves to is as well.
*/
#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lua_tds.h"

/* The resolved folder of path (its parent; the file need not exist),
** malloc'd, or NULL with errno set. */
static char *resolved_parent(const char *path) {
  const char *slash = strrchr(path, '/');
  char *dir;
  if (!slash) dir = strdup(".");
  else if (slash == path) dir = strdup("/");
  else {
    dir = malloc((size_t)(slash - path) + 1);
    if (dir) {
      memcpy(dir, path, (size_t)(slash - path));
      dir[slash - path] = 0;
    }
  }
  if (!dir) return NULL;
  char *real = realpath(dir, NULL);
  free(dir);
  return real;
}

static int is_inside(const char *root, const char *p) {
  size_t n = strlen(root);
  if (n == 1 && root[0] == '/') return 1;
  return strncmp(p, root, n) == 0 && (p[n] == '/' || p[n] == 0);
}

int tds_lua_may_write(lua_State *L, tds_state *st, const char *path) {
  if (!st->safe) return 1;
  char *dir = resolved_parent(path);
  int ok = dir && is_inside(st->outdir, dir);
  free(dir);
  if (ok) {
    /* an existing name (a symlink, say) must also lead inside */
    char *real = realpath(path, NULL);
    if (real) ok = is_inside(st->outdir, real);
    free(real);
  }
  if (ok) return 1;
  tds_lua_nilmsg(L, "safe mode: writing '%s' is refused (outside the output folder '%s')",
                 path, st->outdir);
  return 0;
}

/* A refused function (upvalue 1: its name). */
static int refused(lua_State *L) {
  return tds_lua_error(L, "safe mode: %s is not allowed", lua_tostring(L, lua_upvalueindex(1)));
}

/* Push the library table `name` (such as os) of the table at absolute
** index lib, or lib itself for NULL; or return 0 if there is none. */
static int get_lib(lua_State *L, int lib, const char *name) {
  if (!name) {
    lua_pushvalue(L, lib);
    return 1;
  }
  if (lua_getfield(L, lib, name) == LUA_TTABLE) return 1;
  lua_pop(L, 1);
  return 0;
}

static void refuse(lua_State *L, int libs, const char *lib, const char *fn) {
  if (!get_lib(L, libs, lib)) return;
  lua_pushfstring(L, "%s.%s", lib, fn);
  lua_pushcclosure(L, refused, 1);
  lua_setfield(L, -2, fn);
  lua_pop(L, 1);
}

#define STATE_UP(L) ((tds_state *)lua_touserdata(L, lua_upvalueindex(2)))

/* Raise unless argument i names a place the session may write. */
static void check_write_arg(lua_State *L, int i) {
  tds_state *st = STATE_UP(L);
  const char *path = luaL_checkstring(L, i);
  if (!tds_lua_may_write(L, st, path)) tds_lua_error(L, "%s", lua_tostring(L, -1));
}

/* Call the original function (upvalue 1) with all arguments. */
static int call_original(lua_State *L) {
  int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

/* io.open(name [, mode]) */
static int safe_open(lua_State *L) {
  const char *mode = luaL_optstring(L, 2, "r");
  if (strpbrk(mode, "wa+")) check_write_arg(L, 1);
  return call_original(L);
}

/* io.output([file]): a name opens it for writing */
static int safe_output(lua_State *L) {
  if (lua_type(L, 1) == LUA_TSTRING) check_write_arg(L, 1);
  return call_original(L);
}

/* os.remove(name), os.rename(old, new) */
static int safe_remove(lua_State *L) {
  check_write_arg(L, 1);
  return call_original(L);
}
static int safe_rename(lua_State *L) {
  check_write_arg(L, 1);
  check_write_arg(L, 2);
  return call_original(L);
}

/* Force argument `mode` (a position) to "t", keeping any later argument
** (an env given as nil must stay given); without an env argument, the
** sandbox's default environment (upvalue 3, if a table) is given. */
static int text_mode(lua_State *L, int mode) {
  int n = lua_gettop(L);
  if (n < mode - 1) lua_settop(L, mode - 1);
  lua_pushliteral(L, "t");
  if (n >= mode) lua_replace(L, mode);
  if (n <= mode && lua_istable(L, lua_upvalueindex(3))) {
    lua_settop(L, mode);
    lua_pushvalue(L, lua_upvalueindex(3));
  }
  return call_original(L);
}

/* load(chunk [, name [, mode [, env]]]): text only */
static int safe_load(lua_State *L) { return text_mode(L, 3); }

/* loadfile([name [, mode [, env]]]): text only */
static int safe_loadfile(lua_State *L) { return text_mode(L, 2); }

/* dofile([name]): text only, in the sandbox's default environment */
static int safe_dofile(lua_State *L) {
  const char *name = luaL_optstring(L, 1, NULL);
  lua_settop(L, 1);
  if (luaL_loadfilex(L, name, "t") != LUA_OK) return lua_error(L);
  if (lua_istable(L, lua_upvalueindex(3))) {
    lua_pushvalue(L, lua_upvalueindex(3));
    lua_setupvalue(L, -2, 1);
  }
  lua_call(L, 0, LUA_MULTRET);
  return lua_gettop(L) - 1;
}

/* package.searchers[2] replacement: Lua files from package.path, text only. */
static int safe_searcher(lua_State *L) {
  const char *name = luaL_checkstring(L, 1);
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "searchpath");
  lua_pushstring(L, name);
  lua_getfield(L, -3, "path");
  lua_call(L, 2, 2);
  if (lua_isnil(L, -2)) return 1; /* the list of places tried */
  lua_pop(L, 1);
  const char *file = lua_tostring(L, -1);
  if (luaL_loadfilex(L, file, "t") != LUA_OK)
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name, file,
                      lua_tostring(L, -1));
  lua_pushstring(L, file);
  return 2;
}

/* Replace lib.fn by a C closure (original, state, default environment). */
static void wrap(lua_State *L, tds_state *st, int libs, int env, const char *lib,
                 const char *fn, lua_CFunction f) {
  if (!get_lib(L, libs, lib)) return;
  lua_getfield(L, -1, fn);
  tds_lua_push_state(L, st);
  if (env) lua_pushvalue(L, env);
  else lua_pushnil(L);
  lua_pushcclosure(L, f, 3);
  lua_setfield(L, -2, fn);
  lua_pop(L, 1);
}

int tds_lua_safe(lua_State *L, tds_state *st, const char *outdir) {
  lua_pushglobaltable(L);
  int ok = tds_lua_sandbox(L, st, lua_gettop(L), 0, outdir);
  if (ok) lua_pop(L, 1);
  else lua_remove(L, -2);
  return ok;
}

int tds_lua_sandbox(lua_State *L, tds_state *st, int lib, int env, const char *outdir) {
  lib = lua_absindex(L, lib);
  if (env) env = lua_absindex(L, env);
  char *real = realpath(outdir ? outdir : ".", NULL);
  if (!real) {
    lua_pushfstring(L, "output folder '%s': %s", outdir ? outdir : ".", strerror(errno));
    return 0;
  }
  struct stat sb;
  if (stat(real, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
    lua_pushfstring(L, "output folder '%s' is not a folder", outdir);
    free(real);
    return 0;
  }
  free(st->outdir);
  st->outdir = real;
  st->safe = 1;
  refuse(L, lib, "os", "execute");
  refuse(L, lib, "io", "popen");
  refuse(L, lib, "os", "tmpname");
  refuse(L, lib, "io", "tmpfile");
  refuse(L, lib, "package", "loadlib");
  wrap(L, st, lib, env, "io", "open", safe_open);
  wrap(L, st, lib, env, "io", "output", safe_output);
  wrap(L, st, lib, env, "os", "remove", safe_remove);
  wrap(L, st, lib, env, "os", "rename", safe_rename);
  wrap(L, st, lib, env, NULL, "load", safe_load);
  wrap(L, st, lib, env, NULL, "loadfile", safe_loadfile);
  wrap(L, st, lib, env, NULL, "dofile", safe_dofile);
  lua_pushnil(L);
  lua_setfield(L, lib, "debug");
  if (env) return 1; /* a surface's sandbox has its own require (lua_surface.c) */
  /* require: preloaded modules and Lua text files only */
  lua_getglobal(L, "package");
  lua_pushliteral(L, "");
  lua_setfield(L, -2, "cpath");
  lua_createtable(L, 2, 0);
  lua_getfield(L, -2, "searchers");
  lua_rawgeti(L, -1, 1); /* the preload searcher */
  lua_rawseti(L, -3, 1);
  lua_pop(L, 1);
  lua_pushcfunction(L, safe_searcher);
  lua_rawseti(L, -2, 2);
  lua_setfield(L, -2, "searchers");
  lua_getfield(L, -1, "loaded");
  lua_pushnil(L);
  lua_setfield(L, -2, "debug");
  lua_pop(L, 2);
  return 1;
}
