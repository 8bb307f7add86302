/* newton_strnorm.c: the vertices' normal spaces of hessian_normal in the
** string model (newton_int.h, tds_string_normals), and the choice
** between it and the soap film's rule (tds_hess_normals).
**
** What evolver-nox-d 2.70 does, measured on small networks (its ritz
** eigenvalues and Eigencounts, its vertex_normal attribute; compared in
** tests/evolver/string_hessian.sh):
**   2-D space: an edge's normal is its vector (tail to head, as stored)
**     turned a quarter counterclockwise, (-dy, dx). A vertex with two
**     edges moves along the normal of its chord (the sum of its edges'
**     normals taken along the string: the second one's negated when both
**     edges end, or both start, at the vertex), signed by its lowest
**     edge; a vertex with one edge along that edge's normal; a vertex
**     where three or more edges meet moves in the whole plane.
**     hessian_normal_one: every vertex with edges, junctions too, moves
**     along 19 steps of the power iteration on sum c c^T (c the edges'
**     normals, not made unit) from its lowest edge's normal: exactly
**     Evolver's direction at a vertex with two edges, 1e-8 from it at a
**     junction.
**   3-D space: a vertex with one or two edges moves in the plane across
**     its chord (its edge); a junction moves freely. hessian_normal_one
**     is refused, as Evolver refuses it.
**   hessian_special_normal: every vertex with edges, junctions too,
**     moves along the datafile's vector.
** In 2-D space nothing moves off the plane, with or without the normal. */
#include <string.h>

#include "newton_int.h"
#include "string_model.h"
#include "gather.h"
#include "vec3.h"

/* Stored edge e's vector (tail to head, unwrapped), seen from v's copy. */
static void edge_vec_at(const tds_mesh *m, tds_id e, tds_id v, double out[3]) {
  tds_corners C;
  double d[3];
  tds_gather_edge(m, TDS_OREF(e, 0), &C);
  v3_sub(d, C.x[1], C.x[0]);
  const double *r = tds_norm_seen_from(m, TDS_NONE, e, m->ev[e][0] == v ? 0 : 1, d, out);
  if (r != out) v3_copy(out, r);
}

/* Vertex v's normal data (adjacency current) into w, zeroed first.
** flat: the normal in the xy plane; otherwise the plane across the
** string. */
static void one_vertex(const tds_mesh *m, tds_id v, int flat, int normal_one, vnorm *w) {
  memset(w, 0, sizeof *w);
  w->flat = flat;
  if (m->vflags[v] & TDS_DEAD) return;
  const int32_t *es = m->ve + m->ve_start[v];
  int32_t ne = m->ve_start[v + 1] - m->ve_start[v];
  if (ne == 0) return; /* no normal: the whole motion space */
  if (ne >= 3 && !normal_one) {
    w->full = 1;
    return;
  }
  /* the edges in Evolver's order: the lowest id first, then the others
  ** downwards (only the first matters below) */
  int32_t first = 0;
  for (int32_t i = 1; i < ne; i++)
    if (TDS_OID(es[i]) < TDS_OID(es[first])) first = i;
  double S[3] = {0, 0, 0}, P[3][3] = {{0}}, c0[3] = {0, 0, 0};
  for (int32_t j = 0; j < ne; j++) {
    int32_t i = j == 0 ? first : j == first ? 0 : j;
    tds_id e = TDS_OID(es[i]);
    if (m->ev[e][0] == m->ev[e][1]) continue; /* a loop: no direction */
    double d[3], c[3];
    edge_vec_at(m, e, v, d);
    if (flat) { /* the edge's normal: its vector turned counterclockwise */
      c[0] = -d[1];
      c[1] = d[0];
      c[2] = 0;
    } else {
      v3_copy(c, d);
    }
    if (j == 0) v3_copy(c0, c);
    /* along the string: + where the edge continues the first one (one
    ** ends at v, the other starts there), - where both end or start */
    int tail = m->ev[e][0] == v, tail0 = m->ev[TDS_OID(es[first])][0] == v;
    v3_axpy(S, j == 0 || tail != tail0 ? 1 : -1, c);
    for (int r = 0; r < 3; r++)
      for (int q = 0; q < 3; q++) P[r][q] += c[r] * c[q];
  }
  if (normal_one) { /* Evolver's: 19 steps of the power iteration on
                    ** sum c c^T from the first edge's normal */
    v3_copy(S, c0);
    for (int it = 0; it < 19 && v3_norm(S) > 0; it++) {
      double y[3];
      for (int r = 0; r < 3; r++) y[r] = P[r][0] * S[0] + P[r][1] * S[1] + P[r][2] * S[2];
      v3_copy(S, y);
      v3_scale(S, 1 / v3_norm(S));
    }
  }
  if (!(v3_norm(S) > 0)) return; /* edges of no length */
  w->nf = ne;
  if (flat) {
    v3_copy(w->an, S);
  } else { /* the plane across the string's direction */
    v3_copy(w->td, S);
    w->nt = 1;
  }
}

