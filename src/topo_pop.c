/* topo_pop.c: o / pop on vertices: a vertex where separate cones of
** facets meet (a pinched neck after t) is split into one vertex per cone. */
#include "torus.h"
#include "topo_edit.h"

#include <stdlib.h>
#include <string.h>

#include "gather.h"
#include "snap.h"
#include "symgroup.h"

/* Union-find root with path halving. */
static int root(int *p, int i) {
  while (p[i] != i) i = p[i] = p[p[i]];
  return i;
}

/* Classify the star of v: the number of cones (sets of facets joined
** through edges at v) in *ncone, per-facet cone labels in lab (facets in
** fl), and whether the star is a minimal cone when it is one piece: all
** edges at v of valence 2 (a plane), two of valence 3 (a triple line) or
** four of valence 3 (a tetrahedral point). Returns the facet count, or -1
** when v is not an interior vertex of the surface (an edge at v has fewer
** than two facets). */
static int star(const tds_mesh *m, tds_id v, tds_id *fl, int *lab, int *ncone,
                int *minimal) {
  int nf = 0;
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) fl[nf++] = m->vf[i];
  for (int i = 0; i < nf; i++) lab[i] = i;
  int n2 = 0, n3 = 0, nother = 0;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++) {
    tds_id e = TDS_OID(m->ve[i]);
    int val = tds_edge_valence(m, e);
    if (val < 2) return -1;
    n2 += val == 2;
    n3 += val == 3;
    nother += val > 3;
    /* join the facets on e */
    int first = -1;
    int32_t h = m->eside[e], sd = h;
    do {
      tds_id f = sd / 3;
      for (int j = 0; j < nf; j++)
        if (fl[j] == f) {
          if (first < 0) first = j;
          else lab[root(lab, j)] = root(lab, first);
        }
      sd = m->side_next[sd];
    } while (sd != h);
  }
  int nc = 0;
  for (int i = 0; i < nf; i++) {
    lab[i] = root(lab, i);
    nc += lab[i] == i;
  }
  *ncone = nc;
  *minimal = nother == 0 && (n3 == 0 || n3 == 2 || n3 == 4);
  return nf;
}

/* A pop that builds new geometry at v where its neighbourhood cannot be
** unwrapped into one frame (torus.h). */
static int local_refused(tds_ctx *ctx, const tds_mesh *m, tds_id v) {
  if (tds_mesh_rotates(m))
    return tds_seterr(ctx, TDS_ESYNTAX, "pop: vertex %d: popping a cone is not supported yet "
                      "with SYMMETRY_GROUP \"%s\"", v + 1, tds_sym_name(m->sym));
  return tds_seterr(ctx, TDS_ERANGE, "pop: vertex %d: its neighbourhood wraps round the torus "
                    "(a neighbour at two places); refine first", v + 1);
}

