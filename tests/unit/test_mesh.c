/* test_mesh.c: the element store, its checker, and the topology commands
** (build, refine, flips, vertex averaging) on tiny hand-built meshes.
** The checker runs after every build and every operation. */
#include "helpers.h"

#include "eval.h"

/* ---- building ---- */

static void build_triangle(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_triangle(&ctx, &s));
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 3, 3, 1));
  const tds_mesh *m = &s.m;
  CHECK(m->fv[0][0] == 0 && m->fv[0][1] == 1 && m->fv[0][2] == 2);
  for (tds_id e = 0; e < 3; e++) CHECK(tds_edge_valence(m, e) == 1);
  CHECK(m->forig[0] == 0);
  CHECK(m->ften[0] == 1);
  CHECK_NEAR(h_area(m), 0.5, 1e-15);
  tds_surf_free(&s);
}

static void build_two_triangles(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, NULL));
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 4, 5, 2));
  const tds_mesh *m = &s.m;
  int val[5] = {1, 1, 2, 1, 1};
  for (tds_id e = 0; e < 5; e++) CHECK(tds_edge_valence(m, e) == val[e]);
  /* the shared edge: forwards in facet 1, backwards in facet 2 */
  CHECK(m->fe[0][2] == TDS_OREF(2, 0));
  CHECK(m->fe[1][0] == TDS_OREF(2, 1));
  CHECK(h_stars_match(m));
  /* vertex 1 is on both facets and on edges 1, 3, 5 */
  CHECK(m->vf_start[1] - m->vf_start[0] == 2);
  CHECK(m->ve_start[1] - m->ve_start[0] == 3);
  CHECK_NEAR(h_area(m), 1.0, 1e-15);
  tds_surf_free(&s);
}

static void build_tetra(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_tetra(&ctx, &s, NULL));
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 4, 6, 4));
  CHECK(tds_mesh_count(&s.m, TDS_BODY) == 1);
  const tds_mesh *m = &s.m;
  for (tds_id e = 0; e < 6; e++) CHECK(tds_edge_valence(m, e) == 2);
  for (tds_id f = 0; f < 4; f++) {
    CHECK(m->fb[f][0] == 0 && m->fb[f][1] == TDS_NONE);
    CHECK(m->forig[f] == f);
  }
  /* closed and consistently oriented: each edge used once each way */
  for (tds_id e = 0; e < 6; e++) {
    int fw = 0, bw = 0;
    for (tds_id f = 0; f < 4; f++)
      for (int k = 0; k < 3; k++)
        if (TDS_OID(m->fe[f][k]) == e) {
          if (TDS_OREV(m->fe[f][k])) bw++;
          else fw++;
        }
    CHECK(fw == 1 && bw == 1);
  }
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK_NEAR(s.m.bvol[0], 1.0 / 6, 1e-15);
  CHECK_NEAR(s.area, 1.5 + sqrt(3) / 2, 1e-15);
  tds_surf_free(&s);
}

static void build_cube(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 14, 36, 24));
  const tds_mesh *m = &s.m;
  const int *p = h_cube_loops;
  for (tds_id f = 0; f < 6; f++) {
    int32_t loop[4];
    for (int k = 0; k < 4; k++) loop[k] = h_oe(*p++);
    p++;
    /* the triangle on the face's last loop edge keeps the face's slot,
    ** with the centre vertex first */
    CHECK(m->fe[f][1] == loop[3]);
    tds_id c = m->fv[f][0];
    CHECK(c >= 8);
    double mean[3] = {0, 0, 0};
    for (int k = 0; k < 4; k++) v3_add(mean, mean, m->x[tds_oe_tail(m, loop[k])]);
    v3_scale(mean, 0.25);
    for (int i = 0; i < 3; i++) CHECK_NEAR(m->x[c][i], mean[i], 1e-15);
    /* four facets come from this face, all around its centre */
    int n = 0;
    for (tds_id g = 0; g < m->nf; g++)
      if (m->forig[g] == f) {
        n++;
        CHECK(m->fv[g][0] == c || m->fv[g][1] == c || m->fv[g][2] == c);
        CHECK(m->fb[g][0] == 0 && m->fb[g][1] == TDS_NONE);
      }
    CHECK(n == 4);
    CHECK(m->vf_start[c + 1] - m->vf_start[c] == 4);
    CHECK(m->ve_start[c + 1] - m->ve_start[c] == 4);
  }
  for (tds_id g = 0; g < m->nf; g++) {
    CHECK(m->forig[g] >= 0 && m->forig[g] < 6);
    /* normals point out of the cube */
    const double *a = m->x[m->fv[g][0]], *b = m->x[m->fv[g][1]],
                 *c = m->x[m->fv[g][2]];
    double ab[3], ac[3], N[3], out[3];
    v3_sub(ab, b, a);
    v3_sub(ac, c, a);
    v3_cross(N, ab, ac);
    for (int i = 0; i < 3; i++) out[i] = (a[i] + b[i] + c[i]) / 3 - 0.5;
    CHECK(v3_dot(N, out) > 0);
    CHECK_NEAR(geom_area(a, b, c, NULL), 0.25, 1e-15);
  }
  for (tds_id e = 0; e < m->ne; e++) CHECK(tds_edge_valence(m, e) == 2);
  CHECK(h_stars_match(m));
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK_NEAR(s.m.bvol[0], 1.0, 1e-15);
  CHECK_NEAR(s.area, 6.0, 1e-15);
  tds_surf_free(&s);
}

static void build_triple_junction(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_triple(&ctx, &s, 1.0));
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 5, 7, 3));
  CHECK(tds_edge_valence(&s.m, 0) == 3);
  for (tds_id e = 1; e < 7; e++) CHECK(tds_edge_valence(&s.m, e) == 1);
  /* the ring on edge 1 holds side 1 of each facet, each once */
  int seen[3] = {0, 0, 0};
  int32_t h = s.m.eside[0], sd = h;
  do {
    CHECK(sd % 3 == 0 && sd / 3 < 3);
    if (sd % 3 == 0 && sd / 3 < 3) seen[sd / 3]++;
    sd = s.m.side_next[sd];
  } while (sd != h);
  CHECK(seen[0] == 1 && seen[1] == 1 && seen[2] == 1);
  CHECK(h_stars_match(&s.m));
  tds_surf_free(&s);
}

