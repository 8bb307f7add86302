/* pg_flip.c: Delaunay edge flips of the projected-gradient method
** (Algorithm 1 of the paper; see pg_int.h).
**
** Candidates are the edges tds_flip_ok allows, listed again whenever the
** topology changes. Each iteration first screens them with the cotangents
** of the pass (an edge is Delaunay when cot a + cot b >= 0 for the angles
** a, b opposite it: no square root, no gather); only when some edge fails
** does pg_flip_pass run the work-set algorithm on the positions. */
#include <math.h>
#include <stdlib.h>

#include "pairset.h"
#include "pg_int.h"
#include "topo.h"
#include "vec3.h"

int pg_flip_init(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  size_t ne = (size_t)(m->ne > 0 ? m->ne : 1);
  w->stack = tds_calloc(&w->al, ne, sizeof *w->stack);
  w->cand = tds_calloc(&w->al, ne, sizeof *w->cand);
  w->copp = tds_calloc(&w->al, ne, sizeof *w->copp);
  w->queued = tds_calloc(&w->al, ne, 1);
  if (!w->stack || !w->cand || !w->copp || !w->queued ||
      tds_pairset_init(&w->ps, &w->al, ne) != TDS_OK ||
      tds_pairset_init(&w->gone, &w->al, ne) != TDS_OK)
    return TDS_ENOMEM;
  w->gone_max = (int32_t)ne;
  w->ngone = 0;
  for (tds_id e = 0; e < m->ne; e++)
    if (tds_alive(m->eflags, e)) tds_pairset_add(&w->ps, m->ev[e][0], m->ev[e][1]);
  w->cand_gen = (uint64_t)-1;
  w->cot_gen = (uint64_t)-1;
  return TDS_OK;
}

void pg_flip_free(pgw *w) {
  tds_pairset_free(&w->ps);
  tds_pairset_free(&w->gone);
  w->gone.key = NULL;
  tds_free(&w->al, w->stack);
  tds_free(&w->al, w->cand);
  tds_free(&w->al, w->copp);
  tds_free(&w->al, w->queued);
  w->ps.key = NULL;
  w->stack = w->cand = NULL;
  w->copp = NULL;
  w->queued = NULL;
}

static int same_pair(int32_t a, int32_t b, int32_t c, int32_t d) {
  return (a == c && b == d) || (a == d && b == c);
}

/* Record the flip a-b -> c-d among the last 16; count it in w->cycles
** when it undoes a flip that itself undid one (the quadrilateral went
** a-b, c-d, a-b, c-d: a 2-cycle). */
static void remember(pgw *w, int32_t a, int32_t b, int32_t c, int32_t d) {
  int32_t back = 0;
  for (int i = 0; i < 16; i++) {
    const int32_t *r = w->recent[i];
    if (r[0] != r[1] && same_pair(r[0], r[1], c, d) && same_pair(r[2], r[3], a, b)) {
      back = r[4] + 1;
      break;
    }
  }
  if (back >= 2) w->cycles++;
  int32_t *r = w->recent[w->recent_head];
  r[0] = a;
  r[1] = b;
  r[2] = c;
  r[3] = d;
  r[4] = back;
  w->recent_head = (w->recent_head + 1) % 16;
}

static int side_of(const tds_mesh *m, tds_id f, tds_id e) {
  for (int k = 0; k < 3; k++)
    if (TDS_OID(m->fe[f][k]) == e) return k;
  return 0;
}

/* Nonzero when the angles at c and d opposite a-b sum to more than pi by
** more than the tolerance: sin(a + b) < -tol. */
static int not_delaunay(const double *a, const double *b, const double *c,
                        const double *d, double tol) {
  double u1[3], v1[3], u2[3], v2[3], c1[3], c2[3];
  v3_sub(u1, a, c);
  v3_sub(v1, b, c);
  v3_sub(u2, a, d);
  v3_sub(v2, b, d);
  v3_cross(c1, u1, v1);
  v3_cross(c2, u2, v2);
  double s1 = v3_norm(c1), s2 = v3_norm(c2);
  double k1 = v3_dot(u1, v1), k2 = v3_dot(u2, v2);
  /* sin(alpha + beta) * |u1||v1||u2||v2| */
  double sn = s1 * k2 + k1 * s2;
  double scale = sqrt(v3_dot(u1, u1) * v3_dot(v1, v1) * v3_dot(u2, u2) *
                      v3_dot(v2, v2));
  return sn < -tol * scale;
}

