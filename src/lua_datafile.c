/* lua_datafile.c: loading and writing Surface Evolver datafiles.
**
**   tds.load_datafile(path)      load into the current, empty surface;
**                                raises "path:line: message" on failure
**   tds.dump([path])             write the surface as a datafile; returns
**                                true, or nil and a message (like io.open);
**                                dump([path]) raises the message instead.
**                                Without path: the loaded file's name with
**                                extension .dmp (Evolver's default)
**   tds.load_chunk(path)         for main.c: a function that loads the
**                                datafile when called, or the compiled
**                                .tds chunk
**   tds.datafile_info(text [, name])  parse a datafile given as text into a
**                                scratch surface (the current one is not
**                                touched); returns a table of counts, energy
**                                and parameters, or nil and the message.
**                                For tests and diagnostics.
**   tds.write_text(path, text)   write a file all or nothing (wfile.h)
**   tds.write_fe(path, hdr, rd)  the element lists as a datafile
**   tds.load_replace(path)       Evolver's load: path's surface replaces the
**                                current one (unchanged if path is bad)
**   tds.addload(path)            Evolver's addload: path's elements added to
**                                the current surface (its read section is
**                                not run); unchanged if path is bad
**   tds.replace_load(path)       Evolver's replace_load: the elements go,
**                                path is addloaded (unchanged if bad)
**   tds.read_text()              the loaded datafile's read section (or nil)
**   tds.datafile_name()          the loaded datafile's path (or nil)
**   After a load, tds.on_load(path) is called if set: it runs the read
**   section (lua/evorun.lua); its errors are the load's errors.
**   tds.dump_raise(path)         dump(path) of the namespace: raises
**                                the message instead of returning it
*/
#include <stdlib.h>
#include <string.h>

#include "string_model.h"
#include "datafile.h"
#include "lua_tds.h"
#include "wfile.h"

/* Raise msg as is (no position prefix: it has its own file:line). */
static int raise_msg(lua_State *L, const char *msg) {
  lua_pushstring(L, msg);
  return lua_error(L);
}

static int surface_in_use(const tds_state *st) {
  const tds_surf *s = &st->s;
  if (s->m.nv || s->m.ne || s->m.nf || s->m.nb || s->npar ||
      s->nbdry || s->nquant)
    return 1;
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (s->con[c].number) return 1;
  return 0;
}

static void load(lua_State *L, tds_state *st, const char *path) {
  if (surface_in_use(st))
    tds_lua_error(L, "%s: a surface is already loaded; start a new tds session "
               "to load a datafile", path);
  int rc = tds_datafile_load(&st->ctx, &st->s, path);
  if (rc != TDS_OK) raise_msg(L, st->ctx.errmsg);
  char *copy = strdup(path);
  if (copy) {
    free(st->datafile);
    st->datafile = copy;
  }
  /* The read section runs now, as in Evolver (tds.on_load, lua/evorun.lua). */
  tds_lua_push_lib(L, st);
  lua_getfield(L, -1, "on_load");
  lua_remove(L, -2);
  if (lua_isfunction(L, -1)) {
    lua_pushstring(L, path);
    lua_call(L, 1, 0);
  } else {
    lua_pop(L, 1);
  }
}

/* tds.read_text() -> the loaded datafile's read section, or nil */
static int l_read_text(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  if (!st->s.read_text) return 0;
  lua_pushstring(L, st->s.read_text);
  return 1;
}

/* tds.define_text(text [, name, line]): Evolver's run-time `define
** constraint|boundary|quantity ...` (text without the word define), added
** to the surface as a datafile declaration; messages are name:line. */
static int l_define_text(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  size_t n;
  const char *text = luaL_checklstring(L, 1, &n);
  const char *name = luaL_optstring(L, 2, "(define)");
  int line = (int)luaL_optinteger(L, 3, 1);
  if (tds_datafile_define(&st->ctx, &st->s, name, line, text, n) != TDS_OK)
    return raise_msg(L, st->ctx.errmsg);
  return 0;
}

/* tds.datafile_name() -> the loaded datafile's path, or nil */
static int l_datafile_name(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  if (!st->datafile) return 0;
  lua_pushstring(L, st->datafile);
  return 1;
}

static void silent(void *ud, const char *text) {
  (void)ud;
  (void)text;
}

/* tds.load_replace(path): Evolver's `load`: a new surface from path in
** place of the current one. The file is parsed into a scratch surface
** first, so a bad file leaves the current surface as it was. */
static int l_load_replace(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  tds_surf *tmp = lua_newuserdatauv(L, sizeof *tmp, 0);
  tds_surf_init(tmp);
  /* the trial parse is quiet: its warnings come again from the real load */
  tds_out_fn warn = st->ctx.warn, out = st->ctx.out;
  st->ctx.warn = st->ctx.out = silent;
  int rc = tds_datafile_load(&st->ctx, tmp, path);
  st->ctx.warn = warn;
  st->ctx.out = out;
  tds_surf_free(tmp);
  if (rc != TDS_OK) return raise_msg(L, st->ctx.errmsg);
  tds_surf_free(&st->s);
  tds_surf_init(&st->s);
  load(L, st, path);
  return 0;
}

