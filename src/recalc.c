/* recalc.c: re-place vertices from parameters (contracts in recalc.h). */
#include "torus.h"
#include "recalc.h"

#include <stdlib.h>
#include <string.h>

#include "motion.h"

int tds_recalc(tds_ctx *ctx, tds_surf *s) {
  tds_mesh *m = &s->m;
  int32_t nv = m->nv;
  double (*x0)[3] = tds_malloc(&s->m.alloc, (size_t)(nv > 0 ? nv : 1) * sizeof *x0);
  double (*p0)[2] = tds_malloc(&s->m.alloc, (size_t)(nv > 0 ? nv : 1) * sizeof *p0);
  if (!x0 || !p0) {
    tds_free(&s->m.alloc, x0);
    tds_free(&s->m.alloc, p0);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  if (nv > 0) {
    memcpy(x0, m->x, (size_t)nv * sizeof *x0);
    memcpy(p0, m->vp, (size_t)nv * sizeof *p0);
  }
  tds_id bad = TDS_NONE;
  for (tds_id v = 0; v < nv && bad == TDS_NONE; v++)
    if (tds_alive(m->vflags, v) && tds_motion_enforce(s, v) != TDS_OK) bad = v;
  /* the torus's PERIODS formulas (torus.h); checked before they change */
  int prc = bad == TDS_NONE && m->torus ? tds_torus_periods(ctx, s) : TDS_OK;
  if (bad != TDS_NONE || prc != TDS_OK) {
    memcpy(m->x, x0, (size_t)nv * sizeof *x0);
    memcpy(m->vp, p0, (size_t)nv * sizeof *p0);
  }
  tds_free(&s->m.alloc, x0);
  tds_free(&s->m.alloc, p0);
  if (prc != TDS_OK) return prc;
  if (bad != TDS_NONE)
    return tds_seterr(ctx, TDS_ENUM,
                      "recalc: vertex %d cannot be placed on its %s with the "
                      "current parameters; nothing was moved",
                      bad + 1, m->vbdry[bad] != TDS_NONE ? "boundary" : "constraints");
  m->coord_gen++;
  s->placed_gen = s->param_gen;
  return tds_surf_update(ctx, s);
}

int tds_recalc_if_stale(tds_ctx *ctx, tds_surf *s) {
  return s->placed_gen == s->param_gen ? TDS_OK : tds_recalc(ctx, s);
}
