/* test_live.c: the live view's snapshot (live_snap.c) against the mesh
** and the metrics it claims to carry. The buffer is decoded here
** independently of the page's decoder. */
#include <stdlib.h>

#include "datafile.h"
#include "helpers.h"
#include "live_snap.h"
#include "metrics.h"
#include "torus.h"

#define EX "/usr/share/doc/evolver/examples/"

static uint32_t get_u32(const unsigned char *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
         (uint32_t)p[3] << 24;
}
static float get_f32(const unsigned char *p) {
  uint32_t u = get_u32(p);
  float f;
  memcpy(&f, &u, 4);
  return f;
}

/* The number after "key": in the header, or NAN for null / absent. The
** field entries are searched from `from` (to reach a field's min/max). */
static double head_num(const char *head, const char *from, const char *key) {
  char pat[64];
  snprintf(pat, sizeof pat, "\"%s\":", key);
  const char *p = strstr(from ? from : head, pat);
  if (!p) return NAN;
  p += strlen(pat);
  if (!strncmp(p, "null", 4)) return NAN;
  return strtod(p, NULL);
}

/* Same float, or both NaN. */
static int same(float a, double b) {
  return (isnan(a) && isnan(b)) || a == (float)b;
}

/* A refined unit cube, perturbed (seeded), with a hidden facet, one facet
** coloured and tensioned, and two extra vertices of which the first is
** deleted (so vertex numbers must be compacted). */
static void snapshot_matches_mesh(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  int32_t n;
  REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, &n));
  tds_mesh *m = &s.m;
  uint64_t seed = 12345;
  for (tds_id v = 0; v < m->nv; v++)
    for (int k = 0; k < 3; k++) m->x[v][k] += h_uniform(&seed, -0.05, 0.05);
  m->coord_gen++;
  m->fflags[3] |= TDS_NODISPLAY;
  m->fcolor[5] = 4;
  m->ften[7] = 2.5;
  double xa[3] = {5, 5, 5}, xb[3] = {-1, 2, 3};
  tds_id va = tds_mesh_add_vertex(m, xa), vb = tds_mesh_add_vertex(m, xb);
  CHECK(va != TDS_NONE && vb != TDS_NONE);
  tds_mesh_kill(m, TDS_VERTEX, va);
  REQUIRE_OK(&ctx, tds_mesh_adjacency(m));

  unsigned char *b;
  size_t len;
  REQUIRE_OK(&ctx, tds_live_snap_build(&ctx, &s, 7, 1.25, 2, &b, &len));
  uint32_t hl = get_u32(b);
  CHECK(hl % 4 == 0);
  char *head = calloc(hl + 1, 1);
  memcpy(head, b + 4, hl);
  int32_t nv = tds_mesh_count(m, TDS_VERTEX), ne = tds_mesh_count(m, TDS_EDGE);
  int32_t nf = tds_mesh_count(m, TDS_FACET) - 1;
  CHECK(head_num(head, NULL, "version") == 7);
  CHECK(head_num(head, NULL, "energy") == 1.25);
  CHECK(head_num(head, NULL, "vertices") == nv);
  CHECK(head_num(head, NULL, "edges") == ne);
  CHECK(head_num(head, NULL, "facets") == nf);
  CHECK(strstr(head, "\"color\":\"body\"") != NULL);
  size_t expect = 4 + hl + 12 * (size_t)nv + 12 * (size_t)nf + 8 * (size_t)ne +
                  4 * (size_t)nv + 16 * (size_t)nf;
  CHECK(len == expect);
  if (len != expect) {
    free(head);
    free(b);
    tds_surf_free(&s);
    return;
  }
  const unsigned char *pos = b + 4 + hl, *tri = pos + 12 * nv,
                      *edge = tri + 12 * nf, *fld = edge + 8 * ne;
  /* compact vertex number of every live vertex */
  int32_t *map = malloc((size_t)m->nv * sizeof *map), k = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    map[v] = tds_alive(m->vflags, v) ? k++ : -1;
    if (map[v] >= 0)
      for (int c = 0; c < 3; c++) CHECK(same(get_f32(pos + 12 * map[v] + 4 * c), m->x[v][c]));
  }
  CHECK(map[vb] == nv - 1);
  double lo[5], hi[5];
  for (int i = 0; i < 5; i++) lo[i] = INFINITY, hi[i] = -INFINITY;
  int t = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    if (!tds_alive(m->fflags, f) || (m->fflags[f] & TDS_NODISPLAY)) continue;
    for (int c = 0; c < 3; c++) CHECK(get_u32(tri + 12 * t + 4 * c) == (uint32_t)map[m->fv[f][c]]);
    double want[5] = {0, tds_facet_min_angle(m, f), 1, m->ften[f],
                      f == 5 ? 4 : 15};
    for (int i = 1; i < 5; i++) {
      float got = get_f32(fld + 4 * (size_t)nv + 4 * (size_t)nf * (i - 1) + 4 * t);
      CHECK(same(got, want[i]));
      if (want[i] < lo[i]) lo[i] = want[i];
      if (want[i] > hi[i]) hi[i] = want[i];
    }
    t++;
  }
  int e2 = 0;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) {
      CHECK(get_u32(edge + 8 * e2) == (uint32_t)map[m->ev[e][0]]);
      CHECK(get_u32(edge + 8 * e2 + 4) == (uint32_t)map[m->ev[e][1]]);
      e2++;
    }
  int measured = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (map[v] < 0) continue;
    double h = tds_vertex_mean_curvature(&s, v);
    CHECK(same(get_f32(fld + 4 * map[v]), h));
    if (isfinite(h)) {
      measured++;
      if (h < lo[0]) lo[0] = h;
      if (h > hi[0]) hi[0] = h;
    }
  }
  CHECK(measured == nv - 1); /* all but the bare vertex */
  CHECK(tds_vertex_mean_curvature(&s, vb) != tds_vertex_mean_curvature(&s, vb));
  /* header ranges, field by field, exactly the doubles computed above */
  const char *names[5] = {"mean_curvature", "min_angle", "body", "tension", "color"};
  for (int i = 0; i < 5; i++) {
    char pat[64];
    snprintf(pat, sizeof pat, "\"name\":\"%s\"", names[i]);
    const char *at = strstr(head, pat);
    CHECK(at != NULL);
    if (!at) continue;
    CHECK(head_num(head, at, "min") == lo[i]);
    CHECK(head_num(head, at, "max") == hi[i]);
  }
  CHECK(lo[3] == 1 && hi[3] == 2.5 && lo[4] == 4 && hi[4] == 15);
  free(map);
  free(head);
  free(b);
  tds_surf_free(&s);
}