/* Building refuses bad input with a message. */
static void build_errors(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_triangle(&ctx, &s));
  tds_face_attr at = {0, 0, 1, 15};
  int32_t bad[3] = {h_oe(1), h_oe(3), h_oe(2)}; /* does not chain */
  CHECK(tds_build_face(&ctx, &s, 1, 3, bad, &at) == TDS_ETOPO);
  CHECK(strstr(ctx.errmsg, "face 2") != NULL);
  int32_t again[3] = {h_oe(1), h_oe(2), h_oe(3)};
  CHECK(tds_build_face(&ctx, &s, 0, 3, again, &at) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "declared twice") != NULL);
  CHECK(tds_decl_edge(&ctx, &s, 3, 0, 0, 0, 0, TDS_NONE, 0, 0) == TDS_ETOPO);
  CHECK(tds_decl_edge(&ctx, &s, 3, 0, 7, 0, 0, TDS_NONE, 0, 0) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "vertex 8") != NULL);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 3, 3, 1));
  tds_surf_free(&s);
}

/* ---- the checker catches breakage ---- */

/* Copy m, let `breakit` corrupt the copy, expect TDS_ETOPO naming `what`. */
static void expect_broken(tds_mesh *m, void (*breakit)(tds_mesh *),
                          const char *what) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  tds_mesh c;
  CHECK(tds_mesh_copy(&c, m) == TDS_OK);
  CHECK(h_check(&ctx, &c) == TDS_OK); /* the copy is sound */
  breakit(&c);
  int rc = tds_mesh_check(&ctx, &c);
  CHECK(rc == TDS_ETOPO);
  CHECK(strstr(ctx.errmsg, what) != NULL);
  if (rc != TDS_ETOPO || !strstr(ctx.errmsg, what))
    printf("  expected an error naming '%s', got rc %d: %s\n", what, rc, ctx.errmsg);
  tds_mesh_free(&c);
}

/* Ring of edge 1 (valence 3): the second side points back to itself. */
static void brk_ring_loop(tds_mesh *m) {
  int32_t s2 = m->side_next[m->eside[0]];
  m->side_next[s2] = s2;
}
/* Ring of edge 1: a side links into the ring of edge 2. */
static void brk_ring_cross(tds_mesh *m) { m->side_next[m->eside[0]] = 1; }
/* Facet 2 refers to edge 3, which is dead. */
static void brk_dead_edge(tds_mesh *m) { m->eflags[2] |= TDS_DEAD; }
/* Facet 3 points at an edge slot past the end. */
static void brk_missing_edge(tds_mesh *m) { m->fe[2][1] = TDS_OREF(m->ne + 3, 0); }
/* Edge 4's ends are equal. */
static void brk_loop_edge(tds_mesh *m) { m->ev[3][1] = m->ev[3][0]; }
/* Facet 2's vertex list disagrees with its edges. */
static void brk_fv(tds_mesh *m) {
  tds_id t = m->fv[1][1];
  m->fv[1][1] = m->fv[1][2];
  m->fv[1][2] = t;
}
/* Facet 1's front body does not exist. */
static void brk_body(tds_mesh *m) { m->fb[0][0] = 7; }
/* Vertex 1's star lists a facet that does not contain it. */
static void brk_star(tds_mesh *m) {
  tds_mesh_adjacency(m);
  for (tds_id f = 0; f < m->nf; f++)
    if (m->fv[f][0] != 0 && m->fv[f][1] != 0 && m->fv[f][2] != 0) {
      m->vf[m->vf_start[0]] = f;
      return;
    }
}

/* Vertex 1's star lists one of its facets twice and omits another. */
static void brk_star_dup(tds_mesh *m) {
  tds_mesh_adjacency(m);
  m->vf[m->vf_start[0] + 1] = m->vf[m->vf_start[0]];
}
/* Vertex 1's edge star lists one of its edges twice and omits another. */
static void brk_edge_star_dup(tds_mesh *m) {
  tds_mesh_adjacency(m);
  m->ve[m->ve_start[0] + 1] = m->ve[m->ve_start[0]];
}
/* A facet of vertex 1 is killed, but the adjacency is marked current (as
** an incremental patch that forgot the kill would leave it). */
static void brk_star_dead(tds_mesh *m) {
  tds_mesh_adjacency(m);
  tds_mesh_kill(m, TDS_FACET, m->vf[m->vf_start[0]]);
  m->adj_gen = m->topo_gen;
}

static void check_catches_breakage(void) {
  tds_ctx ctx;
  tds_surf tri, tet;
  h_setup(&ctx, &tri);
  h_setup(&ctx, &tet);
  REQUIRE_OK(&ctx, h_triple(&ctx, &tri, 1.0));
  REQUIRE_OK(&ctx, h_tetra(&ctx, &tet, NULL));
  expect_broken(&tri.m, brk_ring_loop, "edge 1:");
  expect_broken(&tri.m, brk_ring_cross, "edge 1:");
  expect_broken(&tet.m, brk_dead_edge, "facet 1:"); /* edge 3 is on facet 1 */
  expect_broken(&tet.m, brk_missing_edge, "facet 3: side 2");
  expect_broken(&tet.m, brk_loop_edge, "edge 4:");
  expect_broken(&tet.m, brk_fv, "facet 2:");
  expect_broken(&tet.m, brk_body, "facet 1: front body");
  expect_broken(&tet.m, brk_star, "vertex 1:");
  expect_broken(&tet.m, brk_star_dup, "vertex 1:");
  expect_broken(&tet.m, brk_edge_star_dup, "vertex 1:");
  expect_broken(&tet.m, brk_star_dead, "vertex 1:");
  /* the originals are untouched */
  CHECK_MESH(&ctx, &tri.m);
  CHECK_MESH(&ctx, &tet.m);
  tds_surf_free(&tri);
  tds_surf_free(&tet);
}

/* Killing a facet unlinks it from its rings; the mesh stays sound. */
static void kill_facet_unlinks(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_triple(&ctx, &s, 1.0));
  tds_mesh_kill(&s.m, TDS_FACET, 1);
  CHECK_MESH(&ctx, &s.m);
  CHECK(tds_edge_valence(&s.m, 0) == 2);
  CHECK(tds_edge_valence(&s.m, 3) == 0);
  CHECK(h_counts(&s.m, 5, 7, 2));
  CHECK(h_stars_match(&s.m));
  tds_surf_free(&s);
}

/* ---- refine ---- */

