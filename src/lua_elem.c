/* lua_elem.c: element handles (tds.vertex, tds.edge, tds.facet, tds.body),
** their attributes, iteration and selections. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gather.h"
#include "geom.h"
#include "lua_tds.h"
#include "motion.h"

/* A handle: one element of one surface. Its user value 1 is the state's
** userdata, so a handle keeps its surface alive. */
typedef struct handle {
  tds_state *st;
  int kind;
  tds_id id;
} handle;

static const char *const kind_name[TDS_NKINDS] = {"vertex", "edge", "facet",
                                                  "body"};
static const char *const meta_name[TDS_NKINDS] = {"tds.vertex", "tds.edge",
                                                  "tds.facet", "tds.body"};

static int32_t nslots(const tds_mesh *m, int kind) {
  switch (kind) {
  case TDS_VERTEX: return m->nv;
  case TDS_EDGE: return m->ne;
  case TDS_FACET: return m->nf;
  default: return m->nb;
  }
}

static const uint32_t *flags_of(const tds_mesh *m, int kind) {
  switch (kind) {
  case TDS_VERTEX: return m->vflags;
  case TDS_EDGE: return m->eflags;
  case TDS_FACET: return m->fflags;
  default: return m->bflags;
  }
}

static int alive(const tds_mesh *m, int kind, tds_id id) {
  return id >= 0 && id < nslots(m, kind) && tds_alive(flags_of(m, kind), id);
}

/* The interned handle of (kind, id) from the state userdata's cache, or a
** new one stored there. Upvalue 1 of the running binding is the state. */
void tds_push_elem(lua_State *L, int kind, tds_id id) {
  int sti = lua_upvalueindex(1);
  tds_state *st = lua_touserdata(L, sti);
  lua_Integer key = (lua_Integer)id * TDS_NKINDS + kind;
  luaL_checkstack(L, 4, "handle");
  lua_getiuservalue(L, sti, TDS_UV_HANDLES); /* cache */
  if (lua_rawgeti(L, -1, key) == LUA_TUSERDATA) { /* cache h */
    lua_remove(L, -2);
    return;
  }
  lua_pop(L, 1);
  handle *h = lua_newuserdatauv(L, sizeof *h, 1); /* cache h */
  h->st = st;
  h->kind = kind;
  h->id = id;
  lua_pushvalue(L, sti);
  lua_setiuservalue(L, -2, 1);
  lua_getiuservalue(L, sti, TDS_UV_META + kind);
  lua_setmetatable(L, -2);
  lua_pushvalue(L, -1);
  lua_rawseti(L, -3, key); /* cache[key] = h */
  lua_remove(L, -2);
}

static handle *to_handle(lua_State *L, int i) {
  handle *h = lua_touserdata(L, i);
  if (!h || !lua_getmetatable(L, i)) return NULL;
  lua_getfield(L, -1, "__tds_kind");
  int ok = lua_isinteger(L, -1);
  lua_pop(L, 2);
  return ok ? h : NULL;
}

tds_id tds_check_elem(lua_State *L, tds_state *st, int i, int kind, int *kindp) {
  handle *h = to_handle(L, i);
  if (!h || (kind >= 0 && h->kind != kind)) {
    const char *want = kind >= 0 ? kind_name[kind] : "element";
    if (h)
      tds_lua_error(L, "%s expected, got %s %d", want, kind_name[h->kind], (int)h->id + 1);
    tds_lua_error(L, "%s expected, got %s", want, luaL_typename(L, i));
  }
  if (h->st != st)
    tds_lua_error(L, "%s %d belongs to another surface", kind_name[h->kind], (int)h->id + 1);
  if (!alive(&st->s.m, h->kind, h->id))
    luaL_error(L, "%s %d no longer exists", kind_name[h->kind], h->id + 1);
  if (kindp) *kindp = h->kind;
  return h->id;
}

/* Attributes. ------------------------------------------------------------ */

