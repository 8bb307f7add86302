/* lua_render.c: pictures, plots and the progress line.
**
** Raw primitives (lua/pictures.lua gives them their user names):
**   tds.snapshot(path [, opts])         -> projection/colour-range table
**   tds.plot(path [, opts])             -> panel layout table
**   tds.histogram_png(path, counts, lo, hi, title, xtitle [, opts])
**                                       -> panel layout table
**   tds.history()                       -> { iteration = {}, energy = {},
**                                            value = {}, kind = {} }
**   tds.verbose([on])                   -> previous setting
** Options are checked here: an unknown key or a value of the wrong type
** is an error naming the key, raised at the user's line.
*/
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "lua_tds.h"
#include "progress.h"
#include "render.h"

/* The surface's history, anchored to its state (tds_open_render). */
static tds_progress *progress_of(lua_State *L) {
  return TDS_STATE(L)->ctx.progress;
}

static int progress_gc(lua_State *L) {
  tds_progress_free(lua_touserdata(L, 1));
  return 0;
}

/* An option error at the user's line: "file:line: what: message". */
static int opt_error(lua_State *L, tds_state *st, const char *what,
                     const char *key, const char *msg) {
  tds_seterr(&st->ctx, TDS_ERANGE, "%s: option '%s' %s", what, key, msg);
  return tds_lua_fail(L, st, TDS_ERANGE);
}

/* Check every key of the options table at index t against `keys`. */
static void check_keys(lua_State *L, tds_state *st, int t, const char *what,
                       const char *const *keys) {
  lua_pushnil(L);
  while (lua_next(L, t)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING) {
      tds_seterr(&st->ctx, TDS_ERANGE, "%s: option names must be strings", what);
      tds_lua_fail(L, st, TDS_ERANGE);
    }
    const char *k = lua_tostring(L, -1);
    int ok = 0;
    for (int i = 0; keys[i]; i++) ok |= !strcmp(k, keys[i]);
    if (!ok) opt_error(L, st, what, k, "is unknown");
  }
}

static int opt_boolean(lua_State *L, tds_state *st, int t, const char *what,
                       const char *k, int dflt) {
  int ty = lua_getfield(L, t, k), v = dflt;
  if (ty == LUA_TBOOLEAN) v = lua_toboolean(L, -1);
  else if (ty != LUA_TNIL) opt_error(L, st, what, k, "must be true or false");
  lua_pop(L, 1);
  return v;
}

/* A pair {a, b} of numbers at option k; returns 0 when absent. */
static int opt_pair(lua_State *L, tds_state *st, int t, const char *what,
                    const char *k, double v[2], const char *msg) {
  int ty = lua_getfield(L, t, k);
  if (ty == LUA_TNIL) {
    lua_pop(L, 1);
    return 0;
  }
  int ok = ty == LUA_TTABLE && lua_rawlen(L, -1) == 2;
  for (int i = 0; ok && i < 2; i++) {
    lua_rawgeti(L, -1, i + 1);
    v[i] = lua_tonumberx(L, -1, &ok);
    ok = ok && isfinite(v[i]);
    lua_pop(L, 1);
  }
  if (!ok) opt_error(L, st, what, k, msg);
  lua_pop(L, 1);
  return 1;
}

static void opt_size(lua_State *L, tds_state *st, int t, const char *what,
                     int *w, int *h) {
  double v[2];
  if (!opt_pair(L, st, t, what, "size", v, "must be {width, height} in pixels"))
    return;
  if (v[0] != floor(v[0]) || v[1] != floor(v[1]) || v[0] < 16 || v[1] < 16 ||
      v[0] > 8192 || v[1] > 8192)
    opt_error(L, st, what, "size", "must be whole numbers of pixels, 16..8192");
  *w = (int)v[0];
  *h = (int)v[1];
}