static int pop(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *npop) {
  tds_mesh *m = &s->m;
  if (tds_mesh_adjacency(m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  int32_t nv0 = m->nv, cnt = 0, maxf = 0;
  for (tds_id v = 0; v < nv0; v++) {
    int32_t k = m->vf_start[v + 1] - m->vf_start[v];
    if (k > maxf) maxf = k;
  }
  tds_id *fl = tds_malloc(&m->alloc, (size_t)(maxf + 1) * sizeof *fl);
  int *lab = tds_malloc(&m->alloc, (size_t)(maxf + 1) * sizeof *lab);
  tds_id *copy = tds_malloc(&m->alloc, (size_t)(maxf + 1) * sizeof *copy);
  if (!fl || !lab || !copy) {
    tds_free(&m->alloc, fl);
    tds_free(&m->alloc, lab);
    tds_free(&m->alloc, copy);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int rc = TDS_OK;
  tds_cmask gl = tds_surf_global_cons(s);
  /* Splitting v changes only v's own star, so the stars of the vertices
  ** after it, built once above, stay valid; a sphere pop (tds_pop_cone)
  ** changes its neighbours' stars: the adjacency is rebuilt after one. */
  for (tds_id v = 0; v < nv0 && rc == TDS_OK; v++) {
    if (!tds_alive(m->vflags, v) || (sel && !sel[v])) continue;
    if ((m->vflags[v] & TDS_FIXED) || (m->vcon[v] & ~gl) || m->vbdry[v] != TDS_NONE) continue;
    int32_t kf = m->vf_start[v + 1] - m->vf_start[v];
    if (kf > maxf) { /* grown by a sphere pop */
      tds_id *f2 = tds_realloc(&m->alloc, fl, (size_t)(kf + 1) * sizeof *fl);
      if (f2) fl = f2;
      int *l2 = tds_realloc(&m->alloc, lab, (size_t)(kf + 1) * sizeof *lab);
      if (l2) lab = l2;
      tds_id *c2 = tds_realloc(&m->alloc, copy, (size_t)(kf + 1) * sizeof *copy);
      if (c2) copy = c2;
      if (!f2 || !l2 || !c2) {
        rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory while popping");
        break;
      }
      maxf = kf;
    }
    int nc = 0, minimal = 0;
    int nf = star(m, v, fl, lab, &nc, &minimal);
    if (nf <= 0) continue;
    if (nc == 1) {
      if (!minimal) {
        int done = 0;
        tds_torus_local L;
        if (tds_torus_local_begin(m, &v, 1, &L)) {
          rc = local_refused(ctx, m, v);
          break;
        }
        { /* the cone over a prism: Evolver's toggles, or its own choice */
          int r = tds_pop_prism(s, v, s->pop_to_face ? 1 : s->pop_to_edge ? 0 : -1);
          if (r < 0) {
            tds_torus_local_end(m, &L);
            rc = tds_seterr(ctx, -r, "out of memory while popping vertex %d", v + 1);
            break;
          }
          done = r;
        }
        if (!done) rc = tds_pop_cone(s, v, &done);
        tds_torus_local_end(m, &L);
        if (rc != TDS_OK) {
          rc = tds_seterr(ctx, rc, "out of memory while popping vertex %d", v + 1);
          break;
        }
        if (!done) {
          rc = tds_seterr(ctx, TDS_ERANGE, "not supported yet for vertex %d, a "
                          "non-minimal cone whose regions do not form simple cells",
                          v + 1);
          break;
        }
        cnt++;
        if (tds_mesh_adjacency(m) != TDS_OK) {
          rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory while popping");
          break;
        }
      }
      continue;
    }
    if (nc == 2 && s->pop_enjoin) { /* Evolver's pop_enjoin: a neck */
      int done = 0;
      tds_torus_local L;
      if (tds_torus_local_begin(m, &v, 1, &L)) {
        rc = local_refused(ctx, m, v);
        break;
      }
      rc = tds_pop_neck(s, v, fl, lab, nf, &done);
      tds_torus_local_end(m, &L);
      if (rc != TDS_OK) {
        rc = tds_seterr(ctx, rc, "out of memory while popping vertex %d", v + 1);
        break;
      }
      if (done) {
        cnt++;
        if (tds_mesh_adjacency(m) != TDS_OK) {
          rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory while popping");
          break;
        }
        continue;
      }
      tds_warnf(ctx, "pop_enjoin: vertex %d: its two cones do not pair up edge for edge; split instead\n", v + 1);
    }
    if (tds_mesh_room(m, TDS_VERTEX, m->nv + nc) != TDS_OK) {
      rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory while popping");
      break;
    }
    /* The cone of the first facet keeps v; each other cone gets a copy. */
    for (int i = 0; i < nf; i++) copy[i] = TDS_NONE;
    for (int i = 0; i < nf; i++) {
      int r = lab[i];
      if (r == lab[0] || copy[r] != TDS_NONE) continue;
      tds_id w = tds_mesh_add_vertex(m, m->x[v]);
      m->vflags[w] = m->vflags[v];
      m->vcon[w] = m->vcon[v];
      m->vbdry[w] = m->vbdry[v];
      m->vp[w][0] = m->vp[v][0];
      m->vp[w][1] = m->vp[v][1];
      copy[r] = w;
    }
    for (int i = 0; i < nf; i++) {
      tds_id w = copy[lab[i]], f = fl[i];
      if (w == TDS_NONE) continue;
      for (int k = 0; k < 3; k++) {
        if (m->fv[f][k] == v) m->fv[f][k] = w;
        tds_id e = TDS_OID(m->fe[f][k]);
        for (int j = 0; j < 2; j++)
          if (m->ev[e][j] == v) m->ev[e][j] = w;
      }
    }
    m->topo_gen++;
    cnt++;
  }
  tds_free(&m->alloc, fl);
  tds_free(&m->alloc, lab);
  tds_free(&m->alloc, copy);
  if (rc != TDS_OK) return rc;
  *npop = cnt;
  return tds_surf_update(ctx, s);
}

int tds_pop_vertices(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n) {
  return tds_snap_run(ctx, s, pop, sel, n);
}

int tds_pop_raw(tds_ctx *ctx, tds_surf *s, int32_t *nedges, int32_t *nverts) {
  *nedges = *nverts = 0;
  int32_t ne0 = s->m.ne, ne = 0, nv = 0;
  int rc = TDS_OK;
  for (tds_id e = 0; e < ne0 && rc == TDS_OK; e++) {
    int32_t k = 0;
    rc = tds_pop_one_edge(s, e, &k);
    if (rc == TDS_ENOMEM) rc = tds_seterr(ctx, rc, "out of memory while popping edges");
    else if (rc == TDS_ERANGE) rc = tds_torus_pop_refused(ctx, &s->m, "o", e);
    else if (rc != TDS_OK) rc = tds_seterr(ctx, rc, "o: edge %d: the chain changed while popping", e + 1);
    ne += k;
  }
  if (rc == TDS_OK) rc = pop(ctx, s, NULL, &nv);
  if (rc == TDS_OK) {
    *nedges = ne;
    *nverts = nv;
  }
  return rc;
}

int tds_pop(tds_ctx *ctx, tds_surf *s, int32_t *nedges, int32_t *nverts) {
  *nedges = *nverts = 0;
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  int32_t ne = 0, nv = 0;
  rc = tds_snap_end(ctx, s, &sn, tds_pop_raw(ctx, s, &ne, &nv));
  if (rc == TDS_OK) {
    *nedges = ne;
    *nverts = nv;
  }
  return rc;
}
