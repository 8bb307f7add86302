/* lua_decl.c: declaration primitives behind vertices{}, edges{}, faces{},
** bodies{}. Each takes (id, entry) where entry is the user's table, and
** returns the new handle, or nil and a message (the prelude raises it at
** the user's line). */
#include <stdio.h>
#include <string.h>

#include "attr.h"
#include "datafile.h"
#include "lua_attr.h"
#include "lua_tds.h"
#include "topo.h"

/* Keys an entry may carry besides its positional values: the registry's
** attributes of the kind marked TDS_AT_DECL (attr.h), user attributes
** included. check_keys checks every key and value before the element
** exists (and collects the flag bits, which the core's declarations take);
** apply_keys sets the others through their setters afterwards. */
static int is_special(const tds_attr *a) {
  return a->type == TDS_AT_FLAG || a->type == TDS_AT_CONS || a->type == TDS_AT_BDRY;
}

/* Walk the entry's string keys; for each, find its attribute and convert
** (and with `apply`, set on element eid) its value. On a problem push nil
** and a message and return 0. */
static int walk_keys(lua_State *L, tds_state *st, int t, int kind, const char *what, int id,
                     uint32_t *flags, int apply, tds_id eid) {
  char w[64];
  snprintf(w, sizeof w, "%s %d", what, id);
  lua_pushnil(L);
  while (lua_next(L, t)) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      lua_pop(L, 1);
      continue;
    }
    const char *k = lua_tostring(L, -2);
    tds_attr a;
    if (!tds_attr_find(&st->s.m, kind, k, &a) || !(a.io & TDS_AT_DECL)) {
      lua_pushfstring(L, "%s: unknown attribute '%s'", w, k);
      goto fail;
    }
    int sz = a.size > TDS_MAX_CON ? a.size : TDS_MAX_CON;
    double *v = lua_newuserdatauv(L, sizeof(double) * (size_t)sz, 0); /* popped below */
    int n;
    if (a.type == TDS_AT_FLAG && !lua_isboolean(L, -2)) {
      lua_pushfstring(L, "%s: %s must be a boolean (true or false), not a %s", w, k,
                      luaL_typename(L, -2));
      goto fail;
    }
    if (a.type == TDS_AT_BDRY) { /* bdry_field checks it */
      lua_pop(L, 2);
      continue;
    }
    if (a.type == TDS_AT_CONS) {
      if (!lua_isnumber(L, -2) && !lua_istable(L, -2)) {
        lua_pushfstring(L, "%s: %s must be a constraint number or a list of them, not a %s",
                        w, k, luaL_typename(L, -2));
        goto fail;
      }
      lua_pop(L, 2);
      continue;
    }
    if (!tds_lua_attr_values(L, &a, -2, w, v, &n)) goto fail;
    for (const char *x = a.excl; !apply && x && *x;) { /* keys that exclude each other */
      char other[32];
      size_t len = strcspn(x, " ");
      snprintf(other, sizeof other, "%.*s", (int)len, x);
      x += len + (x[len] == ' ');
      lua_getfield(L, t, other);
      int given = !lua_isnil(L, -1);
      lua_pop(L, 1);
      const char *pair[2] = {a.name, other};
      if (given && tds_attr_exclusive(&st->ctx, &st->s.m, kind, w, 0, pair, 2) != TDS_OK) {
        lua_pushstring(L, st->ctx.errmsg);
        goto fail;
      }
    }
    if (!apply) {
      if (tds_attr_check(&st->ctx, &a, w, v, n) != TDS_OK) {
        lua_pushstring(L, st->ctx.errmsg);
        goto fail;
      }
      if (a.type == TDS_AT_FLAG && n && v[0] != 0) *flags |= a.flag;
    } else if (!is_special(&a) && tds_attr_write(&st->ctx, &st->s, &a, eid, v, n) != TDS_OK) {
      lua_pushstring(L, st->ctx.errmsg);
      goto fail;
    }
    lua_pop(L, 2);
  }
  return 1;
