/* topo_renumber.c: renumber_all, Evolver's compaction of element ids: the
** live elements of each kind get the ids 1, 2, ... in their present order
** (tds keeps deleted elements as dead slots, so after t, w or delete the
** ids have gaps; Evolver's list order is its storage order, which is the
** id order here). Every reference follows (edge ends, facet corners and
** edges, bodies of facets, the edge rings, the facets' originals). */
#include "topo_edit.h"

#include <stdlib.h>

#include "snap.h"

static int renumber(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  (void)sel;
  tds_mesh *m = &s->m;
  if (s->str)
    return tds_seterr(ctx, TDS_ERANGE, "renumber_all: not supported yet in the string model");
  int32_t cnt[TDS_NKINDS] = {m->nv, m->ne, m->nf, m->nb};
  const uint32_t *flags[TDS_NKINDS] = {m->vflags, m->eflags, m->fflags, m->bflags};
  int32_t *map[TDS_NKINDS] = {NULL, NULL, NULL, NULL};
  int32_t live[TDS_NKINDS], moved = 0;
  int rc = TDS_OK;
  for (int k = 0; k < TDS_NKINDS && rc == TDS_OK; k++) {
    map[k] = tds_malloc(&m->alloc, (size_t)(cnt[k] > 0 ? cnt[k] : 1) * sizeof *map[k]);
    if (!map[k]) {
      rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      break;
    }
    live[k] = 0;
    for (tds_id i = 0; i < cnt[k]; i++) {
      map[k][i] = tds_alive(flags[k], i) ? live[k]++ : TDS_NONE;
      moved += map[k][i] != TDS_NONE && map[k][i] != i;
    }
  }
  if (rc != TDS_OK) goto out;
  /* references, while the slots are where they were */
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    for (int j = 0; j < 2; j++) m->ev[e][j] = map[TDS_VERTEX][m->ev[e][j]];
    int32_t sd = m->eside[e];
    if (sd != TDS_NONE) m->eside[e] = 3 * map[TDS_FACET][sd / 3] + sd % 3;
  }
  for (tds_id f = 0; f < m->nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    for (int k = 0; k < 3; k++) {
      m->fv[f][k] = map[TDS_VERTEX][m->fv[f][k]];
      int32_t oe = m->fe[f][k];
      m->fe[f][k] = TDS_OREF(map[TDS_EDGE][TDS_OID(oe)], TDS_OREV(oe));
      int32_t sd = m->side_next[3 * f + k];
      if (sd != TDS_NONE) m->side_next[3 * f + k] = 3 * map[TDS_FACET][sd / 3] + sd % 3;
    }
    for (int j = 0; j < 2; j++)
      if (m->fb[f][j] != TDS_NONE) m->fb[f][j] = map[TDS_BODY][m->fb[f][j]];
    if (m->forig[f] != TDS_NONE)
      m->forig[f] = m->forig[f] < m->nf ? map[TDS_FACET][m->forig[f]] : TDS_NONE;
  }
  for (int k = 0; k < TDS_NKINDS; k++) {
    for (tds_id i = 0; i < cnt[k]; i++)
      if (map[k][i] != TDS_NONE) tds_mesh_move_slot(m, k, map[k][i], i);
    tds_mesh_truncate(m, k, live[k]);
  }
  /* per-vertex histories are by slot: start them again */
  s->cg_norm2 = 0;
  s->cg_nv = -1;
  s->stall_facet = 0;
  m->coord_gen++;
  *n = moved;
  rc = tds_surf_update(ctx, s);
out:
  for (int k = 0; k < TDS_NKINDS; k++) tds_free(&m->alloc, map[k]);
  return rc;
}

int tds_renumber_all(tds_ctx *ctx, tds_surf *s, int32_t *n) {
  return tds_snap_run(ctx, s, renumber, NULL, n);
}

/* vertex_merge: v2 joins v1 (see topo_edit.h). */
typedef struct merge_args {
  tds_id v1, v2;
} merge_args;

