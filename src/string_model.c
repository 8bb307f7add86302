/* string_model.c: the cells of the string model (contracts in string_model.h). */
#include "string_model.h"
#include "vec3.h"

#include <string.h>

#include "gather.h"
#include "method.h"

int tds_strings_enable(tds_ctx *ctx, tds_surf *s, int space_dim) {
  if (s->str) {
    s->str->space_dim = space_dim;
    return TDS_OK;
  }
  tds_strings *st = tds_calloc(&s->m.alloc, 1, sizeof *st);
  if (!st) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  st->alloc = s->m.alloc;
  st->space_dim = space_dim;
  st->start = tds_calloc(&st->alloc, 1, sizeof *st->start);
  if (!st->start) {
    tds_free(&s->m.alloc, st);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  s->str = st;
  return TDS_OK;
}

static void free_index(tds_strings *st) {
  tds_free(&st->alloc, st->eb_start);
  tds_free(&st->alloc, st->eb_body);
  tds_free(&st->alloc, st->eb_w);
  tds_free(&st->alloc, st->eb_lift);
  st->eb_start = NULL;
  st->eb_body = NULL;
  st->eb_w = NULL;
  st->eb_lift = NULL;
  st->idx_gen = 0;
  st->idx_ne = 0;
}

static void free_all(tds_strings *st) {
  tds_alloc a = st->alloc;
  free_index(st);
  tds_free(&a, st->flags);
  tds_free(&a, st->fb);
  tds_free(&a, st->color);
  tds_free(&a, st->start);
  tds_free(&a, st->oe);
  tds_free(&a, st);
}

void tds_strings_free(tds_surf *s) {
  if (s->str) free_all(s->str);
  s->str = NULL;
}

static void *dup(const tds_alloc *a, const void *p, size_t n) {
  void *q = tds_malloc(a, n ? n : 1);
  if (q && n) memcpy(q, p, n);
  return q;
}

int tds_strings_copy(const tds_alloc *a, const tds_strings *src, tds_strings **dst) {
  *dst = NULL;
  if (!src) return TDS_OK;
  tds_strings *st = tds_calloc(a, 1, sizeof *st);
  if (!st) return TDS_ENOMEM;
  st->alloc = *a;
  st->space_dim = src->space_dim;
  st->nf = st->capf = src->nf;
  st->noe = st->capoe = src->noe;
  st->gen = src->gen + 1;
  st->flags = dup(a, src->flags, (size_t)src->nf * sizeof *st->flags);
  st->fb = dup(a, src->fb, (size_t)src->nf * sizeof *st->fb);
  st->color = dup(a, src->color, (size_t)src->nf * sizeof *st->color);
  st->start = dup(a, src->start, ((size_t)src->nf + 1) * sizeof *st->start);
  st->oe = dup(a, src->oe, (size_t)src->noe * sizeof *st->oe);
  if (!st->flags || !st->fb || !st->color || !st->start || !st->oe) {
    free_all(st);
    return TDS_ENOMEM;
  }
  *dst = st;
  return TDS_OK;
}

int tds_strings_room(tds_strings *st, int32_t nf, int32_t noe) {
  if (nf > st->capf) {
    int32_t cap = nf < 16 ? 16 : nf + nf / 2, c;
    c = st->capf;
    if (tds_grow(&st->alloc, (void **)&st->flags, sizeof *st->flags, &c, cap)) return TDS_ENOMEM;
    c = st->capf;
    if (tds_grow(&st->alloc, (void **)&st->fb, sizeof *st->fb, &c, cap)) return TDS_ENOMEM;
    c = st->capf;
    if (tds_grow(&st->alloc, (void **)&st->color, sizeof *st->color, &c, cap)) return TDS_ENOMEM;
    c = st->capf + 1;
    if (tds_grow(&st->alloc, (void **)&st->start, sizeof *st->start, &c, cap + 1))
      return TDS_ENOMEM;
    st->capf = cap;
  }
  if (noe > st->capoe &&
      tds_grow(&st->alloc, (void **)&st->oe, sizeof *st->oe, &st->capoe, noe + noe / 2 + 16))
    return TDS_ENOMEM;
  return TDS_OK;
}

int tds_strings_add(tds_ctx *ctx, tds_surf *s, tds_id f, int n, const int32_t *oe,
                    uint32_t flags, int16_t color) {
  tds_strings *st = s->str;
  const tds_mesh *m = &s->m;
  if (f < st->nf)
    return tds_seterr(ctx, TDS_ERANGE, "face %d is declared twice or out of order", f + 1);
  if (n < 1) return tds_seterr(ctx, TDS_ETOPO, "face %d has no edges", f + 1);
  for (int k = 0; k < n; k++) {
    tds_id e = TDS_OID(oe[k]);
    if (oe[k] < 0 || e >= m->ne || !tds_alive(m->eflags, e))
      return tds_seterr(ctx, TDS_ERANGE, "face %d refers to edge %d, which does not exist",
                        f + 1, e + 1);
  }
  for (int k = 0; k + 1 < n; k++)
    if (tds_oe_head(m, oe[k]) != tds_oe_tail(m, oe[k + 1]))
      return tds_seterr(ctx, TDS_ETOPO, "face %d: edge %s%d does not end where edge %s%d starts",
                        f + 1, TDS_OREV(oe[k]) ? "-" : "", TDS_OID(oe[k]) + 1,
                        TDS_OREV(oe[k + 1]) ? "-" : "", TDS_OID(oe[k + 1]) + 1);
  if (tds_strings_room(st, f + 1, st->noe + n)) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (tds_id g = st->nf; g < f; g++) { /* gaps in the ids: dead slots */
    st->flags[g] = TDS_DEAD;
    st->fb[g][0] = st->fb[g][1] = TDS_NONE;
    st->color[g] = 0;
    st->start[g + 1] = st->noe;
  }
  memcpy(st->oe + st->noe, oe, (size_t)n * sizeof *oe);
  st->noe += n;
  st->flags[f] = flags & ~TDS_DEAD;
  st->fb[f][0] = st->fb[f][1] = TDS_NONE;
  st->color[f] = color;
  st->start[f + 1] = st->noe;
  st->nf = f + 1;
  st->gen++;
  return TDS_OK;
}

int tds_string_unsupported(tds_ctx *ctx, const char *what) {
  return tds_seterr(ctx, TDS_ERANGE, "%s works on soap films only, not in the string model", what);
}

int32_t tds_strings_count(const tds_strings *st) {
  int32_t n = 0;
  for (tds_id f = 0; f < st->nf; f++) n += !(st->flags[f] & TDS_DEAD);
  return n;
}

int32_t tds_surf_count(const tds_surf *s, int kind) {
  if (kind == TDS_FACET && s->str) return tds_strings_count(s->str);
  return tds_mesh_count(&s->m, kind);
}

int tds_strings_split(tds_strings *st, const tds_id *split, int32_t ne) {
  int32_t extra = 0;
  for (int32_t i = 0; i < st->noe; i++) {
    tds_id e = TDS_OID(st->oe[i]);
    extra += e < ne && split[e] != TDS_NONE;
  }
  if (!extra) return TDS_OK;
  int32_t *oe = tds_malloc(&st->alloc, (size_t)(st->noe + extra) * sizeof *oe);
  if (!oe) return TDS_ENOMEM;
  int32_t n = 0;
  for (tds_id f = 0; f < st->nf; f++) {
    int32_t a = st->start[f], b = st->start[f + 1];
    st->start[f] = n;
    for (int32_t i = a; i < b; i++) {
      int32_t r = st->oe[i];
      tds_id e = TDS_OID(r);
      if (e >= ne || split[e] == TDS_NONE) {
        oe[n++] = r;
      } else if (!TDS_OREV(r)) { /* tail .. new .. head */
        oe[n++] = r;
        oe[n++] = TDS_OREF(split[e], 0);
      } else { /* head .. new .. tail */
        oe[n++] = TDS_OREF(split[e], 1);
        oe[n++] = r;
      }
    }
  }
  st->start[st->nf] = n;
  tds_free(&st->alloc, st->oe);
  st->oe = oe;
  st->noe = st->capoe = n;
  st->gen++;
  return TDS_OK;
}

int tds_strings_index(tds_ctx *ctx, tds_surf *s) {
  tds_strings *st = s->str;
  const tds_mesh *m = &s->m;
  if (st->eb_start && st->idx_gen == st->gen && st->idx_topo == m->topo_gen &&
      st->idx_ne == m->ne)
    return TDS_OK;
  /* A topology command that knows nothing of cells must not leave them on
  ** deleted edges: refuse to evaluate (its snapshot puts things back). */
  for (tds_id f = 0; f < st->nf; f++) {
    if (st->flags[f] & TDS_DEAD) continue;
    for (int32_t i = st->start[f]; i < st->start[f + 1]; i++) {
      tds_id e = TDS_OID(st->oe[i]);
      if (e >= m->ne || !tds_alive(m->eflags, e))
        return tds_seterr(ctx, TDS_ETOPO, "facet %d refers to edge %d, which no longer "
                          "exists (a command the string model does not support)", f + 1, e + 1);
    }
  }
  free_index(st);
  int32_t ne = m->ne;
  st->eb_start = tds_calloc(&st->alloc, (size_t)ne + 1, sizeof *st->eb_start);
  /* at most two bodies per loop entry */
  size_t cap = 2 * (size_t)st->noe + 1;
  st->eb_body = tds_malloc(&st->alloc, cap * sizeof *st->eb_body);
  st->eb_w = tds_malloc(&st->alloc, cap * sizeof *st->eb_w);
  if (m->torus) st->eb_lift = tds_malloc(&st->alloc, cap * sizeof *st->eb_lift);
  int32_t *cnt = tds_calloc(&ctx->alloc, (size_t)ne + 1, sizeof *cnt);
  if (!st->eb_start || !st->eb_body || !st->eb_w || !cnt || (m->torus && !st->eb_lift)) {
    tds_free(&ctx->alloc, cnt);
    free_index(st);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  /* Count the (cell, body) pairs per edge, lay them out, then merge
  ** repeats of a body within each edge's run. */
  for (tds_id f = 0; f < st->nf; f++) {
    if (st->flags[f] & (TDS_DEAD | TDS_NONCONTENT)) continue;
    int nb = (st->fb[f][0] != TDS_NONE) + (st->fb[f][1] != TDS_NONE);
    for (int32_t i = st->start[f]; i < st->start[f + 1]; i++) cnt[TDS_OID(st->oe[i]) + 1] += nb;
  }
  for (int32_t e = 0; e < ne; e++) cnt[e + 1] += cnt[e];
  for (tds_id f = 0; f < st->nf; f++) {
    if (st->flags[f] & (TDS_DEAD | TDS_NONCONTENT)) continue;
    int32_t lift = 0; /* the loop's lattice translate so far */
    for (int32_t i = st->start[f]; i < st->start[f + 1]; i++) {
      int32_t r = st->oe[i], w = m->torus ? tds_oe_wrap(m, r) : 0;
      double sg = TDS_OREV(r) ? -1 : 1, ty = 0;
      if (m->torus) { /* the stored tail is the head of a reversed entry */
        double t[3];
        tds_wrap_vec(m->period, TDS_OREV(r) ? tds_wrap_add(lift, w) : lift, t);
        ty = t[1];
        lift = tds_wrap_add(lift, w);
      }
      for (int j = 0; j < 2; j++) {
        tds_id b = st->fb[f][j];
        if (b == TDS_NONE) continue;
        int32_t at = cnt[TDS_OID(r)]++;
        st->eb_body[at] = b;
        st->eb_w[at] = j ? -sg : sg;
        if (st->eb_lift) st->eb_lift[at] = st->eb_w[at] * ty;
      }
    }
  }
  /* cnt[e] is now the end of edge e's run; runs start at cnt[e - 1]. */
  int32_t n = 0, a = 0;
  for (int32_t e = 0; e < ne; e++) {
    int32_t b = cnt[e];
    st->eb_start[e] = n;
    int32_t first = n;
    for (int32_t i = a; i < b; i++) {
      int32_t k = first;
      while (k < n && st->eb_body[k] != st->eb_body[i]) k++;
      if (k == n) {
        st->eb_body[n] = st->eb_body[i];
        if (st->eb_lift) st->eb_lift[n] = st->eb_lift[i];
        st->eb_w[n++] = st->eb_w[i];
      } else {
        st->eb_w[k] += st->eb_w[i];
        if (st->eb_lift) st->eb_lift[k] += st->eb_lift[i];
      }
    }
    a = b;
  }
  st->eb_start[ne] = n;
  tds_free(&ctx->alloc, cnt);
  st->idx_gen = st->gen;
  st->idx_topo = m->topo_gen;
  st->idx_ne = ne;
  return TDS_OK;
}

/* Content integrand of constraint slot c at x (0 without one). */
static double content_at(const tds_surf *s, int c, const double *x) {
  const tds_expr *e = s->con[c].content[0];
  if (!e) return 0;
  double vars[TDS_NVARS] = {x[0], x[1], x[2], 0, 0, s->gravity_on ? s->gravity : 0};
  return tds_expr_eval(e, s->parval, vars);
}

/* Sum of the contents of the constraints vertex v is on. */
static double vertex_content(const tds_surf *s, tds_id v) {
  double c = 0;
  for (int k = 0; k < TDS_MAX_CON; k++)
    if (s->con[k].number && (s->m.vcon[v] & ((tds_cmask)1 << k)))
      c += content_at(s, k, s->m.x[v]);
  return c;
}

double tds_strings_area(const tds_surf *s, tds_id f) {
  const tds_strings *st = s->str;
  const tds_mesh *m = &s->m;
  double A = 0;
  int32_t lift = 0;
  for (int32_t i = st->start[f]; i < st->start[f + 1]; i++) {
    tds_corners C;
    tds_mlocal L = {0};
    int32_t r = st->oe[i];
    tds_gather_edge(m, r, &C);
    L.x[0] = C.x[0];
    L.x[1] = C.x[1];
    double a = tds_mk_edge_area(&L, NULL, NULL);
    if (m->torus) { /* gathered from r's own start, which the unwrapped
                    ** loop reaches translated by lift */
      double t[3];
      tds_wrap_vec(m->period, lift, t);
      a -= t[1] * (C.x[1][0] - C.x[0][0]);
      lift = tds_wrap_add(lift, tds_oe_wrap(m, r));
    }
    A += a;
    A += vertex_content(s, tds_oe_head(m, st->oe[i])) - vertex_content(s, tds_oe_tail(m, st->oe[i]));
  }
  return A;
}

int tds_strings_vertex_bodies(tds_surf *s, tds_id v, tds_id *out, int max) {
  const tds_strings *st = s->str;
  const tds_mesh *m = &s->m;
  int n = 0;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++) {
    tds_id e = TDS_OID(m->ve[i]);
    if (e >= st->idx_ne) continue;
    for (int32_t k = st->eb_start[e]; k < st->eb_start[e + 1]; k++) {
      int j = 0;
      while (j < n && out[j] != st->eb_body[k]) j++;
      if (j == n && n < max) out[n++] = st->eb_body[k];
    }
  }
  return n;
}

int tds_strings_check(tds_ctx *ctx, const tds_surf *s) {
  const tds_strings *st = s->str;
  const tds_mesh *m = &s->m;
  if (m->nf)
    return tds_seterr(ctx, TDS_ETOPO, "string model with %d triangles", (int)m->nf);
  for (tds_id f = 0; f < st->nf; f++) {
    if (st->start[f + 1] < st->start[f])
      return tds_seterr(ctx, TDS_ETOPO, "facet %d: bad loop range", f + 1);
    if (st->flags[f] & TDS_DEAD) continue;
    for (int j = 0; j < 2; j++) {
      tds_id b = st->fb[f][j];
      if (b != TDS_NONE && (b < 0 || b >= m->nb || !tds_alive(m->bflags, b)))
        return tds_seterr(ctx, TDS_ETOPO, "facet %d: body %d does not exist", f + 1, b + 1);
    }
    for (int32_t i = st->start[f]; i < st->start[f + 1]; i++) {
      tds_id e = TDS_OID(st->oe[i]);
      if (st->oe[i] < 0 || e >= m->ne || !tds_alive(m->eflags, e))
        return tds_seterr(ctx, TDS_ETOPO, "facet %d: edge %d does not exist", f + 1, e + 1);
      if (i + 1 < st->start[f + 1] &&
          tds_oe_head(m, st->oe[i]) != tds_oe_tail(m, st->oe[i + 1]))
        return tds_seterr(ctx, TDS_ETOPO, "facet %d: edges %d and %d do not chain", f + 1,
                          e + 1, TDS_OID(st->oe[i + 1]) + 1);
    }
    int32_t a = st->start[f], b = st->start[f + 1], w = 0;
    if (m->ewrap && b > a && tds_oe_head(m, st->oe[b - 1]) == tds_oe_tail(m, st->oe[a])) {
      for (int32_t i = a; i < b; i++) w = tds_wrap_add(w, tds_oe_wrap(m, st->oe[i]));
      if (w) return tds_seterr(ctx, TDS_ETOPO, "facet %d: the wraps of its edges do not add "
                               "up to zero", f + 1);
    }
  }
  return TDS_OK;
}

int tds_strings_rawv(const tds_surf *s, tds_id v, double out[3]) {
  const tds_mesh *m = &s->m;
  if (m->vcon[v] || m->vbdry[v] != TDS_NONE) return 0;
  double sum[3] = {0, 0, 0};
  int n = 0;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++) {
    tds_corners E;
    tds_gather_edge(m, m->ve[i], &E);
    v3_add(sum, sum, E.x[1]);
    n++;
  }
  if (n < 2) return 0;
  for (int k = 0; k < 3; k++) out[k] = m->x[v][k] + 0.25 * (sum[k] / n - m->x[v][k]);
  return 1;
}

int tds_strings_vavg(const tds_surf *s, tds_id v, double out[3]) {
  const tds_mesh *m = &s->m;
  if (m->vcon[v] || m->vbdry[v] != TDS_NONE) return 0;
  tds_corners nb[2]; /* the two edges from v: x[1] is the neighbour */
  int n = 0;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++) {
    tds_id e = TDS_OID(m->ve[i]);
    if (m->econ[e] || m->ebdry[e] != TDS_NONE || n == 2) return 0;
    tds_gather_edge(m, m->ve[i], &nb[n++]);
  }
  if (n != 2) return 0;
  const double *a = nb[0].x[1], *c = nb[1].x[1], *b = nb[0].x[0];
  double t[3], d[3], tt = 0, dt = 0;
  for (int k = 0; k < 3; k++) {
    t[k] = c[k] - a[k];
    d[k] = (a[k] + c[k]) / 2 - b[k];
    tt += t[k] * t[k];
    dt += d[k] * t[k];
  }
  if (!(tt > 0)) return 0;
  for (int k = 0; k < 3; k++) out[k] = b[k] + 0.25 * dt / tt * t[k];
  return 1;
}