static void push_cmask(lua_State *L, const tds_surf *s, tds_cmask mask) {
  lua_newtable(L);
  int n = 0;
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (mask & ((tds_cmask)1 << c)) {
      lua_pushinteger(L, s->con[c].number);
      lua_rawseti(L, -2, ++n);
    }
}

/* A constraint number or list of numbers -> mask; raises on unknown ones. */
static tds_cmask check_cmask(lua_State *L, const tds_surf *s, int i) {
  tds_cmask mask = 0;
  if (lua_isnoneornil(L, i) || lua_isboolean(L, i)) return 0;
  int n = lua_istable(L, i) ? (int)luaL_len(L, i) : 1;
  for (int k = 1; k <= n; k++) {
    lua_Integer c;
    if (lua_istable(L, i)) {
      lua_rawgeti(L, i, k);
      c = luaL_checkinteger(L, -1);
      lua_pop(L, 1);
    } else {
      c = luaL_checkinteger(L, i);
    }
    int slot = tds_surf_con_slot(s, (int)(c < 0 ? -c : c));
    if (slot < 0) luaL_error(L, "constraint %d is not defined", (int)c);
    mask |= (tds_cmask)1 << slot;
  }
  return mask;
}

/* The value being assigned (argument 3) as a finite number, or raise
** "vertex 1: x must be finite, not nan" at the user's line. */
static double finite_value(lua_State *L, int kind, tds_id id, const char *k) {
  char what[64];
  snprintf(what, sizeof what, "%s %d: %s", kind_name[kind], (int)id + 1, k);
  return tds_lua_checkfinite(L, 3, what);
}

static int set_flag(lua_State *L, uint32_t *flags, tds_id id, uint32_t bit, int i) {
  if (lua_toboolean(L, i))
    flags[id] |= bit;
  else
    flags[id] &= ~bit;
  return 0;
}

static int push_body(lua_State *L, tds_id b) {
  if (b == TDS_NONE)
    lua_pushnil(L);
  else
    tds_push_elem(L, TDS_BODY, b);
  return 1;
}

static double edge_length(const tds_mesh *m, tds_id e) {
  double d[3];
  tds_edge_vec(m, TDS_OREF(e, 0), d);
  return v3_norm(d);
}

static int on_constraint(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind;
  tds_id id = tds_check_elem(L, st, 1, -1, &kind);
  lua_Integer c = luaL_checkinteger(L, 2);
  int slot = tds_surf_con_slot(&st->s, (int)c);
  const tds_mesh *m = &st->s.m;
  tds_cmask mask = kind == TDS_VERTEX ? m->vcon[id]
                   : kind == TDS_EDGE ? m->econ[id]
                   : kind == TDS_FACET ? m->fcon[id] : 0;
  lua_pushboolean(L, slot >= 0 && (mask & ((tds_cmask)1 << slot)));
  return 1;
}

static int on_boundary(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind;
  tds_id id = tds_check_elem(L, st, 1, -1, &kind);
  lua_Integer b = luaL_checkinteger(L, 2);
  const tds_surf *s = &st->s;
  int32_t slot = kind == TDS_VERTEX ? s->m.vbdry[id]
                 : kind == TDS_EDGE ? s->m.ebdry[id] : TDS_NONE;
  lua_pushboolean(L, slot != TDS_NONE && s->bdry[slot].number == b);
  return 1;
}