static void refine_counts(void) {
  tds_ctx ctx;
  tds_surf s;
  int32_t nsplit = -1;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, NULL));
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &nsplit));
  CHECK(nsplit == 5);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 9, 16, 8));
  CHECK(h_stars_match(&s.m));
  tds_surf_free(&s);

  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_tetra(&ctx, &s, NULL));
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &nsplit));
  CHECK(nsplit == 6);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 10, 24, 16));
  tds_surf_free(&s);

  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &nsplit));
  CHECK(nsplit == 36);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 50, 144, 96));
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &nsplit));
  CHECK(nsplit == 144);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 194, 576, 384));
  CHECK(h_stars_match(&s.m));
  for (tds_id e = 0; e < s.m.ne; e++) CHECK(tds_edge_valence(&s.m, e) == 2);
  CHECK_NEAR(s.m.bvol[0], 1.0, 1e-14);
  CHECK_NEAR(s.area, 6.0, 1e-14);
  tds_surf_free(&s);

  /* the triple junction: every fin splits into 4, edge 1 stays triple */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_triple(&ctx, &s, 1.0));
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &nsplit));
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 12, 14 + 9, 12));
  CHECK(tds_edge_valence(&s.m, 0) == 3);
  tds_surf_free(&s);
}

static void refine_no_refine_edge(void) {
  tds_ctx ctx;
  tds_surf s;
  int32_t nsplit;
  /* Edge 1 (a side of facet 1 only) is no_refine: facet 1 has two split
  ** edges -> 3 facets; facet 2 all three -> 4. Vertices 4 + 4 midpoints;
  ** edges 5 + 4 second halves + 2 + 3 inner = 14; facets 7. */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, NULL));
  s.m.eflags[0] |= TDS_NO_REFINE;
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &nsplit));
  CHECK(nsplit == 4);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 8, 14, 7));
  CHECK(s.m.ev[0][0] == 0 && s.m.ev[0][1] == 1); /* intact */
  int n1 = 0, n2 = 0;
  for (tds_id f = 0; f < s.m.nf; f++) {
    n1 += s.m.forig[f] == 0;
    n2 += s.m.forig[f] == 1;
  }
  CHECK(n1 == 3 && n2 == 4);
  CHECK_NEAR(s.area, 1.0, 1e-15);
  tds_surf_free(&s);

  /* Two no_refine edges of one triangle: one split edge -> 2 facets. */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_triangle(&ctx, &s));
  s.m.eflags[0] |= TDS_NO_REFINE;
  s.m.eflags[1] |= TDS_NO_REFINE;
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &nsplit));
  CHECK(nsplit == 1);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 4, 5, 2));
  CHECK_NEAR(s.area, 0.5, 1e-15);
  tds_surf_free(&s);

  /* Two split edges (a0-a1 at m0, a1-a2 at m1; a2-a0 no_refine): the quad
  ** a0 m0 m1 a2 is cut along its shorter diagonal. */
  static const int ev[3][2] = {{1, 2}, {2, 3}, {3, 1}};
  static const int loops[] = {1, 2, 3, 0};
  static const double shapes[2][3][3] = {
      {{0, 0, 0}, {4, 0, 0}, {0, 1, 0}},  /* |a0 m1|^2 = 4.25 < |m0 a2|^2 = 5 */
      {{0, 0, 0}, {4, 0, 0}, {4, 1, 0}}}; /* 16.25 > 5 */
  for (int k = 0; k < 2; k++) {
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, h_mesh(&ctx, &s, 3, shapes[k], 3, ev, 1, loops));
    s.m.eflags[2] |= TDS_NO_REFINE;
    CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &nsplit));
    CHECK_MESH(&ctx, &s.m);
    CHECK(h_counts(&s.m, 5, 7, 3));
    double m0[3], m1[3];
    for (int i = 0; i < 3; i++) {
      m0[i] = (shapes[k][0][i] + shapes[k][1][i]) / 2;
      m1[i] = (shapes[k][1][i] + shapes[k][2][i]) / 2;
    }
    tds_id vm0 = h_vertex_at(&s.m, m0), vm1 = h_vertex_at(&s.m, m1);
    CHECK(vm0 != TDS_NONE && vm1 != TDS_NONE);
    double d1 = 0, d2 = 0;
    for (int i = 0; i < 3; i++) {
      d1 += (m1[i] - shapes[k][0][i]) * (m1[i] - shapes[k][0][i]);
      d2 += (m0[i] - shapes[k][2][i]) * (m0[i] - shapes[k][2][i]);
    }
    int a0m1 = d1 < d2;
    CHECK((h_find_edge(&s.m, 0, vm1) != TDS_NONE) == a0m1);
    CHECK((h_find_edge(&s.m, vm0, 2) != TDS_NONE) == !a0m1);
    CHECK_NEAR(s.area, geom_area(shapes[k][0], shapes[k][1], shapes[k][2], NULL), 1e-15);
    tds_surf_free(&s);
  }
}

static void refine_selection(void) {
  tds_ctx ctx;
  tds_surf s;
  int32_t nsplit;
  /* Only the diagonal: each facet splits in 2. */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, NULL));
  uint8_t sel[5] = {0, 0, 1, 0, 0};
  CHECK_OK(&ctx, tds_refine(&ctx, &s, sel, &nsplit));
  CHECK(nsplit == 1);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 5, 8, 4));
  double mid[3] = {0.5, 0.5, 0};
  tds_id c = h_vertex_at(&s.m, mid);
  CHECK(c != TDS_NONE);
  if (c != TDS_NONE) {
    CHECK(s.m.vf_start[c + 1] - s.m.vf_start[c] == 4);
    CHECK(s.m.ve_start[c + 1] - s.m.ve_start[c] == 4);
  }
  CHECK_NEAR(s.area, 1.0, 1e-15);
  tds_surf_free(&s);

  /* Only boundary edge 1: facet 1 splits in 2, facet 2 stays. A selection
  ** overrides no_refine. */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, NULL));
  s.m.eflags[0] |= TDS_NO_REFINE;
  uint8_t sel1[5] = {1, 0, 0, 0, 0};
  CHECK_OK(&ctx, tds_refine(&ctx, &s, sel1, &nsplit));
  CHECK(nsplit == 1);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 5, 7, 3));
  CHECK(s.m.fv[1][0] == 0 && s.m.fv[1][1] == 2 && s.m.fv[1][2] == 3);
  tds_surf_free(&s);
}

