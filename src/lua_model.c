/* lua_model.c: constraint(), boundary() and quantity() declarations.
** Each primitive returns true, or nil and a message that the prelude
** raises at the user's line. Formulas and integrands are Evolver
** expressions given as strings (numbers are accepted too). */
#include <string.h>

#include "lua_tds.h"
#include "model.h"

/* Compile the value on top of the stack (string or number; nil gives
** *e = NULL) and pop it. Returns 0 after pushing nil, msg on error. */
static int compile_top(lua_State *L, tds_state *st, int flags, tds_expr **e,
                       const char *what, const char *key) {
  *e = NULL;
  int ok = 1;
  if (!lua_isnil(L, -1)) {
    const char *text = lua_type(L, -1) == LUA_TSTRING || lua_type(L, -1) == LUA_TNUMBER
                           ? lua_tostring(L, -1) : NULL;
    if (!text) {
      lua_pushnil(L);
      lua_pushfstring(L, "%s: %s must be a formula string", what, key);
      ok = 0;
    } else if (tds_model_compile(&st->ctx, &st->s, text, flags, e) != TDS_OK) {
      lua_pushnil(L);
      lua_pushfstring(L, "%s: %s", what, st->ctx.errmsg);
      ok = 0;
    }
  }
  lua_remove(L, ok ? -1 : -3);
  return ok;
}

static int compile_field(lua_State *L, tds_state *st, int t, const char *key,
                         int flags, tds_expr **e, const char *what) {
  lua_getfield(L, t, key);
  return compile_top(L, st, flags, e, what, key);
}

static void free3(tds_expr *e[3]) {
  for (int i = 0; i < 3; i++) tds_expr_free(e[i]);
}

/* A 3-vector of integrands from field `key` ({"e1", "e2", "e3"}). */
static int vector_field(lua_State *L, tds_state *st, int t, const char *key, int flags,
                        tds_expr *out[3], const char *what) {
  out[0] = out[1] = out[2] = NULL;
  lua_getfield(L, t, key);
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    return 1;
  }
  if (!lua_istable(L, -1) || luaL_len(L, -1) > 3) {
    lua_pop(L, 1);
    lua_pushnil(L);
    lua_pushfstring(L, "%s: %s must be a list of up to 3 formulas", what, key);
    return 0;
  }
  int v = lua_gettop(L);
  for (int i = 0; i < 3; i++) {
    lua_rawgeti(L, v, i + 1);
    if (!compile_top(L, st, flags, &out[i], what, key)) {
      free3(out);
      lua_remove(L, v);
      return 0;
    }
  }
  lua_pop(L, 1);
  return 1;
}

/* The energy and content integrands of a constraint or boundary table at
** index 2; on error both are freed and nil, msg pushed. */
static int integrands(lua_State *L, tds_state *st, tds_expr *energy[3],
                      tds_expr *content[3], const char *what) {
  if (!vector_field(L, st, 2, "energy", TDS_MODEL_ON_EDGE, energy, what)) return 0;
  if (vector_field(L, st, 2, "content", TDS_MODEL_ON_EDGE, content, what)) return 1;
  free3(energy);
  return 0;
}

/* Push nil and the core's message (the prelude raises it). */
static int core_failed(lua_State *L, tds_state *st) {
  return tds_lua_nilmsg(L, "%s", st->ctx.errmsg);
}

static int flag(lua_State *L, int t, const char *k) {
  return tds_lua_field_bool(L, t, k, 0);
}

/* tds.constraint(n, { formula =, energy =, content =, nonnegative =,
** nonpositive =, convex =, global = }) */
static int l_constraint(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  lua_Integer n = luaL_checkinteger(L, 1);
  luaL_checktype(L, 2, LUA_TTABLE);
  char what[48];
  snprintf(what, sizeof what, "constraint %d", (int)n);
  tds_expr *formula, *energy[3], *content[3];
  if (!compile_field(L, st, 2, "formula", TDS_EXPR_FORMULA | TDS_MODEL_ON_VERTEX, &formula,
                     what)) return 2;
  if (!integrands(L, st, energy, content, what)) {
    tds_expr_free(formula);
    return 2;
  }
  int flags = (flag(L, 2, "nonnegative") ? TDS_CON_NONNEG : 0) |
              (flag(L, 2, "nonpositive") ? TDS_CON_NONPOS : 0) |
              (flag(L, 2, "convex") ? TDS_CON_CONVEX : 0) |
              (flag(L, 2, "global") ? TDS_CON_GLOBAL : 0);
  if (tds_model_constraint(&st->ctx, &st->s, (int)n, flags, formula, energy,
                           content) != TDS_OK)
    return core_failed(L, st);
  lua_pushboolean(L, 1);
  return 1;
}

