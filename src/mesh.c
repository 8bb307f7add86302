/* mesh.c: element storage, creation, deletion and the edge rings. */
#include "mesh.h"

#include "attr.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* A column is a pointer field of tds_mesh and the size of one element;
** a torus column is allocated only while the mesh is periodic (NULL
** otherwise), so the soapfilm model does not pay for it. */
typedef struct {
  size_t off;
  size_t size;
  int torus;
} column;

#define COL(field, sz) {offsetof(tds_mesh, field), sz, 0}
#define TORUS_COL(field, sz) {offsetof(tds_mesh, field), sz, 1}
static const column vcols[] = {
    COL(x, sizeof(double[3])),  COL(vflags, sizeof(uint32_t)),
    COL(vcon, sizeof(tds_cmask)), COL(vbdry, sizeof(int32_t)),
    COL(vp, sizeof(double[2])), COL(vfile, sizeof(int32_t)),
};
static const column ecols[] = {
    COL(ev, sizeof(tds_id[2])),   COL(eflags, sizeof(uint32_t)),
    COL(econ, sizeof(tds_cmask)), COL(ebdry, sizeof(int32_t)),
    COL(eten, sizeof(double)),    COL(ecolor, sizeof(int16_t)),
    COL(eside, sizeof(int32_t)), COL(efile, sizeof(int32_t)),
    TORUS_COL(ewrap, sizeof(int32_t)),
};
static const column fcols[] = {
    COL(fv, sizeof(tds_id[3])),   COL(fe, sizeof(int32_t[3])),
    COL(fb, sizeof(tds_id[2])),   COL(fflags, sizeof(uint32_t)),
    COL(fcon, sizeof(tds_cmask)), COL(ften, sizeof(double)),
    COL(fcolor, sizeof(int16_t)), COL(forig, sizeof(tds_id)),
    COL(side_next, sizeof(int32_t[3])), COL(ffile, sizeof(int32_t)),
};
static const column bcols[] = {
    COL(bflags, sizeof(uint32_t)),  COL(btarget, sizeof(double)),
    COL(bvolconst, sizeof(double)), COL(bdensity, sizeof(double)),
    COL(bpressure, sizeof(double)), COL(bvol, sizeof(double)),
    COL(bfile, sizeof(int32_t)),
};
#undef COL
#undef TORUS_COL

static const struct {
  const column *cols;
  int ncols;
  size_t n_off, cap_off;
} kinds[TDS_NKINDS] = {
    {vcols, sizeof vcols / sizeof *vcols, offsetof(tds_mesh, nv),
     offsetof(tds_mesh, capv)},
    {ecols, sizeof ecols / sizeof *ecols, offsetof(tds_mesh, ne),
     offsetof(tds_mesh, cape)},
    {fcols, sizeof fcols / sizeof *fcols, offsetof(tds_mesh, nf),
     offsetof(tds_mesh, capf)},
    {bcols, sizeof bcols / sizeof *bcols, offsetof(tds_mesh, nb),
     offsetof(tds_mesh, capb)},
};

static const size_t flag_off[TDS_NKINDS] = {
    offsetof(tds_mesh, vflags), offsetof(tds_mesh, eflags),
    offsetof(tds_mesh, fflags), offsetof(tds_mesh, bflags)};

#define FIELD(m, off, type) (*(type *)((char *)(m) + (off)))
#define CFIELD(m, off, type) (*(type const *)((const char *)(m) + (off)))

static int live(const tds_mesh *m, const column *c) { return !c->torus || m->torus; }

void tds_mesh_init(tds_mesh *m) {
  memset(m, 0, sizeof *m);
  m->topo_gen = 1; /* adj_gen 0: the (empty) adjacency starts stale */
}

void tds_mesh_free(tds_mesh *m) {
  tds_alloc a = m->alloc;
  for (int k = 0; k < TDS_NKINDS; k++)
    for (int c = 0; c < kinds[k].ncols; c++)
      tds_free(&a, FIELD(m, kinds[k].cols[c].off, void *));
  for (int k = 0; k < TDS_NKINDS; k++) {
    for (int c = 0; c < m->nucol[k]; c++) tds_free(&a, m->ucol[k][c].v);
    tds_free(&a, m->ucol[k]);
  }
  tds_free(&a, m->vf_start);
  tds_free(&a, m->vf);
  tds_free(&a, m->ve_start);
  tds_free(&a, m->ve);
  tds_mesh_init(m);
  m->alloc = a;
}