/* Flat pieces: refining keeps the area exactly; a flat-faced polyhedron
** keeps its volume, since every midpoint lies on its faces. */
static void refine_preserves_area_volume(void) {
  tds_ctx ctx;
  tds_surf s;
  /* a skew quad in a tilted plane, non-unit lengths */
  double q[4][3] = {{0.1, 0.2, 0}, {2.3, -0.4, 0}, {1.9, 1.7, 0}, {-0.3, 1.1, 0}};
  for (int k = 0; k < 4; k++) q[k][2] = 0.3 * q[k][0] - 0.7 * q[k][1] + 0.25;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, (const double (*)[3])q));
  double A0 = h_area(&s.m);
  for (int r = 0; r < 3; r++) {
    CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
    CHECK_MESH(&ctx, &s.m);
    CHECK_NEAR(h_area(&s.m), A0, 1e-14);
    CHECK_NEAR(s.area, A0, 1e-14);
  }
  /* 4/5/2 -> 9/16/8 -> 25/56/32 -> 81/208/128 */
  CHECK(h_counts(&s.m, 81, 208, 128));
  tds_surf_free(&s);

  /* a non-degenerate tetrahedron off the origin */
  double t[4][3] = {{0.2, -0.1, 0.3}, {1.4, 0.1, 0.2}, {0.3, 1.2, 0.1}, {0.5, 0.4, 1.3}};
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_tetra(&ctx, &s, (const double (*)[3])t));
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  double V0 = s.m.bvol[0], S0 = s.area;
  CHECK(V0 > 0.1); /* outward faces */
  for (int r = 0; r < 2; r++) {
    CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
    CHECK_MESH(&ctx, &s.m);
    CHECK_NEAR(s.m.bvol[0], V0, 1e-14);
    CHECK_NEAR(s.area, S0, 1e-14);
  }
  /* the same under symmetric content */
  s.symmetric_content = 1;
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK_NEAR(s.m.bvol[0], V0, 1e-14);
  tds_surf_free(&s);
}

static void refine_fixed_edges(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, NULL));
  s.m.eflags[0] |= TDS_FIXED; /* edge 1: (0,0,0)-(1,0,0) */
  s.m.fflags[1] |= TDS_FIXED; /* facet 2: its inner edges are fixed */
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  CHECK_MESH(&ctx, &s.m);
  const tds_mesh *m = &s.m;
  static const double mids[5][3] = {{0.5, 0, 0}, {1, 0.5, 0}, {0.5, 0.5, 0},
                                    {0.5, 1, 0}, {0, 0.5, 0}};
  tds_id mv[5];
  for (int k = 0; k < 5; k++) {
    mv[k] = h_vertex_at(m, mids[k]);
    CHECK(mv[k] != TDS_NONE);
    if (mv[k] == TDS_NONE) {
      tds_surf_free(&s);
      return;
    }
    CHECK(!!(m->vflags[mv[k]] & TDS_FIXED) == (k == 0));
  }
  /* both halves of edge 1 are fixed */
  tds_id h1 = h_find_edge(m, 0, mv[0]), h2 = h_find_edge(m, mv[0], 1);
  CHECK(h1 != TDS_NONE && h2 != TDS_NONE);
  if (h1 != TDS_NONE && h2 != TDS_NONE)
    CHECK((m->eflags[h1] & TDS_FIXED) && (m->eflags[h2] & TDS_FIXED));
  /* inner edges: in facet 2 (midpoints of edges 3, 4, 5) fixed, in facet 1
  ** (midpoints of 1, 2, 3) not */
  tds_id in2 = h_find_edge(m, mv[3], mv[4]), in1 = h_find_edge(m, mv[0], mv[1]);
  CHECK(in2 != TDS_NONE && in1 != TDS_NONE);
  if (in2 != TDS_NONE) CHECK(m->eflags[in2] & TDS_FIXED);
  if (in1 != TDS_NONE) CHECK(!(m->eflags[in1] & TDS_FIXED));
  tds_surf_free(&s);
}

static void refine_inherits(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, NULL));
  s.m.ften[0] = 2.5;
  s.m.fcolor[0] = 3;
  s.m.ften[1] = 0.5;
  s.m.eten[0] = 0.75; /* edge tension goes to both halves */
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  double E0 = s.energy;
  CHECK_NEAR(E0, 2.5 * 0.5 + 0.5 * 0.5 + 0.75, 1e-15);
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  CHECK_MESH(&ctx, &s.m);
  const tds_mesh *m = &s.m;
  int n[2] = {0, 0};
  for (tds_id f = 0; f < m->nf; f++) {
    CHECK(m->forig[f] == 0 || m->forig[f] == 1);
    if (m->forig[f] == 0) CHECK(m->ften[f] == 2.5 && m->fcolor[f] == 3);
    if (m->forig[f] == 1) CHECK(m->ften[f] == 0.5 && m->fcolor[f] == 15);
    if (m->forig[f] == 0 || m->forig[f] == 1) n[m->forig[f]]++;
  }
  CHECK(n[0] == 16 && n[1] == 16);
  CHECK_NEAR(s.energy, E0, 1e-14);
  tds_surf_free(&s);

  /* bodies: every facet of the refined tetrahedron bounds body 1 */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_tetra(&ctx, &s, NULL));
  s.m.bflags[0] |= TDS_TARGET;
  s.m.btarget[0] = 1.0 / 6;
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  CHECK_MESH(&ctx, &s.m);
  for (tds_id f = 0; f < s.m.nf; f++) {
    CHECK(s.m.fb[f][0] == 0 && s.m.fb[f][1] == TDS_NONE);
    CHECK(s.m.forig[f] >= 0 && s.m.forig[f] < 4);
  }
  CHECK(s.m.bflags[0] & TDS_TARGET);
  tds_surf_free(&s);
}

/* ---- flips ---- */

/* Sum of the angles opposite interior edge e (valence 2), or -1. */
static double opp_sum(const tds_mesh *m, tds_id e) {
  if (tds_edge_valence(m, e) != 2) return -1;
  double sum = 0;
  int32_t h = m->eside[e], sd = h;
  do {
    tds_id f = sd / 3;
    int k = sd % 3;
    const double *p = m->x[m->fv[f][(k + 2) % 3]];
    const double *a = m->x[m->ev[e][0]], *b = m->x[m->ev[e][1]];
    double u[3], v[3], w[3];
    v3_sub(u, a, p);
    v3_sub(v, b, p);
    v3_cross(w, u, v);
    sum += atan2(v3_norm(w), v3_dot(u, v));
    sd = m->side_next[sd];
  } while (sd != h);
  return sum;
}