int tds_string_normals(tds_ctx *ctx, tds_surf *s, int normal_one, vnorm *vn) {
  tds_mesh *m = &s->m;
  int flat = s->str->space_dim == 2;
  if (tds_mesh_adjacency(m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
  for (tds_id v = 0; v < m->nv; v++) one_vertex(m, v, flat, normal_one, &vn[v]);
  return TDS_OK;
}

int tds_string_vertex_normal(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_id v,
                             double n[3]) {
  tds_mesh *m = &s->m;
  n[0] = n[1] = n[2] = 0;
  if (tds_mesh_adjacency(m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "vertex_normal: out of memory");
  vnorm w;
  one_vertex(m, v, 1, o->normal_one && s->str->space_dim == 2, &w);
  if (o->special_normal && (w.nf || w.full)) {
    if (!s->special_normal[0])
      return tds_seterr(ctx, TDS_ERANGE, "hessian_special_normal is on but the datafile has no "
                        "HESSIAN_SPECIAL_NORMAL_VECTOR");
    int rc = tds_special_at(ctx, s, v, w.an);
    if (rc != TDS_OK) return rc;
    w.nf = 1;
    w.full = 0;
  }
  w.flat = 0; /* the attribute keeps the special vector's z */
  double W[3][3];
  static const double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tds_normal_columns(&w, I, 3, 0, W);
  for (int i = 0; i < 3; i++) n[i] = W[i][0];
  return TDS_OK;
}

/* hessian_special_normal in the string model: every vertex with edges,
** junctions too (as Evolver: on a 3-D string it leaves one unknown at
** each, measured), moves along the datafile's vector at its place. */
static int string_special(tds_ctx *ctx, const tds_surf *s, vnorm *vn) {
  const tds_mesh *m = &s->m;
  if (!s->special_normal[0])
    return tds_seterr(ctx, TDS_ERANGE, "hessian_special_normal is on but the datafile has no "
                      "HESSIAN_SPECIAL_NORMAL_VECTOR");
  for (tds_id v = 0; v < m->nv; v++) {
    vnorm *w = &vn[v];
    if ((m->vflags[v] & TDS_DEAD) || !(w->nf || w->full)) continue;
    int rc = tds_special_at(ctx, s, v, w->an);
    if (rc != TDS_OK) return rc;
    w->nf = 1;
    w->nt = w->full = 0;
  }
  return TDS_OK;
}

int tds_hess_normals(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, vnorm *vn) {
  if (s->str) {
    if (o->normal && o->normal_one && s->str->space_dim != 2)
      return tds_seterr(ctx, TDS_ERANGE, "hessian_normal_one works in the soap film model and in "
                        "the string model in 2-D space only (as in Evolver): turn it off "
                        "(hessian_normal_one off) for a string in 3-D space");
    int rc = tds_string_normals(ctx, s, o->normal && o->normal_one, vn);
    if (rc == TDS_OK && o->normal && o->special_normal) rc = string_special(ctx, s, vn);
    return rc;
  }
  if (tds_vertex_normals(&ctx->alloc, &s->m, vn) != TDS_OK ||
      (o->normal && o->normal_one && tds_normals_one(&ctx->alloc, &s->m, vn) != TDS_OK))
    return tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
  if (o->normal && o->special_normal) return tds_special_normals(ctx, s, vn);
  return TDS_OK;
}
