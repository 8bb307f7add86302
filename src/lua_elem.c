/* lua_elem.c: element handles (tds.vertex, tds.edge, tds.facet, tds.body),
** their attributes, iteration and selections. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lua_attr.h"
#include "lua_tds.h"
#include "string_model.h"

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

/* Facets are the string model's cells when it is on (string_model.h). */
static int32_t nslots(const tds_surf *s, int kind) {
  const tds_mesh *m = &s->m;
  switch (kind) {
  case TDS_VERTEX: return m->nv;
  case TDS_EDGE: return m->ne;
  case TDS_FACET: return s->str ? s->str->nf : m->nf;
  default: return m->nb;
  }
}

static const uint32_t *flags_of(const tds_surf *s, int kind) {
  const tds_mesh *m = &s->m;
  switch (kind) {
  case TDS_VERTEX: return m->vflags;
  case TDS_EDGE: return m->eflags;
  case TDS_FACET: return s->str ? s->str->flags : m->fflags;
  default: return m->bflags;
  }
}

static int alive(const tds_surf *s, int kind, tds_id id) {
  return id >= 0 && id < nslots(s, kind) && tds_alive(flags_of(s, kind), id);
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
  if (!alive(&st->s, h->kind, h->id))
    tds_lua_error(L, "%s %d no longer exists", kind_name[h->kind], h->id + 1);
  if (kindp) *kindp = h->kind;
  return h->id;
}

/* Attributes. ------------------------------------------------------------ */

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

/* The string model (string_model.h): a facet is a cell, with its area
** (and the constraint content at open ends), flags, colour, bodies and
** edge list; an edge's valence counts the cells using it. */
static int push_body(lua_State *L, tds_id b) {
  if (b == TDS_NONE) lua_pushnil(L);
  else tds_push_elem(L, TDS_BODY, b);
  return 1;
}

static int cell_get(lua_State *L, tds_state *st, tds_id f, const char *k) {
  const tds_surf *s = &st->s;
  const tds_strings *c = s->str;
  if (!strcmp(k, "area")) lua_pushnumber(L, tds_strings_area(s, f));
  else if (!strcmp(k, "fixed")) lua_pushboolean(L, c->flags[f] & TDS_FIXED);
  else if (!strcmp(k, "nodisplay")) lua_pushboolean(L, c->flags[f] & TDS_NODISPLAY);
  else if (!strcmp(k, "color")) lua_pushinteger(L, c->color[f]);
  else if (!strcmp(k, "frontbody")) return push_body(L, c->fb[f][0]);
  else if (!strcmp(k, "backbody")) return push_body(L, c->fb[f][1]);
  else if (!strcmp(k, "edges") || !strcmp(k, "vertices")) {
    int32_t a = c->start[f], n = c->start[f + 1] - a;
    lua_createtable(L, n + 1, 0);
    for (int32_t i = 0; i < n; i++) {
      int32_t r = c->oe[a + i];
      if (k[0] == 'v') tds_push_elem(L, TDS_VERTEX, tds_oe_tail(&s->m, r));
      else lua_pushinteger(L, (TDS_OID(r) + 1) * (TDS_OREV(r) ? -1 : 1));
      lua_rawseti(L, -2, i + 1);
    }
    /* an open list ends at one more vertex (Evolver lists it too) */
    if (k[0] == 'v' && n > 0 && tds_oe_head(&s->m, c->oe[a + n - 1]) != tds_oe_tail(&s->m, c->oe[a])) {
      tds_push_elem(L, TDS_VERTEX, tds_oe_head(&s->m, c->oe[a + n - 1]));
      lua_rawseti(L, -2, n + 1);
    }
  } else return 0;
  return 1;
}

static tds_id opt_body(lua_State *L, tds_state *st, int i) {
  if (lua_isnoneornil(L, i) || (lua_isinteger(L, i) && lua_tointeger(L, i) == 0))
    return TDS_NONE;
  if (lua_isinteger(L, i)) {
    lua_Integer b = lua_tointeger(L, i);
    if (!alive(&st->s, TDS_BODY, (tds_id)b - 1)) tds_lua_error(L, "body %d does not exist", (int)b);
    return (tds_id)b - 1;
  }
  return tds_check_elem(L, st, i, TDS_BODY, NULL);
}

