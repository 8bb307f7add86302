/* autopop.c: autopop and autochop, the mesh maintenance g does itself. */
#include "autopop.h"

#include <math.h>
#include <stdlib.h>

#include "string_model.h"
#include "topo_edit.h"
#include "vec3.h"

/* Where vertex v will be after the move. */
static void moved(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                  tds_id v, double out[3]) {
  v3_copy(out, m->x[v]);
  if (v < nvel) v3_axpy(out, dt, vel[v]);
}

/* Edge e shortens in the move to below L? */
static int short_edge(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                      tds_id e, double L) {
  double a[3], b[3], d[3], d0[3];
  moved(m, vel, nvel, dt, m->ev[e][0], a);
  moved(m, vel, nvel, dt, m->ev[e][1], b);
  v3_sub(d, b, a);
  v3_sub(d0, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
  double l1 = v3_norm(d);
  return l1 < L && l1 < v3_norm(d0);
}

static double new_length(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                         tds_id e) {
  double a[3], b[3], d[3];
  moved(m, vel, nvel, dt, m->ev[e][0], a);
  moved(m, vel, nvel, dt, m->ev[e][1], b);
  v3_sub(d, b, a);
  return v3_norm(d);
}

/* Facet f shrinks in the move to an area below L * perimeter / 2? */
static int small_facet(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                       tds_id f, double L) {
  double p[3][3], u[3], w[3], n[3], per = 0, a0;
  v3_sub(u, m->x[m->fv[f][1]], m->x[m->fv[f][0]]);
  v3_sub(w, m->x[m->fv[f][2]], m->x[m->fv[f][0]]);
  v3_cross(n, u, w);
  a0 = 0.5 * v3_norm(n);
  for (int k = 0; k < 3; k++) moved(m, vel, nvel, dt, m->fv[f][k], p[k]);
  for (int k = 0; k < 3; k++) {
    v3_sub(u, p[(k + 1) % 3], p[k]);
    per += v3_norm(u);
  }
  v3_sub(u, p[1], p[0]);
  v3_sub(w, p[2], p[0]);
  v3_cross(n, u, w);
  double a1 = 0.5 * v3_norm(n);
  return a1 < L * per / 2 && a1 < a0;
}

int tds_autopop(tds_ctx *ctx, tds_surf *s, const double (*vel)[3], int32_t nvel,
                double dt, int *changed) {
  tds_mesh *m = &s->m;
  *changed = 0;
  if (!(dt > 0)) return TDS_OK;
  double L = sqrt(2 * dt);
  int32_t ne0 = m->ne, nf0 = m->nf, cnt = 0;
  uint8_t *flag = NULL;
  if (!s->immediate_autopop) { /* find all first */
    flag = tds_calloc(&m->alloc, (size_t)(ne0 + nf0 + 1), 1);
    if (!flag) return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autopop");
    for (tds_id e = 0; e < ne0; e++)
      flag[e] = tds_alive(m->eflags, e) && short_edge(m, vel, nvel, dt, e, L);
    for (tds_id f = 0; f < nf0; f++)
      flag[ne0 + f] = tds_alive(m->fflags, f) && small_facet(m, vel, nvel, dt, f, L);
  }
  for (tds_id e = 0; e < ne0; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    if (flag ? !flag[e] : !short_edge(m, vel, nvel, dt, e, L)) continue;
    cnt += tds_collapse_edge(s, e);
  }

  for (tds_id f = 0; f < nf0; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    if (flag ? !flag[ne0 + f] : !small_facet(m, vel, nvel, dt, f, L)) continue;
    int r = tds_delete_facet_raw(s, f);
    if (r < 0) {
      tds_free(&m->alloc, flag);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autopop");
    }
    cnt += r;
  }
  tds_free(&m->alloc, flag);
  if (!cnt) return TDS_OK;
  *changed = 1;
  int32_t pe = 0, pv = 0;
  if (s->str) { /* strings: split the vertices where four or more edges meet */
    int rc = tds_strings_pop(ctx, s, NULL, &pv);
    if (rc != TDS_OK) return rc;
    tds_printf(ctx, "Autopopped %d edges, %d vertices.\n", cnt, pv);
    return tds_surf_update(ctx, s);
  }
  int rc = tds_pop_raw(ctx, s, &pe, &pv);
  if (rc != TDS_OK) return rc;
  tds_printf(ctx, "Edges popped: %d\nAutopopped %d edges, %d vertices.\n", pe, cnt, pv);
  return tds_surf_update(ctx, s);
}

int tds_autochop(tds_ctx *ctx, tds_surf *s, const double (*vel)[3], int32_t nvel,
                 double dt, double len, int32_t **ends, int *changed) {
  tds_mesh *m = &s->m;
  *changed = 0;
  *ends = NULL;
  int32_t ne0 = m->ne, cnt = 0;
  for (tds_id e = 0; e < ne0; e++)
    cnt += tds_alive(m->eflags, e) && new_length(m, vel, nvel, dt, e) > len;
  if (!cnt) return TDS_OK;
  int32_t *en = tds_malloc(&m->alloc, (size_t)(2 * cnt) * sizeof *en);
  if (!en) return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autochop");
  cnt = 0;
  for (tds_id e = 0; e < ne0; e++) {
    if (!tds_alive(m->eflags, e) || !(new_length(m, vel, nvel, dt, e) > len)) continue;
    en[2 * cnt] = m->ev[e][0];
    en[2 * cnt + 1] = m->ev[e][1];
    if (tds_split_edge_raw(s, e) != TDS_OK) {
      tds_free(&m->alloc, en);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autochop");
    }
    cnt++;
  }
  *ends = en;
  if (!cnt) return TDS_OK;
  *changed = 1;
  m->coord_gen++;
  tds_printf(ctx, "Autochopped %d edges.\n", cnt);
  return tds_surf_update(ctx, s);
}
