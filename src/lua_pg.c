/* lua_pg.c: the projected-gradient method and mesh metrics.
**
** Raw primitives (lua/pg.lua gives them their user names):
**   tds.pg{ iterations=, max=, nmax=, s=, plain=, depth=, flips=, every=,
**           rtol=, threads=, newton=, probe=, calm=,
**           momentum=, momentum_size= }                     -> result table
**   tds.quality()                          -> statistics table
**   tds.curvature(mode [, value [, measure]]) -> statistics table with
**                                             per-vertex values
**   tds.vertex_mean_curvature(v)           -> number or nil (K . n)
**   tds.vertex_meyer_curvature(v)          -> number or nil (signed |K|)
**   tds.facet_min_angle(f)                 -> degrees
**   tds.pg_multipliers()                   -> { [body id] = pressure }
**   tds.pg_flip_all()                      -> flips
*/
#include <math.h>
#include <stdlib.h>

#include "lua_tds.h"
#include "metrics.h"
#include "pg.h"

static lua_Integer opt_int(lua_State *L, int t, const char *k, lua_Integer d) {
  lua_getfield(L, t, k);
  lua_Integer v = d;
  if (!lua_isnil(L, -1)) {
    int ok;
    v = lua_tointegerx(L, -1, &ok);
    if (!ok) tds_lua_error(L, "pg option '%s' must be an integer", k);
  }
  lua_pop(L, 1);
  return v;
}

static double opt_num(lua_State *L, int t, const char *k, double d) {
  lua_getfield(L, t, k);
  double v = d;
  if (!lua_isnil(L, -1)) {
    int ok;
    v = lua_tonumberx(L, -1, &ok);
    if (!ok) tds_lua_error(L, "pg option '%s' must be a number", k);
  }
  lua_pop(L, 1);
  return v;
}

#define opt_bool tds_lua_field_bool

static void setnum(lua_State *L, const char *k, double v) {
  lua_pushnumber(L, v);
  lua_setfield(L, -2, k);
}
static void setint(lua_State *L, const char *k, lua_Integer v) {
  lua_pushinteger(L, v);
  lua_setfield(L, -2, k);
}

static int l_pg(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_pg_opts o;
  tds_pg_defaults(&o);
  o.threads = 1;
  if (!lua_isnoneornil(L, 1)) {
    luaL_checktype(L, 1, LUA_TTABLE);
    o.iterations = opt_int(L, 1, "iterations", 0);
    o.max_iterations = opt_int(L, 1, "max", o.max_iterations);
    o.nmax = (int)opt_int(L, 1, "nmax", o.nmax);
    o.s = opt_num(L, 1, "s", o.s);
    o.accel = !opt_bool(L, 1, "plain", 0);
    o.depth = (int)opt_int(L, 1, "depth", o.depth);
    o.flips = opt_bool(L, 1, "flips", 1);
    o.every = opt_int(L, 1, "every", 0);
    o.rtol = opt_num(L, 1, "rtol", 0);
    o.threads = (int)opt_int(L, 1, "threads", 1);
    o.newton = opt_bool(L, 1, "newton", 1);
    o.probe = opt_bool(L, 1, "probe", 1);
    o.calm = opt_bool(L, 1, "calm", 1);
    o.momentum = opt_num(L, 1, "momentum", o.momentum);
    lua_Integer ms = opt_int(L, 1, "momentum_size", o.momentum_size);
    luaL_argcheck(L, ms >= 0 && ms <= INT32_MAX, 1, "momentum_size must be in [0, 2^31)");
    o.momentum_size = (int32_t)ms;
  }
  luaL_argcheck(L, o.momentum >= 0 && o.momentum < 1, 1, "momentum must be in [0, 1)");
  luaL_argcheck(L, o.threads >= 1 && o.threads <= 2, 1, "threads must be 1 or 2");
  luaL_argcheck(L, o.iterations >= 0, 1, "iterations must not be negative");
  luaL_argcheck(L, o.nmax >= 1, 1, "nmax must be at least 1");
  luaL_argcheck(L, o.depth >= 0 && o.depth <= 50, 1, "depth must be in 0..50");
  /* refused, not read as something else: a NaN or negative s (the step
  ** would be non-finite), a NaN rtol (never met), a negative max (taken as
  ** the default cap) */
  luaL_argcheck(L, isfinite(o.s) && o.s >= 0, 1, "s must be a finite number >= 0");
  luaL_argcheck(L, isfinite(o.rtol) && o.rtol >= 0, 1, "rtol must be a finite number >= 0");
  luaL_argcheck(L, o.max_iterations >= 0, 1, "max must not be negative");
  tds_pg_result r;
  int rc = tds_pg_run(&st->ctx, &st->s, &o, &r);
  if (rc != TDS_OK) {
    return tds_lua_fail(L, st, rc);
  }
  lua_createtable(L, 0, 14);
  setint(L, "iterations", r.iterations);
  setint(L, "best_iteration", r.best_iteration);
  setnum(L, "r", r.r);
  setnum(L, "r_last", r.r_last);
  setnum(L, "r_relative", r.mean_edge > 0 ? r.r / r.mean_edge : 0);
  setint(L, "flips", r.flips);
  setint(L, "clamps", r.clamps);
  setint(L, "restarts", r.restarts);
  setint(L, "newton_builds", r.newton_builds);
  setint(L, "calms", r.calms);
  setint(L, "cycles", r.cycles);
  setint(L, "probes", r.probes);
  setint(L, "saddles", r.saddles);
  setint(L, "momentum_steps", r.momentum_steps);
  setnum(L, "momentum", r.momentum);
  setint(L, "reached", r.reached);
  setnum(L, "lambda", r.lambda);
  setnum(L, "pressure", -r.lambda);
  setnum(L, "energy", st->s.energy);
  setnum(L, "mean_edge", r.mean_edge);
  setnum(L, "seconds", r.seconds);
  setnum(L, "cpu_seconds", r.cpu_seconds);
  setint(L, "threaded_passes", r.threaded);
  setint(L, "vertices", r.nfree);
  setnum(L, "seconds_per_vertex_iteration",
         r.iterations > 0 && r.nfree > 0
             ? r.seconds / ((double)r.iterations * r.nfree) : 0);
  lua_pushboolean(L, r.converged);
  lua_setfield(L, -2, "converged");
  static const char *const status[] = {"iterations", "converged", "stalled",
                                       "cycling", "max"};
  lua_pushstring(L, status[r.status]);
  lua_setfield(L, -2, "status");
  setnum(L, "hysteresis", r.hysteresis);
  setint(L, "returns", r.returns);
  if (r.status == TDS_PG_CYCLING) setint(L, "window_flips", r.window_flips);
  if (r.message[0]) {
    lua_pushstring(L, r.message);
    lua_setfield(L, -2, "message");
  }
  return 1;
}

