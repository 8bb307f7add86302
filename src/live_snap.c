/* live_snap.c: the live view's snapshot of a surface (see live_snap.h). */
#include "live_snap.h"

#include "eval.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gather.h"
#include "metrics.h"
#include "torus.h"

const char *const tds_live_fields[TDS_LIVE_NFIELDS] = {
    "mean_curvature", "min_angle", "body", "tension", "color"};

int tds_live_field_index(const char *name) {
  for (int i = 0; i < TDS_LIVE_NFIELDS; i++)
    if (!strcmp(name, tds_live_fields[i])) return i;
  return -1;
}

static void put_u32(unsigned char *p, uint32_t v) {
  p[0] = (unsigned char)v;
  p[1] = (unsigned char)(v >> 8);
  p[2] = (unsigned char)(v >> 16);
  p[3] = (unsigned char)(v >> 24);
}

static void put_f32(unsigned char *p, double v) {
  float f = (float)v;
  uint32_t u;
  memcpy(&u, &f, 4);
  put_u32(p, u);
}

/* A JSON number, or null when not finite (JSON has no NaN). */
static int json_num(char *out, size_t n, double v) {
  return isfinite(v) ? snprintf(out, n, "%.17g", v) : snprintf(out, n, "null");
}

static double facet_field(const tds_mesh *m, int field, tds_id f) {
  switch (field) {
  case 1:
    return tds_facet_min_angle(m, f);
  case 2: {
    tds_id b = m->fb[f][0] != TDS_NONE ? m->fb[f][0] : m->fb[f][1];
    return b == TDS_NONE ? 0 : b + 1;
  }
  case 3:
    return m->ften[f];
  default:
    return m->fcolor[f]; /* 15 (white) unless given */
  }
}

/* Whether edge e of a string surface is drawn to its own copy of its head
** (it wraps: the head unwrapped from the tail, no edge across the cell). */
static int own_head(const tds_surf *s, tds_id e) {
  return s->str && s->m.torus && tds_alive(s->m.eflags, e) && s->m.ewrap[e];
}

