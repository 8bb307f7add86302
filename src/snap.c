/* snap.c: snapshots for all-or-nothing commands, and the finiteness check
** of the check mode (contracts in snap.h). */
#include "snap.h"

#include "attr.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "string_model.h"

void tds_snap_free(tds_snap *sn) {
  if (sn->taken) tds_mesh_free(&sn->m);
  tds_free(&sn->alloc, sn->quant);
  tds_free(&sn->alloc, sn->cg_dir);
  tds_free(&sn->alloc, sn->cg_prev);
  if (sn->str) {
    tds_surf tmp = {.str = sn->str};
    tds_strings_free(&tmp);
  }
  memset(sn, 0, sizeof *sn);
}

static void *dup_mem(const tds_alloc *a, const void *p, size_t n) {
  if (!p || !n) return NULL;
  void *q = tds_malloc(a, n);
  if (q) memcpy(q, p, n);
  return q;
}

int tds_snap_take(tds_ctx *ctx, const tds_surf *s, tds_snap *sn) {
  memset(sn, 0, sizeof *sn);
  TDS_REQUIRE(ctx, tds_alloc_same(&ctx->alloc, &s->m.alloc));
  sn->alloc = s->m.alloc;
  if (tds_mesh_copy(&sn->m, &s->m) != TDS_OK)
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory (saving the surface)");
  sn->taken = 1;
  sn->scale = s->scale;
  sn->energy = s->energy;
  sn->area = s->area;
  sn->iterations = s->iterations;
  sn->placed_gen = s->placed_gen;
  sn->nquant = s->nquant;
  sn->cg_norm2 = s->cg_norm2;
  sn->cg_nv = s->cg_nv;
  sn->cg_topo = s->cg_topo;
  int bad = 0;
  if (s->nquant) {
    sn->quant = tds_malloc(&s->m.alloc, (size_t)s->nquant * sizeof *sn->quant);
    bad |= !sn->quant;
    for (int i = 0; sn->quant && i < s->nquant; i++) {
      sn->quant[i][0] = s->quant[i].value;
      sn->quant[i][1] = s->quant[i].pressure;
    }
  }
  size_t ncg = (size_t)(s->cg_nv > 0 ? s->cg_nv : 0) * sizeof *s->cg_dir;
  if (s->cg_dir && ncg) {
    sn->cg_dir = dup_mem(&sn->alloc, s->cg_dir, ncg);
    sn->cg_prev = dup_mem(&sn->alloc, s->cg_prev, ncg);
    bad |= !sn->cg_dir || (s->cg_prev && !sn->cg_prev);
  }
  bad |= tds_strings_copy(&sn->alloc, s->str, &sn->str) != TDS_OK;
  if (bad) {
    tds_snap_free(sn);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory (saving the surface)");
  }
  return TDS_OK;
}

void tds_snap_restore(tds_surf *s, tds_snap *sn) {
  uint64_t topo = s->m.topo_gen, coord = s->m.coord_gen;
  tds_mesh_free(&s->m);
  s->m = sn->m; /* the snapshot's arrays now belong to the surface */
  sn->taken = 0;
  s->m.topo_gen = (topo > sn->m.topo_gen ? topo : sn->m.topo_gen) + 1;
  s->m.coord_gen = coord + 1;
  s->m.adj_gen = 0;
  s->scale = sn->scale;
  s->energy = sn->energy;
  s->area = sn->area;
  s->iterations = sn->iterations;
  s->placed_gen = sn->placed_gen; /* the positions are the old ones again */
  for (int i = 0; sn->quant && i < sn->nquant && i < s->nquant; i++) {
    s->quant[i].value = sn->quant[i][0];
    s->quant[i].pressure = sn->quant[i][1];
  }
  if (sn->str) { /* the cells as they were (the string model) */
    tds_strings_free(s);
    s->str = sn->str;
    s->str->gen += 2;
    sn->str = NULL;
  }
  /* The history is valid only for the topology it was built on. */
  if (sn->cg_dir && s->cg_dir && s->cg_nv == sn->cg_nv) {
    size_t n = (size_t)sn->cg_nv * sizeof *s->cg_dir;
    memcpy(s->cg_dir, sn->cg_dir, n);
    if (sn->cg_prev && s->cg_prev) memcpy(s->cg_prev, sn->cg_prev, n);
    s->cg_norm2 = sn->cg_norm2;
    s->cg_topo = s->m.topo_gen;
  } else {
    s->cg_norm2 = 0; /* a fresh history */
  }
  tds_snap_free(sn);
}

