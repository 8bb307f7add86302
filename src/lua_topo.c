/* lua_topo.c: bindings of the mesh-maintenance commands (topo_edit.h).
** Each prints the line Evolver prints and returns the count; the prelude
** gives them Evolver's names (t, w, l, K, n, delete, edgeswap, ...). */
#include <stdlib.h>

#include "lua_tds.h"
#include "topo_edit.h"

typedef int (*cut_cmd)(tds_ctx *, tds_surf *, double, int32_t *);
typedef int (*sel_cmd)(tds_ctx *, tds_surf *, const uint8_t *, int32_t *);

static int cut(lua_State *L, cut_cmd fn, const char *what, const char *fmt) {
  tds_state *st = TDS_STATE(L);
  double v = tds_lua_checkfinite(L, 1, what);
  int32_t n = 0;
  int rc = fn(&st->ctx, &st->s, v, &n);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_printf(&st->ctx, fmt, n);
  lua_pushinteger(L, n);
  return 1;
}

static int on_set(lua_State *L, int kind, sel_cmd fn, const char *fmt) {
  tds_state *st = TDS_STATE(L);
  uint8_t *sel = tds_lua_selection(L, st, 1, kind);
  int32_t n = 0;
  int rc = fn(&st->ctx, &st->s, sel, &n);
  free(sel);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_printf(&st->ctx, fmt, n);
  lua_pushinteger(L, n);
  return 1;
}

/* tds.edgeweed(len) -> edges collapsed */
static int l_edgeweed(lua_State *L) {
  return cut(L, tds_edgeweed, "edge length", "Deleted edges: %d\n");
}
/* tds.areaweed(area) -> facets removed */
static int l_areaweed(lua_State *L) {
  return cut(L, tds_areaweed, "facet area", "Skinny triangles weeded: %d\n");
}
/* tds.edge_divide(len | edges) -> edges split (the set: Evolver's
** `refine edges`, printed as it prints it) */
static int l_edge_divide(lua_State *L) {
  if (lua_type(L, 1) == LUA_TNUMBER || lua_isnoneornil(L, 1))
    return cut(L, tds_edge_divide, "edge length", "New edges: %d\n");
  return on_set(L, TDS_EDGE, tds_edge_divide_set, "Edges refined: %d\n");
}
/* tds.skinny(angle) -> edges split */
static int l_skinny(lua_State *L) {
  return cut(L, tds_skinny, "angle", "New edges: %d\n");
}
/* tds.notch(angle) -> edges notched */
static int l_notch(lua_State *L) {
  return cut(L, tds_notch, "angle", "Number of edges notched: %d\n");
}
/* tds.delete_edges([edges]) -> edges collapsed */
static int l_delete_edges(lua_State *L) {
  return on_set(L, TDS_EDGE, tds_delete_edges, "Edges deleted: %d\n");
}
/* tds.delete_facets([facets]) -> facets removed */
static int l_delete_facets(lua_State *L) {
  return on_set(L, TDS_FACET, tds_delete_facets, "Facets deleted: %d\n");
}
/* tds.edgeswap([edges]) -> edges flipped */
static int l_edgeswap(lua_State *L) {
  return on_set(L, TDS_EDGE, tds_edgeswap, "Edges swapped: %d\n");
}

/* tds.pop() -> edges + vertices popped (Evolver's o) */
static int l_pop_all(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int32_t ne = 0, nv = 0;
  int rc = tds_pop(&st->ctx, &st->s, &ne, &nv);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_printf(&st->ctx, "Edges popped: %d\nVertices popped: %d\n", ne, nv);
  lua_pushinteger(L, ne + nv);
  return 1;
}

/* tds.pop_edges([edges]) -> vertices pulled apart (Evolver's O, pop edge) */
static int l_pop_edges(lua_State *L) {
  return on_set(L, TDS_EDGE, tds_pop_edges, "Edges popped: %d\n");
}

static int arg_kind(lua_State *L, tds_state *st);

/* tds.pop([vertices or edges]) -> count popped; no argument: o */
static int l_pop(lua_State *L) {
  if (lua_isnoneornil(L, 1)) return l_pop_all(L);
  tds_state *st = TDS_STATE(L);
  int kind = arg_kind(L, st);
  if (kind == TDS_EDGE) return l_pop_edges(L);
  if (kind != TDS_VERTEX && kind >= 0)
    return tds_lua_error(L, "pop works on vertices and edges");
  uint8_t *sel = tds_lua_selection(L, st, 1, TDS_VERTEX);
  int32_t n = 0;
  int rc = tds_pop_vertices(&st->ctx, &st->s, sel, &n);
  free(sel);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_printf(&st->ctx, "Edges popped: 0\nVertices popped: %d\n", n);
  lua_pushinteger(L, n);
  return 1;
}

/* tds.pop_edge_to_tri([edges]), tds.pop_tri_to_edge([facets]) -> count */
static int l_pop_edge_to_tri(lua_State *L) {
  return on_set(L, TDS_EDGE, tds_pop_edge_to_tri, "Edges popped to triangles: %d\n");
}
/* tds.pop_quad_to_quad([facets]) -> quadrilaterals popped */
static int l_pop_quad_to_quad(lua_State *L) {
  return on_set(L, TDS_FACET, tds_pop_quad_to_quad, "pop_quad_to_quad count: %d\n");
}
static int l_pop_tri_to_edge(lua_State *L) {
  return on_set(L, TDS_FACET, tds_pop_tri_to_edge, "Triangles popped to edges: %d\n");
}