static void view_option(lua_State *L, tds_state *st, int t, tds_render_opts *o) {
  int ty = lua_getfield(L, t, "view");
  if (ty == LUA_TSTRING) {
    const char *v = lua_tostring(L, -1);
    if (!strcmp(v, "iso")) {
      o->azimuth = -60;
      o->elevation = 30;
    } else if (!strcmp(v, "top")) {
      o->azimuth = -90;
      o->elevation = 90;
    } else if (!strcmp(v, "front")) {
      o->azimuth = -90;
      o->elevation = 0;
    } else {
      opt_error(L, st, "snapshot", "view", "must be \"iso\", \"top\", \"front\" or "
                "{azimuth, elevation [, distance]}");
    }
  } else if (ty == LUA_TTABLE) {
    int n = (int)lua_rawlen(L, -1), ok = n == 2 || n == 3;
    double v[3] = {0, 0, 0};
    for (int i = 0; ok && i < n; i++) {
      lua_rawgeti(L, -1, i + 1);
      v[i] = lua_tonumberx(L, -1, &ok);
      ok = ok && isfinite(v[i]);
      lua_pop(L, 1);
    }
    if (!ok)
      opt_error(L, st, "snapshot", "view", "must be {azimuth, elevation [, distance]} "
                "(degrees, degrees, bounding radii)");
    if (n == 3 && !(v[2] > 1))
      opt_error(L, st, "snapshot", "view", "distance must exceed 1 (bounding radii)");
    o->azimuth = v[0];
    o->elevation = v[1];
    o->distance = v[2];
  } else if (ty != LUA_TNIL) {
    opt_error(L, st, "snapshot", "view", "must be a string or a table");
  }
  lua_pop(L, 1);
}

static void setnum(lua_State *L, const char *k, double v) {
  lua_pushnumber(L, v);
  lua_setfield(L, -2, k);
}

static void setvec(lua_State *L, const char *k, const double v[3]) {
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; i++) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, k);
}

static int l_snapshot(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  if (!tds_lua_may_write(L, st, path)) /* safe mode: only in its folder */
    return tds_lua_error(L, "%s", lua_tostring(L, -1));
  tds_render_opts o;
  tds_render_defaults(&o);
  if (!lua_isnoneornil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    static const char *const keys[] = {"color", "view", "size", "edges", "range",
                                       "legend", "lighting", "smooth", NULL};
    check_keys(L, st, 2, "snapshot", keys);
    static const char *const cols[] = {"none", "mean_curvature", "min_angle", "body",
                                       "tension", "color", NULL};
    static const int codes[] = {TDS_RCOL_NONE, TDS_RCOL_MEAN_CURVATURE,
                                TDS_RCOL_MIN_ANGLE, TDS_RCOL_BODY,
                                TDS_RCOL_TENSION, TDS_RCOL_COLOR};
    int ty = lua_getfield(L, 2, "color");
    if (ty != LUA_TNIL) {
      const char *c = ty == LUA_TSTRING ? lua_tostring(L, -1) : "";
      int found = -1;
      for (int i = 0; cols[i]; i++)
        if (!strcmp(c, cols[i])) found = i;
      if (found < 0)
        opt_error(L, st, "snapshot", "color", "must be one of \"mean_curvature\", "
                  "\"min_angle\", \"body\", \"tension\", \"color\", \"none\"");
      o.color = codes[found];
    }
    lua_pop(L, 1);
    view_option(L, st, 2, &o);
    opt_size(L, st, 2, "snapshot", &o.width, &o.height);
    o.edges = opt_boolean(L, st, 2, "snapshot", "edges", 0);
    o.legend = opt_boolean(L, st, 2, "snapshot", "legend", 1);
    o.lighting = opt_boolean(L, st, 2, "snapshot", "lighting", 1);
    o.smooth = opt_boolean(L, st, 2, "snapshot", "smooth", 0);
    if (opt_pair(L, st, 2, "snapshot", "range", o.range, "must be {low, high}")) {
      if (!(o.range[0] < o.range[1]))
        opt_error(L, st, "snapshot", "range", "must have low < high");
      o.has_range = 1;
    }
  }
  tds_render_info in;
  int rc = tds_render_png(&st->ctx, &st->s, &o, path, &in);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  lua_createtable(L, 0, 12);
  setvec(L, "center", in.center);
  setvec(L, "right", in.right);
  setvec(L, "up", in.up);
  setvec(L, "toward", in.toward);
  setnum(L, "cx", in.cx);
  setnum(L, "cy", in.cy);
  setnum(L, "scale", in.scale);
  setnum(L, "radius", in.radius);
  if (o.color == TDS_RCOL_MEAN_CURVATURE || o.color == TDS_RCOL_MIN_ANGLE ||
      o.color == TDS_RCOL_TENSION) {
    setnum(L, "lo", in.lo);
    setnum(L, "hi", in.hi);
  }
  if (o.color == TDS_RCOL_BODY) { /* { [body id] = {r, g, b} }, 0..255 */
    lua_createtable(L, 0, st->s.m.nb);
    for (tds_id b = 0; b < st->s.m.nb; b++) {
      if (st->s.m.bflags[b] & TDS_DEAD) continue;
      double rgb[3];
      tds_render_body_color(b, rgb);
      lua_createtable(L, 3, 0);
      for (int k = 0; k < 3; k++) {
        lua_pushinteger(L, (lua_Integer)lround(255 * rgb[k]));
        lua_rawseti(L, -2, k + 1);
      }
      lua_rawseti(L, -2, b + 1);
    }
    lua_setfield(L, -2, "body_colors");
  }
  lua_pushinteger(L, in.drawn);
  lua_setfield(L, -2, st->s.str ? "edges" : "facets"); /* string model: edges drawn */
  lua_pushinteger(L, o.width);
  lua_setfield(L, -2, "width");
  lua_pushinteger(L, o.height);
  lua_setfield(L, -2, "height");
  return 1;
}