static int cell_set(lua_State *L, tds_state *st, tds_id f, const char *k) {
  tds_strings *c = st->s.str;
  uint32_t bit = !strcmp(k, "fixed") ? TDS_FIXED : !strcmp(k, "nodisplay") ? TDS_NODISPLAY : 0;
  if (bit) {
    if (lua_toboolean(L, 3)) c->flags[f] |= bit;
    else c->flags[f] &= ~bit;
  } else if (!strcmp(k, "color")) c->color[f] = (int16_t)luaL_checkinteger(L, 3);
  else if (!strcmp(k, "frontbody")) c->fb[f][0] = opt_body(L, st, 3);
  else if (!strcmp(k, "backbody")) c->fb[f][1] = opt_body(L, st, 3);
  else return 0;
  c->gen++; /* the bodies' edge weights follow */
  return 1;
}

static int string_valence(const tds_surf *s, tds_id e) {
  int n = 0;
  for (int32_t i = 0; i < s->str->noe; i++) n += TDS_OID(s->str->oe[i]) == e;
  return n;
}

/* __index: id, the registry's attributes (attr.h), then computed attributes (functions
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
  if (st->s.str && kind == TDS_FACET) {
    if (cell_get(L, st, id, k)) return 1;
    return tds_lua_error(L, "facet %d has no attribute '%s' in the string model", (int)id + 1, k);
  }
  if (st->s.str && kind == TDS_EDGE && !strcmp(k, "valence")) {
    lua_pushinteger(L, string_valence(&st->s, id));
    return 1;
  }
  tds_attr a;
  if (tds_attr_find(&st->s.m, kind, k, &a)) {
    tds_lua_attr_push(L, st, &a, id);
    return 1;
  }
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
  if (st->s.str && kind == TDS_FACET) {
    if (!cell_set(L, st, id, k))
      return tds_lua_error(L, "facet attribute '%s' cannot be set in the string model", k);
    return 0;
  }
  tds_attr a;
  if (!tds_attr_find(&st->s.m, kind, k, &a))
    return tds_lua_error(L, "%s %d has no attribute '%s'", kind_name[kind], (int)id + 1, k);
  tds_lua_attr_set(L, st, &a, id, 3);
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
  int32_t n = nslots(&st->s, kind);
  const uint32_t *fl = flags_of(&st->s, kind);
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
  if (id < 1 || id > INT32_MAX || !alive(&st->s, kind, (tds_id)id - 1))
    return 0;
  tds_push_elem(L, kind, (tds_id)id - 1);
  return 1;
}

static int l_count(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = (int)luaL_checkinteger(L, 1);
  luaL_argcheck(L, kind >= 0 && kind < TDS_NKINDS, 1, "bad element kind");
  lua_pushinteger(L, tds_surf_count(&st->s, kind));
  return 1;
}

/* tds.edge_ring(id): the facets on live edge id as signed ids (negative
** for a facet that runs along the edge backwards) in the order of the
** edge's ring of facets, from its first side (mesh.h); nil for no edge. */
static int l_edge_ring(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  lua_Integer id = luaL_checkinteger(L, 1);
  const tds_mesh *m = &st->s.m;
  if (id < 1 || id > m->ne || !alive(&st->s, TDS_EDGE, (tds_id)id - 1)) return 0;
  lua_newtable(L);
  int32_t h = m->eside[id - 1], sd = h, n = 0;
  if (h == TDS_NONE) return 1;
  do {
    tds_id f = sd / 3;
    lua_pushinteger(L, TDS_OREV(m->fe[f][sd % 3]) ? -(lua_Integer)(f + 1) : f + 1);
    lua_rawseti(L, -2, ++n);
    sd = m->side_next[sd];
  } while (sd != h);
  return 1;
}

uint8_t *tds_lua_selection(lua_State *L, tds_state *st, int arg, int kind) {
  if (lua_isnoneornil(L, arg)) return NULL;
  int32_t n = nslots(&st->s, kind);
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
  if (!copy) tds_lua_error(L, "out of memory");
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
                                 {"count", l_count}, {"edge_ring", l_edge_ring},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
  for (int k = 0; k < TDS_NKINDS; k++) {
    lua_pushinteger(L, k);
    lua_setfield(L, -2, kind_name[k]); /* tds.vertex = 0, ... */
  }
  tds_open_attr(L, st);
}