static void flip_non_delaunay_quad(void) {
  tds_ctx ctx;
  tds_surf s;
  /* diagonal 3-1 long, 2 and 4 close: the angles at 2 and 4 are obtuse */
  static const double q[4][3] = {{-2, 0, 0}, {0, -0.5, 0}, {2, 0, 0}, {0, 0.5, 0}};
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, q));
  tds_id f1 = -7, f2 = -7;
  CHECK(tds_flip_ok(&s, 2, &f1, &f2) == 1);
  CHECK(f1 == 0 && f2 == 1); /* facet 1 runs along edge 3 forwards */
  CHECK(opp_sum(&s.m, 2) > TDS_PI);
  for (tds_id e = 0; e < 5; e++)
    if (e != 2) CHECK(tds_flip_ok(&s, e, &f1, &f2) == 0); /* border edges */
  int32_t nflips = -1;
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &nflips));
  CHECK(nflips == 1);
  CHECK_MESH(&ctx, &s.m);
  const tds_mesh *m = &s.m;
  /* edge 3 now joins vertices 2 and 4 */
  CHECK((m->ev[2][0] == 1 && m->ev[2][1] == 3) || (m->ev[2][0] == 3 && m->ev[2][1] == 1));
  CHECK(opp_sum(m, 2) < TDS_PI);
  CHECK_NEAR(s.area, 2.0, 1e-15);
  /* orientation kept: both normals +z */
  for (tds_id f = 0; f < 2; f++) {
    const double *a = m->x[m->fv[f][0]], *b = m->x[m->fv[f][1]], *c = m->x[m->fv[f][2]];
    CHECK((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0);
  }
  CHECK(h_stars_match(m));
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &nflips));
  CHECK(nflips == 0);
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);

  /* tds_flip directly, then back again: the original facets return */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, q));
  CHECK(tds_flip_ok(&s, 2, &f1, &f2) == 1);
  tds_flip(&s, 2, f1, f2);
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_stars_match(&s.m));
  CHECK(tds_flip_ok(&s, 2, &f1, &f2) == 1);
  tds_flip(&s, 2, f1, f2);
  CHECK_MESH(&ctx, &s.m);
  CHECK((s.m.ev[2][0] == 0 && s.m.ev[2][1] == 2) || (s.m.ev[2][0] == 2 && s.m.ev[2][1] == 0));
  CHECK(tds_edge_valence(&s.m, 2) == 2);
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  CHECK_NEAR(s.area, 2.0, 1e-15);
  tds_surf_free(&s);
}

static void flip_delaunay_quad(void) {
  tds_ctx ctx;
  tds_surf s;
  /* diagonal 3-1 short, 2 and 4 far: the angles at 2 and 4 are acute */
  static const double q[4][3] = {{-0.5, 0, 0}, {0, -2, 0}, {0.5, 0, 0}, {0, 2, 0}};
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, q));
  tds_id f1, f2;
  CHECK(tds_flip_ok(&s, 2, &f1, &f2) == 1); /* allowed, but not wanted */
  int32_t nflips = -1;
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &nflips));
  CHECK(nflips == 0);
  CHECK((s.m.ev[2][0] == 2 && s.m.ev[2][1] == 0));
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);
}

static void flip_never_triple(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  /* fins close to the edge: any two of them would want a flip */
  REQUIRE_OK(&ctx, h_triple(&ctx, &s, 0.1));
  tds_id f1, f2;
  CHECK(tds_flip_ok(&s, 0, &f1, &f2) == 0);
  CHECK(opp_sum(&s.m, 0) == -1);
  int32_t nflips = -1;
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &nflips));
  CHECK(nflips == 0);
  CHECK(s.m.ev[0][0] == 0 && s.m.ev[0][1] == 1);
  CHECK(tds_edge_valence(&s.m, 0) == 3);
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);
}

static void flip_never_fixed(void) {
  static const double q[4][3] = {{-2, 0, 0}, {0, -0.5, 0}, {2, 0, 0}, {0, 0.5, 0}};
  tds_ctx ctx;
  tds_surf s;
  tds_id f1, f2;
  int32_t nflips = -1;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, q));
  s.m.eflags[2] |= TDS_FIXED;
  CHECK(tds_flip_ok(&s, 2, &f1, &f2) == 0);
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &nflips));
  CHECK(nflips == 0);
  CHECK(s.m.ev[2][0] == 2 && s.m.ev[2][1] == 0);
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);

  /* facets that differ (tension) are not flipped either; nor a selection
  ** that leaves the edge out */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_two_triangles(&ctx, &s, q));
  s.m.ften[1] = 2;
  CHECK(tds_flip_ok(&s, 2, &f1, &f2) == 0);
  s.m.ften[1] = 1;
  uint8_t sel[5] = {1, 1, 0, 1, 1};
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, sel, &nflips));
  CHECK(nflips == 0);
  CHECK(s.m.ev[2][0] == 2 && s.m.ev[2][1] == 0);
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);
}

static void flip_never_duplicates(void) {
  tds_ctx ctx;
  tds_surf s;
  /* A squashed tetrahedron: on edge 1 (a-b) both opposite vertices c, d
  ** are near its midpoint (angles about 157 degrees each), so the edge
  ** wants a flip; but the new edge c-d exists already. The same holds for
  ** every edge of a tetrahedron. */
  static const double t[4][3] = {{-1, 0, 0}, {1, 0, 0}, {0, 0.2, 0}, {0, 0, 0.2}};
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_tetra(&ctx, &s, t));
  CHECK_MESH(&ctx, &s.m);
  CHECK(opp_sum(&s.m, 0) > TDS_PI);
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  double V0 = s.m.bvol[0];
  int32_t nflips = -1;
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &nflips));
  CHECK(nflips == 0);
  CHECK(s.m.ev[0][0] == 0 && s.m.ev[0][1] == 1);
  CHECK(h_counts(&s.m, 4, 6, 4));
  CHECK_MESH(&ctx, &s.m);
  for (tds_id a = 0; a < 4; a++)
    for (tds_id b = a + 1; b < 4; b++) CHECK(h_find_edge(&s.m, a, b) != TDS_NONE);
  CHECK_NEAR(s.m.bvol[0], V0, 1e-15);
  tds_surf_free(&s);
}