static void push_layout(lua_State *L, const tds_plot_info *pi, int npanels) {
  lua_createtable(L, 0, 8);
  setnum(L, "x0", pi->x0);
  setnum(L, "x1", pi->x1);
  setnum(L, "y0", pi->y0);
  setnum(L, "y1", pi->y1);
  setnum(L, "lo", pi->lo[0]);
  setnum(L, "hi", pi->hi[0]);
  if (npanels > 1) {
    setnum(L, "lo2", pi->lo[1]);
    setnum(L, "hi2", pi->hi[1]);
  }
}

static int l_plot(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  if (!tds_lua_may_write(L, st, path)) /* safe mode: only in its folder */
    return tds_lua_error(L, "%s", lua_tostring(L, -1));
  int w = 800, h = 600, mode = 0; /* energy: 0 linear, 1 log, 2 excess */
  if (!lua_isnoneornil(L, 2)) {
    luaL_checktype(L, 2, LUA_TTABLE);
    static const char *const keys[] = {"size", "energy", NULL};
    check_keys(L, st, 2, "plot", keys);
    opt_size(L, st, 2, "plot", &w, &h);
    int ty = lua_getfield(L, 2, "energy");
    const char *e = ty == LUA_TSTRING ? lua_tostring(L, -1) : "";
    if (ty == LUA_TNIL) mode = 0;
    else if (!strcmp(e, "linear")) mode = 0;
    else if (!strcmp(e, "log")) mode = 1;
    else if (!strcmp(e, "excess")) mode = 2;
    else opt_error(L, st, "plot", "energy", "must be \"linear\", \"log\" or \"excess\"");
    lua_pop(L, 1);
  }
  tds_progress *p = progress_of(L);
  if (!p || p->n == 0) {
    tds_seterr(&st->ctx, TDS_ERANGE, "plot: no iterations in this session yet");
    return tds_lua_fail(L, st, TDS_ERANGE);
  }
  /* r only at pg iterations; the energy as asked */
  double *r = lua_newuserdatauv(L, 2 * (size_t)p->n * sizeof *r, 0);
  double *e = r + p->n, emin = INFINITY;
  int haspg = 0;
  for (int32_t i = 0; i < p->n; i++) {
    r[i] = p->kinds[i] == 'p' ? p->value[i] : (double)NAN;
    haspg |= p->kinds[i] == 'p';
    if (p->energy[i] < emin) emin = p->energy[i];
  }
  for (int32_t i = 0; i < p->n; i++) e[i] = mode == 2 ? p->energy[i] - emin : p->energy[i];
  static const char *const etitle[3] = {"energy", "energy, log scale",
                                        "energy above the lowest, log scale"};
  tds_plot_series ser[2] = {{e, etitle[mode], mode > 0}, {r, "r (pg), log scale", 1}};
  tds_plot_info pi;
  int rc = tds_plot_png(&st->ctx, path, w, h, p->iter, p->n, ser, haspg ? 2 : 1,
                        "iteration", &pi);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  push_layout(L, &pi, haspg ? 2 : 1);
  lua_pushinteger(L, p->n);
  lua_setfield(L, -2, "points");
  return 1;
}