fail: /* the caller returns the top two values: nil, message */
  lua_pushnil(L);
  lua_insert(L, -2);
  return 0;
}

static int check_keys(lua_State *L, tds_state *st, int t, int kind, const char *what, int id,
                      uint32_t *flags) {
  *flags = 0;
  return walk_keys(L, st, t, kind, what, id, flags, 0, TDS_NONE);
}

static int apply_keys(lua_State *L, tds_state *st, int t, int kind, const char *what, int id,
                      tds_id eid) {
  return walk_keys(L, st, t, kind, what, id, NULL, 1, eid);
}

#define fail tds_lua_nilmsg

/* Constraint list from entry field `constraint` or `constraints`;
** returns 0 and pushes nil, msg on error. */
static int cmask_field(lua_State *L, tds_state *st, int t, tds_cmask *mask,
                       const char *what, int id) {
  *mask = 0;
  for (int pass = 0; pass < 2; pass++) {
    lua_getfield(L, t, pass ? "constraints" : "constraint");
    int n = lua_istable(L, -1) ? (int)luaL_len(L, -1) : !lua_isnil(L, -1);
    for (int k = 1; k <= n; k++) {
      if (lua_istable(L, -1)) lua_rawgeti(L, -1, k);
      else lua_pushvalue(L, -1);
      int isnum;
      lua_Integer c = lua_tointegerx(L, -1, &isnum);
      lua_pop(L, 1);
      int slot = isnum ? tds_surf_con_slot(&st->s, (int)(c < 0 ? -c : c)) : -1;
      if (slot < 0) {
        lua_pop(L, 1);
        lua_pushnil(L);
        if (isnum)
          lua_pushfstring(L, "%s %d: constraint %d is not defined", what, id, (int)c);
        else
          lua_pushfstring(L, "%s %d: constraint must be a number or list of numbers",
                          what, id);
        return 0;
      }
      *mask |= (tds_cmask)1 << slot;
    }
    lua_pop(L, 1);
  }
  return 1;
}

/* Boundary slot from field `boundary`, or TDS_NONE; -2 after pushing an error. */
static int32_t bdry_field(lua_State *L, tds_state *st, int t, const char *what, int id) {
  lua_getfield(L, t, "boundary");
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    return TDS_NONE;
  }
  lua_Integer b = lua_tointeger(L, -1);
  lua_pop(L, 1);
  for (int32_t i = 0; i < st->s.nbdry; i++)
    if (st->s.bdry[i].number == b && b != 0) return i;
  lua_pushnil(L);
  lua_pushfstring(L, "%s %d: boundary %d is not defined", what, id, (int)b);
  return -2;
}

/* The largest explicit id a declaration may use: as the .fe reader, ids
** are bounded by the size of the input (here 16 per element already
** declared of the kind, plus `extra` about to be), so that one huge id
** cannot make every lower slot exist (gigabytes for one vertex). */
static lua_Integer max_id(const tds_mesh *m, int kind, lua_Integer extra) {
  lua_Integer lim = 1000000 + 16 * ((lua_Integer)tds_mesh_count(m, kind) + extra);
  return lim < TDS_DF_MAXID ? lim : TDS_DF_MAXID;
}

static const char *const decl_name[TDS_NKINDS] = {"vertex", "edge", "face", "body"};

/* Argument 1 as an id of `kind` within max_id; 0 with nil, message pushed
** otherwise. */
static int check_id(lua_State *L, tds_state *st, int kind) {
  lua_Integer id = luaL_checkinteger(L, 1);
  luaL_checktype(L, 2, LUA_TTABLE);
  /* the bound is at least 1000000: below it no count (a count per
  ** declaration made declaring n elements O(n^2): a minute for 100k) */
  lua_Integer lim = id >= 1 && id <= 1000000 ? 1000000 : max_id(&st->s.m, kind, 1);
  if (id < 1 || id > lim) {
    tds_lua_nilmsg(L, "%s id %I is out of range (1 to %I)",
                   decl_name[kind], id, lim);
    return 0;
  }
  return (int)id;
}