/* The snapshot of s; for a torus film s is its drawn mesh (dv), whose
** vertices have the curvature of those they are drawn from in orig. */
static int snap_drawn(tds_ctx *ctx, tds_surf *s, uint64_t version, double energy, int color,
                      unsigned char **buf, size_t *len, tds_surf *orig,
                      const tds_torus_drawn *dv) {
  tds_mesh *m = &s->m;
  if (tds_mesh_adjacency(m) != TDS_OK)
    return tds_seterr(ctx, TDS_ENOMEM, "live view: out of memory");
  int32_t *vmap = tds_malloc(&ctx->alloc, ((size_t)m->nv + 1) * sizeof *vmap);
  double *vals = NULL;
  unsigned char *b = NULL;
  if (!vmap) goto nomem;
  uint32_t nv = 0, nf = 0, ne = 0, nhead = 0;
  for (tds_id v = 0; v < m->nv; v++)
    vmap[v] = tds_alive(m->vflags, v) ? (int32_t)nv++ : -1;
  for (tds_id e = 0; e < m->ne; e++) nhead += (uint32_t)own_head(s, e);
  nv += nhead;
  for (tds_id f = 0; f < m->nf; f++)
    nf += !(m->fflags[f] & (TDS_DEAD | TDS_NODISPLAY));
  for (tds_id e = 0; e < m->ne; e++) ne += tds_alive(m->eflags, e);
  size_t nval = nv > nf ? nv : nf;
  vals = tds_malloc(&ctx->alloc, (nval + 1) * sizeof *vals);
  if (!vals) goto nomem;

  /* Header, with a placeholder for the fields' ranges filled below. */
  char head[4096], num[3][40];
  json_num(num[0], sizeof num[0], energy);
  json_num(num[1], sizeof num[1], tds_surf_area(orig ? orig : s));
  int hn = snprintf(head, sizeof head,
                    "{\"version\":%llu,\"energy\":%s,\"area\":%s,"
                    "\"iterations\":%lld,\"vertices\":%u,\"edges\":%u,"
                    "\"facets\":%u,\"bodies\":%d,\"color\":\"%s\",\"fields\":[",
                    (unsigned long long)version, num[0], num[1],
                    (long long)s->iterations, nv, ne, nf,
                    tds_mesh_count(m, TDS_BODY),
                    color >= 0 ? tds_live_fields[color] : "none");
  size_t body = 12 * (size_t)nv + 12 * (size_t)nf + 8 * (size_t)ne +
                4 * (size_t)nv + 4 * (TDS_LIVE_NFIELDS - 1) * (size_t)nf;
  size_t cap = 4 + sizeof head + body;
  b = tds_malloc(&ctx->alloc, cap);
  if (!b) goto nomem;
  /* Arrays go after the header, whose length is known only at the end:
  ** write them at the largest possible offset and move them down. */
  unsigned char *p = b + 4 + sizeof head;
  for (tds_id v = 0; v < m->nv; v++)
    if (vmap[v] >= 0)
      for (int k = 0; k < 3; k++, p += 4) put_f32(p, m->x[v][k]);
  for (tds_id e = 0; e < m->ne; e++) {
    if (!own_head(s, e)) continue;
    tds_corners C;
    tds_gather_edge(m, TDS_OREF(e, 0), &C);
    for (int k = 0; k < 3; k++, p += 4) put_f32(p, C.x[1][k]);
  }
  for (tds_id f = 0; f < m->nf; f++)
    if (!(m->fflags[f] & (TDS_DEAD | TDS_NODISPLAY)))
      for (int k = 0; k < 3; k++, p += 4) put_u32(p, (uint32_t)vmap[m->fv[f][k]]);
  for (tds_id e = 0, k = (tds_id)(nv - nhead); e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    put_u32(p, (uint32_t)vmap[m->ev[e][0]]);
    put_u32(p + 4, (uint32_t)(own_head(s, e) ? k++ : vmap[m->ev[e][1]]));
    p += 8;
  }
  for (int field = 0; field < TDS_LIVE_NFIELDS; field++) {
    size_t n = 0;
    if (field == 0) {
      for (tds_id v = 0; v < m->nv; v++)
        if (vmap[v] >= 0)
          vals[n++] = dv ? tds_torus_drawn_curvature(dv, orig, v) : tds_vertex_mean_curvature(s, v);
      for (tds_id e = 0; e < m->ne; e++)
        if (own_head(s, e)) vals[n++] = tds_vertex_mean_curvature(s, m->ev[e][1]);
    } else {
      for (tds_id f = 0; f < m->nf; f++)
        if (!(m->fflags[f] & (TDS_DEAD | TDS_NODISPLAY)))
          vals[n++] = facet_field(m, field, f);
    }
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++, p += 4) {
      put_f32(p, vals[i]);
      if (isfinite(vals[i])) {
        if (vals[i] < lo) lo = vals[i];
        if (vals[i] > hi) hi = vals[i];
      }
    }
    json_num(num[0], sizeof num[0], lo);
    json_num(num[1], sizeof num[1], hi);
    hn += snprintf(head + hn, sizeof head - (size_t)hn,
                   "%s{\"name\":\"%s\",\"per\":\"%s\",\"min\":%s,\"max\":%s}",
                   field ? "," : "", tds_live_fields[field],
                   field ? "facet" : "vertex", num[0], num[1]);
  }
  hn += snprintf(head + hn, sizeof head - (size_t)hn, "]}");
  while (hn % 4) head[hn++] = ' ';
  put_u32(b, (uint32_t)hn);
  memcpy(b + 4, head, (size_t)hn);
  memmove(b + 4 + hn, b + 4 + sizeof head, body);
  *buf = b;
  *len = 4 + (size_t)hn + body;
  tds_free(&ctx->alloc, vmap);
  tds_free(&ctx->alloc, vals);
  return TDS_OK;
nomem:
  tds_free(&ctx->alloc, vmap);
  tds_free(&ctx->alloc, vals);
  tds_free(&ctx->alloc, b);
  return tds_seterr(ctx, TDS_ENOMEM, "live view: out of memory");
}

int tds_live_snap_build(tds_ctx *ctx, tds_surf *s, uint64_t version, double energy, int color,
                        unsigned char **buf, size_t *len) {
  if (!s->m.torus || (s->str && s->m.draw != TDS_DRAW_CLIPPED))
    return snap_drawn(ctx, s, version, energy, color, buf, len, NULL, NULL);
  tds_torus_drawn view; /* as drawn: no edge across the cell */
  int rc = tds_torus_view(ctx, s, &view);
  if (rc != TDS_OK) return rc;
  rc = snap_drawn(ctx, &view.s, version, energy, color, buf, len, s, &view);
  tds_torus_view_free(&view);
  return rc;
}
