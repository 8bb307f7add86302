/* mesh_bodies.c: warnings about how facets bound bodies (contracts in
** mesh.h). */
#include "mesh.h"

#include <stdio.h>

#include "gather.h"
#include "geom.h"

/* The body on the side of facet side `sd` that its edge's direction turns
** toward (right-hand rule about the edge), or on the other side. */
static tds_id body_turned(const tds_mesh *m, int32_t sd, int other) {
  tds_id f = sd / 3;
  int forward = !TDS_OREV(m->fe[f][sd % 3]);
  return m->fb[f][forward == !other ? 0 : 1];
}

/* Name a facet for the user: "facet 7 (face 1)" when it descends from a
** declared face with another id. */
static void name_facet(const tds_mesh *m, tds_id f, char *buf, size_t n) {
  tds_id o = m->forig ? m->forig[f] : TDS_NONE;
  if (o != TDS_NONE && o != f)
    snprintf(buf, n, "facet %d (face %d)", f + 1, o + 1);
  else
    snprintf(buf, n, "facet %d", f + 1);
}

/* Around an edge, every region between two neighbouring facets is entered
** through one facet and left through the next, so each body must lie on
** the turned-toward side of as many facets as on the other side. This
** needs no angular order of the ring. Returns a side whose body *body
** breaks the balance and sets *twin to another side with that body on the
** same side, or -1; returns -1 if the edge is balanced. */
static int32_t unbalanced(const tds_mesh *m, tds_id e, tds_id *body, int32_t *twin) {
  int32_t s0 = m->eside[e];
  if (s0 == TDS_NONE || m->side_next[s0] == s0) return -1; /* < 2 facets */
  int32_t s = s0;
  do {
    for (int side = 0; side < 2; side++) {
      tds_id b = body_turned(m, s, side);
      if (b == TDS_NONE) continue;
      int net = 0;
      *twin = -1;
      int32_t t = s0;
      do {
        if (body_turned(m, t, side) == b) {
          net++;
          if (t != s) *twin = t;
        }
        if (body_turned(m, t, !side) == b) net--;
        t = m->side_next[t];
      } while (t != s0);
      if (net != 0) {
        *body = b;
        return s;
      }
    }
    s = m->side_next[s];
  } while (s != s0);
  return -1;
}

int32_t tds_mesh_body_warnings(tds_ctx *ctx, const tds_mesh *m, const char *where) {
  int32_t bad = 0;
  char a[48], b[48];
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    tds_id body;
    int32_t twin, s = unbalanced(m, e, &body, &twin);
    if (s < 0) continue;
    if (++bad > 10) continue;
    name_facet(m, s / 3, a, sizeof a);
    if (twin >= 0) {
      name_facet(m, twin / 3, b, sizeof b);
      tds_warnf(ctx, "%swarning: inconsistent bodies for facets on edge %d: %s and %s "
                "both have body %d on the same side (one of them is listed with "
                "the wrong sign)\n", where, e + 1, a, b, body + 1);
    } else {
      tds_warnf(ctx, "%swarning: inconsistent bodies for facets on edge %d: body %d "
                "lies on one side of %s only\n", where, e + 1, body + 1, a);
    }
  }
  if (bad > 10)
    tds_warnf(ctx, "%swarning: inconsistent bodies on %d edges in all\n", where, bad);
  for (tds_id f = 0; f < m->nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    tds_corners C;
    tds_gather_facet(m, f, &C);
    if (geom_area(C.x[0], C.x[1], C.x[2], NULL) == 0) {
      name_facet(m, f, a, sizeof a);
      tds_warnf(ctx, "%swarning: %s has zero area\n", where, a);
      bad++;
    }
  }
  return bad;
}
