/* torus.c: the torus model's volumes and checks (contracts in torus.h). */
#include "torus.h"

#include <math.h>
#include <string.h>

#include "expr.h"
#include "gather.h"
#include "vec3.h"

double tds_torus_cell_volume(const tds_mesh *m) {
  const double (*p)[3] = m->period;
  double d = p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
             p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
             p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
  return fabs(d);
}

int32_t tds_torus_corner_wrap(const tds_mesh *m, tds_id f, int k) {
  if (k == 0) return 0;
  if (k == 1) return tds_oe_wrap(m, m->fe[f][0]);
  return tds_corner2_wrap(m, f);
}

void tds_torus_facet_corner(const tds_mesh *m, tds_id f, int k, double out[3]) {
  double p[3];
  const double *x = tds_wrap_point(m, m->x[m->fv[f][k]], tds_torus_corner_wrap(m, f, k), p);
  for (int i = 0; i < 3; i++) out[i] = x[i];
}

void tds_torus_facet_at(const tds_mesh *m, tds_id f, int k, double out[3][3]) {
  tds_corners C;
  tds_gather_facet(m, f, &C);
  int32_t back = m->torus && k ? tds_wrap_inv(m, tds_torus_corner_wrap(m, f, k)) : 0;
  for (int j = 0; j < 3; j++) {
    const double *y = tds_wrap_point(m, C.x[j], back, out[j]);
    if (y != out[j]) memcpy(out[j], y, sizeof out[j]);
  }
}

/* Corner of facet f where oriented side k's edge starts (its stored
** tail), so two facets on an edge name the same vertex of it. */
static int tail_corner(const tds_mesh *m, tds_id f, int k) {
  return TDS_OREV(m->fe[f][k]) ? (k + 1) % 3 : k;
}

/* The sides on edge e in angular order about it (right-handed about the
** edge's stored direction): face[i] the facet, side k[i], up[i] whether
** its front body faces the next one (increasing angle). Returns the count
** (at most cap; more are ignored). Translation-invariant: every facet is
** measured in its own unwrapped frame from the edge's tail. */
typedef struct ring_side {
  tds_id f;
  int k, up;
  double ang;
} ring_side;

static int ring_order(const tds_mesh *m, tds_id e, ring_side *rs, int cap) {
  int32_t h = m->eside[e];
  if (h == TDS_NONE) return 0;
  int n = 0;
  double a[3] = {0, 0, 0}, bv[3] = {0, 0, 0}, u[3] = {0, 0, 0};
  int32_t r = h;
  do {
    if (n == cap) break;
    tds_id f = r / 3;
    int k = r % 3, ct = tail_corner(m, f, k), ch = ct == k ? (k + 1) % 3 : k,
        c3 = (k + 2) % 3;
    double P[3][3], d[3], rr[3], nn[3], t[3];
    for (int c = 0; c < 3; c++) tds_torus_facet_corner(m, f, c, P[c]);
    v3_sub(d, P[ch], P[ct]);
    v3_sub(rr, P[c3], P[ct]);
    if (n == 0) {
      double L = sqrt(v3_dot(d, d));
      if (L > 0) { v3_copy(u, d); v3_scale(u, 1 / L); }
    }
    double along = v3_dot(rr, u);
    for (int i = 0; i < 3; i++) rr[i] -= along * u[i];
    if (n == 0) {
      double L = sqrt(v3_dot(rr, rr));
      if (L > 0) { v3_copy(a, rr); v3_scale(a, 1 / L); }
      v3_cross(bv, u, a);
    }
    double e1[3], e2[3];
    v3_sub(e1, P[1], P[0]);
    v3_sub(e2, P[2], P[0]);
    v3_cross(nn, e1, e2);
    v3_cross(t, u, rr);
    /* the front body is behind the normal (Evolver: + in a body's list is
    ** an outward normal) */
    rs[n] = (ring_side){f, k, v3_dot(nn, t) < 0, atan2(v3_dot(rr, bv), v3_dot(rr, a))};
    n++;
    r = m->side_next[r];
  } while (r != h);
  for (int i = 1; i < n; i++) /* insertion sort: a few sides */
    for (int j = i; j > 0 && rs[j].ang < rs[j - 1].ang; j--) {
      ring_side t = rs[j];
      rs[j] = rs[j - 1];
      rs[j - 1] = t;
    }
  return n;
}

#define RING_CAP 64

