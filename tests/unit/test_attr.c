/* test_attr.c: the attribute registry (src/attr.h): its rows agree with
** the mesh's defaults, setters keep their rules and refuse bad values
** leaving the element unchanged, user attributes grow, copy and are
** inherited with the mesh, and every datafile attribute survives a dump
** and a load bit for bit. */
#include "helpers.h"

#include <stdlib.h>
#include <unistd.h>

#include "attr.h"
#include "datafile.h"

static int is_scalar_value(const tds_attr *a) {
  return a->size == 1 && (a->type == TDS_AT_FLAG || a->type == TDS_AT_REAL ||
                          a->type == TDS_AT_INT || a->type == TDS_AT_COLOR);
}

static tds_id first_live(const tds_mesh *m, int kind) {
  const uint32_t *fl = kind == TDS_VERTEX ? m->vflags
                       : kind == TDS_EDGE ? m->eflags
                       : kind == TDS_FACET ? m->fflags : m->bflags;
  int32_t n = kind == TDS_VERTEX ? m->nv : kind == TDS_EDGE ? m->ne
              : kind == TDS_FACET ? m->nf : m->nb;
  for (tds_id i = 0; i < n; i++)
    if (tds_alive(fl, i)) return i;
  return TDS_NONE;
}

/* Names and datafile words are unique per kind; datafile rows can be
** read; a new element's value of every datafile scalar is the row's
** default (so dump leaves defaults out correctly: facet colour 15). */
static void rows_consistent(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
  for (int k = 0; k < TDS_NKINDS; k++) {
    int n = tds_attr_count(&s.m, k);
    CHECK(n > 3);
    tds_id id = first_live(&s.m, k);
    CHECK(id != TDS_NONE);
    for (int i = 0; i < n; i++) {
      tds_attr a, b;
      tds_attr_at(&s.m, k, i, &a);
      CHECK(a.kind == k && a.get != NULL && a.size >= 1);
      CHECK(tds_attr_find(&s.m, k, a.name, &b) && !strcmp(b.name, a.name));
      if (a.io & TDS_AT_FE) {
        CHECK(tds_attr_find_fe(&s.m, k, tds_attr_word(&a), &b) && !strcmp(b.name, a.name));
      }
      if (a.type == TDS_AT_FLAG) CHECK(a.flag != 0);
      if ((a.io & TDS_AT_FE) && is_scalar_value(&a) && a.dumped == NULL) {
        double v[TDS_MAX_CON];
        int nv;
        REQUIRE_OK(&ctx, tds_attr_read(&ctx, &s, &a, id, v, &nv));
        CHECK(nv == 1 && v[0] == a.dflt);
      }
    }
  }
  tds_attr a;
  CHECK(tds_attr_find(&s.m, TDS_FACET, "color", &a) && a.dflt == 15);
  CHECK(tds_attr_find(&s.m, TDS_EDGE, "color", &a) && a.dflt == 0);
  CHECK(tds_attr_find(&s.m, TDS_EDGE, "noncontent", &a) && a.flag == TDS_NONCONTENT);
  CHECK(tds_attr_find(&s.m, TDS_EDGE, "bare", &a) && (a.io & TDS_AT_FE));
  CHECK(!tds_attr_find(&s.m, TDS_VERTEX, "foo", &a));
  CHECK(tds_attr_find_fe(&s.m, TDS_BODY, "volume", &a) && !strcmp(a.name, "target"));
  CHECK(tds_attr_find_fe(&s.m, TDS_FACET, "frontcolor", &a) && !strcmp(a.name, "color"));
  tds_surf_free(&s);
}

