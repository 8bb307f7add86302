/* topo_quad.c: Evolver's pop_quad_to_quad, the foam T1 move on a
** quadrilateral film.
**
** The quadrilateral is the film (facets joined through edges of valence
** 2) of the given facet, between two bodies A and B, bounded by exactly
** four triple edges (its sides, single edges, as Evolver requires) whose
** corners are free tetrahedral points. At each corner one more triple
** edge leaves on A's side and one on B's; their eight far ends must be
** different vertices. The move, as Evolver makes it (measured on seeded
** random foams, tests/evolver/quad.sh):
** * the pair of opposite sides with the smaller total length is shrunk to
**   nothing: each side collapses to its midpoint (ends H and T), the
**   film goes, and the two other sides become one edge L between H and T
**   where the bodies D and F beyond them now meet A and B;
** * H and T each open into two vertices, one taking the triple edges on
**   A's side, one those on B's: the quadrilateral H_A T_A T_B H_B between
**   D and F (two facets) now parts A from B. With c the centroid of the
**   old corners and a_A (a_B) the mean of the far ends of the four triple
**   edges on A's (B's) side, H_A = H + (a_A - c)/3, and so on;
** * the side of the lowest-numbered of those eight triple edges gets new
**   vertices, the other keeps H and T (and L); each film between two
**   triple edges that part follows the new vertex and gains a facet.
** Each facet is done under its own snapshot; one that does not fit is
** skipped with the surface as before and a message saying why. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "motion.h"
#include "snap.h"
#include "topo.h"
#include "topo_edit.h"
#include "topo_t1.h"
#include "torus.h"
#include "vec3.h"

#define MAXQ 512 /* facets in one quadrilateral */

typedef struct quad {
  int nfac;
  tds_id fac[MAXQ];
  tds_id side[4];   /* side[i] joins corner[i] and corner[i + 1] */
  tds_id corner[4];
  tds_id A, B;      /* the bodies on either side */
  tds_id rad[4][2]; /* at corner i: the triple edge on A's side, on B's */
} quad;

static tds_id other_end(const tds_mesh *m, tds_id e, tds_id v) {
  return m->ev[e][0] == v ? m->ev[e][1] : m->ev[e][0];
}

static int32_t oref_from(const tds_mesh *m, tds_id e, tds_id from) {
  return TDS_OREF(e, m->ev[e][0] == from ? 0 : 1);
}

static int has_body(const tds_mesh *m, tds_id f, tds_id b) {
  return m->fb[f][0] == b || m->fb[f][1] == b;
}

static int in_list(const tds_id *l, int n, tds_id x) {
  for (int i = 0; i < n; i++)
    if (l[i] == x) return 1;
  return 0;
}

