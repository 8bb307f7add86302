/* topo_vavg.c: vertex averaging (the V command): the driver and tds's
** centroid rule (Evolver's rule is in topo_vavg_ev.c). */
#include "torus.h"
#include "topo.h"

#include <stdlib.h>
#include <string.h>

#include "gather.h"
#include "geom.h"
#include "motion.h"
#include "snap.h"
#include "string_model.h"

/* Mean of the neighbours of v along its "curve" edges (triple edges, or
** edges on the same constraints when v is on a contact line), if there are
** exactly two; 0 if v should not move. */
static int along_curve(const tds_mesh *m, tds_id v, int triple, double out[3]) {
  tds_corners nb[2]; /* the two edges from v: x[1] is the neighbour */
  int n = 0;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++) {
    tds_id e = TDS_OID(m->ve[i]);
    int val = tds_edge_valence(m, e);
    int on = triple ? val >= 3 : (m->econ[e] == m->vcon[v] && val <= 1);
    if (!on) continue;
    if (n == 2) return 0;
    tds_gather_edge(m, m->ve[i], &nb[n++]);
  }
  if (n != 2) return 0;
  v3_add(out, nb[0].x[1], nb[1].x[1]);
  v3_scale(out, 0.5);
  return 1;
}

/* Area-weighted mean of the centroids of v's facets that share its
** constraints, with the component along their summed normal removed. */
static int over_facets(const tds_mesh *m, tds_id v, double out[3]) {
  double sum[3] = {0, 0, 0}, nsum[3] = {0, 0, 0}, wsum = 0;
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    if (m->fcon[f] != m->vcon[v]) continue;
    double P[3][3]; /* the facet in v's frame (v's copy on a torus) */
    tds_torus_facet_at(m, f, tds_facet_corner(m, f, v), P);
    const double *a = P[0], *b = P[1], *c = P[2];
    double ab[3], ac[3], N[3];
    v3_sub(ab, b, a);
    v3_sub(ac, c, a);
    v3_cross(N, ab, ac);
    double A = 0.5 * v3_norm(N);
    for (int k = 0; k < 3; k++) sum[k] += A * (a[k] + b[k] + c[k]) / 3;
    wsum += A;
    v3_add(nsum, nsum, N);
  }
  if (wsum <= 0) return 0;
  double d[3];
  for (int k = 0; k < 3; k++) d[k] = sum[k] / wsum - m->x[v][k];
  double nn = v3_dot(nsum, nsum);
  if (nn > 0) v3_axpy(d, -v3_dot(d, nsum) / nn, nsum);
  v3_add(out, m->x[v], d);
  return 1;
}

/* Where vertex v goes by the chosen rule (0: it stays). g: scratch. */
static int target(const tds_surf *s, tds_id v, int mode, double *g,
                  int32_t *ord, double out[3]) {
  const tds_mesh *m = &s->m;
  if (s->str) /* the string model's rules */
    return mode == TDS_VAVG_RAW || mode == TDS_VAVG_RAWEST ? tds_strings_rawv(s, v, out)
                                                           : tds_strings_vavg(s, v, out);
  if (mode != TDS_VAVG_CENTROID) return tds_vavg_target(s, v, mode, g, ord, out);
  int triple = 0, border = 0;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++) {
    int val = tds_edge_valence(m, TDS_OID(m->ve[i]));
    triple |= val >= 3;
    border |= val <= 1;
  }
  if (triple) return along_curve(m, v, 1, out);
  if (border) return m->vcon[v] ? along_curve(m, v, 0, out) : 0;
  return over_facets(m, v, out);
}

static int vertex_average(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                          int mode, int seq, int32_t *nmoved) {
  tds_mesh *m = &s->m;
  if (tds_mesh_adjacency(m) != TDS_OK)
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  int32_t maxdeg = 1, maxf = 1;
  for (tds_id v = 0; v < m->nv; v++) {
    if (m->ve_start[v + 1] - m->ve_start[v] > maxdeg) maxdeg = m->ve_start[v + 1] - m->ve_start[v];
    if (m->vf_start[v + 1] - m->vf_start[v] > maxf) maxf = m->vf_start[v + 1] - m->vf_start[v];
  }
  size_t nv = (size_t)(m->nv > 0 ? m->nv : 1);
  double (*nx)[3] = tds_malloc(&s->m.alloc, nv * sizeof *nx);
  uint8_t *mv = tds_calloc(&s->m.alloc, nv, 1);
  double *g = tds_malloc(&s->m.alloc, (size_t)maxdeg * sizeof *g);
  int32_t *ord = tds_malloc(&s->m.alloc, (size_t)maxf * sizeof *ord);
  if (!nx || !mv || !g || !ord) {
    tds_free(&s->m.alloc, nx);
    tds_free(&s->m.alloc, mv);
    tds_free(&s->m.alloc, g);
    tds_free(&s->m.alloc, ord);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int32_t moved = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_vertex_free(s, v) || (sel && !sel[v]) || m->vbdry[v] != TDS_NONE)
      continue;
    mv[v] = (uint8_t)target(s, v, mode, g, ord, nx[v]);
    if (seq && mv[v]) { /* Evolver's vertex_average: move it now */
      v3_copy(m->x[v], nx[v]);
      tds_motion_enforce(s, v);
      mv[v] = 0;
      moved++;
    }
  }
  for (tds_id v = 0; v < m->nv; v++)
    if (mv[v]) {
      v3_copy(m->x[v], nx[v]);
      tds_motion_enforce(s, v);
      moved++;
    }
  tds_free(&s->m.alloc, nx);
  tds_free(&s->m.alloc, mv);
  tds_free(&s->m.alloc, g);
  tds_free(&s->m.alloc, ord);
  m->coord_gen++;
  if (nmoved) *nmoved = moved;
  return tds_surf_update(ctx, s);
}

/* All or nothing: a move that makes the energy non-finite is taken back. */
int tds_vertex_average_mode(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                            int mode, int seq, int32_t *nmoved) {
  if (mode < TDS_VAVG_V || mode > TDS_VAVG_CENTROID)
    return tds_seterr(ctx, TDS_ERANGE, "vertex_average: unknown rule %d", mode);
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  return tds_snap_end(ctx, s, &sn, vertex_average(ctx, s, sel, mode, seq, nmoved));
}

int tds_vertex_average(tds_ctx *ctx, tds_surf *s, const uint8_t *sel,
                       int32_t *nmoved) {
  return tds_vertex_average_mode(ctx, s, sel, TDS_VAVG_V, 0, nmoved);
}
