/* torus_local.c: a neighbourhood of the torus unwrapped into one frame
** (contracts in torus.h). */
#include "torus.h"

#include <string.h>

#include "gather.h"
#include "symgroup.h"

/* Translate vertex v by the lattice vector of w (w's counts added to its
** edges' wraps so that the surface is the same), as wrap_vertex does. */
static void shift(tds_mesh *m, tds_id v, int32_t w) {
  int32_t nw = tds_wrap_neg(w);
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    if (m->ev[e][0] == v) m->ewrap[e] = tds_wrap_add(m->ewrap[e], w);
    if (m->ev[e][1] == v) m->ewrap[e] = tds_wrap_add(m->ewrap[e], nw);
  }
}

/* The vertex's slot in L, or -1. */
static int find(const tds_torus_local *L, tds_id v) {
  for (int i = 0; i < L->n; i++)
    if (L->v[i] == v) return i;
  return -1;
}

/* Record v with offset w; 0, or -1 when v has another offset already (the
** neighbourhood wraps round the torus) or L is full. */
static int put(tds_torus_local *L, tds_id v, int32_t w) {
  int i = find(L, v);
  if (i >= 0) return L->w[i] == w ? 0 : -1;
  if (L->n == TDS_TORUS_LOCAL_MAX) return -1;
  L->v[L->n] = v;
  L->w[L->n] = w;
  L->n++;
  return 0;
}

int tds_torus_local_begin(tds_mesh *m, const tds_id *seed, int nseed, tds_torus_local *L) {
  L->n = 0;
  L->nmoved = 0;
  if (!m->torus || !m->ewrap) return 0;
  if (tds_mesh_rotates(m)) return -1;
  if (tds_mesh_adjacency(m) != TDS_OK) return -1;
  uint8_t done[TDS_TORUS_LOCAL_MAX];
  memset(done, 0, sizeof done);
  if (put(L, seed[0], 0)) return -1;
  /* expand the seeds as they get their offsets: every edge at a seed gives
  ** its other end's (the star's vertices are all such ends) */
  for (int pass = 0, more = 1; more; pass++) {
    more = 0;
    for (int i = 0; i < L->n; i++) {
      tds_id u = L->v[i];
      int is_seed = 0;
      for (int j = 0; j < nseed; j++) is_seed |= seed[j] == u;
      if (!is_seed || done[i]) continue;
      done[i] = 1;
      more = 1;
      for (int32_t k = m->ve_start[u]; k < m->ve_start[u + 1]; k++) {
        int32_t oe = m->ve[k];
        tds_id e = TDS_OID(oe), x = m->ev[e][0] == u ? m->ev[e][1] : m->ev[e][0];
        if (m->ev[e][0] == m->ev[e][1]) return -1; /* a loop round the torus */
        int32_t w = m->ev[e][0] == u ? tds_wrap_add(L->w[i], m->ewrap[e])
                                     : tds_wrap_add(L->w[i], tds_wrap_neg(m->ewrap[e]));
        if (put(L, x, w)) return -1;
      }
    }
  }
  for (int j = 0; j < nseed; j++)
    if (find(L, seed[j]) < 0) return -1; /* not joined to the first */
  for (int i = 0; i < L->n; i++) {
    if (!L->w[i]) continue;
    memcpy(L->x0[i], m->x[L->v[i]], sizeof L->x0[i]);
  }
  for (int i = 0; i < L->n; i++) {
    if (!L->w[i]) continue;
    double d[3];
    tds_wrap_vec(m->period, L->w[i], d);
    shift(m, L->v[i], L->w[i]);
    for (int c = 0; c < 3; c++) m->x[L->v[i]][c] += d[c];
    L->nmoved++;
  }
  return 0;
}

void tds_torus_local_end(tds_mesh *m, tds_torus_local *L) {
  for (int i = 0; i < L->n; i++) {
    tds_id v = L->v[i];
    if (!L->w[i] || !tds_alive(m->vflags, v)) continue;
    int32_t back = tds_wrap_neg(L->w[i]);
    double d[3];
    tds_wrap_vec(m->period, L->w[i], d);
    shift(m, v, back);
    /* bitwise the stored place again when the operation left v alone */
    int same = 1;
    for (int c = 0; c < 3; c++) same &= m->x[v][c] == L->x0[i][c] + d[c];
    for (int c = 0; c < 3; c++) m->x[v][c] = same ? L->x0[i][c] : m->x[v][c] - d[c];
  }
  L->n = 0;
  L->nmoved = 0;
}

int tds_torus_pop_refused(tds_ctx *ctx, const tds_mesh *m, const char *cmd, tds_id e) {
  if (tds_mesh_rotates(m))
    return tds_seterr(ctx, TDS_ESYNTAX, "%s: edge %d: popping an edge is not supported yet "
                      "with SYMMETRY_GROUP \"%s\"", cmd, e + 1, tds_sym_name(m->sym));
  return tds_seterr(ctx, TDS_ERANGE, "%s: edge %d: its neighbourhood wraps round the torus "
                    "(a vertex at two places); refine first", cmd, e + 1);
}