int tds_mesh_reserve(tds_mesh *m, int kind, int32_t n) {
  TDS_ASSERT(kind >= 0 && kind < TDS_NKINDS);
  int32_t *cap = &FIELD(m, kinds[kind].cap_off, int32_t);
  if (n <= *cap) return TDS_OK;
  if (n > INT32_MAX / 8) return TDS_ENOMEM;
  /* Every column is reallocated to the new capacity before *cap changes;
  ** a column that grew before a later failure is merely larger. */
  for (int c = 0; c < kinds[kind].ncols; c++) {
    const column *col = &kinds[kind].cols[c];
    if (!live(m, col)) continue;
    void **p = &FIELD(m, col->off, void *);
    void *q = tds_realloc(&m->alloc, *p, (size_t)n * col->size);
    if (!q) return TDS_ENOMEM;
    memset((char *)q + (size_t)*cap * col->size, 0,
           (size_t)(n - *cap) * col->size);
    *p = q;
  }
  for (int c = 0; c < m->nucol[kind]; c++) {
    tds_ucol *u = &m->ucol[kind][c];
    double *q = tds_realloc(&m->alloc, u->v, (size_t)n * (size_t)u->size * sizeof *q);
    if (!q) return TDS_ENOMEM;
    memset(q + (size_t)*cap * (size_t)u->size, 0,
           (size_t)(n - *cap) * (size_t)u->size * sizeof *q);
    u->v = q;
  }
  *cap = n;
  return TDS_OK;
}

int tds_mesh_set_torus(tds_mesh *m, int torus) {
  if (torus && !m->torus) {
    if (m->cape && !(m->ewrap = tds_calloc(&m->alloc, (size_t)m->cape, sizeof *m->ewrap)))
      return TDS_ENOMEM;
  } else if (!torus) {
    tds_free(&m->alloc, m->ewrap);
    m->ewrap = NULL;
    m->sym = 0; /* a symmetry group ends with its wraps */
  }
  m->torus = torus;
  return TDS_OK;
}

int tds_mesh_room(tds_mesh *m, int kind, int32_t n) {
  int32_t cap = FIELD(m, kinds[kind].cap_off, int32_t);
  if (n <= cap) return TDS_OK;
  int32_t grown = cap < 16 ? 16 : cap + cap / 2;
  return tds_mesh_reserve(m, kind, n > grown ? n : grown);
}

/* Room for one more slot. */
static int room(tds_mesh *m, int kind) {
  return tds_mesh_room(m, kind, FIELD(m, kinds[kind].n_off, int32_t) + 1);
}

static void set_defaults(tds_mesh *m, int kind, tds_id i) {
  for (int c = 0; c < m->nucol[kind]; c++) {
    tds_ucol *u = &m->ucol[kind][c];
    memset(u->v + (size_t)i * (size_t)u->size, 0, (size_t)u->size * sizeof *u->v);
  }
  switch (kind) {
  case TDS_VERTEX:
    memset(m->x[i], 0, sizeof m->x[i]);
    m->vflags[i] = 0;
    m->vcon[i] = 0;
    m->vbdry[i] = TDS_NONE;
    m->vp[i][0] = m->vp[i][1] = 0;
    m->vfile[i] = 0;
    break;
  case TDS_EDGE:
    m->ev[i][0] = m->ev[i][1] = TDS_NONE;
    m->eflags[i] = 0;
    m->econ[i] = 0;
    m->ebdry[i] = TDS_NONE;
    m->eten[i] = 0;
    m->ecolor[i] = 0;
    m->eside[i] = TDS_NONE;
    m->efile[i] = 0;
    if (m->ewrap) m->ewrap[i] = 0;
    break;
  case TDS_FACET:
    for (int k = 0; k < 3; k++) {
      m->fv[i][k] = TDS_NONE;
      m->fe[i][k] = 0;
      m->side_next[3 * i + k] = TDS_NONE;
    }
    m->fb[i][0] = m->fb[i][1] = TDS_NONE;
    m->fflags[i] = 0;
    m->fcon[i] = 0;
    m->ften[i] = 1;
    m->fcolor[i] = 15; /* white, Evolver's default facet colour */
    m->forig[i] = TDS_NONE;
    m->ffile[i] = 0;
    break;
  case TDS_BODY:
    m->bflags[i] = 0;
    m->btarget[i] = m->bvolconst[i] = m->bdensity[i] = 0;
    m->bpressure[i] = m->bvol[i] = 0;
    m->bfile[i] = 0;
    break;
  }
}