static double len(const tds_mesh *m, tds_id e) {
  double d[3];
  v3_sub(d, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
  return v3_norm(d);
}

/* The quadrilateral of facet f into q: NULL, or why there is none (into
** buf). A facet without a triple edge gives "" (skipped silently, as
** Evolver does outside verbose mode). */
static const char *find_quad(const tds_surf *s, tds_id f, quad *q, char *buf, size_t nb) {
  const tds_mesh *m = &s->m;
  int triple = 0;
  for (int k = 0; k < 3; k++) triple |= tds_edge_valence(m, TDS_OID(m->fe[f][k])) == 3;
  if (!triple) return "";
  q->A = m->fb[f][0], q->B = m->fb[f][1];
  if (q->A == q->B) return "the same body is on both sides of its film";
  /* the film: facets joined through edges of valence 2 */
  tds_id bd[4];
  int nbd = 0;
  q->nfac = 1;
  q->fac[0] = f;
  for (int i = 0; i < q->nfac; i++) {
    tds_id g = q->fac[i];
    if ((m->fflags[g] & TDS_FIXED) || m->fcon[g]) {
      snprintf(buf, nb, "facet %d of the quadrilateral is fixed or on a constraint", g + 1);
      return buf;
    }
    if (!has_body(m, g, q->A) || !has_body(m, g, q->B)) {
      snprintf(buf, nb, "facet %d of the quadrilateral is not between the same two bodies", g + 1);
      return buf;
    }
    for (int k = 0; k < 3; k++) {
      tds_id e = TDS_OID(m->fe[g][k]);
      int val = tds_edge_valence(m, e);
      if (val == 3) {
        if (in_list(bd, nbd, e)) {
          snprintf(buf, nb, "triple edge %d borders the quadrilateral twice", e + 1);
          return buf;
        }
        if (nbd == 4) return "didn't find quadrilateral of triple edges";
        bd[nbd++] = e;
        continue;
      }
      if (val != 2) {
        snprintf(buf, nb, "edge %d inside the film has %d facets", e + 1, val);
        return buf;
      }
      int32_t sd = m->eside[e];
      do {
        tds_id h = sd / 3;
        if (h != g && !in_list(q->fac, q->nfac, h)) {
          if (q->nfac == MAXQ) return "the film has too many facets";
          q->fac[q->nfac++] = h;
        }
        sd = m->side_next[sd];
      } while (sd != m->eside[e]);
    }
  }
  if (nbd != 4) return "didn't find quadrilateral of triple edges";
  /* the sides in order round the film, from f's first triple edge the
  ** way f runs (Evolver's walk) */
  int k0 = 0;
  while (tds_edge_valence(m, TDS_OID(m->fe[f][k0])) != 3) k0++;
  int used[4] = {0, 0, 0, 0};
  for (int j = 0; j < 4; j++) used[j] = bd[j] == TDS_OID(m->fe[f][k0]);
  q->side[0] = TDS_OID(m->fe[f][k0]);
  q->corner[0] = tds_oe_tail(m, m->fe[f][k0]);
  q->corner[1] = tds_oe_head(m, m->fe[f][k0]);
  for (int i = 1; i < 4; i++) {
    int next = -1;
    for (int j = 0; j < 4; j++)
      if (!used[j] && (m->ev[bd[j]][0] == q->corner[i] || m->ev[bd[j]][1] == q->corner[i])) {
        if (next >= 0) return "didn't find quadrilateral of triple edges";
        next = j;
      }
    if (next < 0) return "didn't find quadrilateral of triple edges";
    used[next] = 1;
    q->side[i] = bd[next];
    if (i < 3) q->corner[i + 1] = other_end(m, bd[next], q->corner[i]);
    else if (other_end(m, bd[next], q->corner[3]) != q->corner[0])
      return "didn't find quadrilateral of triple edges";
  }
  for (int i = 0; i < 4; i++)
    for (int j = i + 1; j < 4; j++)
      if (q->corner[i] == q->corner[j]) return "didn't find quadrilateral of triple edges";
  /* the corners: free tetrahedral points, one triple edge off to each side */
  tds_id far[8];
  for (int i = 0; i < 4; i++) {
    tds_id c = q->corner[i], t4[4];
    if (!tds_t1_free_vertex(s, c)) {
      snprintf(buf, nb, "corner vertex %d is fixed or on a constraint or boundary", c + 1);
      return buf;
    }
    if (!tds_t1_tetra(m, c, TDS_NONE, t4)) {
      snprintf(buf, nb, "corner vertex %d is not a tetrahedral point", c + 1);
      return buf;
    }
    q->rad[i][0] = q->rad[i][1] = TDS_NONE;
    for (int k = 0; k < 4; k++) {
      tds_id e = t4[k];
      if (in_list(q->side, 4, e)) continue;
      if ((m->eflags[e] & TDS_FIXED) || m->econ[e] || m->ebdry[e] != TDS_NONE) {
        snprintf(buf, nb, "triple edge %d is fixed or on a constraint or boundary", e + 1);
        return buf;
      }
      int ha = tds_t1_around_has(m, e, q->A), hb = tds_t1_around_has(m, e, q->B);
      int j = ha && !hb ? 0 : hb && !ha ? 1 : -1;
      if (j < 0 || q->rad[i][j] != TDS_NONE) {
        snprintf(buf, nb, "the triple edges at corner vertex %d do not part the two bodies", c + 1);
        return buf;
      }
      q->rad[i][j] = e;
    }
    if (q->rad[i][0] == TDS_NONE || q->rad[i][1] == TDS_NONE) {
      snprintf(buf, nb, "the triple edges at corner vertex %d do not part the two bodies", c + 1);
      return buf;
    }
    far[2 * i] = other_end(m, q->rad[i][0], c);
    far[2 * i + 1] = other_end(m, q->rad[i][1], c);
  }
  for (int i = 0; i < 8; i++) {
    if (in_list(q->corner, 4, far[i])) {
      snprintf(buf, nb, "triple edge %d joins two corners", q->rad[i / 2][i % 2] + 1);
      return buf;
    }
    for (int j = i + 1; j < 8; j++)
      if (far[i] == far[j]) {
        snprintf(buf, nb, "triple edges %d and %d have common far endpoint",
                 q->rad[i / 2][i % 2] + 1, q->rad[j / 2][j % 2] + 1);
        return buf;
      }
  }
  for (int i = 0; i < 4; i++) {
    tds_id e = q->side[i];
    if ((m->eflags[e] & TDS_FIXED) || m->econ[e] || m->ebdry[e] != TDS_NONE) {
      snprintf(buf, nb, "side edge %d is fixed or on a constraint or boundary", e + 1);
      return buf;
    }
  }
  /* inside vertices belong to the film alone and are free */
  for (int i = 0; i < q->nfac; i++)
    for (int k = 0; k < 3; k++) {
      tds_id v = m->fv[q->fac[i]][k];
      if (in_list(q->corner, 4, v)) continue;
      if (!tds_t1_free_vertex(s, v)) {
        snprintf(buf, nb, "vertex %d inside the quadrilateral is fixed or on a constraint", v + 1);
        return buf;
      }
    }
  /* the short pair goes: make it sides 1 and 3; side 0, kept, is the
  ** first of the long pair along the walk */
  if (len(m, q->side[0]) + len(m, q->side[2]) <= len(m, q->side[1]) + len(m, q->side[3])) {
    tds_id s0 = q->side[0], c0 = q->corner[0], r0 = q->rad[0][0], r1 = q->rad[0][1];
    for (int i = 0; i < 3; i++) {
      q->side[i] = q->side[i + 1];
      q->corner[i] = q->corner[i + 1];
      q->rad[i][0] = q->rad[i + 1][0];
      q->rad[i][1] = q->rad[i + 1][1];
    }
    q->side[3] = s0, q->corner[3] = c0, q->rad[3][0] = r0, q->rad[3][1] = r1;
  }
  /* the bodies beyond the long sides must differ */
  tds_id third[2];
  for (int h = 0; h < 2; h++) {
    tds_id bs[8];
    int n = tds_t1_bodies_around(m, q->side[2 * h], bs), cnt = 0;
    for (int z = 0; z < n; z++)
      if (bs[z] != q->A && bs[z] != q->B) third[h] = bs[z], cnt++;
    if (cnt != 1) {
      snprintf(buf, nb, "side edge %d is not between three bodies", q->side[2 * h] + 1);
      return buf;
    }
  }
  if (third[0] == third[1]) {
    snprintf(buf, nb, "the new quadrilateral would lie inside body %d", third[0] + 1);
    return buf;
  }
  return NULL;
}

/* Does vertex v have an edge outside the film? */
static int touches_outside(const tds_mesh *m, const quad *q, tds_id v) {
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e) || (m->ev[e][0] != v && m->ev[e][1] != v)) continue;
    int on = 0;
    for (int i = 0; i < q->nfac && !on; i++)
      for (int k = 0; k < 3; k++) on |= TDS_OID(m->fe[q->fac[i]][k]) == e;
    if (!on) return 1;
  }
  return 0;
}