/* Every settable scalar reads back what was set (seeded random values of
** its type). */
static void set_get_roundtrip(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
  uint64_t seed = 12345;
  for (int k = 0; k < TDS_NKINDS; k++) {
    int n = tds_attr_count(&s.m, k);
    tds_id id = first_live(&s.m, k);
    for (int i = 0; i < n; i++) {
      tds_attr a;
      tds_attr_at(&s.m, k, i, &a);
      if (!a.set || !is_scalar_value(&a) || (k == TDS_VERTEX && a.name[0] == 'p')) continue;
      if (!strcmp(a.name, "wrap")) continue; /* torus only (test_torus.c) */
      double x = a.type == TDS_AT_FLAG ? (h_rand(&seed) < 0.5 ? 0 : 1)
                 : a.type == TDS_AT_REAL ? h_uniform(&seed, -3, 3)
                                         : floor(h_uniform(&seed, -100, 100));
      if (!strcmp(a.name, "original")) x = fabs(x); /* an id, or 0 */
      REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &a, id, &x, 1));
      double v[TDS_MAX_CON];
      int nv;
      REQUIRE_OK(&ctx, tds_attr_read(&ctx, &s, &a, id, v, &nv));
      if (strcmp(a.name, "volume")) CHECK(nv == 1 && v[0] == x); /* volume reads the actual */
    }
  }
  tds_surf_free(&s);
}

/* A target volume and a prescribed pressure exclude each other; unsetting
** clears; density turns gravity on, as Evolver's datafile does. */
static void body_rules(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
  tds_attr target, pressure, density;
  CHECK(tds_attr_find(&s.m, TDS_BODY, "target", &target));
  CHECK(tds_attr_find(&s.m, TDS_BODY, "pressure", &pressure));
  CHECK(tds_attr_find(&s.m, TDS_BODY, "density", &density));
  double two = 2, three = 3, v[1];
  int n;
  REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &target, 0, &two, 1));
  CHECK(s.m.bflags[0] & TDS_TARGET);
  REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &pressure, 0, &three, 1));
  CHECK((s.m.bflags[0] & (TDS_TARGET | TDS_PRESSURE)) == TDS_PRESSURE);
  REQUIRE_OK(&ctx, tds_attr_read(&ctx, &s, &target, 0, v, &n));
  CHECK(n == 0); /* nil: no target */
  REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &target, 0, &two, 1));
  CHECK((s.m.bflags[0] & (TDS_TARGET | TDS_PRESSURE)) == TDS_TARGET);
  REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &target, 0, NULL, 0));
  CHECK(!(s.m.bflags[0] & (TDS_TARGET | TDS_PRESSURE)));
  CHECK(!s.gravity_on);
  double zero = 0;
  REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &density, 0, &zero, 1));
  CHECK(s.gravity_on);
  tds_surf_free(&s);
}

/* Wrong values are refused with a message naming the element and the
** attribute, and nothing changes. */
static void check_refuses(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 0));
  tds_attr x, col, ten, len, fl;
  CHECK(tds_attr_find(&s.m, TDS_VERTEX, "x", &x));
  CHECK(tds_attr_find(&s.m, TDS_FACET, "color", &col));
  CHECK(tds_attr_find(&s.m, TDS_EDGE, "tension", &ten));
  CHECK(tds_attr_find(&s.m, TDS_EDGE, "length", &len));
  double nan = NAN, half = 2.5, big = 40000, one = 1;
  double x0 = s.m.x[2][0];
  CHECK(tds_attr_write(&ctx, &s, &x, 2, &nan, 1) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "vertex 3: x must be finite, not NaN") != NULL);
  CHECK(s.m.x[2][0] == x0);
  CHECK(tds_attr_write(&ctx, &s, &col, 0, &half, 1) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "facet 1: color must be a whole number") != NULL);
  CHECK(tds_attr_write(&ctx, &s, &col, 0, &big, 1) == TDS_ERANGE);
  CHECK(s.m.fcolor[0] == 15);
  CHECK(tds_attr_write(&ctx, &s, &len, 0, &one, 1) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "edge 1: length cannot be set") != NULL);
  int32_t dim[1] = {3};
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_FACET, "flags", TDS_AT_INT, 1, dim));
  CHECK(tds_attr_find(&s.m, TDS_FACET, "flags", &fl) && fl.size == 3);
  double two[2] = {1, 2}, frac[3] = {1, 2, 3.5};
  CHECK(tds_attr_write(&ctx, &s, &fl, 0, two, 2) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "flags takes 3 values, got 2") != NULL);
  CHECK(tds_attr_write(&ctx, &s, &fl, 0, frac, 3) == TDS_ERANGE);
  CHECK(s.m.ucol[TDS_FACET][0].v[2] == 0);
  tds_surf_free(&s);
}