static int vertex_get(lua_State *L, tds_state *st, tds_id v, const char *k) {
  tds_surf *s = &st->s;
  tds_mesh *m = &s->m;
  if (!strcmp(k, "x") || !strcmp(k, "y") || !strcmp(k, "z"))
    lua_pushnumber(L, m->x[v][k[0] - 'x']);
  else if (!strcmp(k, "fixed")) lua_pushboolean(L, m->vflags[v] & TDS_FIXED);
  else if (!strcmp(k, "bare")) lua_pushboolean(L, m->vflags[v] & TDS_BARE);
  else if (!strcmp(k, "constraints")) push_cmask(L, s, m->vcon[v]);
  else if (!strcmp(k, "boundary")) {
    if (m->vbdry[v] == TDS_NONE) lua_pushnil(L);
    else lua_pushinteger(L, s->bdry[m->vbdry[v]].number);
  } else if (!strcmp(k, "p1") || !strcmp(k, "p2"))
    lua_pushnumber(L, m->vp[v][k[1] - '1']);
  else if (!strcmp(k, "valence")) {
    if (tds_mesh_adjacency(m) != TDS_OK) return luaL_error(L, "out of memory");
    lua_pushinteger(L, m->ve_start[v + 1] - m->ve_start[v]);
  } else return 0;
  return 1;
}

/* vertex.p1 / .p2 = value: move a boundary vertex along its boundary.
** All or nothing: where the boundary formula is not finite, nothing moves. */
static int set_param(lua_State *L, tds_surf *s, tds_id v, int k) {
  tds_mesh *m = &s->m;
  double p = luaL_checknumber(L, 3);
  if (m->vbdry[v] == TDS_NONE)
    return luaL_error(L, "vertex %d is not on a boundary, so it has no p%d", v + 1, k + 1);
  if (k >= s->bdry[m->vbdry[v]].nparams)
    return luaL_error(L, "vertex %d: boundary %d has only p1", v + 1,
                      s->bdry[m->vbdry[v]].number);
  if (!isfinite(p)) return luaL_error(L, "vertex %d: p%d must be finite", v + 1, k + 1);
  double x0[3], p0 = m->vp[v][k];
  v3_copy(x0, m->x[v]);
  m->vp[v][k] = p;
  if (tds_motion_enforce(s, v) != TDS_OK) {
    m->vp[v][k] = p0;
    v3_copy(m->x[v], x0);
    return luaL_error(L, "vertex %d: boundary %d is not defined at p%d = %g",
                      v + 1, s->bdry[m->vbdry[v]].number, k + 1, p);
  }
  m->coord_gen++;
  return 1;
}

static int vertex_set(lua_State *L, tds_state *st, tds_id v, const char *k) {
  tds_surf *s = &st->s;
  tds_mesh *m = &s->m;
  if (!strcmp(k, "x") || !strcmp(k, "y") || !strcmp(k, "z")) {
    m->x[v][k[0] - 'x'] = finite_value(L, TDS_VERTEX, v, k);
    m->coord_gen++;
  } else if (!strcmp(k, "fixed")) set_flag(L, m->vflags, v, TDS_FIXED, 3);
  else if (!strcmp(k, "bare")) set_flag(L, m->vflags, v, TDS_BARE, 3);
  else if (!strcmp(k, "p1") || !strcmp(k, "p2")) return set_param(L, s, v, k[1] - '1');
  else if (!strcmp(k, "constraint") || !strcmp(k, "constraints")) {
    /* all or nothing: a failed projection leaves the vertex as it was */
    tds_cmask old = m->vcon[v];
    double x[3] = {m->x[v][0], m->x[v][1], m->x[v][2]}, p[2] = {m->vp[v][0], m->vp[v][1]};
    m->vcon[v] = check_cmask(L, s, 3);
    m->coord_gen++;
    if (tds_motion_enforce(s, v) != TDS_OK) {
      m->vcon[v] = old;
      memcpy(m->x[v], x, sizeof x);
      memcpy(m->vp[v], p, sizeof p);
      return tds_lua_error(L, "vertex %d could not be projected onto its constraints", v + 1);
    }
  } else return 0;
  return 1;
}

