/* lua_out.c: output targets for redirection (Evolver's >> "file",
** >>> "file" and | "command"), so that the core's progress lines and the
** command language's own output go to the same place in order.
**
**   tds.output_open(target, mode)  mode "a" (append), "w" (overwrite) or
**                                  "|" (a shell command reading it);
**                                  returns a handle, or nil and a message
**   tds.output_set([handle])       the core's output goes to handle; no
**                                  argument: back to standard output
**   tds.output_write(handle, text) write text to handle
**   tds.output_close(handle)       close it (also done by the collector);
**                                  for a pipe, waits for the command
**   tds.chdir(path)                Evolver's chdir: the current folder
**                                  (refused in safe mode); true or nil, msg
*/
#include <stdio.h>
#include <errno.h>
#include <string.h>
#include <unistd.h>

#include "lua_tds.h"

#define OUT_META "tds.output"

typedef struct target {
  FILE *f;
  int pipe;
  tds_state *st; /* its surface (user value 1 keeps it alive) */
} target;

static target *check_target(lua_State *L, int i) {
  target *t = luaL_checkudata(L, i, OUT_META);
  if (!t->f) tds_lua_error(L, "output target is closed");
  return t;
}

static void close_target(target *t) {
  if (!t->f) return;
  if (t->pipe) pclose(t->f);
  else fclose(t->f);
  t->f = NULL;
}

static void to_file(void *ud, const char *text) {
  FILE *f = ud;
  fputs(text, f);
  fflush(f);
}

static int l_output_open(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  const char *mode = luaL_checkstring(L, 2);
  int pipe = !strcmp(mode, "|");
  if (!pipe && strcmp(mode, "a") && strcmp(mode, "w"))
    return luaL_argerror(L, 2, "expected \"a\", \"w\" or \"|\"");
  /* Safe mode: no command runs, no file is written outside its folder. */
  if (pipe && st->safe)
    return tds_lua_nilmsg(L, "safe mode: piping output to a command is not allowed");
  if (!pipe && !tds_lua_may_write(L, st, path)) return 2;
  target *t = lua_newuserdatauv(L, sizeof *t, 1);
  t->f = NULL;
  t->pipe = pipe;
  t->st = st;
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_setiuservalue(L, -2, 1);
  luaL_setmetatable(L, OUT_META);
  fflush(stdout);
  t->f = pipe ? popen(path, "w") : fopen(path, mode);
  if (!t->f)
    return tds_lua_nilmsg(L, "cannot open '%s'%s", path, pipe ? " as a command" : "");
  return 1;
}

static int l_output_set(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  fflush(stdout);
  if (lua_isnoneornil(L, 1)) {
    st->ctx.out = NULL;
    st->ctx.out_ud = NULL;
  } else {
    target *t = check_target(L, 1);
    st->ctx.out = to_file;
    st->ctx.out_ud = t->f;
  }
  return 0;
}

static int l_output_write(lua_State *L) {
  target *t = check_target(L, 1);
  size_t n;
  const char *s = luaL_checklstring(L, 2, &n);
  fwrite(s, 1, n, t->f);
  fflush(t->f);
  return 0;
}

static int l_output_close(lua_State *L) {
  target *t = luaL_checkudata(L, 1, OUT_META);
  tds_state *st = t->st;
  if (t->f && st->ctx.out_ud == t->f) { /* never leave the core writing to it */
    st->ctx.out = NULL;
    st->ctx.out_ud = NULL;
  }
  close_target(t);
  return 0;
}

static int target_gc(lua_State *L) {
  return l_output_close(L);
}

static int l_chdir(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  if (st->safe) return tds_lua_nilmsg(L, "chdir: not allowed in safe mode");
  if (chdir(path) != 0) return tds_lua_nilmsg(L, "chdir: %s: %s", path, strerror(errno));
  lua_pushboolean(L, 1);
  return 1;
}

void tds_open_out(lua_State *L, tds_state *st) {
  /* The collector closes a target through its own surface (user value 1). */
  if (luaL_newmetatable(L, OUT_META)) {
    lua_pushcfunction(L, target_gc);
    lua_setfield(L, -2, "__gc");
  }
  lua_pop(L, 1);
  static const luaL_Reg fns[] = {{"chdir", l_chdir},
                                 {"output_open", l_output_open},
                                 {"output_set", l_output_set},
                                 {"output_write", l_output_write},
                                 {"output_close", l_output_close},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