/* The unrefined cube: faces split around their centres into right
** isosceles triangles, so every smallest angle is exactly 45 degrees; the
** curvature of a vertex on a flat face is exactly 0 up to rounding. */
static void snapshot_exact_values(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  unsigned char *b;
  size_t len;
  REQUIRE_OK(&ctx, tds_live_snap_build(&ctx, &s, 1, 3.0, -1, &b, &len));
  uint32_t hl = get_u32(b);
  char *head = calloc(hl + 1, 1);
  memcpy(head, b + 4, hl);
  const char *at = strstr(head, "\"name\":\"min_angle\"");
  CHECK(at != NULL);
  if (at) {
    CHECK_NEAR(head_num(head, at, "min"), 45, 1e-12);
    CHECK_NEAR(head_num(head, at, "max"), 45, 1e-12);
  }
  CHECK(strstr(head, "\"color\":\"none\"") != NULL);
  CHECK(head_num(head, NULL, "vertices") == 14 && head_num(head, NULL, "facets") == 24);
  /* vertex 9 (index 8) is the centre of face 1 (the y = 0 face) */
  const unsigned char *fld = b + 4 + hl + 12 * 14 + 12 * 24 + 8 * 36;
  CHECK(fabs(get_f32(fld + 4 * 8)) < 1e-6);
  free(head);
  free(b);
  tds_surf_free(&s);
}

/* An empty surface gives a valid snapshot with null ranges. */
static void snapshot_empty(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  unsigned char *b;
  size_t len;
  REQUIRE_OK(&ctx, tds_live_snap_build(&ctx, &s, 1, NAN, -1, &b, &len));
  uint32_t hl = get_u32(b);
  CHECK(len == 4 + hl);
  char *head = calloc(hl + 1, 1);
  memcpy(head, b + 4, hl);
  CHECK(strstr(head, "\"energy\":null") != NULL);
  CHECK(strstr(head, "\"min\":null,\"max\":null") != NULL);
  CHECK(tds_live_field_index("tension") == 3 && tds_live_field_index("bogus") == -1);
  free(head);
  free(b);
  tds_surf_free(&s);
}

