/*
** lua_tds.h: the Lua bindings' shared state and helpers.
**
** One tds_state per surface: a full userdata passed to every binding of
** that surface as upvalue 1 (several surfaces may live in one lua_State,
** lua_surface.c). Bindings check arguments, call the core, and turn a
** failing status into a Lua error carrying the core's message
** (tds_lua_fail).
*/
#ifndef TDS_LUA_TDS_H
#define TDS_LUA_TDS_H

#include <lauxlib.h>
#include <lua.h>

#include "surf.h"

typedef struct tds_state {
  tds_ctx ctx;
  tds_surf s;
  char *datafile;    /* name of the loaded file, for messages and dumps */
  void (*after_chunk)(void *ud);  /* run after every chunk, or NULL */
  void *after_ud;                 /* (the live view publishes through it) */
  int safe;          /* safe mode (lua_safe.c) */
  char *outdir;      /* safe mode: the only folder written to (resolved) */
  struct tds_state *next_state; /* the process's surfaces (tds_lua_track) */
} tds_state;

/* User values of a state's userdata: the interned handles (a weak-valued
** table keyed by id * TDS_NKINDS + kind), the surface's raw library (its
** `tds` table), then the handles' metatable of each kind (TDS_UV_META +
** kind), private to the surface. */
#define TDS_UV_HANDLES 1
#define TDS_UV_LIB 2
#define TDS_UV_META 3
/* A table where bindings anchor userdata that live as long as the surface
** (tds_lua_keep). */
#define TDS_UV_KEEP (TDS_UV_META + TDS_NKINDS)
#define TDS_STATE_NUV (TDS_UV_KEEP + 1)

#define TDS_STATE(L) ((tds_state *)lua_touserdata(L, lua_upvalueindex(1)))

/* Push "file:line: " of the innermost user code on the stack (skipping C
** functions and the embedded prelude), or "" if there is none. */
void tds_lua_where(lua_State *L);

/* tds.vertex_*(v): push measure(v) for vertex handle 1, or nothing where
** the measure is not defined (NaN); lua_pg.c. */
int tds_lua_vertex_measure(lua_State *L, double (*measure)(const tds_surf *, tds_id));

/* Raise the core's message for rc as a Lua error (never returns). */
int tds_lua_fail(lua_State *L, tds_state *st, int rc);

/* Create the state, open the tds library and the prelude into L's globals.
** Returns the state (owned by L) or NULL with an error message on the
** stack. */
tds_state *tds_lua_open(lua_State *L);

/* Raise a formatted message prefixed with the user's "file:line: " (the
** innermost frame outside C and the embedded prelude). Never returns. */
int tds_lua_error(lua_State *L, const char *fmt, ...);

/* Argument i as a finite number, or raise "<what> must be finite, not nan"
** at the user's line (NaN and infinities are refused everywhere a value
** enters the surface). */
double tds_lua_checkfinite(lua_State *L, int i, const char *what);

/* Field k of the table at index t as a boolean, dflt when absent. */
int tds_lua_field_bool(lua_State *L, int t, const char *k, int dflt);

/* Push nil and a formatted message; returns 2 (the `nil, msg` convention
** of primitives whose errors the prelude raises at the user's line). */
int tds_lua_nilmsg(lua_State *L, const char *fmt, ...);

/* Register functions with the state as upvalue into the table on top. */
void tds_lua_register(lua_State *L, tds_state *st, const luaL_Reg *fns);

/* Push the full userdata of st (a live surface of L; lua_surface.c). A
** closure that needs st takes this as an upvalue, which keeps st alive. */
void tds_lua_push_state(lua_State *L, tds_state *st);
/* Pop the value on top into surface st's anchors under `name`: it lives
** as long as st (a per-surface object the C side points to). */
void tds_lua_keep(lua_State *L, tds_state *st, const char *name);
/* Push the value anchored to st under `name` (nil if none). */
void tds_lua_kept(lua_State *L, tds_state *st, const char *name);
/* Push the raw library (the `tds` table) of surface st. */
void tds_lua_push_lib(lua_State *L, tds_state *st);