/* tds.boundary(n, { parameters = 1|2, x =, y =, z =, energy =, content =,
** convex = }) */
static int l_boundary(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  lua_Integer n = luaL_checkinteger(L, 1);
  luaL_checktype(L, 2, LUA_TTABLE);
  char what[48];
  snprintf(what, sizeof what, "boundary %d", (int)n);
  lua_getfield(L, 2, "parameters");
  lua_Integer np = lua_isnil(L, -1) ? 1 : lua_tointeger(L, -1);
  lua_pop(L, 1);
  tds_expr *x[3] = {NULL, NULL, NULL}, *energy[3], *content[3];
  static const char *const xs[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; i++)
    if (!compile_field(L, st, 2, xs[i], TDS_EXPR_PARAMS | TDS_MODEL_ON_VERTEX, &x[i], what)) {
      free3(x);
      return 2;
    }
  if (!integrands(L, st, energy, content, what)) {
    free3(x);
    return 2;
  }
  int flags = flag(L, 2, "convex") ? TDS_CON_CONVEX : 0;
  if (tds_model_boundary(&st->ctx, &st->s, (int)n, (int)np, flags, x, energy,
                         content) != TDS_OK)
    return core_failed(L, st);
  lua_pushboolean(L, 1);
  return 1;
}

/* One method instance from the table at t: { method =, modulus =,
** vector_integrand = {...} | scalar_integrand = "..." }. With own_modulus
** 0 (the method given inline in the quantity's table) the table's modulus
** is the quantity's, and the instance's is 1. */
static int add_method(lua_State *L, tds_state *st, int t, int qi,
                      const char *what, int own_modulus) {
  lua_getfield(L, t, "method");
  const char *name = lua_tostring(L, -1);
  int method = name ? tds_method_by_name(name) : -1;
  lua_pop(L, 1);
  if (method < 0) {
    lua_pushnil(L);
    lua_pushfstring(L, "%s: unknown or missing method", what);
    return 0;
  }
  double mod = 1;
  if (own_modulus) {
    lua_getfield(L, t, "modulus");
    if (!lua_isnil(L, -1)) mod = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  tds_expr *ig[3];
  int on = tds_methods[method].kind == TDS_EL_FACET  ? TDS_MODEL_ON_FACET
           : tds_methods[method].kind == TDS_EL_EDGE ? TDS_MODEL_ON_EDGE
                                                     : 0;
  if (!vector_field(L, st, t, "vector_integrand", on, ig, what)) return 0;
  if (!ig[0] && !ig[1] && !ig[2]) {
    if (!compile_field(L, st, t, "scalar_integrand", on, &ig[0], what)) return 0;
    if (ig[0] && (method == TDS_M_FACET_VECTOR_INTEGRAL ||
                  method == TDS_M_EDGE_VECTOR_INTEGRAL)) {
      tds_expr_free(ig[0]);
      lua_pushnil(L);
      lua_pushfstring(L, "%s: method %s needs a vector_integrand, not a scalar_integrand",
                      what, tds_methods[method].name);
      return 0;
    }
  }
  if (tds_model_method(&st->ctx, &st->s, qi, method, mod, ig) != TDS_OK) {
    lua_pushnil(L);
    lua_pushstring(L, st->ctx.errmsg);
    return 0;
  }
  return 1;
}

/* tds.quantity{ name =, energy = true | fixed = target | info_only = true,
** modulus =, method = ... | methods = { {...}, ... } } */
static int l_quantity(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  luaL_checktype(L, 1, LUA_TTABLE);
  lua_getfield(L, 1, "name");
  const char *name = lua_tostring(L, -1);
  if (!name) {
    lua_pushnil(L);
    lua_pushliteral(L, "quantity: name = \"...\" is required");
    return 2;
  }
  char what[96];
  snprintf(what, sizeof what, "quantity %s", name);
  int kind = TDS_Q_ENERGY;
  double target = 0;
  lua_getfield(L, 1, "fixed");
  if (!lua_isnil(L, -1)) {
    if (!lua_isnumber(L, -1)) {
      lua_pushnil(L);
      lua_pushfstring(L, "%s: fixed = target value expected", what);
      return 2;
    }
    kind = TDS_Q_FIXED;
    target = lua_tonumber(L, -1);
  }
  lua_pop(L, 1);
  if (flag(L, 1, "info_only")) kind = TDS_Q_INFO;
  lua_getfield(L, 1, "modulus");
  double mod = lua_isnil(L, -1) ? 1 : lua_tonumber(L, -1);
  lua_pop(L, 1);
  int qi;
  /* all or nothing: a failing method takes the declaration back (a
  ** redeclared quantity keeps its old definition) */
  tds_quantity saved;
  if (tds_model_quantity(&st->ctx, &st->s, name, kind, mod, target, &qi, &saved) != TDS_OK)
    return core_failed(L, st);
  lua_getfield(L, 1, "methods");
  if (lua_istable(L, -1)) {
    int ms = lua_gettop(L);
    for (lua_Integer i = 1; i <= luaL_len(L, ms); i++) {
      lua_rawgeti(L, ms, i);
      if (!lua_istable(L, -1)) {
        tds_model_quantity_undo(&st->s, qi, &saved);
        lua_pushnil(L);
        lua_pushfstring(L, "%s: methods must be a list of tables", what);
        return 2;
      }
      if (!add_method(L, st, lua_gettop(L), qi, what, 1)) { /* nil, message pushed */
        tds_model_quantity_undo(&st->s, qi, &saved);
        return 2;
      }
      lua_pop(L, 1);
    }
  } else if (!add_method(L, st, 1, qi, what, 0)) {
    tds_model_quantity_undo(&st->s, qi, &saved);
    return 2;
  }
  tds_model_quantity_forget(&st->s, &saved);
  lua_pushboolean(L, 1);
  return 1;
}

/* tds.quantity_info(name) -> value, target, pressure, kind, modulus,
** volconst; nil if none */
static int l_quantity_info(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int qi = tds_model_quantity_find(&st->s, luaL_checkstring(L, 1));
  if (qi < 0) return 0;
  if (tds_surf_update(&st->ctx, &st->s) != TDS_OK) return tds_lua_fail(L, st, 0);
  const tds_quantity *q = &st->s.quant[qi];
  static const char *const kinds[] = {"energy", "fixed", "info_only"};
  lua_pushnumber(L, q->value);
  lua_pushnumber(L, q->target);
  lua_pushnumber(L, q->pressure);
  lua_pushstring(L, kinds[q->kind]);
  lua_pushnumber(L, q->modulus);
  lua_pushnumber(L, q->volconst);
  return 6;
}

/* tds.constraint_named(name) -> the number of a named constraint, or nil */
static int l_constraint_named(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  size_t n;
  const char *name = luaL_checklstring(L, 1, &n);
  int slot = tds_surf_con_named(&st->s, name, n);
  if (slot < 0) return 0;
  lua_pushinteger(L, st->s.con[slot].number);
  return 1;
}

/* tds.declared("constraint"|"boundary", n) -> whether number n is declared */
static int l_declared(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  static const char *const kinds[] = {"constraint", "boundary", NULL};
  int kind = luaL_checkoption(L, 1, NULL, kinds);
  lua_Integer n = luaL_checkinteger(L, 2);
  int ok = n >= 1 && n <= 1000000000 &&
           (kind == 0 ? tds_surf_con_slot(&st->s, (int)n) : tds_model_boundary_slot(&st->s, (int)n)) >= 0;
  lua_pushboolean(L, ok);
  return 1;
}

/* tds.quantity_set(name, attr, value): set the target, modulus or volconst
** of a named quantity (Evolver's `qname.target := 3.12`); true, or nil and
** a message. */
static int l_quantity_set(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  const char *name = luaL_checkstring(L, 1);
  const char *attr = luaL_checkstring(L, 2);
  double v = tds_lua_checkfinite(L, 3, attr);
  int qi = tds_model_quantity_find(&st->s, name);
  if (qi < 0) return tds_lua_nilmsg(L, "no quantity named '%s'", name);
  tds_quantity *q = &st->s.quant[qi];
  if (!strcmp(attr, "target")) {
    if (q->kind != TDS_Q_FIXED)
      return tds_lua_nilmsg(L, "quantity %s: only a FIXED quantity has a target", name);
    q->target = v;
  } else if (!strcmp(attr, "modulus")) {
    q->modulus = v;
  } else if (!strcmp(attr, "volconst")) {
    q->volconst = v;
  } else if (!strcmp(attr, "fixed")) { /* Evolver's fix / unfix qname */
    if (q->kind == TDS_Q_ENERGY)
      return tds_lua_nilmsg(L, "quantity %s: an ENERGY quantity cannot be fixed or unfixed",
                            name);
    q->kind = v != 0 ? TDS_Q_FIXED : TDS_Q_INFO;
  } else {
    return tds_lua_nilmsg(L, "quantity %s: '%s' cannot be set (target, modulus, volconst, fixed can)",
                          name, attr);
  }
  lua_pushboolean(L, 1);
  return 1;
}

void tds_open_model(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {{"constraint", l_constraint},
                                 {"boundary", l_boundary},
                                 {"quantity", l_quantity},
                                 {"quantity_info", l_quantity_info},
                                 {"quantity_set", l_quantity_set},
                                 {"declared", l_declared},
                                 {"constraint_named", l_constraint_named},
                                 {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
