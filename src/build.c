/* build.c: building declared faces (polygons split around a centre). */
#include "topo.h"

#include <math.h>
#include <stdlib.h>

#include "gather.h"
#include "motion.h"
#include "vec3.h"

static void apply_attr(tds_mesh *m, tds_id f, tds_id orig,
                       const tds_face_attr *at) {
  m->fflags[f] = at->flags;
  m->fcon[f] = at->con;
  m->ften[f] = at->tension;
  m->fcolor[f] = at->color;
  m->forig[f] = orig;
  m->ffile[f] = orig + 1;
}

int tds_build_face(tds_ctx *ctx, tds_surf *s, tds_id f, int n,
                   const int32_t *oe, const tds_face_attr *at) {
  tds_mesh *m = &s->m;
  if (n < 3) return tds_seterr(ctx, TDS_ETOPO, "face %d has %d edges; at least 3 are needed", f + 1, n);
  for (int k = 0; k < n; k++) {
    tds_id e = TDS_OID(oe[k]);
    if (oe[k] < 0 || e >= m->ne || !tds_alive(m->eflags, e))
      return tds_seterr(ctx, TDS_ERANGE, "face %d refers to edge %d, which does not exist",
                        f + 1, e + 1);
  }
  for (int k = 0; k < n; k++)
    if (tds_oe_head(m, oe[k]) != tds_oe_tail(m, oe[(k + 1) % n]))
      return tds_seterr(ctx, TDS_ETOPO,
                        "face %d: edge %s%d does not end where edge %s%d starts",
                        f + 1, TDS_OREV(oe[k]) ? "-" : "", TDS_OID(oe[k]) + 1,
                        TDS_OREV(oe[(k + 1) % n]) ? "-" : "",
                        TDS_OID(oe[(k + 1) % n]) + 1);
  if (f < m->nf && tds_alive(m->fflags, f))
    return tds_seterr(ctx, TDS_ERANGE, "face %d is declared twice", f + 1);
  /* torus: wrap[k] = where the tail of oe[k] is, unwrapped along the face
  ** from its first vertex; the loop must close (wraps adding up to 0) */
  int32_t wsum = 0;
  if (m->torus) {
    for (int k = 0; k < n; k++) {
      if (!tds_mesh_rotates(m) && tds_wrap_overflows(wsum, tds_oe_wrap(m, oe[k])))
        return tds_seterr(ctx, TDS_ERANGE, "face %d: wraps out of range", f + 1);
      wsum = tds_wrap_mul(m, wsum, tds_oe_wrap(m, oe[k])); /* in order: groups need not commute */
    }
    if (wsum != 0)
      return tds_seterr(ctx, TDS_ETOPO,
                        tds_mesh_rotates(m)
                            ? "face %d: the product of its edges' wraps is not the identity "
                              "(the face does not close in the quotient space)"
                            : "face %d: the wraps of its edges do not add up to zero (the "
                              "face does not close in the torus)",
                        f + 1);
  }
  /* Reserve everything first: nothing below may fail. */
  if (tds_mesh_extend_dead(m, TDS_FACET, f + 1) ||
      tds_mesh_room(m, TDS_FACET, m->nf + (n > 3 ? n - 1 : 0)) ||
      tds_mesh_room(m, TDS_EDGE, m->ne + (n > 3 ? n : 0)) ||
      tds_mesh_room(m, TDS_VERTEX, m->nv + 1))
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  tds_mesh_claim(m, TDS_FACET, f);
  apply_attr(m, f, f, at);
  if (n == 3) {
    tds_mesh_set_facet(m, f, oe);
    return TDS_OK;
  }
  double c[3] = {0, 0, 0};
  for (int k = 0, w = 0; k < n; k++) {
    double p[3];
    v3_add(c, c, tds_wrap_point(m, m->x[tds_oe_tail(m, oe[k])], w, p));
    if (m->torus) w = tds_wrap_mul(m, w, tds_oe_wrap(m, oe[k]));
  }
  v3_scale(c, 1.0 / n);
  tds_id cv = tds_mesh_add_vertex(m, c);
  m->vflags[cv] = at->flags & TDS_FIXED;
  m->vcon[cv] = at->con | tds_surf_global_cons(s);
  tds_id spoke0 = m->ne; /* spoke k runs from the tail of oe[k] to cv */
  for (int k = 0, w = 0; k < n; k++) {
    tds_id e = tds_mesh_add_edge(m, tds_oe_tail(m, oe[k]), cv);
    m->eflags[e] = at->flags & (TDS_FIXED | TDS_NO_REFINE);
    m->econ[e] = at->con;
    /* the centre is where the face's first vertex sees it */
    if (m->torus) {
      m->ewrap[e] = tds_wrap_inv(m, w);
      w = tds_wrap_mul(m, w, tds_oe_wrap(m, oe[k]));
    }
  }
  for (int k = 0; k < n; k++) {
    tds_id in = spoke0 + (k + 1) % n, out = spoke0 + k;
    if (k < n - 1) {
      int32_t t[3] = {oe[k], TDS_OREF(in, 0), TDS_OREF(out, 1)};
      tds_id nf = tds_mesh_add_facet(m, t);
      apply_attr(m, nf, f, at);
    } else { /* the last triangle keeps the face's slot, centre first */
      int32_t t[3] = {TDS_OREF(out, 1), oe[k], TDS_OREF(in, 0)};
      tds_mesh_set_facet(m, f, t);
    }
  }
  /* Evolver's facet-edge loop on the first spoke starts at the face's own
  ** facet (the ring order ee.facet reports, mesh.h) */
  m->eside[spoke0] = 3 * f + 2;
  if (m->vcon[cv]) tds_motion_enforce(s, cv);
  m->coord_gen++;
  return TDS_OK;
}

