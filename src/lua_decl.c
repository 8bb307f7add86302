/* lua_decl.c: declaration primitives behind vertices{}, edges{}, faces{},
** bodies{}. Each takes (id, entry) where entry is the user's table, and
** returns the new handle, or nil and a message (the prelude raises it at
** the user's line). */
#include <string.h>

#include "datafile.h"
#include "lua_tds.h"
#include "topo.h"

/* Keys an entry may carry besides its positional values, each with the
** type its value must have: b boolean, n number, c a constraint number or
** a list of them. */
static const char *const vertex_keys[] = {"fixed=b", "constraint=c", "constraints=c",
                                          "boundary=n", "bare=b", NULL};
static const char *const edge_keys[] = {"fixed=b", "no_refine=b", "constraint=c",
                                        "constraints=c", "boundary=n", "tension=n",
                                        "density=n", "color=n", "bare=b", NULL};
static const char *const face_keys[] = {"fixed=b", "no_refine=b", "constraint=c",
                                        "constraints=c", "tension=n", "density=n",
                                        "color=n", "nodisplay=b", NULL};
static const char *const body_keys[] = {"volume=n", "density=n", "volconst=n",
                                        "pressure=n", NULL};

/* Check the entry's string keys and the types of their values; on an
** unknown key or a wrong type push nil, message and return 1. */
static int bad_keys(lua_State *L, int t, const char *what, int id,
                    const char *const *keys) {
  static const char *const want[] = {"b", "a boolean (true or false)", "n", "a number",
                                     "c", "a constraint number or a list of them", NULL};
  lua_pushnil(L);
  while (lua_next(L, t)) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      lua_pop(L, 1);
      continue;
    }
    const char *k = lua_tostring(L, -2);
    size_t n = strlen(k);
    char type = 0;
    for (int i = 0; keys[i] && !type; i++)
      if (!strncmp(k, keys[i], n) && keys[i][n] == '=') type = keys[i][n + 1];
    int vt = lua_type(L, -1);
    int ok = type == 'b' ? vt == LUA_TBOOLEAN
             : type == 'n' ? vt == LUA_TNUMBER
                           : vt == LUA_TNUMBER || vt == LUA_TTABLE;
    if (!type || !ok) {
      const char *tn = luaL_typename(L, -1);
      lua_pop(L, 2);
      lua_pushnil(L);
      if (!type) {
        lua_pushfstring(L, "%s %d: unknown attribute '%s'", what, id, k);
      } else {
        const char *w = "";
        for (int i = 0; want[i]; i += 2)
          if (want[i][0] == type) w = want[i + 1];
        lua_pushfstring(L, "%s %d: %s must be %s, not a %s", what, id, k, w, tn);
      }
      return 1;
    }
    lua_pop(L, 1);
  }
  return 0;
}

#define fail tds_lua_nilmsg

static int flag(lua_State *L, int t, const char *k) {
  return tds_lua_field_bool(L, t, k, 0);
}

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

static double num_field(lua_State *L, int t, const char *k, double dflt, int *given) {
  lua_getfield(L, t, k);
  int isnum;
  double v = lua_tonumberx(L, -1, &isnum);
  if (isnum) tds_lua_checkfinite(L, -1, k); /* NaN and inf never enter the surface */
  lua_pop(L, 1);
  if (given) *given = isnum;
  return isnum ? v : dflt;
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
  lua_Integer lim = max_id(&st->s.m, kind, 1);
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
  if (bad_keys(L, 2, "vertex", id, vertex_keys)) return 2;
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
  uint32_t flags = (flag(L, 2, "fixed") ? TDS_FIXED : 0) | (flag(L, 2, "bare") ? TDS_BARE : 0);
  int rc = tds_decl_vertex(&st->ctx, &st->s, id - 1, x, bd, p, flags, con);
  if (rc != TDS_OK) return fail(L, "%s", st->ctx.errmsg);
  tds_push_elem(L, TDS_VERTEX, id - 1);
  return 1;
}

static int l_decl_edge(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int id = check_id(L, st, TDS_EDGE);
  if (!id) return 2;
  if (bad_keys(L, 2, "edge", id, edge_keys)) return 2;
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
  uint32_t flags = (flag(L, 2, "fixed") ? TDS_FIXED : 0) |
                   (flag(L, 2, "no_refine") ? TDS_NO_REFINE : 0) |
                   (flag(L, 2, "bare") ? TDS_BARE : 0);
  double ten = num_field(L, 2, "tension", num_field(L, 2, "density", 0, NULL), NULL);
  int16_t color = (int16_t)num_field(L, 2, "color", 0, NULL);
  int rc = tds_decl_edge(&st->ctx, &st->s, id - 1, (tds_id)ends[0] - 1,
                         (tds_id)ends[1] - 1, flags, con, bd, ten, color);
  if (rc != TDS_OK) return fail(L, "%s", st->ctx.errmsg);
  tds_push_elem(L, TDS_EDGE, id - 1);
  return 1;
}

static int l_decl_face(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int id = check_id(L, st, TDS_FACET);
  if (!id) return 2;
  if (bad_keys(L, 2, "face", id, face_keys)) return 2;
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
  tds_face_attr at = {0};
  if (!cmask_field(L, st, 2, &at.con, "face", id)) return 2;
  at.flags = (flag(L, 2, "fixed") ? TDS_FIXED : 0) |
             (flag(L, 2, "no_refine") ? TDS_NO_REFINE : 0) |
             (flag(L, 2, "nodisplay") ? TDS_NODISPLAY : 0);
  at.tension = num_field(L, 2, "tension", num_field(L, 2, "density", 1, NULL), NULL);
  at.color = (int16_t)num_field(L, 2, "color", 0, NULL);
  int rc = tds_build_face(&st->ctx, &st->s, id - 1, n, oe, &at);
  if (rc != TDS_OK) return fail(L, "%s", st->ctx.errmsg);
  tds_push_elem(L, TDS_FACET, id - 1);
  return 1;
}

static int l_decl_body(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int id = check_id(L, st, TDS_BODY);
  if (!id) return 2;
  if (bad_keys(L, 2, "body", id, body_keys)) return 2;
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
  /* every value is read and checked before the body exists (all or nothing) */
  int has_vol, has_pr, has_den, has_vc;
  double vol = num_field(L, 2, "volume", 0, &has_vol);
  double pr = num_field(L, 2, "pressure", 0, &has_pr);
  double den = num_field(L, 2, "density", 0, &has_den);
  double vc = num_field(L, 2, "volconst", 0, &has_vc);
  if (has_vol && has_pr) return fail(L, "body %d: give either volume or pressure, not both", id);
  int rc = tds_decl_body(&st->ctx, &st->s, id - 1, n, faces);
  if (rc != TDS_OK) return fail(L, "%s", st->ctx.errmsg);
  tds_mesh *m = &st->s.m;
  if (has_vol) {
    m->btarget[id - 1] = vol;
    m->bflags[id - 1] |= TDS_TARGET;
  }
  if (has_pr) {
    m->bpressure[id - 1] = pr;
    m->bflags[id - 1] |= TDS_PRESSURE;
  }
  m->bdensity[id - 1] = den;
  if (has_den) st->s.gravity_on = 1; /* Evolver: any declared density, even 0 */
  m->bvolconst[id - 1] = vc;
  if (has_vc) m->bflags[id - 1] |= TDS_VOLCONST;
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
    return luaL_error(L, "out of memory");
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