/* tds.addload(path): Evolver's `addload` (datafile.h). */
static int l_addload(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  if (tds_datafile_addload(&st->ctx, &st->s, path) != TDS_OK)
    return raise_msg(L, st->ctx.errmsg);
  if (!st->datafile) { /* addload into an empty session names the surface */
    char *copy = strdup(path);
    if (copy) st->datafile = copy;
  }
  return 0;
}

/* tds.replace_load(path): Evolver's `replace_load` (datafile.h). */
static int l_replace_load(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  if (tds_datafile_replace_load(&st->ctx, &st->s, path) != TDS_OK)
    return raise_msg(L, st->ctx.errmsg);
  return 0;
}

/* tds.load_datafile(path) */
static int l_load_datafile(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  load(L, st, luaL_checkstring(L, 1));
  return 0;
}

/* The function tds.load_chunk returns for a datafile (upvalue 2: path). */
static int datafile_chunk(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  load(L, st, lua_tostring(L, lua_upvalueindex(2)));
  return 0;
}

/* tds.load_chunk(path) -> function */
static int l_load_chunk(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  /* In safe mode only a file named .tds or .lua runs as Lua: a name that
  ** does not say so is read as a datafile, whatever its content. */
  size_t n = strlen(path);
  int named_lua = (n >= 4 && !strcmp(path + n - 4, ".tds")) ||
                  (n >= 4 && !strcmp(path + n - 4, ".lua"));
  if (st->safe ? !named_lua : tds_datafile_detect(path)) {
    tds_lua_push_state(L, st);
    lua_pushvalue(L, 1);
    lua_pushcclosure(L, datafile_chunk, 2);
    return 1;
  }
  if (luaL_loadfilex(L, path, "t") != LUA_OK) { /* never bytecode */
    const char *msg = lua_tostring(L, -1);
    if (msg && !strstr(msg, path)) lua_pushfstring(L, "%s: %s", path, msg); /* name the file */
    return lua_error(L);
  }
  /* A surface with a namespace of its own runs the script in it (a safe
  ** surface's script never sees the host's globals). */
  tds_lua_kept(L, st, "env");
  if (lua_istable(L, -1)) lua_setupvalue(L, -2, 1);
  else lua_pop(L, 1);
  return 1;
}

/* Default dump name: the datafile's name with its extension replaced. */
static const char *default_dump_name(lua_State *L, tds_state *st) {
  if (!st->datafile) return NULL;
  const char *p = st->datafile;
  const char *slash = strrchr(p, '/');
  const char *dot = strrchr(slash ? slash : p, '.');
  size_t n = dot && dot != (slash ? slash + 1 : p) ? (size_t)(dot - p) : strlen(p);
  lua_pushlstring(L, p, n);
  lua_pushliteral(L, ".dmp");
  lua_concat(L, 2);
  return lua_tostring(L, -1);
}