static int edge_get(lua_State *L, tds_state *st, tds_id e, const char *k) {
  tds_surf *s = &st->s;
  tds_mesh *m = &s->m;
  if (!strcmp(k, "length")) lua_pushnumber(L, edge_length(m, e));
  else if (!strcmp(k, "tail")) tds_push_elem(L, TDS_VERTEX, m->ev[e][0]);
  else if (!strcmp(k, "head")) tds_push_elem(L, TDS_VERTEX, m->ev[e][1]);
  else if (!strcmp(k, "fixed")) lua_pushboolean(L, m->eflags[e] & TDS_FIXED);
  else if (!strcmp(k, "no_refine")) lua_pushboolean(L, m->eflags[e] & TDS_NO_REFINE);
  else if (!strcmp(k, "tension") || !strcmp(k, "density")) lua_pushnumber(L, m->eten[e]);
  else if (!strcmp(k, "color")) lua_pushinteger(L, m->ecolor[e]);
  else if (!strcmp(k, "valence")) lua_pushinteger(L, tds_edge_valence(m, e));
  else if (!strcmp(k, "constraints")) push_cmask(L, s, m->econ[e]);
  else if (!strcmp(k, "boundary")) {
    if (m->ebdry[e] == TDS_NONE) lua_pushnil(L);
    else lua_pushinteger(L, s->bdry[m->ebdry[e]].number);
  } else return 0;
  return 1;
}

static int edge_set(lua_State *L, tds_state *st, tds_id e, const char *k) {
  tds_surf *s = &st->s;
  tds_mesh *m = &s->m;
  if (!strcmp(k, "fixed")) set_flag(L, m->eflags, e, TDS_FIXED, 3);
  else if (!strcmp(k, "no_refine")) set_flag(L, m->eflags, e, TDS_NO_REFINE, 3);
  else if (!strcmp(k, "tension") || !strcmp(k, "density")) m->eten[e] = finite_value(L, TDS_EDGE, e, k);
  else if (!strcmp(k, "color")) m->ecolor[e] = (int16_t)luaL_checkinteger(L, 3);
  else if (!strcmp(k, "constraint") || !strcmp(k, "constraints")) m->econ[e] = check_cmask(L, s, 3);
  else return 0;
  return 1;
}

static int facet_get(lua_State *L, tds_state *st, tds_id f, const char *k) {
  tds_surf *s = &st->s;
  tds_mesh *m = &s->m;
  if (!strcmp(k, "area")) {
    tds_corners C;
    tds_gather_facet(m, f, &C);
    lua_pushnumber(L, geom_area(C.x[0], C.x[1], C.x[2], NULL));
  } else if (!strcmp(k, "tension") || !strcmp(k, "density")) lua_pushnumber(L, m->ften[f]);
  else if (!strcmp(k, "fixed")) lua_pushboolean(L, m->fflags[f] & TDS_FIXED);
  else if (!strcmp(k, "no_refine")) lua_pushboolean(L, m->fflags[f] & TDS_NO_REFINE);
  else if (!strcmp(k, "nodisplay")) lua_pushboolean(L, m->fflags[f] & TDS_NODISPLAY);
  else if (!strcmp(k, "color")) lua_pushinteger(L, m->fcolor[f]);
  else if (!strcmp(k, "frontbody")) return push_body(L, m->fb[f][0]);
  else if (!strcmp(k, "backbody")) return push_body(L, m->fb[f][1]);
  else if (!strcmp(k, "original")) {
    if (m->forig[f] == TDS_NONE) lua_pushnil(L);
    else lua_pushinteger(L, m->forig[f] + 1);
  } else if (!strcmp(k, "constraints")) push_cmask(L, s, m->fcon[f]);
  else if (!strcmp(k, "vertices") || !strcmp(k, "edges")) {
    lua_createtable(L, 3, 0);
    for (int i = 0; i < 3; i++) {
      if (k[0] == 'v') tds_push_elem(L, TDS_VERTEX, m->fv[f][i]);
      else lua_pushinteger(L, (TDS_OID(m->fe[f][i]) + 1) * (TDS_OREV(m->fe[f][i]) ? -1 : 1));
      lua_rawseti(L, -2, i + 1);
    }
  } else return 0;
  return 1;
}

