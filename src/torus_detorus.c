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

void tds_torus_to_lattice(const tds_mesh *m, const double x[3], double c[3]) {
  const double(*p)[3] = m->period;
  double inv[3][3], det = 0; /* x = sum_i c_i period[i], so c = x P^-1 */
  for (int i = 0; i < 3; i++) {
    int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; j++) {
      int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      inv[j][i] = p[i1][j1] * p[i2][j2] - p[i1][j2] * p[i2][j1]; /* cofactor, transposed */
    }
  }
  for (int j = 0; j < 3; j++) det += p[0][j] * inv[j][0];
  for (int i = 0; i < 3; i++) c[i] = (x[0] * inv[0][i] + x[1] * inv[1][i] + x[2] * inv[2][i]) / det;
}

void tds_torus_box(const tds_mesh *m, double lo[3]) {
  if (!m->has_origin) {
    lo[0] = lo[1] = lo[2] = 0;
    return;
  }
  tds_torus_to_lattice(m, m->origin, lo);
}

/* A facet as drawn: facet f with its first corner moved by wrap w,
** keeping its bodies on the sides whose bit is set in keep (1 front,
** 2 back). */
typedef struct placed {
  tds_id f;
  int32_t w;
  int keep;
} placed;

/* The mesh becomes the placed facets (each alive facet at least once):
** the first placement of f is facet f, later ones are new facets; corners
** are the vertices' copies at their wraps, edges likewise. */
static int place(tds_ctx *ctx, tds_mesh *m, const placed *pl, int32_t npl, int32_t *src[2]) {
  int32_t nv = m->nv, ne = m->ne, nf = m->nf;
  tds_alloc *a = &m->alloc;
  copies cv = {0}, ce = {0};
  size_t nc = (size_t)(3 * npl + ne);
  int32_t *newfe = tds_malloc(a, (size_t)(3 * (npl > 0 ? npl : 1)) * sizeof *newfe);
  tds_id(*ofb)[2] = tds_malloc(a, (size_t)(nf > 0 ? nf : 1) * sizeof *ofb);
  uint8_t *bare = tds_calloc(a, (size_t)(ne > 0 ? ne : 1), 1);
  uint8_t *taken = tds_calloc(a, (size_t)(nf > 0 ? nf : 1), 1);
  uint8_t *used = tds_calloc(a, (size_t)nv + nc + 1, 1);
  int rc = newfe && ofb && bare && taken && used ? TDS_OK : TDS_ENOMEM;
  if (!rc) rc = copies_init(a, &cv, nc);
  if (!rc) rc = copies_init(a, &ce, nc);
  if (!rc && (tds_mesh_reserve(m, TDS_VERTEX, nv + (int32_t)nc) ||
              tds_mesh_reserve(m, TDS_EDGE, ne + 3 * npl) ||
              tds_mesh_reserve(m, TDS_FACET, nf + npl)))
    rc = TDS_ENOMEM;
  if (!rc && src) {
    src[0] = src[1] = NULL;
    if (!(src[0] = tds_malloc(a, ((size_t)nv + nc + 1) * sizeof *src[0])) ||
        !(src[1] = tds_malloc(a, ((size_t)nf + (size_t)npl + 1) * sizeof *src[1])))
      rc = TDS_ENOMEM;
  }
  if (rc) {
    if (src) {
      tds_free(a, src[0]);
      tds_free(a, src[1]);
    }
    goto done;
  }
  for (int32_t i = 0; i < npl; i++) {
    tds_id f = pl[i].f;
    for (int k = 0; k < 3; k++) {
      int32_t oe = m->fe[f][k];
      tds_id e = TDS_OID(oe);
      int ct = TDS_OREV(oe) ? (k + 1) % 3 : k; /* corner of e's stored tail */
      int32_t wt = tds_wrap_mul(m, pl[i].w, tds_torus_corner_wrap(m, f, ct));
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
      newfe[3 * i + k] = TDS_OREF(ne2, TDS_OREV(oe));
    }
  }
  for (tds_id e = 0; e < ne; e++) bare[e] = tds_alive(m->eflags, e) && m->eside[e] == TDS_NONE;
  if (nf) memcpy(ofb, m->fb, (size_t)nf * sizeof *ofb); /* m->fb is NULL without facets */
  if (src)
    for (tds_id f = 0; f < nf + npl; f++) src[1][f] = f < nf && tds_alive(m->fflags, f) ? f : -1;
  for (int32_t i = 0; i < npl; i++) {
    tds_id f = pl[i].f, g = f;
    if (!taken[f]) {
      taken[f] = 1;
      if (memcmp(newfe + 3 * i, m->fe[f], 3 * sizeof *newfe)) tds_mesh_set_facet(m, f, newfe + 3 * i);
    } else {
      g = tds_mesh_add_facet(m, newfe + 3 * i);
      tds_facet_inherit(m, g, f);
      if (src) src[1][g] = f;
    }
    for (int side = 0; side < 2; side++)
      m->fb[g][side] = pl[i].keep >> side & 1 ? ofb[f][side] : TDS_NONE;
  }
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
  if (src) {
    for (tds_id v = 0; v < m->nv; v++) src[0][v] = v < nv && tds_alive(m->vflags, v) ? v : -1;
    for (uint32_t h = 0; h <= cv.mask; h++)
      if (cv.key[h] != -1) src[0][cv.id[h]] = cv.key[h];
  }
  tds_mesh_set_torus(m, 0);
  m->topo_gen++;
  m->coord_gen++;
done:
  tds_free(a, used);
  tds_free(a, taken);
  tds_free(a, newfe);
  tds_free(a, ofb);
  tds_free(a, bare);
  copies_free(a, &cv);
  copies_free(a, &ce);
  return rc ? tds_seterr(ctx, rc, "out of memory") : TDS_OK;
}