static tds_id append(tds_mesh *m, int kind) {
  if (room(m, kind) != TDS_OK) return TDS_NONE;
  int32_t *n = &FIELD(m, kinds[kind].n_off, int32_t);
  tds_id i = (*n)++;
  set_defaults(m, kind, i);
  m->topo_gen++;
  return i;
}

int tds_mesh_extend_dead(tds_mesh *m, int kind, int32_t n) {
  TDS_ASSERT(kind >= 0 && kind < TDS_NKINDS);
  int32_t *cnt = &FIELD(m, kinds[kind].n_off, int32_t);
  if (n <= *cnt) return TDS_OK;
  if (tds_mesh_room(m, kind, n) != TDS_OK) return TDS_ENOMEM;
  for (int32_t i = *cnt; i < n; i++) {
    set_defaults(m, kind, i);
    FIELD(m, flag_off[kind], uint32_t *)[i] = TDS_DEAD;
  }
  *cnt = n;
  m->topo_gen++;
  return TDS_OK;
}

tds_id tds_mesh_add_vertex(tds_mesh *m, const double x[3]) {
  tds_id v = append(m, TDS_VERTEX);
  if (v != TDS_NONE) {
    memcpy(m->x[v], x, sizeof m->x[v]);
    m->coord_gen++;
  }
  return v;
}

tds_id tds_mesh_add_edge(tds_mesh *m, tds_id v0, tds_id v1) {
  TDS_ASSERT(v0 >= 0 && v0 < m->nv && tds_alive(m->vflags, v0));
  TDS_ASSERT(v1 >= 0 && v1 < m->nv && tds_alive(m->vflags, v1));
  tds_id e = append(m, TDS_EDGE);
  if (e != TDS_NONE) {
    m->ev[e][0] = v0;
    m->ev[e][1] = v1;
  }
  return e;
}

tds_id tds_mesh_add_body(tds_mesh *m) { return append(m, TDS_BODY); }

int tds_mesh_claim(tds_mesh *m, int kind, tds_id id) {
  TDS_ASSERT(kind >= 0 && kind < TDS_NKINDS);
  if (id < 0 || id >= INT32_MAX / 8) return TDS_ERANGE;
  if (tds_mesh_extend_dead(m, kind, id + 1) != TDS_OK) return TDS_ENOMEM;
  uint32_t *fl = FIELD(m, flag_off[kind], uint32_t *);
  if (!(fl[id] & TDS_DEAD)) return TDS_ERANGE;
  set_defaults(m, kind, id);
  m->topo_gen++;
  return TDS_OK;
}

/* Edge rings. ------------------------------------------------------------ */

static void ring_link(tds_mesh *m, int32_t s) {
  tds_id e = TDS_OID(m->fe[s / 3][s % 3]);
  int32_t h = m->eside[e];
  if (h == TDS_NONE) {
    m->eside[e] = s;
    m->side_next[s] = s;
  } else {
    m->side_next[s] = m->side_next[h];
    m->side_next[h] = s;
  }
}

static void ring_unlink(tds_mesh *m, int32_t s) {
  if (m->side_next[s] == TDS_NONE) return; /* never linked */
  tds_id e = TDS_OID(m->fe[s / 3][s % 3]);
  int32_t p = s;
  while (m->side_next[p] != s) p = m->side_next[p];
  if (p == s) {
    m->eside[e] = TDS_NONE;
  } else {
    m->side_next[p] = m->side_next[s];
    if (m->eside[e] == s) m->eside[e] = p;
  }
  m->side_next[s] = TDS_NONE;
}