/* Move the sides of facets around edge L that have body `with` and not
** `without` onto edge to (same ends as L). */
static void move_films(tds_mesh *m, tds_id L, tds_id to, tds_id with, tds_id without) {
  tds_id fl[16];
  int nf = 0;
  int32_t sd = m->eside[L];
  do {
    tds_id g = sd / 3;
    if (has_body(m, g, with) && !has_body(m, g, without) && nf < 16) fl[nf++] = g;
    sd = m->side_next[sd];
  } while (sd != m->eside[L]);
  int same = m->ev[L][0] == m->ev[to][0];
  for (int i = 0; i < nf; i++) {
    tds_id g = fl[i];
    int32_t oe[3] = {m->fe[g][0], m->fe[g][1], m->fe[g][2]};
    for (int k = 0; k < 3; k++)
      if (TDS_OID(oe[k]) == L) oe[k] = TDS_OREF(to, same ? TDS_OREV(oe[k]) : !TDS_OREV(oe[k]));
    tds_mesh_set_facet(m, g, oe);
  }
}

/* The move on quadrilateral q; 1 done, <0 a negated error code. */
static int pop_quad(tds_surf *s, quad *q) {
  tds_mesh *m = &s->m;
  if (tds_mesh_room(m, TDS_VERTEX, m->nv + 2) || tds_mesh_room(m, TDS_EDGE, m->ne + 8) ||
      tds_mesh_room(m, TDS_FACET, m->nf + 8))
    return -TDS_ENOMEM;
  for (int i = 0; i < q->nfac; i++)
    for (int k = 0; k < 3; k++) {
      tds_id v = m->fv[q->fac[i]][k];
      if (!in_list(q->corner, 4, v) && touches_outside(m, q, v)) return -TDS_ETOPO;
    }
  /* where things go, from the old places */
  double c[3] = {0, 0, 0}, mean[2][3] = {{0, 0, 0}, {0, 0, 0}}, u[2][3], toD[3];
  for (int i = 0; i < 4; i++) {
    v3_axpy(c, 0.25, m->x[q->corner[i]]);
    for (int j = 0; j < 2; j++) v3_axpy(mean[j], 0.25, m->x[other_end(m, q->rad[i][j], q->corner[i])]);
  }
  for (int j = 0; j < 2; j++) {
    v3_sub(u[j], mean[j], c);
    v3_scale(u[j], 1.0 / 3);
  }
  for (int k = 0; k < 3; k++) /* from F's side (side 2) toward D's (side 0) */
    toD[k] = 0.5 * (m->x[q->corner[0]][k] + m->x[q->corner[1]][k] -
                    m->x[q->corner[2]][k] - m->x[q->corner[3]][k]);
  tds_id D = TDS_NONE, F = TDS_NONE, bs[8];
  for (int h = 0; h < 2; h++) {
    int n = tds_t1_bodies_around(m, q->side[2 * h], bs);
    for (int z = 0; z < n; z++)
      if (bs[z] != q->A && bs[z] != q->B) *(h ? &F : &D) = bs[z];
  }
  /* the side with the lowest-numbered leaving triple edge gets new vertices */
  int nside = 0;
  tds_id low = q->rad[0][0];
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 2; j++)
      if (q->rad[i][j] < low) low = q->rad[i][j], nside = j;
  tds_id NB = nside ? q->B : q->A, OB = nside ? q->A : q->B;
  int head_is_1 = 1; /* H: where side 1 shrinks, ahead along the walk */
  uint32_t fl0 = m->fflags[q->fac[0]];
  tds_id src = q->fac[0];
  /* the film goes, with its inside edges and vertices */
  for (int i = 0; i < q->nfac; i++) tds_mesh_kill(m, TDS_FACET, q->fac[i]);
  for (int i = 0; i < q->nfac; i++)
    for (int k = 0; k < 3; k++) {
      tds_id e = TDS_OID(m->fe[q->fac[i]][k]), v = m->fv[q->fac[i]][k];
      if (tds_alive(m->eflags, e) && !in_list(q->side, 4, e)) tds_mesh_kill(m, TDS_EDGE, e);
      if (tds_alive(m->vflags, v) && !in_list(q->corner, 4, v)) tds_mesh_kill(m, TDS_VERTEX, v);
    }
  /* the short sides shrink to their midpoints */
  if (tds_collapse_edge(s, q->side[1]) <= 0 || tds_collapse_edge(s, q->side[3]) <= 0)
    return -TDS_ETOPO;
  tds_id end1 = tds_alive(m->vflags, q->corner[1]) ? q->corner[1] : q->corner[2];
  tds_id end3 = tds_alive(m->vflags, q->corner[3]) ? q->corner[3] : q->corner[0];
  tds_id H = head_is_1 ? end1 : end3, T = head_is_1 ? end3 : end1;
  tds_id L = TDS_NONE;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e) && ((m->ev[e][0] == H && m->ev[e][1] == T) ||
                                    (m->ev[e][0] == T && m->ev[e][1] == H))) {
      if (L != TDS_NONE) return -TDS_ETOPO;
      L = e;
    }
  if (L == TDS_NONE || tds_edge_valence(m, L) != 4) return -TDS_ETOPO;
  /* the new side's films leave L for their own edge */
  tds_id LN = tds_mesh_add_edge(m, H, T);
  tds_edge_inherit(m, LN, L);
  move_films(m, L, LN, NB, OB);
  if (tds_edge_valence(m, L) != 2 || tds_edge_valence(m, LN) != 2) return -TDS_ETOPO;
  /* the ends open */
  tds_id ends[2] = {H, T}, nw[2], conn[2];
  for (int h = 0; h < 2; h++) {
    tds_id v = ends[h];
    double xn[3], xo[3];
    v3_add(xn, m->x[v], u[nside]);
    v3_add(xo, m->x[v], u[!nside]);
    nw[h] = tds_mesh_add_vertex(m, xn);
    m->vcon[nw[h]] = m->vcon[v];
    v3_copy(m->x[v], xo);
    /* H: old -> new; T: new -> old (Evolver's) */
    conn[h] = h == 0 ? tds_mesh_add_edge(m, v, nw[h]) : tds_mesh_add_edge(m, nw[h], v);
    tds_edge_inherit(m, conn[h], L);
    /* the triple edges leaving v (found again: the collapses may have
    ** merged some of them into edges of the films they bounded) */
    tds_id te[6], tv[6];
    int nt = 0;
    for (tds_id e = 0; e < m->ne; e++) {
      if (!tds_alive(m->eflags, e) || e == L || e == LN || e == conn[h]) continue;
      if ((m->ev[e][0] != v && m->ev[e][1] != v) || tds_edge_valence(m, e) != 3) continue;
      int ha = tds_t1_around_has(m, e, q->A), hb = tds_t1_around_has(m, e, q->B);
      if (ha == hb || nt == 4) return -TDS_ETOPO;
      te[nt] = e;
      tv[nt++] = (hb ? 1 : 0) == nside ? nw[h] : v;
    }
    if (nt != 4) return -TDS_ETOPO;
    te[4] = LN, tv[4] = nw[h];
    te[5] = L, tv[5] = v;
    int rc = tds_t1_expand(m, v, 6, te, tv, &conn[h], 1, 0, NULL, nw[h]);
    if (rc != TDS_OK) return -rc;
  }
  /* the new quadrilateral: (T, H_N, T_N) and (H, H_N, T) */
  tds_id HN = nw[0], TN = nw[1];
  tds_id dg = tds_mesh_add_edge(m, HN, T);
  int32_t f1[3] = {oref_from(m, dg, T), oref_from(m, LN, HN), oref_from(m, conn[1], TN)};
  int32_t f2[3] = {oref_from(m, conn[0], H), oref_from(m, dg, HN), oref_from(m, L, T)};
  double a[3], b[3], n[3];
  v3_sub(a, m->x[HN], m->x[T]);
  v3_sub(b, m->x[TN], m->x[T]);
  v3_cross(n, a, b);
  int toward_d = v3_dot(n, toD) > 0; /* the normal points out of the front body */
  for (int k = 0; k < 2; k++) {
    tds_id g = tds_mesh_add_facet(m, k ? f2 : f1);
    tds_facet_inherit(m, g, src);
    m->fflags[g] = fl0;
    m->fb[g][0] = toward_d ? F : D;
    m->fb[g][1] = toward_d ? D : F;
  }
  tds_motion_enforce(s, H);
  tds_motion_enforce(s, T);
  tds_motion_enforce(s, HN);
  tds_motion_enforce(s, TN);
  m->coord_gen++;
  m->topo_gen++;
  return 1;
}