static tds_id opt_body(lua_State *L, tds_state *st, int i) {
  if (lua_isnoneornil(L, i) || (lua_isinteger(L, i) && lua_tointeger(L, i) == 0))
    return TDS_NONE;
  if (lua_isinteger(L, i)) {
    lua_Integer b = lua_tointeger(L, i);
    if (!alive(&st->s.m, TDS_BODY, (tds_id)b - 1))
      luaL_error(L, "body %d does not exist", (int)b);
    return (tds_id)b - 1;
  }
  return tds_check_elem(L, st, i, TDS_BODY, NULL);
}

static int facet_set(lua_State *L, tds_state *st, tds_id f, const char *k) {
  tds_surf *s = &st->s;
  tds_mesh *m = &s->m;
  if (!strcmp(k, "tension") || !strcmp(k, "density")) m->ften[f] = finite_value(L, TDS_FACET, f, k);
  else if (!strcmp(k, "fixed")) set_flag(L, m->fflags, f, TDS_FIXED, 3);
  else if (!strcmp(k, "no_refine")) set_flag(L, m->fflags, f, TDS_NO_REFINE, 3);
  else if (!strcmp(k, "nodisplay")) set_flag(L, m->fflags, f, TDS_NODISPLAY, 3);
  else if (!strcmp(k, "color")) m->fcolor[f] = (int16_t)luaL_checkinteger(L, 3);
  else if (!strcmp(k, "frontbody")) m->fb[f][0] = opt_body(L, st, 3);
  else if (!strcmp(k, "backbody")) m->fb[f][1] = opt_body(L, st, 3);
  else if (!strcmp(k, "constraint") || !strcmp(k, "constraints")) m->fcon[f] = check_cmask(L, s, 3);
  else return 0;
  m->topo_gen++; /* bodies and constraints feed derived data */
  return 1;
}

static int body_get(lua_State *L, tds_state *st, tds_id b, const char *k) {
  tds_surf *s = &st->s;
  tds_mesh *m = &s->m;
  if (!strcmp(k, "volume")) {
    int rc = tds_surf_update(&st->ctx, s);
    if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
    lua_pushnumber(L, m->bvol[b]);
  } else if (!strcmp(k, "target")) {
    if (m->bflags[b] & TDS_TARGET) lua_pushnumber(L, m->btarget[b]);
    else lua_pushnil(L);
  } else if (!strcmp(k, "pressure")) lua_pushnumber(L, m->bpressure[b]);
  else if (!strcmp(k, "density")) lua_pushnumber(L, m->bdensity[b]);
  else if (!strcmp(k, "volconst")) lua_pushnumber(L, m->bvolconst[b]);
  else return 0;
  return 1;
}

static int body_set(lua_State *L, tds_state *st, tds_id b, const char *k) {
  tds_surf *s = &st->s;
  tds_mesh *m = &s->m;
  if (!strcmp(k, "target") || !strcmp(k, "volume")) {
    if (lua_isnil(L, 3)) {
      m->bflags[b] &= ~TDS_TARGET;
    } else {
      m->btarget[b] = finite_value(L, TDS_BODY, b, k);
      m->bflags[b] = (m->bflags[b] | TDS_TARGET) & ~TDS_PRESSURE;
    }
  } else if (!strcmp(k, "pressure")) {
    if (lua_isnil(L, 3)) {
      m->bflags[b] &= ~TDS_PRESSURE;
    } else {
      m->bpressure[b] = finite_value(L, TDS_BODY, b, k);
      m->bflags[b] = (m->bflags[b] | TDS_PRESSURE) & ~TDS_TARGET;
    }
  } else if (!strcmp(k, "density")) {
    m->bdensity[b] = finite_value(L, TDS_BODY, b, k);
    if (m->bdensity[b] != 0) s->gravity_on = 1;
  } else if (!strcmp(k, "volconst")) {
    m->bvolconst[b] = finite_value(L, TDS_BODY, b, k);
    m->bflags[b] |= TDS_VOLCONST;
  } else return 0;
  return 1;
}