/* Candidate edges and, for each, the facet sides (3f + k) of the corners
** opposite it: the entries of w->fcot to add (facets by their position
** in the pass's order). */
static void build_candidates(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  w->ncand = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    tds_id f1, f2;
    if (!tds_flip_ok(s, e, &f1, &f2)) continue;
    int32_t h = m->eside[e], h2 = m->side_next[h];
    w->copp[w->ncand][0] = 3 * w->fpos[h / 3] + (h % 3 + 2) % 3;
    w->copp[w->ncand][1] = 3 * w->fpos[h2 / 3] + (h2 % 3 + 2) % 3;
    w->cand[w->ncand++] = e;
  }
  w->cand_gen = m->topo_gen;
}

int pg_flip_needed(tds_surf *s, pgw *w) {
  if (w->cand_gen != s->m.topo_gen) build_candidates(s, w);
  const double *cot = w->fcot;
  for (int32_t i = 0; i < w->ncand; i++)
    if (cot[w->copp[i][0]] + cot[w->copp[i][1]] < -w->flip_tol) return 1;
  return 0;
}

int32_t pg_flip_pass(tds_surf *s, pgw *w) {
  tds_mesh *m = &s->m;
  /* The cotangents of the last pass screen the candidates (when they are
  ** the current candidates' and of these positions: pg_flip_needed just
  ** ran on them): cot a + cot b = sin(a + b) / (sin a sin b), so an edge
  ** with sin(a + b) < -tol also has cot a + cot b < -tol, and the edges
  ** skipped here would not pass not_delaunay below. The same stack as
  ** testing every candidate, without a square root per edge of the
  ** mesh (at 100k vertices that was a tenth of an iteration). */
  int screen = w->cand_gen == m->topo_gen && w->cot_gen == m->coord_gen;
  if (w->cand_gen != m->topo_gen) build_candidates(s, w);
  const double *cot = w->fcot;
  int32_t top = 0, flips = 0;
  for (int32_t i = 0; i < w->ncand; i++) {
    double c0 = screen ? cot[w->copp[i][0]] : 0, c1 = screen ? cot[w->copp[i][1]] : 0;
    if (c0 != 0 && c1 != 0 && !(c0 + c1 < -w->flip_tol)) continue; /* 0: a degenerate
                                                                       facet's, test it */
    tds_id e = w->cand[i];
    int32_t h = m->eside[e], h2 = m->side_next[h];
    tds_id c = m->fv[h / 3][(h % 3 + 2) % 3], d = m->fv[h2 / 3][(h2 % 3 + 2) % 3];
    if (not_delaunay(m->x[m->ev[e][0]], m->x[m->ev[e][1]], m->x[c], m->x[d], w->flip_tol)) {
      w->stack[top++] = e;
      w->queued[e] = 1;
    }
  }
  int64_t budget = 20 * (int64_t)m->ne + 100;
  while (top > 0 && budget-- > 0) {
    tds_id e = w->stack[--top], f1, f2;
    w->queued[e] = 0;
    if (!tds_flip_ok(s, e, &f1, &f2)) continue;
    tds_id c = m->fv[f1][(side_of(m, f1, e) + 2) % 3];
    tds_id d = m->fv[f2][(side_of(m, f2, e) + 2) % 3];
    tds_id a = m->ev[e][0], b = m->ev[e][1];
    if (!not_delaunay(m->x[a], m->x[b], m->x[c], m->x[d], w->flip_tol)) continue;
    if (tds_pairset_has(&w->ps, c, d)) continue;
    tds_pairset_remove(&w->ps, a, b);
    tds_flip(s, e, f1, f2);
    tds_pairset_add(&w->ps, c, d);
    remember(w, a, b, c, d);
    if (tds_pairset_has(&w->gone, c, d)) { /* back to an earlier edge */
      w->returns++;
      tds_pairset_remove(&w->gone, c, d);
      w->ngone--;
    }
    if (w->ngone < w->gone_max) { /* full: later removals go unrecorded */
      tds_pairset_add(&w->gone, a, b);
      w->ngone++;
    }
    flips++;
    for (int k = 0; k < 3; k++) {
      tds_id q1 = TDS_OID(m->fe[f1][k]), q2 = TDS_OID(m->fe[f2][k]);
      if (q1 != e && !w->queued[q1]) {
        w->stack[top++] = q1;
        w->queued[q1] = 1;
      }
      if (q2 != e && !w->queued[q2]) {
        w->stack[top++] = q2;
        w->queued[q2] = 1;
      }
    }
  }
  while (top > 0) w->queued[w->stack[--top]] = 0;
  if (flips) m->coord_gen++;
  return flips;
}

void pg_flip_forget(pgw *w) {
  tds_pairset_clear(&w->gone);
  w->ngone = 0;
}