/* Many flips on a jittered flat grid: the result is Delaunay, the area is
** kept, and after the flips the rings check and the adjacency equals a
** full rebuild (and a brute-force star computation). */
static void flip_grid_adjacency(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_grid(&ctx, &s, 6, 0.2, 12345));
  CHECK_MESH(&ctx, &s.m);
  CHECK(h_counts(&s.m, 49, 36 * 3 + 12, 72));
  CHECK_OK(&ctx, tds_surf_update(&ctx, &s));
  double A0 = s.area;
  CHECK_NEAR(A0, 36, 1e-13);
  int32_t nflips = -1;
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &nflips));
  CHECK(nflips > 3);
  CHECK_MESH(&ctx, &s.m);
  tds_mesh *m = &s.m;
  CHECK(h_counts(m, 49, 120, 72));
  CHECK_NEAR(s.area, A0, 1e-13);
  for (tds_id e = 0; e < m->ne; e++) {
    double os = opp_sum(m, e);
    CHECK(os < TDS_PI + 1e-9); /* -1 for border edges */
  }
  /* adjacency as the core left it (patched or rebuilt) */
  CHECK(tds_mesh_adjacency(m) == TDS_OK);
  CHECK(h_stars_match(m));
  int32_t nvf = m->vf_start[m->nv], nve = m->ve_start[m->nv];
  int32_t *vf = malloc(sizeof *vf * (size_t)nvf), *ve = malloc(sizeof *ve * (size_t)nve);
  int32_t *vfs = malloc(sizeof *vfs * (size_t)(m->nv + 1)),
          *ves = malloc(sizeof *ves * (size_t)(m->nv + 1));
  CHECK(vf && ve && vfs && ves);
  if (vf && ve && vfs && ves) {
    memcpy(vf, m->vf, sizeof *vf * (size_t)nvf);
    memcpy(ve, m->ve, sizeof *ve * (size_t)nve);
    memcpy(vfs, m->vf_start, sizeof *vfs * (size_t)(m->nv + 1));
    memcpy(ves, m->ve_start, sizeof *ves * (size_t)(m->nv + 1));
    m->topo_gen++; /* force a full rebuild */
    CHECK(tds_mesh_adjacency(m) == TDS_OK);
    CHECK_MESH(&ctx, m);
    for (tds_id v = 0; v < m->nv; v++) {
      CHECK(m->vf_start[v + 1] - m->vf_start[v] == vfs[v + 1] - vfs[v]);
      CHECK(m->ve_start[v + 1] - m->ve_start[v] == ves[v + 1] - ves[v]);
      if (m->vf_start[v + 1] - m->vf_start[v] != vfs[v + 1] - vfs[v] ||
          m->ve_start[v + 1] - m->ve_start[v] != ves[v + 1] - ves[v])
        break;
      qsort(vf + vfs[v], (size_t)(vfs[v + 1] - vfs[v]), sizeof *vf, h_cmp_i32);
      qsort(m->vf + m->vf_start[v], (size_t)(vfs[v + 1] - vfs[v]), sizeof *vf, h_cmp_i32);
      CHECK(memcmp(vf + vfs[v], m->vf + m->vf_start[v],
                   sizeof *vf * (size_t)(vfs[v + 1] - vfs[v])) == 0);
      qsort(ve + ves[v], (size_t)(ves[v + 1] - ves[v]), sizeof *ve, h_cmp_i32);
      qsort(m->ve + m->ve_start[v], (size_t)(ves[v + 1] - ves[v]), sizeof *ve, h_cmp_i32);
      CHECK(memcmp(ve + ves[v], m->ve + m->ve_start[v],
                   sizeof *ve * (size_t)(ves[v + 1] - ves[v])) == 0);
    }
  }
  free(vf);
  free(ve);
  free(vfs);
  free(ves);
  /* a second pass finds nothing */
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &nflips));
  CHECK(nflips == 0);
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);
}

/* ---- vertex averaging ---- */

static void vertex_average_flat(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  /* 3 x 3 vertices, the middle one (index 4) off-centre; the patch lies
  ** in the tilted plane z = 0.3 x + 0.2 y. */
  REQUIRE_OK(&ctx, h_grid(&ctx, &s, 2, 0, 1));
  tds_mesh *m = &s.m;
  m->x[4][0] = 1.3;
  m->x[4][1] = 0.8;
  for (tds_id v = 0; v < m->nv; v++) m->x[v][2] = 0.3 * m->x[v][0] + 0.2 * m->x[v][1];
  CHECK_MESH(&ctx, m);
  CHECK(m->vf_start[5] - m->vf_start[4] == 6);
  /* expected: the area-weighted mean of the centroids of its 6 facets */
  double want[3] = {0, 0, 0}, W = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    const tds_id *fv = m->fv[f];
    if (fv[0] != 4 && fv[1] != 4 && fv[2] != 4) continue;
    double A = geom_area(m->x[fv[0]], m->x[fv[1]], m->x[fv[2]], NULL);
    for (int i = 0; i < 3; i++)
      want[i] += A * (m->x[fv[0]][i] + m->x[fv[1]][i] + m->x[fv[2]][i]) / 3;
    W += A;
  }
  for (int i = 0; i < 3; i++) want[i] /= W;
  double old[9][3];
  memcpy(old, m->x, sizeof old);
  double A0 = h_area(m);
  int32_t nmoved = -1;
  CHECK_OK(&ctx, tds_vertex_average_mode(&ctx, &s, NULL, TDS_VAVG_CENTROID, 0, &nmoved));
  CHECK(nmoved == 1); /* border vertices have no constraint: they stay */
  CHECK_MESH(&ctx, m);
  for (int i = 0; i < 3; i++) CHECK_NEAR(m->x[4][i], want[i], 1e-14);
  CHECK_NEAR(m->x[4][2], 0.3 * m->x[4][0] + 0.2 * m->x[4][1], 1e-14);
  /* it moved toward the centre (1, 1) */
  double d0 = hypot(old[4][0] - 1, old[4][1] - 1), d1 = hypot(m->x[4][0] - 1, m->x[4][1] - 1);
  CHECK(d1 < 0.75 * d0);
  for (tds_id v = 0; v < 9; v++)
    if (v != 4)
      for (int i = 0; i < 3; i++) CHECK(m->x[v][i] == old[v][i]);
  CHECK_NEAR(h_area(m), A0, 1e-14); /* flat: the area of the patch is kept */
  /* repeated averaging converges to the centre */
  for (int it = 0; it < 60; it++) CHECK_OK(&ctx, tds_vertex_average_mode(&ctx, &s, NULL, TDS_VAVG_CENTROID, 0, NULL));
  CHECK_NEAR(m->x[4][0], 1.0, 1e-9);
  CHECK_NEAR(m->x[4][1], 1.0, 1e-9);
  tds_surf_free(&s);

  /* a fixed vertex does not move */
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_grid(&ctx, &s, 2, 0, 1));
  s.m.x[4][0] = 1.3;
  s.m.x[4][1] = 0.8;
  s.m.vflags[4] |= TDS_FIXED;
  CHECK_OK(&ctx, tds_vertex_average_mode(&ctx, &s, NULL, TDS_VAVG_CENTROID, 0, &nmoved));
  CHECK(nmoved == 0);
  CHECK(s.m.x[4][0] == 1.3 && s.m.x[4][1] == 0.8 && s.m.x[4][2] == 0);
  CHECK_MESH(&ctx, &s.m);
  /* nor one left out of the selection */
  s.m.vflags[4] &= ~(uint32_t)TDS_FIXED;
  uint8_t sel[9] = {1, 1, 1, 1, 0, 1, 1, 1, 1};
  CHECK_OK(&ctx, tds_vertex_average_mode(&ctx, &s, sel, TDS_VAVG_CENTROID, 0, &nmoved));
  CHECK(nmoved == 0);
  CHECK(s.m.x[4][0] == 1.3 && s.m.x[4][1] == 0.8);
  tds_surf_free(&s);
}

