/* torus_detorus.c: detorus and rewrap (contracts in torus.h). */
#include "torus.h"

#include <math.h>
#include <string.h>

#include "gather.h"
#include "topo.h"

/* Copies of an element at a lattice translation: (key, wrap) -> id, open
** addressing. */
typedef struct copies {
  int32_t *key, *wrap, *id;
  uint32_t mask;
} copies;

static int copies_init(tds_alloc *a, copies *c, size_t n) {
  size_t cap = 16;
  while (cap < 2 * n) cap *= 2;
  c->mask = (uint32_t)cap - 1;
  c->key = tds_malloc(a, cap * sizeof *c->key);
  c->wrap = tds_malloc(a, cap * sizeof *c->wrap);
  c->id = tds_malloc(a, cap * sizeof *c->id);
  if (!c->key || !c->wrap || !c->id) return TDS_ENOMEM;
  for (size_t i = 0; i < cap; i++) c->key[i] = -1;
  return TDS_OK;
}

static void copies_free(tds_alloc *a, copies *c) {
  tds_free(a, c->key);
  tds_free(a, c->wrap);
  tds_free(a, c->id);
}

/* The slot of (k, w): found (c->key[slot] == k) or empty. */
static uint32_t slot(const copies *c, int32_t k, int32_t w) {
  uint32_t h = ((uint32_t)k * 2654435761u) ^ ((uint32_t)w * 40503u);
  for (h &= c->mask;; h = (h + 1) & c->mask)
    if (c->key[h] == -1 || (c->key[h] == k && c->wrap[h] == w)) return h;
}

/* Vertex v translated by w: v itself for w = 0, else its copy there. */
static tds_id vcopy(tds_mesh *m, copies *c, tds_id v, int32_t w) {
  if (!w) return v;
  uint32_t h = slot(c, v, w);
  if (c->key[h] == v) return c->id[h];
  double x[3];
  tds_wrap_point(m, m->x[v], w, x);
  tds_id n = tds_mesh_add_vertex(m, tds_wrap_point(m, m->x[v], w, x));
  m->vflags[n] = m->vflags[v];
  m->vcon[n] = m->vcon[v];
  m->vbdry[n] = m->vbdry[v];
  m->vp[n][0] = m->vp[v][0];
  m->vp[n][1] = m->vp[v][1];
  tds_mesh_inherit(m, TDS_VERTEX, n, v);
  c->key[h] = v;
  c->wrap[h] = w;
  c->id[h] = n;
  return n;
}

int tds_torus_detorus(tds_ctx *ctx, tds_mesh *m) {
  if (!m->torus) return TDS_OK;
  int32_t nv = m->nv, ne = m->ne, nf = m->nf;
  tds_alloc *a = &m->alloc;
  copies cv = {0}, ce = {0};
  int32_t *newfe = tds_malloc(a, (size_t)(3 * (nf > 0 ? nf : 1)) * sizeof *newfe);
  uint8_t *bare = tds_calloc(a, (size_t)(ne > 0 ? ne : 1), 1);
  uint8_t *used = tds_calloc(a, (size_t)(nv + 3 * nf + ne + 1), 1);
  int rc = newfe && bare && used ? TDS_OK : TDS_ENOMEM;
  if (!rc) rc = copies_init(a, &cv, (size_t)(3 * nf + ne));
  if (!rc) rc = copies_init(a, &ce, (size_t)(3 * nf + ne));
  if (!rc && (tds_mesh_reserve(m, TDS_VERTEX, nv + 3 * nf + ne) ||
              tds_mesh_reserve(m, TDS_EDGE, ne + 3 * nf)))
    rc = TDS_ENOMEM;
  if (rc) {
    tds_free(a, newfe);
    tds_free(a, bare);
    tds_free(a, used);
    copies_free(a, &cv);
    copies_free(a, &ce);
    return tds_seterr(ctx, rc, "out of memory");
  }
  /* every facet as it is drawn from its first corner (raw cells) */
  for (tds_id f = 0; f < nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    for (int k = 0; k < 3; k++) {
      int32_t oe = m->fe[f][k];
      tds_id e = TDS_OID(oe);
      int ct = TDS_OREV(oe) ? (k + 1) % 3 : k; /* corner of e's stored tail */
      int32_t wt = tds_torus_corner_wrap(m, f, ct);
      tds_id ne2 = e;
      if (wt || m->ewrap[e]) {
        uint32_t h = slot(&ce, e, wt);
        if (ce.key[h] == e) {
          ne2 = ce.id[h];
        } else {
          tds_id t = vcopy(m, &cv, m->ev[e][0], wt);
          tds_id hd = vcopy(m, &cv, m->ev[e][1], tds_wrap_mul(m, wt, m->ewrap[e]));
          ne2 = tds_mesh_add_edge(m, t, hd);
          tds_edge_inherit(m, ne2, e);
          ce.key[h] = e;
          ce.wrap[h] = wt;
          ce.id[h] = ne2;
        }
      }
      newfe[3 * f + k] = TDS_OREF(ne2, TDS_OREV(oe));
    }
  }
  for (tds_id e = 0; e < ne; e++) bare[e] = tds_alive(m->eflags, e) && m->eside[e] == TDS_NONE;
  for (tds_id f = 0; f < nf; f++)
    if (tds_alive(m->fflags, f) && memcmp(newfe + 3 * f, m->fe[f], 3 * sizeof *newfe))
      tds_mesh_set_facet(m, f, newfe + 3 * f);
  /* bare edges reach their head's copy; edges no facet uses any more go */
  for (tds_id e = 0; e < ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    if (bare[e]) {
      if (m->ewrap[e]) m->ev[e][1] = vcopy(m, &cv, m->ev[e][1], m->ewrap[e]);
    } else if (m->eside[e] == TDS_NONE) {
      tds_mesh_kill(m, TDS_EDGE, e);
    }
  }
  for (tds_id e = 0; e < m->ne; e++) m->ewrap[e] = 0;
  /* vertices left on no edge (every use moved to a copy) go too */
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) used[m->ev[e][0]] = used[m->ev[e][1]] = 1;
  for (tds_id v = 0; v < nv; v++)
    if (tds_alive(m->vflags, v) && !used[v] && !(m->vflags[v] & TDS_BARE))
      tds_mesh_kill(m, TDS_VERTEX, v);
  tds_free(a, used);
  tds_free(a, newfe);
  tds_free(a, bare);
  copies_free(a, &cv);
  copies_free(a, &ce);
  tds_mesh_set_torus(m, 0);
  m->topo_gen++;
  m->coord_gen++;
  return TDS_OK;
}