/* The facet side (2 g + jg) that bounds the same wedge about the edge of
** facet f's side k as side j of f, g's side on that edge in *kg: the next
** facet round the edge in angular order (angular), or in the edge's ring
** (Evolver's facet-edge order, right-handed about the stored edge: the
** ring's order is the one to follow where flips have folded the surface
** so that the angles mislead). -1 if there is none. */
static int32_t across(const tds_mesh *m, tds_id f, int j, int k, int angular, int *kg) {
  if (!angular) {
    int32_t me = 3 * f + k, prev = me;
    while (m->side_next[prev] != me) prev = m->side_next[prev];
    /* a facet along the edge has its front body clockwise of it */
    int ccw = (j == 1) == !TDS_OREV(m->fe[f][k]);
    int32_t sg = ccw ? m->side_next[me] : prev;
    int gfwd = !TDS_OREV(m->fe[sg / 3][sg % 3]);
    *kg = sg % 3;
    return 2 * (sg / 3) + (ccw ? !gfwd : gfwd);
  }
  ring_side rs[RING_CAP];
  int n = ring_order(m, TDS_OID(m->fe[f][k]), rs, RING_CAP);
  int i = 0;
  while (i < n && !(rs[i].f == f && rs[i].k == k)) i++;
  if (i == n) return -1;
  int fwd = (j == 0) == rs[i].up; /* faces increasing angle */
  const ring_side *g = &rs[fwd ? (i + 1) % n : (i + n - 1) % n];
  *kg = g->k;
  return 2 * g->f + (fwd ? (g->up ? 1 : 0) : (g->up ? 0 : 1));
}

/* One walk (tds_torus_walk) in the given order. */
static int walk(const tds_mesh *m, int32_t *lift, uint8_t *seen, int32_t *queue, int32_t root,
                int angular, int32_t *nq) {
  tds_id b = m->fb[root / 2][root & 1];
  int closed = 1;
  int32_t qh = 0, qt = 0;
  queue[qt++] = root;
  seen[root] = 1;
  lift[root] = 0;
  while (qh < qt) {
    int32_t sd = queue[qh++];
    tds_id f = sd / 2;
    for (int k = 0; k < 3; k++) {
      int kg;
      int32_t sg = across(m, f, sd & 1, k, angular, &kg);
      if (sg < 0) continue;
      if (m->fb[sg / 2][sg & 1] != b) {
        closed = 0; /* the bodies are not consistent round the edge */
        continue;
      }
      /* where the edge's tail is in f's lifted frame, then g's lift */
      int32_t at = tds_wrap_mul(m, lift[sd], tds_torus_corner_wrap(m, f, tail_corner(m, f, k)));
      int32_t want = tds_wrap_mul(m, at, tds_wrap_inv(m, tds_torus_corner_wrap(m, sg / 2, tail_corner(m, sg / 2, kg))));
      if (!seen[sg]) {
        seen[sg] = 1;
        lift[sg] = want;
        queue[qt++] = sg;
      } else if (lift[sg] != want) {
        closed = 0;
      }
    }
  }
  *nq = qt;
  return closed;
}

int tds_torus_walk(const tds_mesh *m, int32_t *lift, uint8_t *seen, int32_t *queue, int32_t root,
                   int32_t *nq) {
  if (walk(m, lift, seen, queue, root, 1, nq)) return 1;
  for (int32_t i = 0; i < *nq; i++) seen[queue[i]] = 0; /* the ring's order */
  if (walk(m, lift, seen, queue, root, 0, nq)) return 1;
  for (int32_t i = 0; i < *nq; i++) seen[queue[i]] = 0; /* neither: the angles' */
  walk(m, lift, seen, queue, root, 1, nq);
  return 0;
}

int tds_torus_lifts(tds_ctx *ctx, tds_surf *s) {
  tds_mesh *m = &s->m;
  if (s->tlift_gen == m->topo_gen && s->tlift_gen != 0) return 0;
  int32_t need = 2 * (m->nf > 0 ? m->nf : 1);
  if (need > s->tlift_cap) {
    int32_t *p = tds_realloc(&m->alloc, s->tlift, (size_t)need * sizeof *p);
    if (!p) {
      tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      return -TDS_ENOMEM;
    }
    s->tlift = p;
    s->tlift_cap = need;
  }
  int32_t *queue = tds_malloc(&m->alloc, (size_t)need * sizeof *queue);
  uint8_t *seen = tds_calloc(&m->alloc, (size_t)need, 1);
  /* the bodies found open (a body's facets may start several walks) */
  uint8_t *open = tds_calloc(&m->alloc, (size_t)m->nb + 1, 1);
  if (!queue || !seen || !open) {
    tds_free(&m->alloc, queue);
    tds_free(&m->alloc, seen);
    tds_free(&m->alloc, open);
    tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    return -TDS_ENOMEM;
  }
  int bad = 0;
  for (int32_t i = 0; i < 2 * m->nf; i++) s->tlift[i] = 0;
  for (int32_t root = 0; root < 2 * m->nf; root++) {
    tds_id f0 = root / 2;
    if (seen[root] || !tds_alive(m->fflags, f0) || m->fb[f0][root & 1] == TDS_NONE) continue;
    tds_id b = m->fb[f0][root & 1];
    int32_t nq;
    int closed = tds_torus_walk(m, s->tlift, seen, queue, root, &nq);
    if (!closed && !open[b]) {
      open[b] = 1;
      bad++;
    }
  }
  tds_free(&m->alloc, queue);
  tds_free(&m->alloc, seen);
  tds_free(&m->alloc, open);
  s->tlift_gen = m->topo_gen;
  return bad;
}