static int l_decl_vertex(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int id = check_id(L, st, TDS_VERTEX);
  if (!id) return 2;
  uint32_t flags;
  if (!check_keys(L, st, 2, TDS_VERTEX, "vertex", id, &flags)) return 2;
  tds_cmask con;
  if (!cmask_field(L, st, 2, &con, "vertex", id)) return 2;
  int32_t bd = bdry_field(L, st, 2, "vertex", id);
  if (bd == -2) return 2;
  double x[3] = {0, 0, 0}, p[2] = {0, 0};
  int need = bd == TDS_NONE ? 3 : st->s.bdry[bd].nparams;
  if ((int)luaL_len(L, 2) != need)
    return fail(L, bd == TDS_NONE ? "vertex %d needs 3 coordinates, got %d"
                                  : "vertex %d on a boundary needs %d parameters",
                id, bd == TDS_NONE ? (int)luaL_len(L, 2) : need);
  for (int k = 0; k < need; k++) {
    lua_rawgeti(L, 2, k + 1);
    int isnum;
    double val = lua_tonumberx(L, -1, &isnum);
    lua_pop(L, 1);
    if (!isnum) return fail(L, "vertex %d: value %d is not a number", id, k + 1);
    if (bd == TDS_NONE) x[k] = val;
    else p[k] = val;
  }
  int rc = tds_decl_vertex(&st->ctx, &st->s, id - 1, x, bd, p, flags, con);
  if (rc != TDS_OK) return fail(L, "%s", st->ctx.errmsg);
  if (!apply_keys(L, st, 2, TDS_VERTEX, "vertex", id, id - 1)) return 2;
  if (st->s.nxa_kind[TDS_VERTEX] && st->s.m.vcon[id - 1] &&
      tds_decl_vertex_done(&st->ctx, &st->s, id - 1) != TDS_OK)
    return fail(L, "%s", st->ctx.errmsg);
  tds_push_elem(L, TDS_VERTEX, id - 1);
  return 1;
}

static int l_decl_edge(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int id = check_id(L, st, TDS_EDGE);
  if (!id) return 2;
  uint32_t flags;
  if (!check_keys(L, st, 2, TDS_EDGE, "edge", id, &flags)) return 2;
  if (luaL_len(L, 2) != 2) return fail(L, "edge %d needs two vertex ids", id);
  lua_Integer ends[2];
  for (int k = 0; k < 2; k++) {
    lua_rawgeti(L, 2, k + 1);
    int isnum;
    ends[k] = lua_tointegerx(L, -1, &isnum);
    lua_pop(L, 1);
    if (!isnum || ends[k] < 1 || ends[k] > INT32_MAX)
      return fail(L, "edge %d: vertex ids must be positive integers", id);
  }
  tds_cmask con;
  if (!cmask_field(L, st, 2, &con, "edge", id)) return 2;
  int32_t bd = bdry_field(L, st, 2, "edge", id);
  if (bd == -2) return 2;
  int rc = tds_decl_edge(&st->ctx, &st->s, id - 1, (tds_id)ends[0] - 1,
                         (tds_id)ends[1] - 1, flags, con, bd, 0, 0);
  if (rc != TDS_OK) return fail(L, "%s", st->ctx.errmsg);
  if (!apply_keys(L, st, 2, TDS_EDGE, "edge", id, id - 1)) return 2;
  tds_push_elem(L, TDS_EDGE, id - 1);
  return 1;
}