/* User columns: zero for every element, grown with the mesh, copied with
** it, inherited by refinement (edges and facets, not the new vertices:
** Evolver's rule), redefinition rules. */
static void user_columns(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_VERTEX, "weight", TDS_AT_REAL, 0, NULL));
  int32_t d2[2] = {2, 3};
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_EDGE, "m", TDS_AT_REAL, 2, d2));
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_FACET, "tag", TDS_AT_INT, 0, NULL));
  /* again, same shape: fine; other shape, built-in or bad names: refused */
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_VERTEX, "weight", TDS_AT_REAL, 0, NULL));
  CHECK(tds_attr_define(&ctx, &s.m, TDS_VERTEX, "weight", TDS_AT_INT, 0, NULL) == TDS_ERANGE);
  CHECK(tds_attr_define(&ctx, &s.m, TDS_EDGE, "tension", TDS_AT_REAL, 0, NULL) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "built-in") != NULL);
  CHECK(tds_attr_define(&ctx, &s.m, TDS_EDGE, "2x", TDS_AT_REAL, 0, NULL) == TDS_ERANGE);
  int32_t huge[2] = {100, 100};
  CHECK(tds_attr_define(&ctx, &s.m, TDS_EDGE, "big", TDS_AT_REAL, 2, huge) == TDS_ERANGE);
  CHECK(s.m.nucol[TDS_VERTEX] == 1 && s.m.nucol[TDS_EDGE] == 1);
  tds_attr w, m6, tag;
  CHECK(tds_attr_find(&s.m, TDS_VERTEX, "weight", &w) && (w.io & TDS_AT_USER));
  CHECK(tds_attr_find(&s.m, TDS_EDGE, "m", &m6) && m6.size == 6);
  CHECK(tds_attr_find(&s.m, TDS_FACET, "tag", &tag));
  for (tds_id v = 0; v < s.m.nv; v++) CHECK(s.m.ucol[TDS_VERTEX][0].v[v] == 0);
  double vals[6] = {1, 2, 3, 4, 5, 6}, t = 7, wv = -1.25;
  for (tds_id e = 0; e < s.m.ne; e++) {
    vals[0] = e;
    REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &m6, e, vals, 6));
  }
  for (tds_id f = 0; f < s.m.nf; f++) {
    t = f % 5;
    REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &tag, f, &t, 1));
  }
  REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &w, 0, &wv, 1));
  tds_mesh copy;
  REQUIRE_OK(&ctx, tds_mesh_copy(&copy, &s.m));
  CHECK(copy.nucol[TDS_EDGE] == 1 &&
        !memcmp(copy.ucol[TDS_EDGE][0].v, s.m.ucol[TDS_EDGE][0].v,
                sizeof(double) * 6 * (size_t)s.m.ne));
  tds_mesh_free(&copy);
  int32_t nv0 = s.m.nv, ne0 = s.m.ne, nf0 = s.m.nf;
  REQUIRE_OK(&ctx, tds_refine(&ctx, &s, NULL, NULL));
  CHECK_MESH(&ctx, &s.m);
  CHECK(s.m.nv > nv0 && s.m.ucol[TDS_VERTEX][0].v[0] == -1.25);
  for (tds_id v = nv0; v < s.m.nv; v++) CHECK(s.m.ucol[TDS_VERTEX][0].v[v] == 0);
  /* each original edge is split in two halves with the same values; the
  ** edges inside facets start at zero */
  int halves = 0, zero = 0;
  for (tds_id e = ne0; e < s.m.ne; e++) {
    const double *q = s.m.ucol[TDS_EDGE][0].v + 6 * (size_t)e;
    if (q[5] == 6) {
      halves++;
      CHECK(q[0] >= 0 && q[0] < ne0);
    } else {
      zero += q[0] == 0 && q[5] == 0;
    }
  }
  CHECK(halves == ne0 && zero == s.m.ne - 2 * ne0);
  for (tds_id f = nf0; f < s.m.nf; f++) {
    tds_id o = s.m.forig[f];
    (void)o;
    CHECK(s.m.ucol[TDS_FACET][0].v[f] >= 0 && s.m.ucol[TDS_FACET][0].v[f] <= 4);
  }
  /* the children of facet 1 (slot 0) carry its tag 0, of facet 2 tag 1 */
  int kids1 = 0;
  for (tds_id f = nf0; f < s.m.nf; f++)
    if (s.m.ucol[TDS_FACET][0].v[f] == 1) kids1++;
  CHECK(kids1 >= 3);
  tds_surf_free(&s);
}