int tds_torus_periods(tds_ctx *ctx, tds_surf *s) {
  double p[3][3];
  memcpy(p, s->m.period, sizeof p);
  double vars[TDS_NVARS] = {0};
  vars[TDS_G] = s->gravity;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      if (!s->period_expr[i][j]) continue;
      double v = tds_expr_eval(s->period_expr[i][j], s->parval, vars);
      if (!isfinite(v))
        return tds_seterr(ctx, TDS_ENUM, "PERIODS row %d, column %d: '%s' is not finite",
                          i + 1, j + 1, tds_expr_text(s->period_expr[i][j]));
      p[i][j] = v;
    }
  tds_mesh tmp;
  memcpy(tmp.period, p, sizeof p);
  double vnew = tds_torus_cell_volume(&tmp);
  if (!(vnew > 0))
    return tds_seterr(ctx, TDS_ENUM, "PERIODS: the period vectors span no volume");
  double vold = tds_torus_cell_volume(&s->m);
  /* volconsts follow the cell's volume proportionately (Evolver) */
  if (vold > 0 && vnew != vold)
    for (tds_id b = 0; b < s->m.nb; b++) s->m.bvolconst[b] *= vnew / vold;
  if (memcmp(p, s->m.period, sizeof p)) {
    memcpy(s->m.period, p, sizeof p);
    s->m.coord_gen++;
  }
  return TDS_OK;
}

void tds_torus_settle(tds_surf *s) {
  tds_mesh *m = &s->m;
  double vc = tds_torus_cell_volume(m);
  if (!(vc > 0)) return;
  for (tds_id b = 0; b < m->nb; b++) {
    if (!tds_alive(m->bflags, b)) continue;
    double v = m->bvol[b], n;
    if (m->bflags[b] & TDS_TARGET) n = nearbyint((m->btarget[b] - v) / vc);
    else n = -floor(v / vc + 1e-12);
    if (n != 0) {
      m->bvolconst[b] += n * vc;
      m->bvol[b] += n * vc;
    }
  }
}

int tds_torus_check(tds_ctx *ctx, const tds_mesh *m) {
  for (tds_id f = 0; f < m->nf; f++) {
    if (!tds_alive(m->fflags, f)) continue;
    if (tds_facet_wrap(m, f) != 0 && !tds_facet_axial(m, f))
      return tds_seterr(ctx, TDS_ETOPO,
                        m->sym > TDS_SYM_TORUS
                            ? "facet %d: the product of its edges' wraps is not the identity"
                            : "facet %d: the wraps of its edges do not add up to zero",
                        (int)f + 1);
  }
  return TDS_OK;
}

tds_id tds_torus_dropped_body(const tds_mesh *m) {
  if (m->torus != 2) return TDS_NONE;
  for (tds_id b = 0; b < m->nb; b++)
    if (tds_alive(m->bflags, b) && (m->bflags[b] & TDS_TARGET)) return b;
  return TDS_NONE;
}

void tds_torus_close(tds_mesh *m, tds_id f, int k) {
  int32_t oe = m->fe[f][k];
  /* w_k w_k+1 w_k+2 = 1 (a facet's product, rotated), so oe carries
  ** (w_k+1 w_k+2)^-1; stored forwards, so inverted again if reversed */
  int32_t w = tds_wrap_mul(m, tds_oe_wrap(m, m->fe[f][(k + 1) % 3]),
                           tds_oe_wrap(m, m->fe[f][(k + 2) % 3]));
  m->ewrap[TDS_OID(oe)] = TDS_OREV(oe) ? w : tds_wrap_inv(m, w);
}

int tds_facet_axial(const tds_mesh *m, tds_id f) {
  for (int k = 0; k < 3; k++)
    if (m->vflags[m->fv[f][k]] & TDS_AXIAL) return 1;
  return 0;
}

