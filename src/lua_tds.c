/* lua_tds.c: the state, the raw `tds` library, the embedded prelude. */
#include "lua_tds.h"

#include <lualib.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* Push "file:line: " of the innermost user code on the stack from level
** up (skipping C functions and the embedded prelude), or "" if none. */
static void where_user_from(lua_State *L, int level) {
  lua_Debug ar;
  for (; lua_getstack(L, level, &ar); level++) {
    lua_getinfo(L, "Sl", &ar);
    if (ar.currentline > 0 && strncmp(ar.source, "=[tds ", 6) != 0) {
      lua_pushfstring(L, "%s:%d: ", ar.short_src, ar.currentline);
      return;
    }
  }
  lua_pushliteral(L, "");
}

void tds_lua_where(lua_State *L) { where_user_from(L, 1); }

int tds_lua_fail(lua_State *L, tds_state *st, int rc) {
  (void)rc;
  tds_lua_where(L);
  lua_pushstring(L, st->ctx.errmsg);
  lua_concat(L, 2);
  return lua_error(L);
}

int tds_lua_error(lua_State *L, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  tds_lua_where(L);
  lua_pushvfstring(L, fmt, ap);
  va_end(ap);
  lua_concat(L, 2);
  return lua_error(L);
}

double tds_lua_checkfinite(lua_State *L, int i, const char *what) {
  if (lua_type(L, i) != LUA_TNUMBER)
    tds_lua_error(L, "%s must be a number, not %s", what, luaL_typename(L, i));
  double v = lua_tonumber(L, i);
  if (isnan(v)) tds_lua_error(L, "%s must be finite, not NaN", what);
  if (!isfinite(v)) tds_lua_error(L, "%s must be finite, not %sinf", what, v < 0 ? "-" : "");
  return v;
}

int tds_lua_field_bool(lua_State *L, int t, const char *k, int dflt) {
  lua_getfield(L, t, k);
  int v = lua_isnil(L, -1) ? dflt : lua_toboolean(L, -1);
  lua_pop(L, 1);
  return v;
}

int tds_lua_nilmsg(lua_State *L, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  lua_pushnil(L);
  lua_pushvfstring(L, fmt, ap);
  va_end(ap);
  return 2;
}

void tds_lua_register(lua_State *L, tds_state *st, const luaL_Reg *fns) {
  for (; fns->name; fns++) {
    tds_lua_push_state(L, st);
    lua_pushcclosure(L, fns->func, 1);
    lua_setfield(L, -2, fns->name);
  }
}

int tds_lua_is_quit(lua_State *L, int idx, int *code) {
  if (!lua_istable(L, idx)) return 0;
  lua_getfield(L, idx, "tds_quit");
  int isq = lua_isinteger(L, -1);
  if (isq && code) *code = (int)lua_tointeger(L, -1);
  lua_pop(L, 1);
  return isq;
}

/* SIGINT: flag the core's loops and stop running Lua code (as lua.c).
** The stop is sticky until the chunk ends: the hook stays armed, so a
** pcall that catches the interruption is interrupted again at its next
** instruction, and the whole chunk (script, -e code, prompt line) stops. */
static lua_State *sig_L;
/* Every live surface: the handler flags all of them, so a command running
** on a tds.new() surface stops too. Changed with the signals blocked. */
static tds_state *all_states;

void tds_lua_track(tds_state *st, int on) {
  sigset_t set, old;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, &old);
  if (on) {
    st->next_state = all_states;
    all_states = st;
  } else {
    for (tds_state **p = &all_states; *p; p = &(*p)->next_state)
      if (*p == st) {
        *p = st->next_state;
        break;
      }
  }
  pthread_sigmask(SIG_SETMASK, &old, NULL);
}

static void set_interrupt(int v) {
  for (tds_state *p = all_states; p; p = p->next_state) p->ctx.interrupt = v;
}
static volatile sig_atomic_t sig_seen; /* an interruption since the chunk began */
static int sig_also_term;              /* --on-interrupt: SIGTERM stops too */

static void stop_hook(lua_State *L, lua_Debug *ar) {
  /* Raise only in the user's Lua code, not in tds's embedded modules (the
  ** check mode's wrapper, the Evolver runtime), which finish and re-raise
  ** the command's own message ("interrupted: 3 of 10 iterations done");
  ** the hook stays armed and fires again at the next instruction. A C
  ** function polls ctx.interrupt itself. */
  if (lua_getinfo(L, "S", ar) &&
      (ar->what[0] == 'C' || strncmp(ar->source, "=[tds ", 6) == 0))
    return;
  set_interrupt(0);
  where_user_from(L, 0); /* the user's line, not the prelude's */
  lua_pushliteral(L, "interrupted");
  lua_concat(L, 2);
  lua_error(L);
}

static void on_sigint(int sig) {
  signal(sig, SIG_DFL); /* a second Ctrl-C kills the process */
  sig_seen = 1;
  set_interrupt(1);
  if (sig_L)
    lua_sethook(sig_L, stop_hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKCOUNT, 1);
}

void tds_lua_sigint(lua_State *L, tds_state *st, int on) {
  if (on) {
    sig_L = L;
    (void)st; /* every surface is flagged (all_states) */
    sig_seen = 0;
    set_interrupt(0);
    signal(SIGINT, on_sigint);
    if (sig_also_term) signal(SIGTERM, on_sigint);
  } else {
    signal(SIGINT, SIG_DFL);
    if (sig_also_term) signal(SIGTERM, SIG_DFL);
    lua_sethook(L, NULL, 0, 0);
    sig_L = NULL;
  }
}

int tds_lua_interrupted(void) { return sig_seen != 0; }

void tds_lua_sigterm_stops(int on) { sig_also_term = on; }