/* A new surface (lua_surface.c): its state and raw bindings (the table
** `tds` of its namespace), its prelude run with the table at index env as
** its namespace (its globals). env may be the global table (the program's
** default surface, tds.globals()). safe: the surface's file writes stay
** in outdir and the code it runs sees a sandboxed library (doc/embedding.md).
** Returns the state, or NULL with an error message on the stack. */
tds_state *tds_lua_surface_new(lua_State *L, int env, int safe, const char *outdir);

/* The module opener (`require "tds"`): returns the table { new, globals }. */
int luaopen_tds(lua_State *L);

/* The sandbox of safe mode applied to the table at index lib (the global
** table for `tds --safe`, or a surface's private copy of the library);
** env: index of the table that load/loadfile/dofile use as the default
** environment, or 0 for the global table. Returns 1, or 0 with a message. */
int tds_lua_sandbox(lua_State *L, tds_state *st, int lib, int env, const char *outdir);

/* Openers of the binding files; each adds its functions to the table on
** top of the stack (the raw `tds` table). */
void tds_open_elem(lua_State *L, tds_state *st);
void tds_open_decl(lua_State *L, tds_state *st);
void tds_open_cmd(lua_State *L, tds_state *st);
void tds_open_model(lua_State *L, tds_state *st);     /* lua_model.c */
void tds_open_datafile(lua_State *L, tds_state *st);  /* lua_datafile.c */
void tds_open_pg(lua_State *L, tds_state *st);        /* lua_pg.c */
void tds_open_string(lua_State *L, tds_state *st);    /* lua_string.c */
void tds_open_export(lua_State *L, tds_state *st);    /* lua_export.c */
void tds_open_live(lua_State *L, tds_state *st);      /* lua_live.c */
void tds_open_render(lua_State *L, tds_state *st);    /* lua_render.c */
void tds_open_check(lua_State *L, tds_state *st);     /* lua_check.c */

/* Safe mode (lua_safe.c): no process spawning, no native libraries, no
** bytecode, no file written outside outdir (NULL: the current folder).
** Returns 1, or 0 with an error message on the stack. */
int tds_lua_safe(lua_State *L, tds_state *st, const char *outdir);
/* May the session write `path`? Always outside safe mode; in safe mode
** only inside the output folder. Returns 1, or 0 after pushing nil and
** the reason (the io.open convention). */
int tds_lua_may_write(lua_State *L, tds_state *st, const char *path);
void tds_open_out(lua_State *L, tds_state *st);       /* lua_out.c */
void tds_open_topo(lua_State *L, tds_state *st);      /* lua_topo.c */
void tds_open_newton(lua_State *L, tds_state *st);    /* lua_newton.c */
void tds_open_view(lua_State *L, tds_state *st);      /* lua_view.c */

/* Push the handle of element (kind, 0-based id) of the surface of the
** running binding (its upvalue 1). Handles are interned: while a handle is
** alive, the same element gives the same userdata (so handles work as
** table keys), and each knows its surface. */
void tds_push_elem(lua_State *L, int kind, tds_id id);
/* Check that argument i is a live element of `kind` (-1: any) of surface
** st (a handle of another surface is an error); returns its 0-based id
** and stores the kind. */
tds_id tds_check_elem(lua_State *L, tds_state *st, int i, int kind, int *kindp);

/* Element selection from an iterator or handle list argument: returns a
** malloc'd 0/1 array of `n` entries for `kind` (caller frees) or NULL when
** the argument is absent (meaning all). Raises on bad arguments. */
uint8_t *tds_lua_selection(lua_State *L, tds_state *st, int arg, int kind);

/* Sigint support for the REPL and main: install / restore the handler that
** sets ctx.interrupt and interrupts running Lua code. */
void tds_lua_sigint(lua_State *L, tds_state *st, int on);

/* Add (on) or remove a surface from those Ctrl-C interrupts: every
** surface's command stops, not only the program's surface's. */
void tds_lua_track(tds_state *st, int on);

/* Whether the last chunk run under tds_lua_sigint was interrupted. */
int tds_lua_interrupted(void);
/* Make SIGTERM stop a chunk as SIGINT does (tds --on-interrupt). */
void tds_lua_sigterm_stops(int on);

/* q()/quit() raise a table { tds_quit = code }; this recognises it. */
int tds_lua_is_quit(lua_State *L, int idx, int *code);

#endif