int tds_decl_vertex(tds_ctx *ctx, tds_surf *s, tds_id v, const double x[3],
                    int32_t bdry, const double p[2], uint32_t flags,
                    tds_cmask con) {
  tds_mesh *m = &s->m;
  int rc = tds_mesh_claim(m, TDS_VERTEX, v);
  if (rc == TDS_ERANGE)
    return tds_seterr(ctx, rc, "vertex %d is declared twice", v + 1);
  if (rc != TDS_OK) return tds_seterr(ctx, rc, "out of memory");
  v3_copy(m->x[v], x);
  m->vfile[v] = v + 1;
  m->vflags[v] = flags;
  m->vcon[v] = con | (bdry == TDS_NONE ? tds_surf_global_cons(s) : 0);
  m->vbdry[v] = bdry;
  if (bdry != TDS_NONE) {
    m->vp[v][0] = p[0];
    m->vp[v][1] = p[1];
  }
  m->coord_gen++;
  /* formulas reading vertex attributes wait for them (tds_decl_vertex_done) */
  if (s->nxa_kind[TDS_VERTEX] && m->vcon[v]) return TDS_OK;
  return tds_decl_vertex_done(ctx, s, v);
}

int tds_decl_vertex_done(tds_ctx *ctx, tds_surf *s, tds_id v) {
  tds_mesh *m = &s->m;
  if (tds_motion_enforce(s, v) != TDS_OK)
    tds_warnf(ctx, "vertex %d: projection onto its constraints did not "
              "converge\n", v + 1);
  if (!isfinite(m->x[v][0] + m->x[v][1] + m->x[v][2])) {
    m->vflags[v] |= TDS_DEAD;
    return tds_seterr(ctx, TDS_ERANGE, "vertex %d: coordinates are not finite", v + 1);
  }
  return TDS_OK;
}