/* tds.histogram_png(path, counts, lo, hi, title, xtitle [, opts]) */
static int l_histogram_png(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *path = luaL_checkstring(L, 1);
  if (!tds_lua_may_write(L, st, path)) /* safe mode: only in its folder */
    return tds_lua_error(L, "%s", lua_tostring(L, -1));
  luaL_checktype(L, 2, LUA_TTABLE);
  double lo = luaL_checknumber(L, 3), hi = luaL_checknumber(L, 4);
  const char *title = luaL_checkstring(L, 5), *xtitle = luaL_checkstring(L, 6);
  int w = 800, h = 500;
  if (!lua_isnoneornil(L, 7)) {
    luaL_checktype(L, 7, LUA_TTABLE);
    opt_size(L, st, 7, "quality", &w, &h);
  }
  int n = (int)lua_rawlen(L, 2);
  luaL_argcheck(L, n >= 1 && n <= 1000 && hi > lo, 2, "1..1000 counts over lo < hi");
  int32_t *c = lua_newuserdatauv(L, (size_t)n * sizeof *c, 0);
  for (int i = 0; i < n; i++) {
    lua_rawgeti(L, 2, i + 1);
    c[i] = (int32_t)luaL_checkinteger(L, -1);
    lua_pop(L, 1);
  }
  tds_plot_info pi;
  int rc = tds_histogram_png(&st->ctx, path, w, h, c, n, lo, hi, title, xtitle, &pi);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  push_layout(L, &pi, 1);
  return 1;
}

static int l_history(lua_State *L) {
  tds_progress *p = progress_of(L);
  int32_t n = p ? p->n : 0;
  lua_createtable(L, 0, 4);
  const char *names[3] = {"iteration", "energy", "value"};
  for (int j = 0; j < 3; j++) {
    lua_createtable(L, n, 0);
    for (int32_t i = 0; i < n; i++) {
      double v = j == 0 ? p->iter[i] : j == 1 ? p->energy[i] : p->value[i];
      if (j == 0) lua_pushinteger(L, (lua_Integer)v);
      else lua_pushnumber(L, v);
      lua_rawseti(L, -2, i + 1);
    }
    lua_setfield(L, -2, names[j]);
  }
  lua_createtable(L, n, 0);
  for (int32_t i = 0; i < n; i++) {
    lua_pushstring(L, p->kinds[i] == 'p' ? "pg" : "g");
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "kind");
  return 1;
}

static int l_verbose(lua_State *L) {
  tds_progress *p = progress_of(L);
  lua_pushboolean(L, p && p->verbose);
  if (p && !lua_isnone(L, 1)) p->verbose = lua_toboolean(L, 1);
  return 1;
}

void tds_open_render(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"snapshot", l_snapshot},
                                 {"plot", l_plot},
                                 {"histogram_png", l_histogram_png},
                                 {"history", l_history},
                                 {"verbose", l_verbose},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
  tds_progress *p = lua_newuserdatauv(L, sizeof *p, 0);
  tds_progress_init(p);
  p->tty = isatty(STDOUT_FILENO);
  lua_newtable(L);
  lua_pushcfunction(L, progress_gc);
  lua_setfield(L, -2, "__gc");
  lua_setmetatable(L, -2);
  tds_lua_keep(L, st, "progress");
  st->ctx.progress = p;
}
