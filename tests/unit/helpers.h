/*
** helpers.h: tiny hand-built meshes for the C unit tests (pmp-library
** style), built through the core API exactly as the datafile reader and
** the Lua declarations do: tds_decl_vertex / tds_decl_edge /
** tds_build_face / tds_decl_body, or tds_mesh_add_* for generated grids.
**
** Ids in the tables below are 1-based and signed as in a datafile (edge
** -3 is edge 3 reversed); the helpers convert to 0-based oriented refs.
** Every builder returns TDS_OK or the failing status (message in ctx).
*/
#ifndef TDS_TEST_HELPERS_H
#define TDS_TEST_HELPERS_H

#include <stdint.h>
#include <stdlib.h>

#include "check.h"
#include "geom.h"
#include "mesh.h"
#include "surf.h"
#include "topo.h"
#include "vec3.h"

/* ---- setup, checking, random numbers ---- */

/* A quiet context and an empty surface. */
static inline void h_setup(tds_ctx *ctx, tds_surf *s) {
  tds_ctx_init(ctx);
  ctx->quiet = 1;
  tds_surf_init(s);
}

/* Rebuild adjacency if stale, then run the checker. */
static inline int h_check(tds_ctx *ctx, tds_mesh *m) {
  int rc = tds_mesh_adjacency(m);
  if (rc != TDS_OK) return tds_seterr(ctx, rc, "adjacency: out of memory");
  return tds_mesh_check(ctx, m);
}

/* CHECK that the mesh passes the checker; prints the message if not. */
#define CHECK_MESH(ctx, m)                                                 \
  do {                                                                     \
    int rc_ = h_check((ctx), (m));                                         \
    CHECK(rc_ == TDS_OK);                                                  \
    if (rc_ != TDS_OK) printf("  %s:%d: %s\n", __FILE__, __LINE__,          \
                              (ctx)->errmsg);                              \
  } while (0)

/* CHECK that a call returned TDS_OK; prints the message if not. */
#define CHECK_OK(ctx, call)                                                \
  do {                                                                     \
    int rc_ = (call);                                                      \
    CHECK(rc_ == TDS_OK);                                                  \
    if (rc_ != TDS_OK) printf("  %s:%d: rc %d: %s\n", __FILE__, __LINE__,   \
                              rc_, (ctx)->errmsg);                         \
  } while (0)

/* Like CHECK_OK, but a failure ends the test function (for the set-up
** steps that everything after them depends on). */
#define REQUIRE_OK(ctx, call)                                              \
  do {                                                                     \
    int rc_ = (call);                                                      \
    CHECK(rc_ == TDS_OK);                                                  \
    if (rc_ != TDS_OK) {                                                   \
      printf("  %s:%d: rc %d: %s\n", __FILE__, __LINE__, rc_,              \
             (ctx)->errmsg);                                               \
      return;                                                              \
    }                                                                      \
  } while (0)

/* xorshift64*: deterministic, so every run tests the same numbers. */
static inline double h_rand(uint64_t *st) {
  uint64_t x = *st;
  x ^= x >> 12;
  x ^= x << 25;
  x ^= x >> 27;
  *st = x;
  return (double)((x * 0x2545F4914F6CDD1DULL) >> 11) * 0x1.0p-53;
}
/* Uniform in [lo, hi). */
static inline double h_uniform(uint64_t *st, double lo, double hi) {
  return lo + (hi - lo) * h_rand(st);
}

/* Datafile-style signed 1-based edge id to an oriented reference. */
static inline int32_t h_oe(int signed_id) {
  return signed_id < 0 ? TDS_OREF(-signed_id - 1, 1) : TDS_OREF(signed_id - 1, 0);
}

/* ---- generic builder ---- */