void tds_torus_cell_offset(const tds_mesh *m, const double x[3], int k[3]) {
  /* lattice coordinates: x = sum_i c_i period[i], c = x P^-1 */
  const double (*p)[3] = m->period;
  double inv[3][3], det = 0;
  for (int i = 0; i < 3; i++) {
    int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; j++) {
      int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      inv[j][i] = p[i1][j1] * p[i2][j2] - p[i1][j2] * p[i2][j1]; /* cofactor, transposed */
    }
  }
  for (int j = 0; j < 3; j++) det += p[0][j] * inv[j][0];
  for (int i = 0; i < 3; i++) {
    double c = 0;
    for (int j = 0; j < 3; j++) c += x[j] * inv[j][i];
    c /= det;
    k[i] = isfinite(c) && fabs(c) < 1e6 ? -(int)floor(c) : 0;
  }
}

int tds_torus_rewrap(tds_ctx *ctx, tds_surf *s, int32_t *n) {
  tds_mesh *m = &s->m;
  *n = 0;
  if (!m->torus) return tds_seterr(ctx, TDS_ERANGE, "rewrap needs the torus model (TORUS)");
  if (tds_mesh_rotates(m))
    return tds_seterr(ctx, TDS_ESYNTAX, "rewrap is not supported yet with SYMMETRY_GROUP \"%s\"",
                      tds_sym_name(m->sym));
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_alive(m->vflags, v)) continue;
    int k[3];
    tds_torus_cell_offset(m, m->x[v], k);
    int any = 0;
    for (int i = 0; i < 3; i++) {
      if (k[i] > 100 || k[i] < -100)
        return tds_seterr(ctx, TDS_ERANGE, "rewrap: vertex %d is %d cells away", (int)v + 1, -k[i]);
      any |= k[i] != 0;
    }
    if (!any) continue;
    int rc = tds_torus_wrap_vertex(ctx, s, v, tds_wrap_pack(k));
    if (rc) return rc;
    ++*n;
  }
  return TDS_OK;
}

int tds_torus_view(tds_ctx *ctx, const tds_surf *s, tds_surf *view) {
  *view = *s;
  /* derived arrays of s are not shared: the view builds its own */
  view->tlift = NULL;
  view->tlift_cap = 0;
  view->tlift_gen = 0;
  view->tplan = NULL;
  view->orig_start = view->orig_facets = NULL;
  view->orig_gen = 0;
  view->cg_dir = view->cg_prev = NULL;
  view->cg_nv = 0;
  tds_mesh_init(&view->m);
  view->m.alloc = s->m.alloc;
  if (tds_mesh_copy(&view->m, &s->m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  int rc = tds_torus_detorus(ctx, &view->m);
  if (rc != TDS_OK) tds_mesh_free(&view->m);
  return rc;
}

void tds_torus_view_free(tds_surf *view) {
  tds_alloc a = view->m.alloc;
  tds_mesh_free(&view->m);
  tds_free(&a, view->tlift);
  tds_free(&a, view->tplan);
  tds_free(&a, view->orig_start);
  tds_free(&a, view->orig_facets);
  tds_free(&a, view->cg_dir);
  tds_free(&a, view->cg_prev);
}