int32_t tds_facet_wrap(const tds_mesh *m, tds_id f) {
  return tds_wrap_mul(m, tds_wrap_mul(m, tds_oe_wrap(m, m->fe[f][0]), tds_oe_wrap(m, m->fe[f][1])),
                      tds_oe_wrap(m, m->fe[f][2]));
}

double tds_torus_wrap_code(int32_t w) {
  int k[3];
  tds_wrap_unpack(w, k);
  double code = 0;
  for (int i = 0; i < 3; i++) code += (double)((unsigned)k[i] & 31u) * (double)(1u << (6 * i));
  return code;
}

int tds_torus_wrap_from_code(double code, int32_t *w) {
  if (!(code >= 0 && code < (double)(1u << 18)) || code != floor(code)) return TDS_ERANGE;
  unsigned c = (unsigned)code;
  int k[3];
  for (int i = 0; i < 3; i++) {
    unsigned f = (c >> (6 * i)) & 63u;
    if (f & 32u) return TDS_ERANGE;
    k[i] = f >= 16 ? (int)f - 32 : (int)f;
  }
  *w = tds_wrap_pack(k);
  return TDS_OK;
}

int tds_torus_set_wrap(tds_ctx *ctx, tds_surf *s, tds_id e, double code) {
  tds_mesh *m = &s->m;
  if (!m->torus)
    return tds_seterr(ctx, TDS_ERANGE, "edge %d: wrap needs the torus model (TORUS)", e + 1);
  int32_t w;
  if (m->sym > TDS_SYM_TORUS) {
    if (tds_sym_from_code(m->sym, m->symp, code, &w) != TDS_OK)
      return tds_seterr(ctx, TDS_ERANGE, "edge %d: wrap %g is no element of SYMMETRY_GROUP \"%s\"",
                        e + 1, code, tds_sym_name(m->sym));
  } else if (tds_torus_wrap_from_code(code, &w) != TDS_OK)
    return tds_seterr(ctx, TDS_ERANGE,
                      "edge %d: wrap %g is not a wrap code (6 bits per period, each "
                      "count -16..15 in two's complement of 5 bits)", e + 1, code);
  int32_t old = m->ewrap[e];
  m->ewrap[e] = w;
  int32_t h = m->eside[e];
  if (h != TDS_NONE) {
    int32_t r = h;
    do {
      tds_id f = r / 3;
      if (tds_facet_wrap(m, f) != 0) {
        m->ewrap[e] = old;
        return tds_seterr(ctx, TDS_ETOPO,
                          "edge %d: with wrap %g facet %d would not close in the torus "
                          "(use wrap_vertex to move a vertex to another cell)",
                          e + 1, code, (int)f + 1);
      }
      r = m->side_next[r];
    } while (r != h);
  }
  if (w != old) m->topo_gen++;
  return TDS_OK;
}

int tds_torus_unsupported(tds_ctx *ctx, const char *what) {
  return tds_seterr(ctx, TDS_ESYNTAX, "%s is not supported yet in the torus model", what);
}

int tds_torus_wrap_vertex(tds_ctx *ctx, tds_surf *s, tds_id v, int32_t w) {
  tds_mesh *m = &s->m;
  if (!m->torus) return tds_seterr(ctx, TDS_ERANGE, "wrap_vertex needs the torus model (TORUS)");
  if (tds_mesh_rotates(m))
    return tds_seterr(ctx, TDS_ESYNTAX, "wrap_vertex is not supported yet with SYMMETRY_GROUP \"%s\"",
                      tds_sym_name(m->sym));
  if (v < 0 || v >= m->nv || !tds_alive(m->vflags, v))
    return tds_seterr(ctx, TDS_ERANGE, "vertex %d does not exist", (int)v + 1);
  if (!w) return TDS_OK;
  int32_t nw = tds_wrap_neg(w);
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e) || (m->ev[e][0] != v && m->ev[e][1] != v)) continue;
    if (tds_wrap_overflows(m->ewrap[e], m->ev[e][0] == v ? w : nw))
      return tds_seterr(ctx, TDS_ERANGE, "wrap_vertex: edge %d's wrap would be out of range",
                        (int)e + 1);
  }
  /* the tail moves by w: its edges' heads are w further; heads the other way */
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    if (m->ev[e][0] == v) m->ewrap[e] = tds_wrap_add(m->ewrap[e], w);
    else if (m->ev[e][1] == v) m->ewrap[e] = tds_wrap_add(m->ewrap[e], nw);
  }
  double d[3];
  tds_wrap_vec(m->period, w, d);
  for (int i = 0; i < 3; i++) m->x[v][i] += d[i];
  m->topo_gen++;
  m->coord_gen++;
  return TDS_OK;
}