/* Declare nv vertices, ne edges (1-based ends) and nf faces given as one
** array of signed 1-based edge loops, each ended by 0. Facet slots of all
** declared faces are reserved first, so the triangles split off polygons
** come after them (as the Lua declarations do). */
static inline int h_mesh(tds_ctx *ctx, tds_surf *s, int nv, const double (*x)[3],
                         int ne, const int (*ev)[2], int nf, const int *loops) {
  int rc;
  for (int v = 0; v < nv; v++)
    if ((rc = tds_decl_vertex(ctx, s, v, x[v], TDS_NONE, NULL, 0, 0))) return rc;
  for (int e = 0; e < ne; e++)
    if ((rc = tds_decl_edge(ctx, s, e, ev[e][0] - 1, ev[e][1] - 1, 0, 0,
                            TDS_NONE, 0, 0)))
      return rc;
  if (tds_mesh_extend_dead(&s->m, TDS_FACET, nf) != TDS_OK)
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  const int *p = loops;
  for (int f = 0; f < nf; f++) {
    int32_t oe[16];
    int n = 0;
    while (*p && n < 16) oe[n++] = h_oe(*p++);
    p++; /* the 0 */
    tds_face_attr at = {0, 0, 1.0, 15}; /* colour 15: white, the default */
    if ((rc = tds_build_face(ctx, s, f, n, oe, &at))) return rc;
  }
  return TDS_OK;
}

/* Body b+1 made of faces 1..nf, all with outward normals; with a target
** volume (TDS_TARGET) when target > 0. */
static inline int h_body_all(tds_ctx *ctx, tds_surf *s, int nf, double target) {
  int32_t faces[16];
  for (int i = 0; i < nf; i++) faces[i] = i + 1;
  int rc = tds_decl_body(ctx, s, 0, nf, faces);
  if (rc) return rc;
  if (target > 0) {
    s->m.btarget[0] = target;
    s->m.bflags[0] |= TDS_TARGET;
  }
  return TDS_OK;
}

/* ---- the meshes ---- */