/* A tent: the middle vertex lifted. The centroid of its star lies below
** it, but the move has no component along the star's summed area normal
** (the volume under the star is kept to first order). */
static void vertex_average_tent(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_grid(&ctx, &s, 2, 0, 1));
  tds_mesh *m = &s.m;
  const double x0[3] = {1.3, 0.8, 0.4};
  v3_copy(m->x[4], x0);
  CHECK_MESH(&ctx, m);
  double nsum[3] = {0, 0, 0};
  for (tds_id f = 0; f < m->nf; f++) {
    const tds_id *fv = m->fv[f];
    if (fv[0] != 4 && fv[1] != 4 && fv[2] != 4) continue;
    double ab[3], ac[3], N[3];
    v3_sub(ab, m->x[fv[1]], m->x[fv[0]]);
    v3_sub(ac, m->x[fv[2]], m->x[fv[0]]);
    v3_cross(N, ab, ac);
    v3_add(nsum, nsum, N);
  }
  int32_t nmoved;
  CHECK_OK(&ctx, tds_vertex_average_mode(&ctx, &s, NULL, TDS_VAVG_CENTROID, 0, &nmoved));
  CHECK(nmoved == 1);
  CHECK_MESH(&ctx, m);
  double d[3];
  v3_sub(d, m->x[4], x0);
  CHECK(v3_norm(d) > 0.05);
  CHECK(fabs(v3_dot(d, nsum)) <= 1e-14 * v3_norm(d) * v3_norm(nsum));
  /* the summed normal of this star is (0, 0, 4): the vertex keeps its
  ** height and moves toward (1, 1) */
  CHECK_NEAR(nsum[0], 0, 1e-15);
  CHECK_NEAR(nsum[1], 0, 1e-15);
  CHECK_NEAR(m->x[4][2], 0.4, 1e-15);
  CHECK(hypot(m->x[4][0] - 1, m->x[4][1] - 1) < hypot(0.3, 0.2));
  tds_surf_free(&s);
}

/* Three fins on a spine of two edges p0-p1-p2 (a triple line), each fin a
** strip of two quads cut into triangles; built with tds_mesh_add_*.
** The middle spine vertex is placed at height z1. */
static int triple_line(tds_ctx *ctx, tds_surf *s, double z1) {
  tds_mesh *m = &s->m;
  const double pz[3] = {0, z1, 2};
  for (int j = 0; j < 3; j++) {
    double x[3] = {0, 0, pz[j]};
    if (tds_mesh_add_vertex(m, x) == TDS_NONE) return TDS_ENOMEM;
  }
  for (int k = 0; k < 3; k++)
    for (int j = 0; j < 3; j++) {
      double a = 2 * TDS_PI * k / 3;
      double x[3] = {cos(a), sin(a), j};
      if (tds_mesh_add_vertex(m, x) == TDS_NONE) return TDS_ENOMEM;
    }
  for (int k = 0; k < 3; k++)
    for (int j = 0; j < 2; j++) {
      tds_id p0 = j, p1 = j + 1, q0 = 3 + 3 * k + j, q1 = q0 + 1;
      tds_id tri[2][3] = {{p0, q0, q1}, {p0, q1, p1}};
      for (int t = 0; t < 2; t++) {
        int32_t oe[3];
        for (int i = 0; i < 3; i++)
          if ((oe[i] = h_edge_between(m, tri[t][i], tri[t][(i + 1) % 3])) < 0)
            return TDS_ENOMEM;
        if (!tds_mesh_edges_chain(m, oe)) return tds_seterr(ctx, TDS_ETOPO, "chain");
        if (tds_mesh_add_facet(m, oe) == TDS_NONE) return TDS_ENOMEM;
      }
    }
  return TDS_OK;
}

/* Evolver's rule (topo_vavg_ev.c) on the 3 x 3 grid with its middle vertex
** lifted and moved off-centre, the others fixed: rawv moves it a quarter
** of the way to sum g_e^2 x_e / sum g_e^2 (g_e: the area of the facets on
** edge e), computed here from the facets directly; V moves it by that
** move minus its component along the summed area vector (to rounding). */
static void vertex_average_evolver(void) {
  for (int mode = TDS_VAVG_V; mode <= TDS_VAVG_RAWEST; mode++) {
    tds_ctx ctx;
    tds_surf s;
    h_setup(&ctx, &s);
    REQUIRE_OK(&ctx, h_grid(&ctx, &s, 2, 0, 1));
    tds_mesh *m = &s.m;
    const double x0[3] = {1.3, 0.8, 0.4};
    v3_copy(m->x[4], x0);
    for (tds_id v = 0; v < m->nv; v++)
      if (v != 4) m->vflags[v] |= TDS_FIXED;
    double g[9] = {0}, nsum[3] = {0, 0, 0};
    for (tds_id f = 0; f < m->nf; f++) {
      const tds_id *fv = m->fv[f];
      if (fv[0] != 4 && fv[1] != 4 && fv[2] != 4) continue;
      double ab[3], ac[3], N[3];
      v3_sub(ab, m->x[fv[1]], m->x[fv[0]]);
      v3_sub(ac, m->x[fv[2]], m->x[fv[0]]);
      v3_cross(N, ab, ac);
      v3_add(nsum, nsum, N);
      for (int k = 0; k < 3; k++)
        if (fv[k] != 4) g[fv[k]] += 0.5 * v3_norm(N);
    }
    double T[3] = {0, 0, 0}, W = 0, d[3];
    for (tds_id v = 0; v < 9; v++) {
      v3_axpy(T, g[v] * g[v], m->x[v]);
      W += g[v] * g[v];
    }
    v3_scale(T, 1 / W);
    v3_sub(d, T, x0);
    v3_scale(d, 0.25);
    if (mode == TDS_VAVG_V) v3_axpy(d, -v3_dot(d, nsum) / v3_dot(nsum, nsum), nsum);
    int32_t nmoved = -1;
    CHECK_OK(&ctx, tds_vertex_average_mode(&ctx, &s, NULL, mode, 0, &nmoved));
    CHECK(nmoved == 1);
    CHECK_MESH(&ctx, m);
    for (int i = 0; i < 3; i++) CHECK_NEAR(m->x[4][i], x0[i] + d[i], 1e-15);
    if (mode == TDS_VAVG_V) CHECK_NEAR(m->x[4][2], 0.4, 1e-15); /* nsum is (0, 0, 4) */
    tds_surf_free(&s);
  }
}

