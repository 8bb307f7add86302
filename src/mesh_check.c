/* mesh_check.c: validate every invariant of the element store.
** Walks the raw arrays (not iterators) so a broken mesh is still readable.
** Messages use 1-based ids, as users see them. */
#include "torus.h"
#include "mesh.h"

#include <math.h>
#include <stdlib.h>

#define FAIL(...) return tds_seterr(ctx, TDS_ETOPO, "mesh check: " __VA_ARGS__)

static int live_vertex(const tds_mesh *m, tds_id v) {
  return v >= 0 && v < m->nv && tds_alive(m->vflags, v);
}

static int check_facets(tds_ctx *ctx, const tds_mesh *m) {
  for (tds_id f = 0; f < m->nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    for (int k = 0; k < 3; k++) {
      int32_t oe = m->fe[f][k];
      tds_id e = TDS_OID(oe);
      if (oe < 0 || e >= m->ne || !tds_alive(m->eflags, e))
        FAIL("facet %d: side %d refers to a missing edge", f + 1, k + 1);
      if (m->fv[f][k] != tds_oe_tail(m, oe))
        FAIL("facet %d: vertex %d is not the tail of edge %s%d", f + 1, k + 1,
             TDS_OREV(oe) ? "-" : "", e + 1);
    }
    if (!tds_mesh_edges_chain(m, m->fe[f]))
      FAIL("facet %d: edges do not form a closed loop", f + 1);
    tds_id a = m->fv[f][0], b = m->fv[f][1], c = m->fv[f][2];
    if (a == b || b == c || c == a)
      FAIL("facet %d: repeated vertex", f + 1);
    for (int j = 0; j < 2; j++) {
      tds_id bd = m->fb[f][j];
      if (bd != TDS_NONE && (bd < 0 || bd >= m->nb || !tds_alive(m->bflags, bd)))
        FAIL("facet %d: %s body does not exist", f + 1, j ? "back" : "front");
    }
  }
  return TDS_OK;
}

static int check_rings(tds_ctx *ctx, const tds_mesh *m) {
  int64_t sides = 0, ringed = 0;
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f)) sides += 3;
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    int32_t h = m->eside[e];
    if (h == TDS_NONE) continue;
    int32_t s = h;
    int64_t steps = 0;
    do {
      if (s < 0 || s >= 3 * m->nf || !tds_alive(m->fflags, s / 3))
        FAIL("edge %d: ring reaches a missing facet side", e + 1);
      if (TDS_OID(m->fe[s / 3][s % 3]) != e)
        FAIL("edge %d: ring holds side %d of facet %d, which is on edge %d",
             e + 1, s % 3 + 1, s / 3 + 1, TDS_OID(m->fe[s / 3][s % 3]) + 1);
      if (++steps > sides) FAIL("edge %d: ring does not close", e + 1);
      s = m->side_next[s];
    } while (s != h);
    ringed += steps;
  }
  if (ringed != sides)
    FAIL("%lld facet sides, but the edge rings hold %lld", (long long)sides,
         (long long)ringed);
  return TDS_OK;
}

/* Has `key` been seen in the list of vertex v already? With a mark array
** (mark[key] holds the last vertex + 1 that listed it) in O(1), else by
** scanning the entries list[lo..i-1]. */
static int seen_before(int32_t *mark, const int32_t *list, int32_t lo,
                       int32_t i, int32_t key, tds_id v) {
  if (mark) {
    if (mark[key] == v + 1) return 1;
    mark[key] = v + 1;
    return 0;
  }
  for (int32_t j = lo; j < i; j++)
    if (list[j] == key) return 1;
  return 0;
}