static int l_quality(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_quality_out q;
  tds_quality(&st->s, &q);
  lua_createtable(L, 0, 12);
  setint(L, "n", q.n);
  setnum(L, "min", q.min);
  setnum(L, "mean", q.mean);
  setnum(L, "std", q.std);
  setnum(L, "above30", q.above[0]);
  setnum(L, "above40", q.above[1]);
  setnum(L, "above50", q.above[2]);
  setnum(L, "above55", q.above[3]);
  lua_createtable(L, 12, 0);
  for (int i = 0; i < 12; i++) {
    lua_pushinteger(L, q.hist[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "histogram");
  if (q.worst != TDS_NONE) setint(L, "worst", q.worst + 1);
  return 1;
}

static void push_stats(lua_State *L, const tds_curv_stats *o, int32_t n) {
  lua_createtable(L, 0, 5);
  setnum(L, "max", o->max);
  setnum(L, "mean", o->mean);
  setnum(L, "rms", o->rms);
  setnum(L, "mean_curvature", o->hmean);
  if (n > 0 && o->worst != TDS_NONE) setint(L, "worst", o->worst + 1);
}

/* tds.curvature(mode, value, measure): measure "meyer" (signed |K|) or
** "normal" (K . n) picks the per-vertex values and the top-level figures;
** both measures' statistics are in .meyer and .normal, and the RMS of both
** by vertex valence in .by_valence[k] = { n, rms, rms_normal }. */
static int l_curvature(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  static const char *const modes[] = {"value", "lambda", "pressure", NULL};
  static const char *const measures[] = {"meyer", "normal", NULL};
  int mode = luaL_checkoption(L, 1, "value", modes);
  double value = luaL_optnumber(L, 2, 0);
  int measure = luaL_checkoption(L, 3, "meyer", measures);
  tds_mesh *m = &st->s.m;
  size_t nv = (size_t)(m->nv > 0 ? m->nv : 1);
  double *hm = lua_newuserdatauv(L, 3 * nv * sizeof *hm, 0);
  double *hn = hm + nv, *tg = hn + nv;
  tds_curv_out c;
  int rc = tds_curvature(&st->ctx, &st->s, mode, value, hm, hn, tg, &c);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  const double *h = measure ? hn : hm;
  const tds_curv_stats *o = measure ? &c.normal : &c.meyer;
  lua_createtable(L, 0, 16);
  lua_pushstring(L, measures[measure]);
  lua_setfield(L, -2, "measure");
  setint(L, "n", c.n);
  setnum(L, "max", o->max);
  setnum(L, "mean", o->mean);
  setnum(L, "rms", o->rms);
  setnum(L, "mean_curvature", o->hmean);
  if (c.n > 0 && o->worst != TDS_NONE) {
    setint(L, "worst", o->worst + 1);
    setnum(L, "worst_value", h[o->worst]);
    setnum(L, "worst_target", tg[o->worst]);
  }
  push_stats(L, &c.meyer, c.n);
  lua_setfield(L, -2, "meyer");
  push_stats(L, &c.normal, c.n);
  lua_setfield(L, -2, "normal");
  /* by valence (edges at the vertex): counts and sums of squares */
  enum { VMAX = 64 };
  int32_t cnt[VMAX + 1] = {0};
  double s2[VMAX + 1][2] = {{0}};
  for (tds_id v = 0; v < m->nv; v++) {
    if (isnan(hm[v])) continue;
    int k = (int)(m->ve_start[v + 1] - m->ve_start[v]);
    if (k > VMAX) k = VMAX;
    double e0 = hm[v] - tg[v], e1 = hn[v] - tg[v];
    cnt[k]++;
    s2[k][0] += e0 * e0;
    s2[k][1] += e1 * e1;
  }
  lua_newtable(L);
  for (int k = 0; k <= VMAX; k++) {
    if (!cnt[k]) continue;
    lua_createtable(L, 0, 3);
    setint(L, "n", cnt[k]);
    setnum(L, "rms", sqrt(s2[k][measure] / cnt[k]));
    setnum(L, "rms_meyer", sqrt(s2[k][0] / cnt[k]));
    setnum(L, "rms_normal", sqrt(s2[k][1] / cnt[k]));
    lua_rawseti(L, -2, k);
  }
  lua_setfield(L, -2, "by_valence");
  lua_newtable(L);
  lua_newtable(L);
  lua_newtable(L);
  for (tds_id v = 0; v < m->nv; v++) {
    if (isnan(h[v])) continue;
    lua_pushnumber(L, h[v]);
    lua_rawseti(L, -4, v + 1);
    lua_pushnumber(L, h[v] - tg[v]);
    lua_rawseti(L, -3, v + 1);
    lua_pushnumber(L, tg[v]);
    lua_rawseti(L, -2, v + 1);
  }
  lua_setfield(L, -4, "targets");
  lua_setfield(L, -3, "errors");
  lua_setfield(L, -2, "values");
  return 1;
}

int tds_lua_vertex_measure(lua_State *L, double (*measure)(const tds_surf *, tds_id)) {
  tds_state *st = TDS_STATE(L);
  tds_id v = tds_check_elem(L, st, 1, TDS_VERTEX, NULL);
  if (tds_mesh_adjacency(&st->s.m) != TDS_OK) return tds_lua_error(L, "out of memory");
  double h = measure(&st->s, v);
  if (isnan(h)) return 0;
  lua_pushnumber(L, h);
  return 1;
}

static int l_vertex_mean_curvature(lua_State *L) {
  return tds_lua_vertex_measure(L, tds_vertex_mean_curvature);
}

static int l_vertex_meyer_curvature(lua_State *L) {
  return tds_lua_vertex_measure(L, tds_vertex_meyer_curvature);
}

static int l_facet_min_angle(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_id f = tds_check_elem(L, st, 1, TDS_FACET, NULL);
  lua_pushnumber(L, tds_facet_min_angle(&st->s.m, f));
  return 1;
}

static int l_pg_multipliers(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_mesh *m = &st->s.m;
  double *mult = lua_newuserdatauv(L, (size_t)(m->nb > 0 ? m->nb : 1) * sizeof *mult, 0);
  int rc = tds_pg_multipliers(&st->ctx, &st->s, mult);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  lua_newtable(L);
  for (tds_id b = 0; b < m->nb; b++) {
    if (!tds_alive(m->bflags, b)) continue;
    lua_pushnumber(L, mult[b]);
    lua_rawseti(L, -2, b + 1);
  }
  return 1;
}

static int l_pg_flip_all(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int32_t n = 0;
  int rc = tds_pg_flip_all(&st->ctx, &st->s, &n);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  lua_pushinteger(L, n);
  return 1;
}

/* tds.pg_polish(steps, floor_degrees, mean_floor_degrees) -> phi0, phi1, moved */
static int l_pg_polish(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  lua_Integer steps = luaL_checkinteger(L, 1);
  double fl = luaL_checknumber(L, 2), mfl = luaL_optnumber(L, 3, 0);
  if (steps < 0 || steps > 1000000) return tds_lua_error(L, "pg_polish: steps must be 0 to 1000000");
  double p0 = 0, p1 = 0;
  int32_t n = 0;
  int rc = tds_pg_polish(&st->ctx, &st->s, (int)steps, fl, mfl, &p0, &p1, &n);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  lua_pushnumber(L, p0);
  lua_pushnumber(L, p1);
  lua_pushinteger(L, n);
  return 3;
}

void tds_open_pg(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {
      {"pg", l_pg},
      {"quality", l_quality},
      {"curvature", l_curvature},
      {"vertex_mean_curvature", l_vertex_mean_curvature},
      {"vertex_meyer_curvature", l_vertex_meyer_curvature},
      {"facet_min_angle", l_facet_min_angle},
      {"pg_multipliers", l_pg_multipliers},
      {"pg_flip_all", l_pg_flip_all},
      {"pg_polish", l_pg_polish},
      {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
