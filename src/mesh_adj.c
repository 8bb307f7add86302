/* mesh_adj.c: derived adjacency (vertex stars), rebuilt by counting sort. */
#include "mesh.h"

#include <stdlib.h>
#include <string.h>

/* Resize a derived int array to exactly n entries. */
static int resize(const tds_alloc *a, int32_t **p, int32_t *cap, int32_t n) {
  if (n <= *cap && n >= *cap / 2) return TDS_OK;
  int32_t *q = tds_realloc(a, *p, (size_t)(n > 0 ? n : 1) * sizeof **p);
  if (!q) return TDS_ENOMEM;
  *p = q;
  *cap = n;
  return TDS_OK;
}

int tds_mesh_adjacency(tds_mesh *m) {
  if (m->adj_gen == m->topo_gen) return TDS_OK;
  int32_t nv = m->nv, nfs = 0, nes = 0;
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f)) nfs += 3;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) nes += 2;
  const tds_alloc *a = &m->alloc;
  if (resize(a, &m->vf_start, &m->adj_cap[0], nv + 1) ||
      resize(a, &m->ve_start, &m->adj_cap[1], nv + 1) ||
      resize(a, &m->vf, &m->adj_cap[2], nfs) || resize(a, &m->ve, &m->adj_cap[3], nes))
    return TDS_ENOMEM;

  int32_t *fs = m->vf_start, *es = m->ve_start;
  memset(fs, 0, sizeof *fs * (size_t)(nv + 1));
  memset(es, 0, sizeof *es * (size_t)(nv + 1));
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f))
      for (int k = 0; k < 3; k++) fs[m->fv[f][k] + 1]++;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) {
      es[m->ev[e][0] + 1]++;
      es[m->ev[e][1] + 1]++;
    }
  for (int32_t v = 0; v < nv; v++) {
    fs[v + 1] += fs[v];
    es[v + 1] += es[v];
  }
  /* Fill using the start arrays shifted down by one as cursors. */
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f))
      for (int k = 0; k < 3; k++) m->vf[fs[m->fv[f][k]]++] = f;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) {
      m->ve[es[m->ev[e][0]]++] = TDS_OREF(e, 0);
      m->ve[es[m->ev[e][1]]++] = TDS_OREF(e, 1);
    }
  for (int32_t v = nv; v > 0; v--) {
    fs[v] = fs[v - 1];
    es[v] = es[v - 1];
  }
  fs[0] = es[0] = 0;
  m->adj_gen = m->topo_gen;
  return TDS_OK;
}

tds_id tds_vertex_min_edge(const tds_mesh *m, tds_id v) {
  tds_id emin = INT32_MAX;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++)
    if (TDS_OID(m->ve[i]) < emin) emin = TDS_OID(m->ve[i]);
  return emin;
}
