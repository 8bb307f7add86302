/* lua_live.c: the live view's primitives; lua/live.lua builds show() on
** them. The server (live.c) runs in its own thread and only reads
** snapshots; every snapshot is built here, on the thread running Lua:
** after each chunk (REPL line, script, -e), after an iteration of g or pg
** (at most every PUBLISH_GAP seconds), and when show() is called. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "live.h"
#include "live_snap.h"
#include "lua_tds.h"

#define PUBLISH_GAP 0.1 /* seconds between snapshots during an iteration */

typedef struct live_ud {
  tds_state *st;
  tds_live *lv;        /* NULL when stopped */
  uint64_t version;    /* of the last snapshot published */
  int color;           /* initial field of the page: index, -1 = none */
  double last;         /* monotonic time of the last snapshot */
} live_ud;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Build and publish a snapshot; failures (out of memory) skip it: the
** page keeps the previous one. */
static void publish(live_ud *u, double energy) {
  unsigned char *buf;
  size_t len;
  tds_ctx quiet = u->st->ctx; /* keep the user's last error message */
  if (tds_live_snap_build(&quiet, &u->st->s, u->version + 1, energy, u->color,
                          &buf, &len) != TDS_OK)
    return;
  u->version++;
  tds_live_publish(u->lv, buf, len, u->version);
  u->last = now();
}

static void drop(void *ud, const char *text) {
  (void)ud;
  (void)text;
}

/* Energy and area of the surface as it is now (totals() does the same),
** without touching the user's error message or printing warnings. */
static double current_energy(live_ud *u) {
  tds_ctx quiet = u->st->ctx;
  quiet.quiet = 1;
  quiet.warn = drop;
  if (tds_surf_update(&quiet, &u->st->s) != TDS_OK) return NAN;
  return u->st->s.energy;
}

static void on_step(void *ud, double energy) {
  live_ud *u = ud;
  if (u->lv && now() - u->last >= PUBLISH_GAP) publish(u, energy);
}

static void on_chunk(void *ud) {
  live_ud *u = ud;
  if (u->lv) publish(u, current_energy(u));
}

/* The surface's live view: upvalue 2 of the live functions (each surface
** has its own; the collector stops its server). */
static live_ud *get_ud(lua_State *L) {
  return lua_touserdata(L, lua_upvalueindex(2));
}

static void stop(live_ud *u) {
  if (!u->lv) return;
  tds_live_stop(u->lv);
  u->lv = NULL;
  u->st->ctx.step = NULL;
  u->st->after_chunk = NULL;
}

static int live_gc(lua_State *L) {
  stop(lua_touserdata(L, 1));
  return 0;
}

/* tds.live_start(port, color, edges) -> port | nil, message. Starts the
** server unless it runs (a different nonzero port restarts it), sets the
** page's initial field ("none" or a field name) and publishes. */
static int l_live_start(lua_State *L) {
  live_ud *u = get_ud(L);
  lua_Integer port = luaL_checkinteger(L, 1);
  const char *color = luaL_checkstring(L, 2);
  int field = strcmp(color, "none") ? tds_live_field_index(color) : -1;
  if (field < 0 && strcmp(color, "none"))
    return tds_lua_nilmsg(L, "unknown colour field '%s'", color);
  if (port < 0 || port > 65535)
    return tds_lua_nilmsg(L, "port %d is not 0..65535", (int)port);
  if (!u->lv || (port && port != tds_live_port(u->lv))) {
    /* A new server; the running one (if any) stops only once the new one
    ** listens, so a refused port leaves the view as it was. */
    tds_ctx *ctx = &u->st->ctx;
    tds_live *lv;
    char *web = tds_live_find_web(ctx, NULL);
    if (!web) return tds_lua_nilmsg(L, "%s", ctx->errmsg);
    int rc = tds_live_start(ctx, web, (int)port, &lv);
    free(web);
    if (rc != TDS_OK) return tds_lua_nilmsg(L, "%s", ctx->errmsg);
    stop(u);
    u->lv = lv;
    u->st->ctx.step = on_step;
    u->st->ctx.step_ud = u;
    u->st->after_chunk = on_chunk;
    u->st->after_ud = u;
  }
  u->color = field;
  publish(u, current_energy(u));
  lua_pushinteger(L, tds_live_port(u->lv));
  return 1;
}

/* tds.live_stop() -> true if a server was running */
static int l_live_stop(lua_State *L) {
  live_ud *u = get_ud(L);
  lua_pushboolean(L, u->lv != NULL);
  stop(u);
  return 1;
}

/* tds.live_port() -> port, version of the last snapshot | nil */
static int l_live_port(lua_State *L) {
  live_ud *u = get_ud(L);
  if (!u->lv) return 0;
  lua_pushinteger(L, tds_live_port(u->lv));
  lua_pushinteger(L, (lua_Integer)u->version);
  return 2;
}

void tds_open_live(lua_State *L, tds_state *st) {
  live_ud *u = lua_newuserdatauv(L, sizeof *u, 0);
  memset(u, 0, sizeof *u);
  u->st = st;
  u->color = -1;
  lua_newtable(L);
  lua_pushcfunction(L, live_gc);
  lua_setfield(L, -2, "__gc");
  lua_setmetatable(L, -2); /* tds u */
  static const luaL_Reg fns[] = {{"live_start", l_live_start},
                                 {"live_stop", l_live_stop},
                                 {"live_port", l_live_port},
                                 {NULL, NULL}};
  for (const luaL_Reg *f = fns; f->name; f++) {
    tds_lua_push_state(L, st);
    lua_pushvalue(L, -2);
    lua_pushcclosure(L, f->func, 2);
    lua_setfield(L, -3, f->name);
  }
  lua_pop(L, 1);
}
