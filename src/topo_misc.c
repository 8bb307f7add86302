/* topo_misc.c: dissolve and reverse_orientation. */
#include "torus.h"
#include "topo_edit.h"

#include <stdlib.h>

#include "snap.h"

static int dissolve(tds_ctx *ctx, tds_surf *s, int kind, const uint8_t *sel, int32_t *n) {
  tds_mesh *m = &s->m;
  int32_t cnt = 0;
  uint8_t *used = NULL;
  if (kind == TDS_VERTEX || kind == TDS_BODY) {
    int32_t ns = kind == TDS_VERTEX ? m->nv : m->nb;
    used = tds_calloc(&m->alloc, (size_t)ns + 1, 1);
    if (!used) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    if (kind == TDS_VERTEX) {
      for (tds_id e = 0; e < m->ne; e++)
        if (tds_alive(m->eflags, e)) used[m->ev[e][0]] = used[m->ev[e][1]] = 1;
    } else {
      for (tds_id f = 0; f < m->nf; f++)
        if (tds_alive(m->fflags, f))
          for (int q = 0; q < 2; q++)
            if (m->fb[f][q] != TDS_NONE) used[m->fb[f][q]] = 1;
    }
  }
  int32_t nslot = kind == TDS_VERTEX ? m->nv : kind == TDS_EDGE ? m->ne :
                  kind == TDS_FACET ? m->nf : m->nb;
  const uint32_t *fl = kind == TDS_VERTEX ? m->vflags : kind == TDS_EDGE ? m->eflags :
                       kind == TDS_FACET ? m->fflags : m->bflags;
  for (tds_id i = 0; i < nslot; i++) {
    if (!tds_alive(fl, i) || (sel && !sel[i])) continue;
    int ok;
    switch (kind) {
    case TDS_VERTEX: ok = !used[i]; break;
    case TDS_EDGE: ok = m->eside[i] == TDS_NONE; break;
    case TDS_FACET:
      ok = m->fb[i][0] == TDS_NONE || m->fb[i][1] == TDS_NONE || m->fb[i][0] == m->fb[i][1];
      break;
    default: ok = !used[i];
    }
    if (!ok) continue;
    tds_mesh_kill(m, kind, i);
    cnt++;
  }
  tds_free(&m->alloc, used);
  *n = cnt;
  return tds_surf_update(ctx, s);
}

static int reverse(tds_ctx *ctx, tds_surf *s, int kind, const uint8_t *sel, int32_t *n) {
  tds_mesh *m = &s->m;
  int32_t cnt = 0;
  if (kind == TDS_FACET) {
    for (tds_id f = 0; f < m->nf; f++) {
      if (!tds_alive(m->fflags, f) || (sel && !sel[f])) continue;
      int32_t oe[3];
      for (int k = 0; k < 3; k++) {
        int32_t o = m->fe[f][2 - k];
        oe[k] = TDS_OREF(TDS_OID(o), !TDS_OREV(o));
      }
      tds_mesh_set_facet(m, f, oe);
      tds_id b = m->fb[f][0];
      m->fb[f][0] = m->fb[f][1];
      m->fb[f][1] = b;
      cnt++;
    }
  } else {
    for (tds_id e = 0; e < m->ne; e++) {
      if (!tds_alive(m->eflags, e) || (sel && !sel[e])) continue;
      tds_id t = m->ev[e][0];
      m->ev[e][0] = m->ev[e][1];
      m->ev[e][1] = t;
      m->eflags[e] ^= TDS_CONREV;
      int32_t h = m->eside[e], sd = h;
      if (h != TDS_NONE) do {
        int32_t *o = &m->fe[sd / 3][sd % 3];
        *o = TDS_OREF(e, !TDS_OREV(*o));
        sd = m->side_next[sd];
      } while (sd != h);
      cnt++;
    }
  }
  if (cnt) m->topo_gen++;
  *n = cnt;
  return tds_surf_update(ctx, s);
}

typedef int (*kind_fn)(tds_ctx *, tds_surf *, int, const uint8_t *, int32_t *);

static int snap_run(tds_ctx *ctx, tds_surf *s, kind_fn fn, int kind, const uint8_t *sel,
                    int32_t *n) {
  if (n) *n = 0;
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  int32_t cnt = 0;
  rc = tds_snap_end(ctx, s, &sn, fn(ctx, s, kind, sel, &cnt));
  if (n) *n = rc == TDS_OK ? cnt : 0;
  return rc;
}

int tds_dissolve(tds_ctx *ctx, tds_surf *s, int kind, const uint8_t *sel, int32_t *n) {
  return snap_run(ctx, s, dissolve, kind, sel, n);
}

int tds_reverse_orientation(tds_ctx *ctx, tds_surf *s, int kind, const uint8_t *sel,
                            int32_t *n) {
  if (kind != TDS_EDGE && kind != TDS_FACET)
    return tds_seterr(ctx, TDS_ERANGE, "reverse_orientation works on edges and facets");
  return snap_run(ctx, s, reverse, kind, sel, n);
}