/* One triangle (0,0,0), (1,0,0), (0,1,0); normal +z. */
static inline int h_triangle(tds_ctx *ctx, tds_surf *s) {
  static const double x[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  static const int ev[3][2] = {{1, 2}, {2, 3}, {3, 1}};
  static const int loops[] = {1, 2, 3, 0};
  return h_mesh(ctx, s, 3, x, 3, ev, 1, loops);
}

/* Two triangles sharing edge 3 (vertex 3 -> vertex 1), the quad 1 2 3 4:
** face 1 = 1->2->3 (edges 1, 2, 3), face 2 = 1->3->4 (edges -3, 4, 5).
** x gives the four corners (NULL: the unit square in z = 0). */
static inline int h_two_triangles(tds_ctx *ctx, tds_surf *s, const double (*x)[3]) {
  static const double sq[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  static const int ev[5][2] = {{1, 2}, {2, 3}, {3, 1}, {3, 4}, {4, 1}};
  static const int loops[] = {1, 2, 3, 0, -3, 4, 5, 0};
  return h_mesh(ctx, s, 4, x ? x : sq, 5, ev, 2, loops);
}

/* The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) (or x), faces with
** outward normals, body 1 made of all four (volume 1/6). */
static inline int h_tetra(tds_ctx *ctx, tds_surf *s, const double (*x)[3]) {
  static const double t[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  static const int ev[6][2] = {{1, 2}, {2, 3}, {3, 1}, {1, 4}, {2, 4}, {3, 4}};
  static const int loops[] = {-3, -2, -1, 0, 1, 5, -4, 0,
                              4,  -6, 3,  0, 2, 6, -5, 0};
  int rc = h_mesh(ctx, s, 4, x ? x : t, 6, ev, 4, loops);
  return rc ? rc : h_body_all(ctx, s, 4, 0);
}

/* The unit cube of scripts/cube.tds: 8 corners, 12 edges, 6 quads (each
** split around a centre vertex), body 1 of all faces; target volume 1 when
** target > 0. 14 vertices, 36 edges, 24 facets. */
static const double h_cube_x[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                      {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
static const int h_cube_loops[] = {1, 10, -5, -9,  0, 2, 11, -6, -10, 0,
                                   3, 12, -7, -11, 0, 4, 9,  -8, -12, 0,
                                   5, 6,  7,  8,   0, -4, -3, -2, -1, 0};
static inline int h_cube(tds_ctx *ctx, tds_surf *s, double target) {
  static const int ev[12][2] = {{1, 2}, {2, 3}, {3, 4}, {4, 1}, {5, 6}, {6, 7},
                                {7, 8}, {8, 5}, {1, 5}, {2, 6}, {3, 7}, {4, 8}};
  int rc = h_mesh(ctx, s, 8, h_cube_x, 12, ev, 6, h_cube_loops);
  return rc ? rc : h_body_all(ctx, s, 6, target);
}

/* Three facets on one edge (a triple junction): edge 1 runs from
** (0,0,0) to (0,0,1); fin k has its third vertex at distance r from the
** edge's midpoint, at angle 120k degrees. Fins 1 and 2 run along edge 1
** forwards, fin 3 backwards (so fins 1 and 3 alone would look like an
** ordinary flippable pair). 5 vertices, 7 edges, 3 facets; side 1 of
** every facet is on edge 1. */
static inline int h_triple(tds_ctx *ctx, tds_surf *s, double r) {
  double x[5][3] = {{0, 0, 0}, {0, 0, 1}};
  for (int k = 0; k < 3; k++) {
    double a = 2 * TDS_PI * k / 3;
    x[2 + k][0] = r * cos(a);
    x[2 + k][1] = r * sin(a);
    x[2 + k][2] = 0.5;
  }
  /* edges: 1: 1->2; then for fin k: 2->(3+k), (3+k)->1 */
  static const int ev[7][2] = {{1, 2}, {2, 3}, {3, 1}, {2, 4},
                               {4, 1}, {2, 5}, {5, 1}};
  static const int loops[] = {1, 2, 3, 0, 1, 4, 5, 0, -1, -7, -6, 0};
  return h_mesh(ctx, s, 5, (const double (*)[3])x, 7, ev, 3, loops);
}

/* Find or add the edge between a and b; the oriented reference a -> b. */
static inline int32_t h_edge_between(tds_mesh *m, tds_id a, tds_id b) {
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    if (m->ev[e][0] == a && m->ev[e][1] == b) return TDS_OREF(e, 0);
    if (m->ev[e][0] == b && m->ev[e][1] == a) return TDS_OREF(e, 1);
  }
  tds_id e = tds_mesh_add_edge(m, a, b);
  return e == TDS_NONE ? -1 : TDS_OREF(e, 0);
}

/* A flat n x n grid of unit cells in z = 0 built with tds_mesh_add_*:
** vertex (i, j) is i + (n+1) j, interior vertices jittered by up to
** +-jitter in x and y (seeded); each cell cut along its (i,j)-(i+1,j+1)
** diagonal; normals +z. (n+1)^2 vertices, 2 n^2 facets. */
static inline int h_grid(tds_ctx *ctx, tds_surf *s, int n, double jitter,
                         uint64_t seed) {
  tds_mesh *m = &s->m;
  uint64_t st = seed ? seed : 1;
  for (int j = 0; j <= n; j++)
    for (int i = 0; i <= n; i++) {
      double x[3] = {i, j, 0};
      if (i > 0 && i < n && j > 0 && j < n) {
        x[0] += h_uniform(&st, -jitter, jitter);
        x[1] += h_uniform(&st, -jitter, jitter);
      }
      if (tds_mesh_add_vertex(m, x) == TDS_NONE)
        return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    }
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      tds_id p00 = i + (n + 1) * j, p10 = p00 + 1, p01 = p00 + n + 1,
             p11 = p01 + 1;
      tds_id tri[2][3] = {{p00, p10, p11}, {p00, p11, p01}};
      for (int t = 0; t < 2; t++) {
        int32_t oe[3];
        for (int k = 0; k < 3; k++) {
          oe[k] = h_edge_between(m, tri[t][k], tri[t][(k + 1) % 3]);
          if (oe[k] < 0) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
        }
        if (!tds_mesh_edges_chain(m, oe))
          return tds_seterr(ctx, TDS_ETOPO, "grid: edges do not chain");
        if (tds_mesh_add_facet(m, oe) == TDS_NONE)
          return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      }
    }
  return TDS_OK;
}

/* ---- measurements ---- */

/* Total area of the live facets. */
static inline double h_area(const tds_mesh *m) {
  double A = 0;
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f))
      A += geom_area(m->x[m->fv[f][0]], m->x[m->fv[f][1]], m->x[m->fv[f][2]], NULL);
  return A;
}

/* Live vertex, edge, facet counts equal (nv, ne, nf)? Prints if not. */
static inline int h_counts(const tds_mesh *m, int nv, int ne, int nf) {
  int32_t v = tds_mesh_count(m, TDS_VERTEX), e = tds_mesh_count(m, TDS_EDGE),
          f = tds_mesh_count(m, TDS_FACET);
  if (v == nv && e == ne && f == nf) return 1;
  printf("  counts %d/%d/%d, expected %d/%d/%d\n", v, e, f, nv, ne, nf);
  return 0;
}

static int h_cmp_i32(const void *a, const void *b) {
  int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
  return (x > y) - (x < y);
}

/* Does the current derived adjacency equal, as sets per vertex, the stars
** computed by brute force from fv and ev? Needs adj_gen == topo_gen. */
static inline int h_stars_match(const tds_mesh *m) {
  if (m->adj_gen != m->topo_gen) return 0;
  int32_t *want = malloc(sizeof *want * (size_t)(3 * m->nf + 2 * m->ne + 1));
  int32_t *have = malloc(sizeof *have * (size_t)(3 * m->nf + 2 * m->ne + 1));
  int ok = want && have;
  for (tds_id v = 0; ok && v < m->nv; v++) {
    int n = 0, k = 0;
    for (tds_id f = 0; f < m->nf; f++)
      if (tds_alive(m->fflags, f) &&
          (m->fv[f][0] == v || m->fv[f][1] == v || m->fv[f][2] == v))
        want[n++] = f;
    for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++)
      have[k++] = m->vf[i];
    qsort(want, (size_t)n, sizeof *want, h_cmp_i32);
    qsort(have, (size_t)k, sizeof *have, h_cmp_i32);
    if (n != k || (n && memcmp(want, have, sizeof *want * (size_t)n))) ok = 0;
    n = k = 0;
    for (tds_id e = 0; e < m->ne; e++)
      if (tds_alive(m->eflags, e)) {
        if (m->ev[e][0] == v) want[n++] = TDS_OREF(e, 0);
        if (m->ev[e][1] == v) want[n++] = TDS_OREF(e, 1);
      }
    for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++)
      have[k++] = m->ve[i];
    qsort(want, (size_t)n, sizeof *want, h_cmp_i32);
    qsort(have, (size_t)k, sizeof *have, h_cmp_i32);
    if (n != k || (n && memcmp(want, have, sizeof *want * (size_t)n))) ok = 0;
  }
  free(want);
  free(have);
  return ok;
}

/* Index of the live vertex at x (within 1e-12), or TDS_NONE. */
static inline tds_id h_vertex_at(const tds_mesh *m, const double x[3]) {
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_alive(m->vflags, v)) continue;
    double d[3];
    v3_sub(d, m->x[v], x);
    if (v3_norm(d) < 1e-12) return v;
  }
  return TDS_NONE;
}

/* Live edge between a and b (either direction), or TDS_NONE. */
static inline tds_id h_find_edge(const tds_mesh *m, tds_id a, tds_id b) {
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e) &&
        ((m->ev[e][0] == a && m->ev[e][1] == b) ||
         (m->ev[e][0] == b && m->ev[e][1] == a)))
      return e;
  return TDS_NONE;
}

#endif