/* Move the placed facets list[0..n) (facet sides 2 f + s, at wrap[f]) by
** the lattice vector that brings the mean of their corners into the clip
** box. */
static void recentre(const tds_mesh *m, const int32_t *list, int32_t n, int32_t *wrap) {
  double sum[3] = {0, 0, 0}, lo[3], c[3];
  for (int32_t i = 0; i < n; i++) {
    double d[3], x[3];
    tds_wrap_vec(m->period, wrap[list[i]], d);
    for (int k = 0; k < 3; k++) {
      tds_torus_facet_corner(m, list[i] / 2, k, x);
      for (int j = 0; j < 3; j++) sum[j] += x[j] + d[j];
    }
  }
  for (int j = 0; j < 3; j++) sum[j] /= 3.0 * n;
  tds_torus_to_lattice(m, sum, c);
  tds_torus_box(m, lo);
  int k[3];
  for (int i = 0; i < 3; i++) {
    double s = -floor(c[i] - lo[i]);
    if (!(fabs(s) < TDS_WRAP_MAX / 2)) return; /* far away or not finite: as placed */
    k[i] = (int)s;
  }
  int32_t shift = tds_wrap_pack(k);
  for (int32_t i = 0; i < n; i++)
    if (tds_wrap_overflows(shift, wrap[list[i]])) return;
  for (int32_t i = 0; i < n; i++) wrap[list[i]] = tds_wrap_add(shift, wrap[list[i]]);
}

/* The placements of CONNECTED (tds_torus_detorus). A body's boundary is
** made of facet sides (2 f + s: facet f seen from body fb[f][s]), laid
** out by tds_torus_walk from its lowest side, each piece then moved into
** the clip box. A facet with the same body on both sides is placed twice;
** a facet whose two sides land at the same wrap once. *out gets at most
** 2 nf placements. */
static int connected(tds_ctx *ctx, tds_mesh *m, placed **out, int32_t *nout) {
  int32_t nf = m->nf;
  tds_alloc *a = &m->alloc;
  size_t n2 = 2 * (size_t)(nf > 0 ? nf : 1);
  placed *pl = tds_malloc(a, n2 * sizeof *pl);
  int32_t *wrap = tds_malloc(a, n2 * sizeof *wrap);   /* per facet side */
  int32_t *first = tds_malloc(a, n2 / 2 * sizeof *first); /* f's first placement */
  uint8_t *seen = tds_calloc(a, n2, 1);
  int32_t *queue = tds_malloc(a, n2 * sizeof *queue);
  if (!pl || !wrap || !first || !seen || !queue) {
    tds_free(a, pl);
    pl = NULL;
    goto done;
  }
  int32_t npl = 0;
  for (tds_id f = 0; f < nf; f++) first[f] = -1;
  for (tds_id b = 0; b < m->nb; b++) {
    if (!tds_alive(m->bflags, b)) continue;
    for (int32_t n0 = 0; n0 < 2 * nf; n0++) {
      tds_id f0 = n0 / 2;
      if (seen[n0] || !tds_alive(m->fflags, f0) || m->fb[f0][n0 % 2] != b) continue;
      int32_t tail; /* one edge-connected piece of the body */
      tds_torus_walk(m, wrap, seen, queue, n0, &tail);
      if (!tds_mesh_rotates(m)) recentre(m, queue, tail, wrap);
      for (int32_t i = 0; i < tail; i++) {
        int32_t n = queue[i];
        tds_id f = n / 2;
        int bits = 1 << (n % 2);
        if (first[f] >= 0 && pl[first[f]].w == wrap[n]) {
          pl[first[f]].keep |= bits;
          continue;
        }
        if (first[f] < 0) first[f] = npl;
        pl[npl++] = (placed){f, wrap[n], bits};
      }
    }
  }
  for (tds_id f = 0; f < nf; f++) /* on no body: as drawn raw */
    if (tds_alive(m->fflags, f) && first[f] < 0) pl[npl++] = (placed){f, 0, 3};
  *nout = npl;
done:
  tds_free(a, wrap);
  tds_free(a, first);
  tds_free(a, seen);
  tds_free(a, queue);
  *out = pl;
  return pl ? TDS_OK : tds_seterr(ctx, TDS_ENOMEM, "out of memory");
}

int tds_torus_detorus(tds_ctx *ctx, tds_mesh *m, int32_t *src[2]) {
  if (!m->torus) return TDS_OK;
  if (m->draw == TDS_DRAW_CLIPPED) return tds_torus_clip(ctx, m, src);
  placed *pl = NULL;
  int32_t npl = 0;
  int rc = m->draw == TDS_DRAW_CONNECTED ? connected(ctx, m, &pl, &npl) : TDS_OK;
  if (rc) return rc;
  if (m->draw != TDS_DRAW_CONNECTED) {
    pl = tds_malloc(&m->alloc, (size_t)(m->nf > 0 ? m->nf : 1) * sizeof *pl);
    if (!pl) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    for (tds_id f = 0; f < m->nf; f++)
      if (tds_alive(m->fflags, f)) pl[npl++] = (placed){f, 0, 3};
  }
  rc = place(ctx, m, pl, npl, src);
  tds_free(&m->alloc, pl);
  return rc;
}

void tds_torus_cell_offset(const tds_mesh *m, const double x[3], int k[3]) {
  double c[3];
  tds_torus_to_lattice(m, x, c);
  for (int i = 0; i < 3; i++) k[i] = isfinite(c[i]) && fabs(c[i]) < 1e6 ? -(int)floor(c[i]) : 0;
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