int tds_pop_quad_to_quad(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  if (n) *n = 0;
  if (s->m.torus) return tds_torus_unsupported(ctx, "pop_quad_to_quad");
  if (s->str) return tds_seterr(ctx, TDS_ETOPO, "pop_quad_to_quad: not in the string model (it works on films)");
  quad *q = tds_malloc(&s->m.alloc, sizeof *q);
  if (!q) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  tds_snap all;
  int rc = tds_snap_take(ctx, s, &all);
  if (rc != TDS_OK) {
    tds_free(&s->m.alloc, q);
    return rc;
  }
  int32_t cnt = 0, said = 0, nslot = s->m.nf;
  char buf[200];
  for (tds_id f = 0; f < nslot && rc == TDS_OK; f++) {
    if ((sel && !sel[f]) || !tds_alive(s->m.fflags, f)) continue;
    const char *why = find_quad(s, f, q, buf, sizeof buf);
    if (why) {
      if (*why && sel && said++ < 10) tds_printf(ctx, "pop_quad_to_quad fails on facet %d: %s\n", f + 1, why);
      continue;
    }
    tds_snap sn;
    rc = tds_snap_take(ctx, s, &sn);
    if (rc != TDS_OK) break;
    int r = pop_quad(s, q);
    if (r == 1) {
      tds_snap_free(&sn);
      cnt++;
    } else {
      tds_snap_restore(s, &sn);
      if (r == -TDS_ENOMEM) rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      else if (sel && said++ < 10)
        tds_printf(ctx, "pop_quad_to_quad fails on facet %d: the film does not collapse cleanly\n", f + 1);
    }
  }
  if (said > 10) tds_printf(ctx, "pop_quad_to_quad: %d more facets failed\n", said - 10);
  tds_free(&s->m.alloc, q);
  if (rc == TDS_OK) rc = tds_surf_update(ctx, s);
  rc = tds_snap_end(ctx, s, &all, rc);
  if (n) *n = rc == TDS_OK ? cnt : 0;
  return rc;
}