/* The read section a dump writes, pushed: tds.E.dump_read(the loaded
** text) when the command language is there (its definitions and
** variables, not its commands, as Evolver's dump: lua/evolang.lua), else
** the loaded text; nil when there is none. */
static const char *push_dump_read(lua_State *L, const tds_surf *s) {
  if (!s->read_text) {
    lua_pushnil(L);
    return NULL;
  }
  lua_getglobal(L, "tds");
  if (lua_istable(L, -1)) {
    lua_getfield(L, -1, "E");
    if (lua_istable(L, -1)) {
      lua_getfield(L, -1, "dump_read");
      if (lua_isfunction(L, -1)) {
        lua_pushstring(L, s->read_text);
        if (lua_pcall(L, 1, 1, 0) == LUA_OK && lua_isstring(L, -1)) {
          lua_replace(L, -3);
          lua_pop(L, 1);
          return lua_tostring(L, -1);
        }
      }
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  lua_pushstring(L, s->read_text);
  return lua_tostring(L, -1);
}

/* tds.dump([path]) -> true | nil, msg */
static int l_dump(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_optstring(L, 1, NULL);
  if (!path) path = default_dump_name(L, st);
  if (!path) return tds_lua_nilmsg(L, "dump: give a file name (no datafile was loaded)");
  if (!tds_lua_may_write(L, st, path)) return 2;
  const char *read = push_dump_read(L, &st->s);
  if (tds_datafile_dump_read(&st->ctx, &st->s, path, read) != TDS_OK) {
    lua_pushnil(L);
    lua_pushstring(L, st->ctx.errmsg);
    return 2;
  }
  lua_pushboolean(L, 1);
  return 1;
}

/* dump([path]) -> true; a failure is an error at the caller's line (a
** script stops with a non-zero status, the prompt shows the message). */
static int l_dump_global(lua_State *L) {
  int n = l_dump(L);
  if (n == 2) return tds_lua_error(L, "%s", lua_tostring(L, -1));
  return n;
}

/* tds.write_fe(path [, header [, read]]) -> true | nil, msg: the plain
** element lists (tds_datafile_write_fe), behind write_fe in lua/pg.lua. */
static int l_write_fe(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  const char *header = luaL_optstring(L, 2, NULL);
  const char *read = luaL_optstring(L, 3, NULL);
  if (!tds_lua_may_write(L, st, path)) return 2;
  if (tds_datafile_write_fe(&st->ctx, &st->s, path, header, read) != TDS_OK)
    return tds_lua_nilmsg(L, "%s", st->ctx.errmsg);
  lua_pushboolean(L, 1);
  return 1;
}

/* tds.write_text(path, text) -> true | nil, msg: write a whole file the
** way dumps are written (wfile.h: temporary file, fsync, rename; refused
** outside the output folder in safe mode). */
static int l_write_text(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  size_t len;
  const char *text = luaL_checklstring(L, 2, &len);
  if (!tds_lua_may_write(L, st, path)) return 2;
  tds_wfile w;
  int rc = tds_wfile_open(&st->ctx, &w, path);
  if (rc == TDS_OK) {
    fwrite(text, 1, len, w.f); /* a short write shows in the commit's check */
    rc = tds_wfile_commit(&st->ctx, &w);
    tds_wfile_abort(&w);
  }
  if (rc != TDS_OK) {
    lua_pushnil(L);
    lua_pushstring(L, st->ctx.errmsg);
    return 2;
  }
  lua_pushboolean(L, 1);
  return 1;
}

static void no_output(void *ud, const char *text) {
  (void)ud;
  (void)text;
}

/* tds.datafile_info(text [, name]) -> table | nil, msg */
static int l_datafile_info(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  size_t len;
  const char *text = luaL_checklstring(L, 1, &len);
  const char *name = luaL_optstring(L, 2, "(string)");
  tds_surf *s = lua_newuserdatauv(L, sizeof *s, 0); /* scratch, freed below */
  tds_surf_init(s);
  tds_ctx ctx = st->ctx;
  ctx.warn = no_output;
  ctx.out = no_output;
  int rc = tds_datafile_load_buffer(&ctx, s, name, text, len);
  if (rc != TDS_OK) {
    tds_surf_free(s);
    lua_pushnil(L);
    lua_pushstring(L, ctx.errmsg);
    return 2;
  }
  lua_createtable(L, 0, 12);
  lua_pushinteger(L, tds_mesh_count(&s->m, TDS_VERTEX));
  lua_setfield(L, -2, "vertices");
  lua_pushinteger(L, tds_mesh_count(&s->m, TDS_EDGE));
  lua_setfield(L, -2, "edges");
  lua_pushinteger(L, tds_surf_count(s, TDS_FACET));
  lua_setfield(L, -2, "facets");
  lua_pushinteger(L, tds_mesh_count(&s->m, TDS_BODY));
  lua_setfield(L, -2, "bodies");
  int ncon = 0;
  for (int c = 0; c < TDS_MAX_CON; c++) ncon += s->con[c].number != 0;
  lua_pushinteger(L, ncon);
  lua_setfield(L, -2, "constraints");
  lua_pushinteger(L, s->nbdry);
  lua_setfield(L, -2, "boundaries");
  lua_pushinteger(L, s->nquant);
  lua_setfield(L, -2, "quantities");
  lua_pushnumber(L, s->gravity);
  lua_setfield(L, -2, "gravity_constant");
  lua_pushboolean(L, s->gravity_on);
  lua_setfield(L, -2, "gravity");
  lua_pushboolean(L, s->symmetric_content);
  lua_setfield(L, -2, "symmetric_content");
  if (s->read_text) {
    lua_pushstring(L, s->read_text);
    lua_setfield(L, -2, "read");
  }
  lua_newtable(L);
  for (int i = 0; i < s->npar; i++) {
    lua_pushnumber(L, s->parval[i]);
    lua_setfield(L, -2, s->parname[i]);
  }
  lua_setfield(L, -2, "parameters");
  tds_ctx ectx = st->ctx;
  if (tds_surf_update(&ectx, s) == TDS_OK) {
    lua_pushnumber(L, s->energy);
    lua_setfield(L, -2, "energy");
    lua_pushnumber(L, s->area);
    lua_setfield(L, -2, "area");
  }
  tds_surf_free(s);
  return 1;
}

void tds_open_datafile(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"load_datafile", l_load_datafile},
                                 {"dump", l_dump},
                                 {"write_fe", l_write_fe},
                                 {"load_chunk", l_load_chunk},
                                 {"datafile_info", l_datafile_info},
                                 {"write_text", l_write_text},
                                 {"read_text", l_read_text},
                                 {"load_replace", l_load_replace},
                                 {"addload", l_addload},
                                 {"replace_load", l_replace_load},
                                 {"datafile_name", l_datafile_name},
                                 {"define_text", l_define_text},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
  tds_lua_push_state(L, st);
  lua_pushcclosure(L, l_dump_global, 1);
  lua_setfield(L, -2, "dump_raise"); /* the namespace's dump (lua/prelude.lua) */
}