static int (*const getters[TDS_NKINDS])(lua_State *, tds_state *, tds_id,
                                        const char *) = {vertex_get, edge_get,
                                                         facet_get, body_get};
static int (*const setters[TDS_NKINDS])(lua_State *, tds_state *, tds_id,
                                        const char *) = {vertex_set, edge_set,
                                                         facet_set, body_set};

/* __index: id, built-in attributes, then computed attributes (functions
** in the metatable's `props` table, called with the handle: tds.props.<kind>),
** then methods (tds.methods.<kind>: C methods and Lua extensions). */
static int elem_index(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind;
  tds_id id = tds_check_elem(L, st, 1, -1, &kind);
  const char *k = luaL_checkstring(L, 2);
  if (!strcmp(k, "id")) {
    lua_pushinteger(L, id + 1);
    return 1;
  }
  if (getters[kind](L, st, id, k)) return 1;
  lua_getmetatable(L, 1);
  lua_getfield(L, -1, "props");
  if (lua_getfield(L, -1, k) == LUA_TFUNCTION) {
    lua_pushvalue(L, 1);
    lua_call(L, 1, 1);
    return 1;
  }
  lua_pop(L, 2);
  lua_getfield(L, -1, "methods");
  if (lua_getfield(L, -1, k) == LUA_TNIL) /* a misspelt name is not nil */
    return tds_lua_error(L, "%s %d has no attribute '%s'", kind_name[kind], (int)id + 1, k);
  return 1;
}

static int elem_newindex(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind;
  tds_id id = tds_check_elem(L, st, 1, -1, &kind);
  const char *k = luaL_checkstring(L, 2);
  if (!setters[kind](L, st, id, k))
    return luaL_error(L, "%s attribute '%s' cannot be set", kind_name[kind], k);
  return 0;
}

static int elem_tostring(lua_State *L) {
  handle *h = to_handle(L, 1);
  lua_pushfstring(L, "%s %d", kind_name[h->kind], (int)h->id + 1);
  return 1;
}

static int elem_eq(lua_State *L) {
  handle *a = to_handle(L, 1), *b = to_handle(L, 2);
  lua_pushboolean(L, a && b && a->st == b->st && a->kind == b->kind && a->id == b->id);
  return 1;
}

/* tds.next(kind, i): the next live 1-based id after i (0 = start), or nil. */
static int l_next(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = (int)luaL_checkinteger(L, 1);
  luaL_argcheck(L, kind >= 0 && kind < TDS_NKINDS, 1, "bad element kind");
  lua_Integer i = luaL_checkinteger(L, 2);
  const tds_mesh *m = &st->s.m;
  int32_t n = nslots(m, kind);
  const uint32_t *fl = flags_of(m, kind);
  for (tds_id j = (tds_id)(i < 0 ? 0 : i); j < n; j++)
    if (!(fl[j] & TDS_DEAD)) {
      lua_pushinteger(L, j + 1);
      tds_push_elem(L, kind, j);
      return 2;
    }
  return 0;
}

/* tds.get(kind, id): the handle of a live element, or nil. */
static int l_get(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = (int)luaL_checkinteger(L, 1);
  luaL_argcheck(L, kind >= 0 && kind < TDS_NKINDS, 1, "bad element kind");
  lua_Integer id = luaL_checkinteger(L, 2);
  if (id < 1 || id > INT32_MAX || !alive(&st->s.m, kind, (tds_id)id - 1))
    return 0;
  tds_push_elem(L, kind, (tds_id)id - 1);
  return 1;
}

static int l_count(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = (int)luaL_checkinteger(L, 1);
  luaL_argcheck(L, kind >= 0 && kind < TDS_NKINDS, 1, "bad element kind");
  lua_pushinteger(L, tds_mesh_count(&st->s.m, kind));
  return 1;
}