static int l_decl_face(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int id = check_id(L, st, TDS_FACET);
  if (!id) return 2;
  tds_face_attr at = {0};
  if (!check_keys(L, st, 2, TDS_FACET, "face", id, &at.flags)) return 2;
  int n = (int)luaL_len(L, 2);
  if (n < 3) return fail(L, "face %d needs at least 3 edges, got %d", id, n);
  int32_t *oe = lua_newuserdatauv(L, sizeof *oe * (size_t)n, 0);
  for (int k = 0; k < n; k++) {
    lua_rawgeti(L, 2, k + 1);
    int isnum;
    lua_Integer e = lua_tointegerx(L, -1, &isnum);
    lua_pop(L, 1);
    if (!isnum || e == 0 || e > INT32_MAX / 4 || e < -(INT32_MAX / 4))
      return fail(L, "face %d: edge %d of the loop is not a nonzero integer", id, k + 1);
    tds_id eid = (tds_id)(e < 0 ? -e : e) - 1;
    if (eid >= st->s.m.ne || !tds_alive(st->s.m.eflags, eid))
      return fail(L, "face %d refers to edge %d, which does not exist", id, eid + 1);
    oe[k] = TDS_OREF(eid, e < 0);
  }
  if (!cmask_field(L, st, 2, &at.con, "face", id)) return 2;
  at.tension = 1;
  at.color = 15;
  int32_t nf0 = st->s.m.nf;
  int rc = tds_build_face(&st->ctx, &st->s, id - 1, n, oe, &at);
  if (rc != TDS_OK) return fail(L, "%s", st->ctx.errmsg);
  /* the other attributes on every facet built from the face */
  if (!apply_keys(L, st, 2, TDS_FACET, "face", id, id - 1)) return 2;
  for (tds_id f = nf0 > id ? nf0 : id; f < st->s.m.nf; f++)
    if (st->s.m.forig[f] == id - 1 && !apply_keys(L, st, 2, TDS_FACET, "face", id, f))
      return 2;
  tds_push_elem(L, TDS_FACET, id - 1);
  return 1;
}

static int l_decl_body(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int id = check_id(L, st, TDS_BODY);
  if (!id) return 2;
  uint32_t flags;
  if (!check_keys(L, st, 2, TDS_BODY, "body", id, &flags)) return 2;
  int n = (int)luaL_len(L, 2);
  int32_t *faces = lua_newuserdatauv(L, sizeof *faces * (size_t)(n > 0 ? n : 1), 0);
  for (int k = 0; k < n; k++) {
    lua_rawgeti(L, 2, k + 1);
    int isnum;
    lua_Integer f = lua_tointegerx(L, -1, &isnum);
    lua_pop(L, 1);
    if (!isnum || f == 0 || f > INT32_MAX / 4 || f < -(INT32_MAX / 4))
      return fail(L, "body %d: face %d of the list is not a nonzero integer", id, k + 1);
    faces[k] = (int32_t)f;
  }
  /* every value was checked before the body exists (all or nothing) */
  int rc = tds_decl_body(&st->ctx, &st->s, id - 1, n, faces);
  if (rc != TDS_OK) return fail(L, "%s", st->ctx.errmsg);
  if (!apply_keys(L, st, 2, TDS_BODY, "body", id, id - 1)) return 2;
  tds_push_elem(L, TDS_BODY, id - 1);
  return 1;
}

/* tds.reserve(kind, n): make slots up to n exist (dead), so that elements
** appended while building (face centres) come after every declared id. */
static int l_reserve(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = (int)luaL_checkinteger(L, 1);
  lua_Integer n = luaL_checkinteger(L, 2);
  luaL_argcheck(L, kind >= 0 && kind < TDS_NKINDS, 1, "bad element kind");
  lua_Integer extra = luaL_optinteger(L, 3, 0);
  luaL_argcheck(L, extra >= 0 && extra <= INT32_MAX, 3, "count out of range");
  lua_Integer lim = max_id(&st->s.m, kind, extra);
  if (n < 0 || n > lim)
    return tds_lua_nilmsg(L, "%s id %I is out of range (1 to %I)",
                          decl_name[kind], n, lim);
  if (tds_mesh_extend_dead(&st->s.m, kind, (int32_t)n) != TDS_OK)
    return tds_lua_error(L, "out of memory");
  lua_pushboolean(L, 1);
  return 1;
}

void tds_open_decl(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"decl_vertex", l_decl_vertex},
                                 {"decl_edge", l_decl_edge},
                                 {"decl_face", l_decl_face},
                                 {"decl_body", l_decl_body},
                                 {"reserve", l_reserve},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