int tds_mesh_edges_chain(const tds_mesh *m, const int32_t oe[3]) {
  for (int k = 0; k < 3; k++) {
    tds_id e = TDS_OID(oe[k]);
    if (oe[k] < 0 || e >= m->ne || !tds_alive(m->eflags, e)) return 0;
  }
  for (int k = 0; k < 3; k++)
    if (tds_oe_head(m, oe[k]) != tds_oe_tail(m, oe[(k + 1) % 3])) return 0;
  return 1;
}

static void facet_fill(tds_mesh *m, tds_id f, const int32_t oe[3]) {
  for (int k = 0; k < 3; k++) {
    m->fe[f][k] = oe[k];
    m->fv[f][k] = tds_oe_tail(m, oe[k]);
  }
  for (int k = 0; k < 3; k++) ring_link(m, 3 * f + k);
}

tds_id tds_mesh_add_facet(tds_mesh *m, const int32_t oe[3]) {
  TDS_ASSERT(tds_mesh_edges_chain(m, oe));
  tds_id f = append(m, TDS_FACET);
  if (f != TDS_NONE) facet_fill(m, f, oe);
  return f;
}

void tds_mesh_set_facet(tds_mesh *m, tds_id f, const int32_t oe[3]) {
  TDS_ASSERT(f >= 0 && f < m->nf && tds_alive(m->fflags, f));
  TDS_ASSERT(tds_mesh_edges_chain(m, oe));
  for (int k = 0; k < 3; k++) ring_unlink(m, 3 * f + k);
  facet_fill(m, f, oe);
  m->topo_gen++;
}

void tds_mesh_kill(tds_mesh *m, int kind, tds_id id) {
  TDS_ASSERT(kind >= 0 && kind < TDS_NKINDS);
  TDS_ASSERT(id >= 0 && id < CFIELD(m, kinds[kind].n_off, int32_t));
  switch (kind) {
  case TDS_VERTEX: m->vflags[id] |= TDS_DEAD; break;
  case TDS_EDGE: m->eflags[id] |= TDS_DEAD; break;
  case TDS_FACET:
    for (int k = 0; k < 3; k++) ring_unlink(m, 3 * id + k);
    m->fflags[id] |= TDS_DEAD;
    break;
  case TDS_BODY: m->bflags[id] |= TDS_DEAD; break;
  }
  m->topo_gen++;
}

int tds_edge_valence(const tds_mesh *m, tds_id e) {
  TDS_ASSERT(e >= 0 && e < m->ne);
  int32_t h = m->eside[e];
  if (h == TDS_NONE) return 0;
  int n = 0;
  int32_t s = h;
  do {
    n++;
    s = m->side_next[s];
  } while (s != h);
  return n;
}

int32_t tds_mesh_count(const tds_mesh *m, int kind) {
  int32_t n = CFIELD(m, kinds[kind].n_off, int32_t), c = 0;
  const uint32_t *fl = CFIELD(m, flag_off[kind], uint32_t *);
  for (int32_t i = 0; i < n; i++) c += !(fl[i] & TDS_DEAD);
  return c;
}

void tds_mesh_inherit(tds_mesh *m, int kind, tds_id dst, tds_id src) {
  int32_t *file = tds_mesh_file_ids(m, kind);
  file[dst] = file[src];
  for (int c = 0; c < m->nucol[kind]; c++) {
    tds_ucol *u = &m->ucol[kind][c];
    if (kind == TDS_FACET && !strncmp(u->name, TDS_FE_ATTR_PREFIX, sizeof TDS_FE_ATTR_PREFIX - 1))
      continue; /* facetedge attributes: new sides start at 0, as in Evolver */
    memcpy(u->v + (size_t)dst * (size_t)u->size, u->v + (size_t)src * (size_t)u->size,
           (size_t)u->size * sizeof *u->v);
  }
}