int tds_snap_end(tds_ctx *ctx, tds_surf *s, tds_snap *sn, int rc) {
  if (rc == TDS_OK || rc == TDS_EINTR) {
    tds_snap_free(sn);
    return rc;
  }
  tds_snap_restore(s, sn);
  static const char note[] = "; the surface is as before the command";
  size_t n = strlen(ctx->errmsg);
  if (n + sizeof note <= sizeof ctx->errmsg) memcpy(ctx->errmsg + n, note, sizeof note);
  return rc;
}

/* Compare n rows of a column; -1 if equal, else the first differing row. */
static int32_t diff_rows(const void *a, const void *b, int32_t n, size_t size) {
  if (!n) return -1;
  if (!memcmp(a, b, (size_t)n * size)) return -1;
  for (int32_t i = 0; i < n; i++)
    if (memcmp((const char *)a + (size_t)i * size, (const char *)b + (size_t)i * size, size))
      return i;
  return -1;
}

#define SAME(field, n, what)                                                   \
  do {                                                                         \
    int32_t i_ = diff_rows(a->field, b->field, n, sizeof *a->field);           \
    if (i_ >= 0)                                                               \
      return tds_seterr(ctx, TDS_ENUM, "%s %d changed (%s)", what, i_ + 1, #field); \
  } while (0)

int tds_snap_same(tds_ctx *ctx, const tds_surf *s, const tds_snap *sn) {
  const tds_mesh *a = &s->m, *b = &sn->m;
  if (a->nv != b->nv || a->ne != b->ne || a->nf != b->nf || a->nb != b->nb)
    return tds_seterr(ctx, TDS_ENUM, "element counts changed (%d %d %d %d -> %d %d %d %d)",
                      b->nv, b->ne, b->nf, b->nb, a->nv, a->ne, a->nf, a->nb);
  SAME(x, a->nv, "vertex");
  SAME(vp, a->nv, "vertex");
  SAME(vflags, a->nv, "vertex");
  SAME(vcon, a->nv, "vertex");
  SAME(vbdry, a->nv, "vertex");
  SAME(ev, a->ne, "edge");
  SAME(eflags, a->ne, "edge");
  SAME(econ, a->ne, "edge");
  SAME(eten, a->ne, "edge");
  SAME(fv, a->nf, "facet");
  SAME(fe, a->nf, "facet");
  SAME(fb, a->nf, "facet");
  SAME(fflags, a->nf, "facet");
  SAME(fcon, a->nf, "facet");
  SAME(ften, a->nf, "facet");
  SAME(bflags, a->nb, "body");
  SAME(btarget, a->nb, "body");
  SAME(bdensity, a->nb, "body");
  SAME(bpressure, a->nb, "body");
  SAME(bvolconst, a->nb, "body");
  const int32_t cnt[TDS_NKINDS] = {a->nv, a->ne, a->nf, a->nb};
  for (int k = 0; k < TDS_NKINDS; k++) {
    if (a->nucol[k] != b->nucol[k])
      return tds_seterr(ctx, TDS_ENUM, "%s attributes were defined", tds_kind_name[k]);
    for (int c = 0; c < a->nucol[k]; c++) {
      const tds_ucol *u = &a->ucol[k][c];
      int32_t i = diff_rows(u->v, b->ucol[k][c].v, cnt[k], sizeof(double) * (size_t)u->size);
      if (i >= 0)
        return tds_seterr(ctx, TDS_ENUM, "%s %d changed (%s)", tds_kind_name[k], i + 1, u->name);
    }
  }
  if (s->nquant != sn->nquant)
    return tds_seterr(ctx, TDS_ENUM, "number of quantities changed");
  for (int i = 0; i < s->nquant; i++)
    if (memcmp(&s->quant[i].pressure, &sn->quant[i][1], sizeof(double)))
      return tds_seterr(ctx, TDS_ENUM, "quantity %s: multiplier changed", s->quant[i].name);
  if (memcmp(&s->scale, &sn->scale, sizeof(double)))
    return tds_seterr(ctx, TDS_ENUM, "scale changed (%g -> %g)", sn->scale, s->scale);
  if (s->iterations != sn->iterations)
    return tds_seterr(ctx, TDS_ENUM, "iteration count changed");
  return TDS_OK;
}
#undef SAME

int tds_surf_all_finite(tds_ctx *ctx, const tds_surf *s, int derived) {
  const tds_mesh *m = &s->m;
  for (tds_id v = 0; v < m->nv; v++) {
    if (m->vflags[v] & TDS_DEAD) continue;
    for (int k = 0; k < 3; k++)
      if (!isfinite(m->x[v][k]))
        return tds_seterr(ctx, TDS_ENUM, "vertex %d: coordinate is %g", v + 1, m->x[v][k]);
    for (int k = 0; k < 2; k++)
      if (!isfinite(m->vp[v][k]))
        return tds_seterr(ctx, TDS_ENUM, "vertex %d: boundary parameter is %g", v + 1,
                          m->vp[v][k]);
  }
  for (tds_id e = 0; e < m->ne; e++)
    if (!(m->eflags[e] & TDS_DEAD) && !isfinite(m->eten[e]))
      return tds_seterr(ctx, TDS_ENUM, "edge %d: tension is %g", e + 1, m->eten[e]);
  for (tds_id f = 0; f < m->nf; f++)
    if (!(m->fflags[f] & TDS_DEAD) && !isfinite(m->ften[f]))
      return tds_seterr(ctx, TDS_ENUM, "facet %d: tension is %g", f + 1, m->ften[f]);
  for (tds_id b = 0; b < m->nb; b++) {
    if (m->bflags[b] & TDS_DEAD) continue;
    const double val[5] = {m->btarget[b], m->bvolconst[b], m->bdensity[b], m->bpressure[b],
                           m->bvol[b]};
    static const char *const name[5] = {"target", "volconst", "density", "pressure", "volume"};
    for (int k = 0; k < (derived ? 5 : 4); k++)
      if (!isfinite(val[k]))
        return tds_seterr(ctx, TDS_ENUM, "body %d: %s is %g", b + 1, name[k], val[k]);
  }
  for (int k = 0; k < TDS_NKINDS; k++)
    for (int c = 0; c < m->nucol[k]; c++) {
      const tds_ucol *u = &m->ucol[k][c];
      int32_t n = k == TDS_VERTEX ? m->nv : k == TDS_EDGE ? m->ne : k == TDS_FACET ? m->nf : m->nb;
      for (size_t i = 0; i < (size_t)n * (size_t)u->size; i++)
        if (!isfinite(u->v[i]))
          return tds_seterr(ctx, TDS_ENUM, "%s %d: %s is %g", tds_kind_name[k],
                            (int)(i / (size_t)u->size) + 1, u->name, u->v[i]);
    }
  for (int i = 0; i < s->npar; i++)
    if (!isfinite(s->parval[i]))
      return tds_seterr(ctx, TDS_ENUM, "parameter %s is %g", s->parname[i], s->parval[i]);
  for (int i = 0; i < s->nquant; i++) {
    const tds_quantity *q = &s->quant[i];
    if ((derived && !isfinite(q->value)) || !isfinite(q->pressure) || !isfinite(q->target) ||
        !isfinite(q->modulus))
      return tds_seterr(ctx, TDS_ENUM, "quantity %s: value %g, multiplier %g", q->name,
                        q->value, q->pressure);
  }
  const double g[5] = {s->gravity, s->scale, s->scale_limit, s->energy, s->area};
  static const char *const gname[5] = {"gravity constant", "scale", "scale limit", "energy",
                                       "area"};
  for (int k = 0; k < (derived ? 5 : 3); k++)
    if (!isfinite(g[k])) return tds_seterr(ctx, TDS_ENUM, "%s is %g", gname[k], g[k]);
  return TDS_OK;
}

int tds_snap_run(tds_ctx *ctx, tds_surf *s, tds_snap_cmd fn, const uint8_t *sel, int32_t *n) {
  if (n) *n = 0;
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  int32_t cnt = 0;
  rc = tds_snap_end(ctx, s, &sn, fn(ctx, s, sel, &cnt));
  if (n) *n = rc == TDS_OK ? cnt : 0;
  return rc;
}
