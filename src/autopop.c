/* autopop.c: autopop and autochop, the mesh maintenance g does itself. */
#include "autopop.h"

#include <math.h>
#include <stdlib.h>

#include "string_model.h"
#include "topo_edit.h"
#include "torus.h"
#include "wrap.h"
#include "vec3.h"

/* Where vertex v will be after the move. */
static void moved(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                  tds_id v, double out[3]) {
  v3_copy(out, m->x[v]);
  if (v < nvel) v3_axpy(out, dt, vel[v]);
}

/* Edge e's vector after the move (unwrapped: torus wraps count), and
** before it in d0 if not NULL. */
static void moved_edge(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                       tds_id e, double d[3], double d0[3]) {
  double a[3], b[3], w[3] = {0, 0, 0};
  if (m->ewrap && m->ewrap[e]) tds_wrap_vec(m->period, m->ewrap[e], w);
  moved(m, vel, nvel, dt, m->ev[e][0], a);
  moved(m, vel, nvel, dt, m->ev[e][1], b);
  v3_sub(d, b, a);
  v3_add(d, d, w);
  if (d0) {
    v3_sub(d0, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
    v3_add(d0, d0, w);
  }
}

/* Edge e is shorter than L after the move and still shortening at its
** end: (d0 + dt dv) . dv < 0 with d0 the edge before and d after. Measured
** against Evolver on cat.fe's pinched neck (r; u; g 120) at fixed scales
** from 5e-4 to 0.05: its neck edges shorten in the move up to scale
** 0.0045 but stop shortening before its end from 0.0027 on, and Evolver
** pops them exactly up to 0.0026. */
static int short_edge(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                      tds_id e, double L) {
  double d[3], d0[3], dd[3];
  moved_edge(m, vel, nvel, dt, e, d, d0);
  v3_sub(dd, d, d0);
  return v3_norm(d) < L && v3_dot(d, dd) < 0;
}

static double new_length(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                         tds_id e) {
  double d[3];
  moved_edge(m, vel, nvel, dt, e, d, NULL);
  return v3_norm(d);
}

/* Facet f has an area below L * perimeter / 4 after the move and is still
** shrinking at its end (n . dn/dt < 0 for the normal n = u x w there).
** Evolver's manual says perimeter / 2; what it does is / 4 (measured: on
** cat.fe's neck it leaves the facets of area 0.15 and perimeter 2.3
** alone up to scale 0.03 and pops at 0.04; on cube.fe refined three
** times and evolved, immediate_autopop at scale 5e-4 leaves Evolver's
** counts exactly, where / 2 removes half the surface). */
static int small_facet(const tds_mesh *m, const double (*vel)[3], int32_t nvel, double dt,
                       tds_id f, double L) {
  double p[3][3], u[3], w[3], du[3], dw[3], n[3], c[3], dn[3], per = 0;
  for (int k = 0; k < 3; k++) moved(m, vel, nvel, dt, m->fv[f][k], p[k]);
  for (int k = 0; k < 3; k++) {
    v3_sub(u, p[(k + 1) % 3], p[k]);
    per += v3_norm(u);
  }
  v3_sub(u, p[1], p[0]);
  v3_sub(w, p[2], p[0]);
  v3_cross(n, u, w);
  /* the edge vectors' rates: dt * (their change over the move) */
  v3_sub(du, u, m->x[m->fv[f][1]]);
  v3_add(du, du, m->x[m->fv[f][0]]);
  v3_sub(dw, w, m->x[m->fv[f][2]]);
  v3_add(dw, dw, m->x[m->fv[f][0]]);
  v3_cross(dn, du, w);
  v3_cross(c, u, dw);
  v3_add(dn, dn, c);
  return 0.5 * v3_norm(n) < L * per / 4 && v3_dot(n, dn) < 0;
}

/* How many live edges end at v (a loop counts twice). */
static int valence(const tds_mesh *m, tds_id v) {
  int k = 0;
  for (tds_id d = 0; d < m->ne; d++)
    if (tds_alive(m->eflags, d)) k += (m->ev[d][0] == v) + (m->ev[d][1] == v);
  return k;
}

/* Append the motion rule (dst, a, b) to *mix (3 ints each). */
static int mix_add(tds_mesh *m, int32_t **mix, int32_t *nmix, int32_t *cap, tds_id dst,
                   tds_id a, tds_id b) {
  if (*nmix == *cap) {
    int32_t nc = *cap ? 2 * *cap : 16;
    int32_t *p = tds_realloc(&m->alloc, *mix, (size_t)nc * 3 * sizeof *p);
    if (!p) return -1;
    *mix = p;
    *cap = nc;
  }
  (*mix)[3 * *nmix] = dst;
  (*mix)[3 * *nmix + 1] = a;
  (*mix)[3 * *nmix + 2] = b;
  (*nmix)++;
  return 0;
}

int tds_autopop(tds_ctx *ctx, tds_surf *s, const double (*vel)[3], int32_t nvel,
                double dt, int32_t **mixp, int32_t *nmixp, int32_t *deferred, int *changed) {
  tds_mesh *m = &s->m;
  *changed = 0;
  *deferred = 0;
  *mixp = NULL;
  *nmixp = 0;
  int32_t *mix = NULL, nmix = 0, cap = 0;
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
    /* strings (Evolver's choices, measured on 100grain.fe): an end
    ** where only two edges meet goes and the other stays where it is;
    ** otherwise (two junctions, or two ends of two edges each: a
    ** vanishing cell's last edge) the tail stays at the midpoint and
    ** moves with the mean of both ends' motions. Films: the midpoint,
    ** as t. */
    int end = -1;
    tds_id t = m->ev[e][0], h = m->ev[e][1];
    if (s->str) {
      int vt = valence(m, t), vh = valence(m, h);
      if ((vt == 2) != (vh == 2)) end = vt != 2 ? 0 : 1;
    }
    int r = tds_collapse_edge_at(s, e, end);
    if (r > 0 && s->str && end < 0 && mix_add(m, &mix, &nmix, &cap, t, t, h)) r = -1;
    if (r < 0) {
      tds_free(&m->alloc, flag);
      tds_free(&m->alloc, mix);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autopop");
    }
    cnt += r;
  }

  for (tds_id f = 0; f < nf0; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    if (flag ? !flag[ne0 + f] : !small_facet(m, vel, nvel, dt, f, L)) continue;
    int r = tds_delete_facet_raw(s, f);
    if (r < 0) {
      tds_free(&m->alloc, flag);
      tds_free(&m->alloc, mix);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autopop");
    }
    cnt += r;
  }
  tds_free(&m->alloc, flag);
  if (!cnt) {
    tds_free(&m->alloc, mix);
    return TDS_OK;
  }
  *changed = 1;
  if (s->str) { /* Evolver pops after the step's move (tds_autopop_pop) */
    *mixp = mix;
    *nmixp = nmix;
    *deferred = cnt;
    return tds_surf_update(ctx, s);
  }
  /* immediate_autopop on films pops no vertices afterwards (Evolver:
  ** cat.fe's collapsed neck stays one vertex where two cones meet, which
  ** o then pops) */
  int32_t pe = 0, pv = 0;
  int rc = s->immediate_autopop ? TDS_OK : tds_pop_raw(ctx, s, &pe, &pv);
  if (rc != TDS_OK) return rc;
  tds_printf(ctx, "Edges popped: %d\nAutopopped %d edges, %d vertices.\n", pe, cnt, pv);
  return tds_surf_update(ctx, s);
}