static int merge(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  const merge_args *a = (const merge_args *)(const void *)sel;
  tds_mesh *m = &s->m;
  tds_id v1 = a->v1, v2 = a->v2;
  if (tds_mesh_adjacency(m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (int32_t i = m->ve_start[v2]; i < m->ve_start[v2 + 1]; i++) {
    tds_id e = TDS_OID(m->ve[i]);
    tds_id w = m->ev[e][0] == v2 ? m->ev[e][1] : m->ev[e][0];
    if (w == v1)
      return tds_seterr(ctx, TDS_ETOPO, "vertex_merge: vertices %d and %d are joined by edge %d",
                        v1 + 1, v2 + 1, e + 1);
    for (int32_t j = m->ve_start[v1]; j < m->ve_start[v1 + 1]; j++) {
      tds_id g = TDS_OID(m->ve[j]);
      if (m->ev[g][0] == w || m->ev[g][1] == w)
        return tds_seterr(ctx, TDS_ETOPO, "vertex_merge: vertices %d and %d both have an edge "
                          "to vertex %d (edges %d and %d would run side by side)",
                          v1 + 1, v2 + 1, w + 1, g + 1, e + 1);
    }
  }
  for (int32_t i = m->ve_start[v2]; i < m->ve_start[v2 + 1]; i++) {
    tds_id e = TDS_OID(m->ve[i]);
    for (int j = 0; j < 2; j++)
      if (m->ev[e][j] == v2) m->ev[e][j] = v1;
  }
  for (int32_t i = m->vf_start[v2]; i < m->vf_start[v2 + 1]; i++) {
    tds_id f = m->vf[i];
    for (int k = 0; k < 3; k++)
      if (m->fv[f][k] == v2) m->fv[f][k] = v1;
  }
  tds_mesh_kill(m, TDS_VERTEX, v2);
  m->topo_gen++;
  *n = 1;
  return tds_surf_update(ctx, s);
}

int tds_vertex_merge(tds_ctx *ctx, tds_surf *s, tds_id v1, tds_id v2) {
  const tds_mesh *m = &s->m;
  if (v1 < 0 || v1 >= m->nv || !tds_alive(m->vflags, v1) || v2 < 0 || v2 >= m->nv ||
      !tds_alive(m->vflags, v2))
    return tds_seterr(ctx, TDS_ERANGE, "vertex_merge: vertex %d does not exist",
                      (v1 < 0 || v1 >= m->nv || !tds_alive(m->vflags, v1) ? v1 : v2) + 1);
  if (v1 == v2) return tds_seterr(ctx, TDS_ERANGE, "vertex_merge: a vertex cannot merge with itself (%d)", v1 + 1);
  if (s->str) return tds_seterr(ctx, TDS_ERANGE, "vertex_merge: not supported yet in the string model");
  merge_args a = {v1, v2};
  int32_t n = 0;
  return tds_snap_run(ctx, s, merge, (const uint8_t *)(const void *)&a, &n);
}

/* rebody (see topo_edit.h). */
static int froot(int32_t *p, int32_t i) {
  while (p[i] != i) i = p[i] = p[p[i]];
  return i;
}

static int rebody(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  (void)sel;
  tds_mesh *m = &s->m;
  int32_t nb0 = m->nb, nf = m->nf, made = 0;
  int32_t *par = tds_malloc(&m->alloc, (size_t)(nf > 0 ? nf : 1) * sizeof *par);
  tds_id *nbody = tds_malloc(&m->alloc, (size_t)(nf > 0 ? nf : 1) * sizeof *nbody);
  if (!par || !nbody) {
    tds_free(&m->alloc, par);
    tds_free(&m->alloc, nbody);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int rc = TDS_OK;
  uint8_t *fixed = tds_calloc(&m->alloc, (size_t)(nb0 > 0 ? nb0 : 1), 1);
  if (!fixed) rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (tds_id b = 0; b < nb0 && rc == TDS_OK; b++) {
    if (!tds_alive(m->bflags, b)) continue;
    for (tds_id f = 0; f < nf; f++) par[f] = f;
    /* facets of b that share an edge are in one piece */
    for (tds_id e = 0; e < m->ne; e++) {
      if (!tds_alive(m->eflags, e) || m->eside[e] == TDS_NONE) continue;
      int32_t h = m->eside[e], sd = h, first = -1;
      do {
        tds_id f = sd / 3;
        if (m->fb[f][0] == b || m->fb[f][1] == b) {
          if (first < 0) first = f;
          else {
            int32_t x = froot(par, f), y = froot(par, first);
            if (x != y) par[x < y ? y : x] = x < y ? x : y; /* lowest facet is the root */
          }
        }
        sd = m->side_next[sd];
      } while (sd != h);
    }
    tds_id keep = TDS_NONE;
    for (tds_id f = 0; f < nf; f++) nbody[f] = TDS_NONE;
    for (tds_id f = 0; f < nf && rc == TDS_OK; f++) {
      if (!tds_alive(m->fflags, f) || (m->fb[f][0] != b && m->fb[f][1] != b)) continue;
      int32_t r = froot(par, f);
      if (keep == TDS_NONE) keep = r;
      if (r == keep || nbody[r] != TDS_NONE) continue;
      if (tds_mesh_room(m, TDS_BODY, m->nb + 1) != TDS_OK) {
        rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
        break;
      }
      tds_id nb = tds_mesh_add_body(m);
      tds_mesh_move_slot(m, TDS_BODY, nb, b); /* a copy: the same attributes */
      nbody[r] = nb;
      made++;
    }
    if (rc != TDS_OK) break;
    for (tds_id f = 0; f < nf; f++) {
      if (!tds_alive(m->fflags, f) || (m->fb[f][0] != b && m->fb[f][1] != b)) continue;
      tds_id nb = nbody[froot(par, f)];
      if (nb == TDS_NONE) continue;
      for (int j = 0; j < 2; j++)
        if (m->fb[f][j] == b) m->fb[f][j] = nb;
    }
    fixed[b] = (m->bflags[b] & TDS_TARGET) && keep != TDS_NONE;
  }
  tds_free(&m->alloc, par);
  tds_free(&m->alloc, nbody);
  if (rc == TDS_OK) {
    m->topo_gen++;
    rc = tds_surf_update(ctx, s);
  }
  /* pieces of a body with a target volume: each its actual volume */
  if (rc == TDS_OK && made) {
    for (tds_id b = 0; b < m->nb; b++) {
      int was = b < nb0 ? fixed[b] : (m->bflags[b] & TDS_TARGET) != 0;
      if (was && tds_alive(m->bflags, b)) m->btarget[b] = m->bvol[b];
    }
    rc = tds_surf_update(ctx, s);
  }
  tds_free(&m->alloc, fixed);
  *n = made;
  return rc;
}

int tds_rebody(tds_ctx *ctx, tds_surf *s, int32_t *n) {
  return tds_snap_run(ctx, s, rebody, NULL, n);
}