/* The derived stars, if current, must be exactly the incidences of the
** primary arrays. Each vertex's lists are checked to hold only live
** elements incident to it, each at most once; with the totals equal to
** 3 per live facet and 2 per live edge, every list is then complete. */
static int check_stars(tds_ctx *ctx, const tds_mesh *m, int32_t *fmark,
                       int32_t *emark) {
  int64_t nfs = 0, nes = 0;
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f)) nfs += 3;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) nes += 2;
  for (tds_id v = 0; v < m->nv; v++) {
    int32_t f0 = m->vf_start[v], f1 = m->vf_start[v + 1];
    int32_t e0 = m->ve_start[v], e1 = m->ve_start[v + 1];
    if (f0 < 0 || f1 < f0 || f1 > m->adj_cap[2] || e0 < 0 || e1 < e0 ||
        e1 > m->adj_cap[3])
      FAIL("vertex %d: star ranges are out of order", v + 1);
    for (int32_t i = f0; i < f1; i++) {
      tds_id f = m->vf[i];
      if (f < 0 || f >= m->nf || !tds_alive(m->fflags, f))
        FAIL("vertex %d: star lists facet %d, which does not exist", v + 1,
             f + 1);
      if (m->fv[f][0] != v && m->fv[f][1] != v && m->fv[f][2] != v)
        FAIL("vertex %d: star lists facet %d, which does not contain it",
             v + 1, f + 1);
      if (seen_before(fmark, m->vf, f0, i, f, v))
        FAIL("vertex %d: star lists facet %d twice", v + 1, f + 1);
    }
    for (int32_t i = e0; i < e1; i++) {
      int32_t oe = m->ve[i];
      tds_id e = TDS_OID(oe);
      if (oe < 0 || e >= m->ne || !tds_alive(m->eflags, e))
        FAIL("vertex %d: star lists edge %d, which does not exist", v + 1,
             e + 1);
      if (tds_oe_tail(m, oe) != v)
        FAIL("vertex %d: star lists an edge that does not leave it", v + 1);
      if (seen_before(emark, m->ve, e0, i, oe, v))
        FAIL("vertex %d: star lists edge %s%d twice", v + 1,
             TDS_OREV(oe) ? "-" : "", e + 1);
    }
  }
  if (m->nv > 0 && m->vf_start[m->nv] != nfs)
    FAIL("vertex stars hold %d facet corners, expected %lld",
         m->vf_start[m->nv], (long long)nfs);
  if (m->nv > 0 && m->ve_start[m->nv] != nes)
    FAIL("vertex stars hold %d edge ends, expected %lld", m->ve_start[m->nv],
         (long long)nes);
  return TDS_OK;
}

static int check_adjacency(tds_ctx *ctx, const tds_mesh *m) {
  if (m->adj_gen != m->topo_gen) return TDS_OK;
  /* Mark arrays make the duplicate test linear; without memory it falls
  ** back to scanning each star. */
  int32_t *fmark = tds_calloc(&m->alloc, (size_t)m->nf + 1, sizeof *fmark);
  int32_t *emark = tds_calloc(&m->alloc, 2 * (size_t)m->ne + 2, sizeof *emark);
  if (!fmark || !emark) {
    tds_free(&m->alloc, fmark);
    tds_free(&m->alloc, emark);
    fmark = emark = NULL;
  }
  int rc = check_stars(ctx, m, fmark, emark);
  tds_free(&m->alloc, fmark);
  tds_free(&m->alloc, emark);
  return rc;
}

int tds_mesh_check(tds_ctx *ctx, tds_mesh *m) {
  if (m->nv > m->capv || m->ne > m->cape || m->nf > m->capf || m->nb > m->capb)
    FAIL("slot count exceeds capacity");
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_alive(m->vflags, v)) continue;
    for (int i = 0; i < 3; i++)
      if (!isfinite(m->x[v][i])) FAIL("vertex %d: coordinate is not finite", v + 1);
  }
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    if (!live_vertex(m, m->ev[e][0]) || !live_vertex(m, m->ev[e][1]))
      FAIL("edge %d: endpoint does not exist", e + 1);
    if (m->ev[e][0] == m->ev[e][1]) FAIL("edge %d: both ends are one vertex", e + 1);
  }
  int rc = check_facets(ctx, m);
  if (rc == TDS_OK) rc = check_rings(ctx, m);
  if (rc == TDS_OK) rc = check_adjacency(ctx, m);
  if (rc == TDS_OK && m->torus) rc = tds_torus_check(ctx, m); /* facets close */
  return rc;
}