uint8_t *tds_lua_selection(lua_State *L, tds_state *st, int arg, int kind) {
  if (lua_isnoneornil(L, arg)) return NULL;
  int32_t n = nslots(&st->s.m, kind);
  /* A full userdata owns the buffer so a raised error cannot leak it. */
  uint8_t *sel = lua_newuserdatauv(L, (size_t)(n > 0 ? n : 1), 0);
  memset(sel, 0, (size_t)(n > 0 ? n : 1));
  int top = lua_gettop(L);
  if (lua_isfunction(L, arg)) {
    for (;;) {
      lua_pushvalue(L, arg);
      lua_call(L, 0, 1);
      if (lua_isnil(L, -1)) break;
      sel[tds_check_elem(L, st, -1, kind, NULL)] = 1;
      lua_settop(L, top);
    }
  } else if (lua_istable(L, arg)) {
    lua_Integer len = luaL_len(L, arg);
    for (lua_Integer i = 1; i <= len; i++) {
      lua_rawgeti(L, arg, i);
      sel[tds_check_elem(L, st, -1, kind, NULL)] = 1;
      lua_settop(L, top);
    }
  } else {
    sel[tds_check_elem(L, st, arg, kind, NULL)] = 1;
  }
  lua_settop(L, top);
  uint8_t *copy = malloc((size_t)(n > 0 ? n : 1));
  if (!copy) luaL_error(L, "out of memory");
  memcpy(copy, sel, (size_t)(n > 0 ? n : 1));
  lua_pop(L, 1);
  return copy;
}

void tds_open_elem(lua_State *L, tds_state *st) {
  static const luaL_Reg meta[] = {{"__index", elem_index},
                                  {"__newindex", elem_newindex},
                                  {"__tostring", elem_tostring},
                                  {"__eq", elem_eq},
                                  {NULL, NULL}};
  static const luaL_Reg methods[] = {{"on_constraint", on_constraint},
                                     {"on_boundary", on_boundary},
                                     {NULL, NULL}};
  lua_newtable(L); /* tds.methods: per kind, methods (C ones, Lua extensions) */
  lua_newtable(L); /* tds.props: per kind, computed attributes */
  lua_createtable(L, 0, TDS_NKINDS); /* tds.metatables: the handles' */
  lua_pushvalue(L, -1);
  lua_setfield(L, -5, "metatables");
  tds_lua_push_state(L, st); /* tds methods props metatables st */
  for (int k = 0; k < TDS_NKINDS; k++) {
    /* The surface's own metatable: its metamethods are bound to it. */
    lua_newtable(L); /* tds methods props metatables st mt */
    lua_pushstring(L, meta_name[k]);
    lua_setfield(L, -2, "__name"); /* for luaL_typeerror's messages */
    tds_lua_register(L, st, meta);
    lua_pushinteger(L, k);
    lua_setfield(L, -2, "__tds_kind");
    lua_newtable(L);
    tds_lua_register(L, st, methods);
    lua_pushvalue(L, -1);
    lua_setfield(L, -7, kind_name[k]); /* methods.vertex = ... */
    lua_setfield(L, -2, "methods");
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setfield(L, -6, kind_name[k]); /* props.vertex = ... */
    lua_setfield(L, -2, "props");
    lua_pushvalue(L, -1);
    lua_setfield(L, -4, kind_name[k]); /* metatables.vertex = ... */
    lua_setiuservalue(L, -2, TDS_UV_META + k);
  }
  lua_pop(L, 2); /* tds methods props */
  lua_setfield(L, -3, "props");
  lua_setfield(L, -2, "methods");
  static const luaL_Reg fns[] = {{"next", l_next}, {"get", l_get},
                                 {"count", l_count}, {NULL, NULL}};
  tds_lua_register(L, st, fns);
  for (int k = 0; k < TDS_NKINDS; k++) {
    lua_pushinteger(L, k);
    lua_setfield(L, -2, kind_name[k]); /* tds.vertex = 0, ... */
  }
}