/* The longest segment of the snapshot (triangle sides and edges), and
** whether every point lies in [lo, hi] on each axis. */
static double longest(const unsigned char *b, double lo, double hi, int *inside) {
  uint32_t hl = get_u32(b);
  char *head = calloc(hl + 1, 1);
  memcpy(head, b + 4, hl);
  int32_t nv = (int32_t)head_num(head, NULL, "vertices"), nf = (int32_t)head_num(head, NULL, "facets");
  int32_t ne = (int32_t)head_num(head, NULL, "edges");
  free(head);
  const unsigned char *pos = b + 4 + hl, *tri = pos + 12 * nv, *edge = tri + 12 * nf;
  double worst = 0;
  *inside = 1;
  for (int32_t v = 0; v < nv; v++)
    for (int c = 0; c < 3; c++) {
      double x = get_f32(pos + 12 * v + 4 * c);
      if (x < lo || x > hi) *inside = 0;
    }
  for (int32_t i = 0; i < 3 * nf + 2 * ne; i++) {
    int last = i < 3 * nf ? (i % 3 == 2) : (i - 3 * nf) % 2 == 1;
    const unsigned char *p = i < 3 * nf ? tri + 4 * i : edge + 4 * (i - 3 * nf);
    uint32_t a = get_u32(p), c = get_u32(last ? p - (i < 3 * nf ? 8 : 4) : p + 4);
    double d = 0;
    for (int k = 0; k < 3; k++) {
      double t = get_f32(pos + 12 * a + 4 * k) - get_f32(pos + 12 * c + 4 * k);
      d += t * t;
    }
    worst = fmax(worst, sqrt(d));
  }
  return worst;
}

/* A torus surface is drawn as it is exported: no segment across the cell
** (twointor's longest edge is 0.36 of its unit cell; 100grain's, a string
** foam, 0.24 of its 1-cell), clipped into the cell when asked; the
** mean curvature of a vertex copy is its vertex's. */
static void snapshot_torus(void) {
  tds_ctx ctx;
  tds_surf s;
  unsigned char *b;
  size_t len;
  int inside;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, EX "twointor.fe"));
  for (tds_id v = 0; v < s.m.nv; v++) s.m.x[v][0] += 0.1; /* facets across the faces */
  s.m.coord_gen++;
  REQUIRE_OK(&ctx, tds_live_snap_build(&ctx, &s, 1, 0, 0, &b, &len));
  CHECK(longest(b, -2, 3, &inside) < 0.5);
  free(b);
  s.m.draw = TDS_DRAW_CLIPPED;
  REQUIRE_OK(&ctx, tds_live_snap_build(&ctx, &s, 2, 0, 0, &b, &len));
  CHECK(longest(b, -1e-6, 1 + 1e-6, &inside) < 0.5);
  CHECK(inside);
  free(b);
  /* copies carry their vertex's curvature: a drawn vertex has it */
  tds_torus_drawn view;
  s.m.draw = TDS_DRAW_RAW;
  REQUIRE_OK(&ctx, tds_mesh_adjacency(&s.m));
  REQUIRE_OK(&ctx, tds_torus_view(&ctx, &s, &view));
  for (tds_id v = 0; v < view.s.m.nv; v++) {
    if (!tds_alive(view.s.m.vflags, v)) continue;
    CHECK(view.vsrc[v] >= 0 && view.vsrc[v] < s.m.nv);
    double h0 = tds_vertex_mean_curvature(&s, view.vsrc[v]);
    double h1 = tds_torus_drawn_curvature(&view, &s, v);
    CHECK(h0 == h1 || (isnan(h0) && isnan(h1)));
  }
  tds_torus_view_free(&view);
  tds_surf_free(&s);
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &s, EX "100grain.fe"));
  REQUIRE_OK(&ctx, tds_live_snap_build(&ctx, &s, 1, 0, 0, &b, &len));
  CHECK(longest(b, -5, 5, &inside) < 0.3);
  free(b);
  tds_surf_free(&s);
}

int main(void) {
  RUN(snapshot_matches_mesh);
  RUN(snapshot_exact_values);
  RUN(snapshot_empty);
  RUN(snapshot_torus);
  return check_done();
}