/* The user attribute columns of src, empty, in dst (before reserving). */
static int copy_ucols(tds_mesh *dst, const tds_mesh *src) {
  for (int k = 0; k < TDS_NKINDS; k++) {
    if (!src->nucol[k]) continue;
    dst->ucol[k] = tds_calloc(&dst->alloc, (size_t)src->nucol[k], sizeof *dst->ucol[k]);
    if (!dst->ucol[k]) return TDS_ENOMEM;
    for (int c = 0; c < src->nucol[k]; c++) {
      dst->ucol[k][c] = src->ucol[k][c];
      dst->ucol[k][c].v = NULL;
    }
    dst->nucol[k] = src->nucol[k];
  }
  return TDS_OK;
}

int tds_mesh_copy(tds_mesh *dst, const tds_mesh *src) {
  tds_mesh_init(dst);
  dst->alloc = src->alloc;
  dst->torus = src->torus;
  if (copy_ucols(dst, src) != TDS_OK) {
    tds_mesh_free(dst);
    return TDS_ENOMEM;
  }
  for (int k = 0; k < TDS_NKINDS; k++) {
    int32_t cap = CFIELD(src, kinds[k].cap_off, int32_t);
    if (tds_mesh_reserve(dst, k, cap) != TDS_OK) {
      tds_mesh_free(dst);
      return TDS_ENOMEM;
    }
    for (int c = 0; c < kinds[k].ncols; c++) {
      const column *col = &kinds[k].cols[c];
      if (cap && live(src, col))
        memcpy(FIELD(dst, col->off, void *), CFIELD(src, col->off, void *),
               (size_t)cap * col->size);
    }
    for (int c = 0; c < src->nucol[k] && cap; c++)
      memcpy(dst->ucol[k][c].v, src->ucol[k][c].v,
             (size_t)cap * (size_t)src->ucol[k][c].size * sizeof(double));
    FIELD(dst, kinds[k].n_off, int32_t) = CFIELD(src, kinds[k].n_off, int32_t);
  }
  memcpy(dst->period, src->period, sizeof dst->period);
  dst->sym = src->sym;
  memcpy(dst->symp, src->symp, sizeof dst->symp);
  dst->draw = src->draw;
  dst->has_origin = src->has_origin;
  memcpy(dst->origin, src->origin, sizeof dst->origin);
  dst->topo_gen = src->topo_gen + 1;
  dst->coord_gen = src->coord_gen;
  dst->adj_gen = 0;
  return TDS_OK;
}

size_t tds_mesh_bytes(const tds_mesh *m) {
  size_t b = 0;
  for (int k = 0; k < TDS_NKINDS; k++) {
    int32_t cap = CFIELD(m, kinds[k].cap_off, int32_t);
    for (int c = 0; c < kinds[k].ncols; c++)
      if (live(m, &kinds[k].cols[c])) b += (size_t)cap * kinds[k].cols[c].size;
    for (int c = 0; c < m->nucol[k]; c++)
      b += (size_t)cap * (size_t)m->ucol[k][c].size * sizeof(double);
  }
  for (int k = 0; k < 4; k++) b += sizeof(int32_t) * (size_t)m->adj_cap[k];
  return b;
}

void tds_mesh_move_slot(tds_mesh *m, int kind, tds_id dst, tds_id src) {
  TDS_ASSERT(kind >= 0 && kind < TDS_NKINDS);
  if (dst == src) return;
  for (int c = 0; c < kinds[kind].ncols; c++) {
    const column *col = &kinds[kind].cols[c];
    if (!live(m, col)) continue;
    char *p = FIELD(m, col->off, char *);
    memmove(p + (size_t)dst * col->size, p + (size_t)src * col->size, col->size);
  }
  for (int c = 0; c < m->nucol[kind]; c++) {
    tds_ucol *u = &m->ucol[kind][c];
    memmove(u->v + (size_t)dst * (size_t)u->size, u->v + (size_t)src * (size_t)u->size,
            (size_t)u->size * sizeof *u->v);
  }
}

void tds_mesh_truncate(tds_mesh *m, int kind, int32_t n) {
  TDS_ASSERT(kind >= 0 && kind < TDS_NKINDS);
  FIELD(m, kinds[kind].n_off, int32_t) = n;
  m->topo_gen++;
}