int tds_decl_edge(tds_ctx *ctx, tds_surf *s, tds_id e, tds_id t, tds_id h,
                  uint32_t flags, tds_cmask con, int32_t bdry, double tension,
                  int16_t color) {
  tds_mesh *m = &s->m;
  tds_id ends[2] = {t, h};
  for (int k = 0; k < 2; k++)
    if (ends[k] < 0 || ends[k] >= m->nv || !tds_alive(m->vflags, ends[k]))
      return tds_seterr(ctx, TDS_ERANGE,
                        "edge %d refers to vertex %d, which does not exist", e + 1,
                        ends[k] + 1);
  if (t == h)
    return tds_seterr(ctx, TDS_ETOPO, "edge %d starts and ends at vertex %d",
                      e + 1, t + 1);
  int rc = tds_mesh_claim(m, TDS_EDGE, e);
  if (rc == TDS_ERANGE)
    return tds_seterr(ctx, rc, "edge %d is declared twice", e + 1);
  if (rc != TDS_OK) return tds_seterr(ctx, rc, "out of memory");
  m->ev[e][0] = t;
  m->ev[e][1] = h;
  m->efile[e] = e + 1;
  m->eflags[e] = flags;
  m->econ[e] = con;
  m->ebdry[e] = bdry;
  m->eten[e] = tension;
  m->ecolor[e] = color;
  return TDS_OK;
}

/* The facets of every declared face, by face slot (CSR over forig), built
** once per topology and shared by all body declarations. */
static int orig_index(tds_surf *s) {
  tds_mesh *m = &s->m;
  if (s->orig_start && s->orig_gen == m->topo_gen) return TDS_OK;
  int32_t *start = tds_calloc(&s->m.alloc, (size_t)m->nf + 2, sizeof *start);
  int32_t *list = tds_malloc(&s->m.alloc, (size_t)(m->nf > 0 ? m->nf : 1) * sizeof *list);
  if (!start || !list) {
    tds_free(&s->m.alloc, start);
    tds_free(&s->m.alloc, list);
    return TDS_ENOMEM;
  }
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f) && m->forig[f] != TDS_NONE) start[m->forig[f] + 2]++;
  for (int32_t i = 0; i < m->nf; i++) start[i + 2] += start[i + 1];
  for (tds_id f = 0; f < m->nf; f++)
    if (tds_alive(m->fflags, f) && m->forig[f] != TDS_NONE)
      list[start[m->forig[f] + 1]++] = f;
  tds_free(&s->m.alloc, s->orig_start);
  tds_free(&s->m.alloc, s->orig_facets);
  s->orig_start = start; /* now start[o] .. start[o + 1] */
  s->orig_facets = list;
  s->orig_gen = m->topo_gen;
  return TDS_OK;
}

int tds_decl_body(tds_ctx *ctx, tds_surf *s, tds_id b, int n,
                  const int32_t *faces) {
  tds_mesh *m = &s->m;
  for (int i = 0; i < n; i++) {
    int32_t fid = faces[i] < 0 ? -faces[i] : faces[i];
    if (fid < 1 || fid > m->nf || !tds_alive(m->fflags, fid - 1) ||
        m->forig[fid - 1] != fid - 1)
      return tds_seterr(ctx, TDS_ERANGE,
                        "body %d refers to face %d, which does not exist", b + 1, fid);
  }
  if (orig_index(s) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  uint64_t gen = m->topo_gen;
  int rc = tds_mesh_claim(m, TDS_BODY, b);
  if (rc == TDS_ERANGE)
    return tds_seterr(ctx, rc, "body %d is declared twice", b + 1);
  if (rc != TDS_OK) return tds_seterr(ctx, rc, "out of memory");
  m->topo_gen = gen; /* a new body slot changes no facet adjacency */
  m->bfile[b] = b + 1;
  for (int i = 0; i < n; i++) {
    int32_t o = (faces[i] < 0 ? -faces[i] : faces[i]) - 1;
    for (int32_t k = s->orig_start[o]; k < s->orig_start[o + 1]; k++)
      m->fb[s->orig_facets[k]][faces[i] > 0 ? 0 : 1] = b;
  }
  return TDS_OK;
}
