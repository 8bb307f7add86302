/* newton_vnorm.c: one vertex's hessian normal (newton.h,
** tds_vertex_normal_at): the rule of tds_vertex_normals (newton_norm.c)
** on the vertex's star from the adjacency, so reading the normal of
** every vertex costs its degree each, not the whole mesh. */
#include <math.h>
#include <string.h>

#include "newton.h"
#include "newton_int.h"
#include "vec3.h"

static void area_vec(const tds_mesh *m, tds_id f, double c[3]) {
  const tds_id *fv = m->fv[f];
  double a[3], b[3];
  v3_sub(a, m->x[fv[1]], m->x[fv[0]]);
  v3_sub(b, m->x[fv[2]], m->x[fv[0]]);
  v3_cross(c, a, b);
  v3_scale(c, 0.5);
}

int tds_vertex_normal_at(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_id v,
                         double n[3]) {
  if (s->str) return tds_string_vertex_normal(ctx, s, o, v, n);
  tds_mesh *m = &s->m;
  n[0] = n[1] = n[2] = 0;
  if (tds_mesh_adjacency(m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "vertex_normal: out of memory");
  const int32_t *fs = m->vf + m->vf_start[v], *es = m->ve + m->ve_start[v];
  int32_t nf = m->vf_start[v + 1] - m->vf_start[v], ne = m->ve_start[v + 1] - m->ve_start[v];
  if (nf == 0) return TDS_OK;
  vnorm w;
  memset(&w, 0, sizeof w);
  w.nf = nf;
  for (int32_t i = 0; i < nf; i++) {
    double c[3];
    area_vec(m, fs[i], c);
    v3_add(w.an, w.an, c);
  }
  /* the facets spread (any beyond 30 degrees of the plain sum): the
  ** running sum in Evolver's order */
  double l = v3_norm(w.an), P[6] = {0, 0, 0, 0, 0, 0};
  int bad = !(l > 0);
  for (int32_t i = 0; i < nf && !bad; i++) {
    double c[3];
    area_vec(m, fs[i], c);
    if (!(v3_dot(c, w.an) >= 0.8660254037844386 * v3_norm(c) * l)) bad = 1;
  }
  if (bad) {
    tds_id emin = tds_vertex_min_edge(m, v);
    tds_fkey *a = tds_malloc(&ctx->alloc, (size_t)nf * sizeof *a);
    if (!a) return tds_seterr(ctx, TDS_ENOMEM, "vertex_normal: out of memory");
    for (int32_t i = 0; i < nf; i++) {
      tds_id f = fs[i];
      int k = tds_facet_corner(m, f, v);
      a[i] = (tds_fkey){tds_star_key(m, f, k, emin), f, k};
    }
    tds_evolver_sum(m, a, nf, w.an);
    tds_free(&ctx->alloc, a);
  }
  /* triple junction lines through v, as tds_vertex_normals counts them */
  for (int32_t i = 0; i < ne; i++) {
    tds_id e = TDS_OID(es[i]);
    if (tds_edge_valence(m, e) < 3) continue;
    double d[3];
    v3_sub(d, m->x[m->ev[e][1]], m->x[m->ev[e][0]]);
    double len = v3_norm(d);
    if (!(len > 0)) continue;
    v3_scale(d, 1 / len);
    if (w.nt) {
      double dot = v3_dot(d, w.td) / v3_norm(w.td);
      if (fabs(dot) < 0.5) w.bent = 1;
      v3_axpy(w.td, dot < 0 ? -1 : 1, d);
    } else {
      v3_copy(w.td, d);
    }
    w.nt++;
  }
  if (o->normal_one) {
    for (int32_t i = 0; i < nf; i++) {
      double c[3];
      area_vec(m, fs[i], c);
      tds_unit_nnt(c, P);
    }
    double e[3];
    if (tds_lead_eig(P, w.an, e)) {
      v3_copy(w.an, e);
      w.nt = w.bent = 0;
    }
  }
  if (o->special_normal && !w.nt) {
    if (!s->special_normal[0])
      return tds_seterr(ctx, TDS_ERANGE, "hessian_special_normal is on but the datafile has no "
                        "HESSIAN_SPECIAL_NORMAL_VECTOR");
    int rc = tds_special_at(ctx, s, v, w.an);
    if (rc != TDS_OK) return rc;
  }
  /* the first direction of the normal space (its only one off triple
  ** junctions); the whole space: (1, 0, 0) */
  static const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double W[3][3];
  tds_normal_columns(&w, I, 3, 0, W);
  for (int i = 0; i < 3; i++) n[i] = W[i][0];
  return TDS_OK;
}