int tds_autopop_pop(tds_ctx *ctx, tds_surf *s, int32_t cnt) {
  int32_t pv = 0;
  int rc = tds_strings_pop_raw(ctx, s, &pv);
  if (rc != TDS_OK) return rc;
  tds_printf(ctx, "Autopopped %d edges, %d vertices.\n", cnt, pv);
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
  /* the string model: which new edge took each split edge's head half,
  ** for the cells' loops (tds_strings_split) */
  tds_id *half = s->str ? tds_malloc(&m->alloc, (size_t)ne0 * sizeof *half) : NULL;
  if (!en || (s->str && !half)) {
    tds_free(&m->alloc, en);
    tds_free(&m->alloc, half);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autochop");
  }
  for (tds_id e = 0; half && e < ne0; e++) half[e] = TDS_NONE;
  cnt = 0;
  for (tds_id e = 0; e < ne0; e++) {
    if (!tds_alive(m->eflags, e) || !(new_length(m, vel, nvel, dt, e) > len)) continue;
    en[2 * cnt] = m->ev[e][0];
    en[2 * cnt + 1] = m->ev[e][1];
    if (tds_split_edge_raw(s, e) != TDS_OK) {
      tds_free(&m->alloc, en);
      tds_free(&m->alloc, half);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autochop");
    }
    if (half) half[e] = m->ne - 1; /* a cell-less edge: one new edge */
    cnt++;
  }
  int rc = half && cnt ? tds_strings_split(s->str, half, ne0) : TDS_OK;
  tds_free(&m->alloc, half);
  if (rc != TDS_OK) {
    tds_free(&m->alloc, en);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory in autochop");
  }
  if (!cnt) {
    tds_free(&m->alloc, en);
    return TDS_OK;
  }
  *changed = 1;
  m->coord_gen++;
  tds_printf(ctx, "Autochopped %d edges.\n", cnt);
  rc = tds_surf_update(ctx, s);
  if (rc == TDS_OK) *ends = en;
  else tds_free(&m->alloc, en);
  return rc;
}