/* Every datafile attribute of every element, user arrays included,
** survives dump and load bit for bit (random values, seeded). */
static void dump_load_roundtrip(void) {
  tds_ctx ctx;
  tds_surf s, r;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  int32_t d3[1] = {3}, d22[2] = {2, 2};
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_VERTEX, "weight", TDS_AT_REAL, 0, NULL));
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_EDGE, "ew", TDS_AT_REAL, 2, d22));
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_FACET, "flags", TDS_AT_INT, 1, d3));
  REQUIRE_OK(&ctx, tds_attr_define(&ctx, &s.m, TDS_BODY, "bw", TDS_AT_REAL, 0, NULL));
  uint64_t seed = 99;
  for (int k = 0; k < TDS_NKINDS; k++) {
    int n = tds_attr_count(&s.m, k);
    int32_t cnt = k == TDS_VERTEX ? s.m.nv : k == TDS_EDGE ? s.m.ne
                  : k == TDS_FACET ? s.m.nf : s.m.nb;
    for (int i = 0; i < n; i++) {
      tds_attr a;
      tds_attr_at(&s.m, k, i, &a);
      if (!(a.io & TDS_AT_FE) || !a.set || a.type == TDS_AT_CONS || a.type == TDS_AT_BDRY)
        continue; /* boundaries can only be unset */
      if (!strcmp(a.name, "pressure") || !strcmp(a.name, "density")) continue;
      if (!strcmp(a.name, "wrap")) continue; /* torus only (test_torus.c) */
      for (tds_id id = 0; id < cnt; id++) {
        double v[16];
        for (int j = 0; j < a.size; j++)
          v[j] = a.type == TDS_AT_FLAG ? (h_rand(&seed) < 0.5)
                 : a.type == TDS_AT_REAL ? h_uniform(&seed, -1e3, 1e3) / 7
                                         : floor(h_uniform(&seed, -20, 20));
        REQUIRE_OK(&ctx, tds_attr_write(&ctx, &s, &a, id, v, a.size));
      }
    }
  }
  char path[] = "/tmp/tds_test_attr_XXXXXX";
  int fd = mkstemp(path);
  CHECK(fd >= 0);
  close(fd);
  REQUIRE_OK(&ctx, tds_datafile_dump(&ctx, &s, path));
  h_setup(&ctx, &r);
  REQUIRE_OK(&ctx, tds_datafile_load(&ctx, &r, path));
  remove(path);
  for (int k = 0; k < TDS_NKINDS; k++) {
    CHECK(tds_attr_count(&r.m, k) == tds_attr_count(&s.m, k));
    int n = tds_attr_count(&s.m, k);
    int32_t cnt = k == TDS_VERTEX ? s.m.nv : k == TDS_EDGE ? s.m.ne
                  : k == TDS_FACET ? s.m.nf : s.m.nb;
    for (int i = 0; i < n; i++) {
      tds_attr a, b;
      tds_attr_at(&s.m, k, i, &a);
      tds_attr_at(&r.m, k, i, &b);
      if (!(a.io & TDS_AT_FE)) continue;
      for (tds_id id = 0; id < cnt; id++) {
        double v[TDS_MAX_CON], w[TDS_MAX_CON];
        int nv, nw;
        REQUIRE_OK(&ctx, tds_attr_read(&ctx, &s, &a, id, v, &nv));
        REQUIRE_OK(&ctx, tds_attr_read(&ctx, &r, &b, id, w, &nw));
        CHECK(nv == nw && !memcmp(v, w, sizeof *v * (size_t)nv));
      }
    }
  }
  tds_surf_free(&r);
  tds_surf_free(&s);
}

int main(void) {
  RUN(rows_consistent);
  RUN(set_get_roundtrip);
  RUN(body_rules);
  RUN(check_refuses);
  RUN(user_columns);
  RUN(dump_load_roundtrip);
  return check_done();
}