/* With tds's centroid rule a vertex on a triple line moves along it, to
** the mean of its two neighbours on the line; the line's ends and the
** fins' borders stay. */
static void vertex_average_triple_line(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, triple_line(&ctx, &s, 1.3));
  tds_mesh *m = &s.m;
  CHECK_MESH(&ctx, m);
  CHECK(h_counts(m, 12, 2 + 3 * 7, 12)); /* spine + 7 edges per fin */
  tds_id e01 = h_find_edge(m, 0, 1), e12 = h_find_edge(m, 1, 2);
  CHECK(e01 != TDS_NONE && e12 != TDS_NONE);
  if (e01 == TDS_NONE || e12 == TDS_NONE) {
    tds_surf_free(&s);
    return;
  }
  CHECK(tds_edge_valence(m, e01) == 3 && tds_edge_valence(m, e12) == 3);
  int32_t nmoved = -1;
  CHECK_OK(&ctx, tds_vertex_average_mode(&ctx, &s, NULL, TDS_VAVG_CENTROID, 0, &nmoved));
  CHECK(nmoved == 1);
  CHECK_MESH(&ctx, m);
  CHECK_NEAR(m->x[1][0], 0, 1e-15);
  CHECK_NEAR(m->x[1][1], 0, 1e-15);
  CHECK_NEAR(m->x[1][2], 1, 1e-15);
  /* refining keeps the line triple: 4 spine edges of valence 3 */
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  CHECK_MESH(&ctx, m);
  int ntriple = 0;
  for (tds_id e = 0; e < m->ne; e++) ntriple += tds_edge_valence(m, e) == 3;
  CHECK(ntriple == 4);
  CHECK(h_counts(m, 12 + 23, 46 + 36, 48));
  tds_surf_free(&s);
}

/* Dead elements (a killed fin) are skipped by refine, flips and
** averaging, and the mesh stays sound. */
static void dead_elements_skipped(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, triple_line(&ctx, &s, 1.3));
  tds_mesh *m = &s.m;
  /* kill fin 3 (facets 9..12, its 3 outer vertices and their edges) */
  for (tds_id f = 8; f < 12; f++) tds_mesh_kill(m, TDS_FACET, f);
  for (tds_id e = 0; e < m->ne; e++)
    if (m->ev[e][0] >= 9 || m->ev[e][1] >= 9) tds_mesh_kill(m, TDS_EDGE, e);
  for (tds_id v = 9; v < 12; v++) tds_mesh_kill(m, TDS_VERTEX, v);
  CHECK_MESH(&ctx, m);
  CHECK(h_counts(m, 9, 16, 8));
  CHECK(tds_edge_valence(m, h_find_edge(m, 0, 1)) == 2);
  /* the spine is now an ordinary interior line between two fins */
  int32_t n;
  CHECK_OK(&ctx, tds_vertex_average(&ctx, &s, NULL, &n));
  CHECK_MESH(&ctx, m);
  CHECK_OK(&ctx, tds_equiangulate(&ctx, &s, NULL, &n));
  CHECK_MESH(&ctx, m);
  CHECK(h_counts(m, 9, 16, 8));
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &n));
  CHECK(n == 16);
  CHECK_MESH(&ctx, m);
  CHECK(h_counts(m, 25, 32 + 24, 32));
  for (tds_id f = 0; f < m->nf; f++)
    if (!tds_alive(m->fflags, f)) CHECK(f >= 8 && f < 12); /* slots kept */
  CHECK(h_stars_match(m));
  tds_surf_free(&s);
}

/* On a closed surface every free vertex is averaged; one on a flat star
** stays in its plane. */
static void vertex_average_closed(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  /* push one face centre slightly off its face, within the face plane */
  tds_id c = 8; /* centre of face 1 (y = 0) */
  CHECK_NEAR(s.m.x[c][1], 0, 0);
  s.m.x[c][0] += 0.1;
  int32_t nmoved;
  CHECK_OK(&ctx, tds_vertex_average(&ctx, &s, NULL, &nmoved));
  CHECK(nmoved == 50);
  CHECK_MESH(&ctx, &s.m);
  /* the face centre is on a flat star: it moves within the plane y = 0 */
  CHECK_NEAR(s.m.x[c][1], 0, 1e-15);
  CHECK(fabs(s.m.x[c][0] - 0.5) < 0.1);
  tds_surf_free(&s);
}

int main(void) {
  RUN(build_triangle);
  RUN(build_two_triangles);
  RUN(build_tetra);
  RUN(build_cube);
  RUN(build_triple_junction);
  RUN(build_errors);
  RUN(check_catches_breakage);
  RUN(kill_facet_unlinks);
  RUN(refine_counts);
  RUN(refine_no_refine_edge);
  RUN(refine_selection);
  RUN(refine_preserves_area_volume);
  RUN(refine_fixed_edges);
  RUN(refine_inherits);
  RUN(flip_non_delaunay_quad);
  RUN(flip_delaunay_quad);
  RUN(flip_never_triple);
  RUN(flip_never_fixed);
  RUN(flip_never_duplicates);
  RUN(flip_grid_adjacency);
  RUN(vertex_average_flat);
  RUN(vertex_average_tent);
  RUN(vertex_average_evolver);
  RUN(vertex_average_triple_line);
  RUN(dead_elements_skipped);
  RUN(vertex_average_closed);
  return check_done();
}