/* Kind of the first element of argument 1 (a handle or a list). */
static int arg_kind(lua_State *L, tds_state *st) {
  int kind = -1;
  if (lua_istable(L, 1)) {
    if (luaL_len(L, 1) == 0) return -1;
    lua_rawgeti(L, 1, 1);
    tds_check_elem(L, st, -1, -1, &kind);
    lua_pop(L, 1);
  } else {
    tds_check_elem(L, st, 1, -1, &kind);
  }
  return kind;
}

static const char *const kind_plural[] = {"Vertices", "Edges", "Facets", "Bodies"};

/* tds.dissolve(elements) -> count */
static int l_dissolve(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = arg_kind(L, st);
  if (kind < 0) {
    lua_pushinteger(L, 0);
    return 1;
  }
  uint8_t *sel = tds_lua_selection(L, st, 1, kind);
  int32_t n = 0;
  int rc = tds_dissolve(&st->ctx, &st->s, kind, sel, &n);
  free(sel);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  if (n) tds_printf(&st->ctx, "%s dissolved: %d\n", kind_plural[kind], n);
  lua_pushinteger(L, n);
  return 1;
}

/* tds.reverse_orientation(edges or facets) -> count */
static int l_reverse(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = arg_kind(L, st);
  if (kind < 0) {
    lua_pushinteger(L, 0);
    return 1;
  }
  if (kind != TDS_EDGE && kind != TDS_FACET)
    return tds_lua_error(L, "reverse_orientation works on edges and facets");
  uint8_t *sel = tds_lua_selection(L, st, 1, kind);
  int32_t n = 0;
  int rc = tds_reverse_orientation(&st->ctx, &st->s, kind, sel, &n);
  free(sel);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_printf(&st->ctx, "%s reversed: %d\n", kind_plural[kind], n);
  lua_pushinteger(L, n);
  return 1;
}

/* tds.delete(elements) -> count: an edge or facet handle, or a list of
** them (all of one kind; the prelude turns iterators into lists). */
static int l_delete(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int kind = TDS_EDGE;
  if (lua_istable(L, 1)) {
    if (luaL_len(L, 1) == 0) {
      lua_pushinteger(L, 0);
      return 1;
    }
    lua_rawgeti(L, 1, 1);
    tds_check_elem(L, st, -1, -1, &kind);
    lua_pop(L, 1);
  } else {
    tds_check_elem(L, st, 1, -1, &kind);
  }
  if (kind == TDS_EDGE)
    return on_set(L, TDS_EDGE, tds_delete_edges, "Edges deleted: %d\n");
  if (kind == TDS_FACET)
    return on_set(L, TDS_FACET, tds_delete_facets, "Facets deleted: %d\n");
  return tds_lua_error(L, "delete works on edges and facets, not %s",
                       kind == TDS_VERTEX ? "vertices" : "bodies");
}

/* tds.renumber_all() -> elements whose id changed */
static int l_renumber_all(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int32_t n = 0;
  int rc = tds_renumber_all(&st->ctx, &st->s, &n);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  lua_pushinteger(L, n);
  return 1;
}

/* tds.vertex_merge(v1, v2): v2 joins v1 */
static int l_vertex_merge(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  tds_id a = tds_check_elem(L, st, 1, TDS_VERTEX, NULL);
  tds_id b = tds_check_elem(L, st, 2, TDS_VERTEX, NULL);
  int rc = tds_vertex_merge(&st->ctx, &st->s, a, b);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  return 0;
}

/* tds.rebody() -> new bodies */
static int l_rebody(lua_State *L) {
  tds_state *st = TDS_STATE(L);
  int32_t n = 0;
  int rc = tds_rebody(&st->ctx, &st->s, &n);
  if (rc != TDS_OK) return tds_lua_fail(L, st, rc);
  tds_printf(&st->ctx, "New bodies: %d\n", n);
  lua_pushinteger(L, n);
  return 1;
}

void tds_open_topo(lua_State *L, tds_state *st) {
  static const luaL_Reg fns[] = {
      {"edgeweed", l_edgeweed},         {"areaweed", l_areaweed},
      {"edge_divide", l_edge_divide},   {"skinny", l_skinny},
      {"notch", l_notch},               {"delete_edges", l_delete_edges},
      {"delete_facets", l_delete_facets}, {"edgeswap", l_edgeswap},
      {"delete", l_delete},
      {"pop", l_pop},                   {"pop_edges", l_pop_edges},
      {"renumber_all", l_renumber_all}, {"vertex_merge", l_vertex_merge},
      {"rebody", l_rebody},
      {"dissolve", l_dissolve},         {"reverse_orientation", l_reverse},
      {"pop_edge_to_tri", l_pop_edge_to_tri}, {"pop_tri_to_edge", l_pop_tri_to_edge},
      {"pop_quad_to_quad", l_pop_quad_to_quad},
      {NULL, NULL}};
  tds_lua_register(L, st, fns);
}
