/* fixq_dep.c: area targets of the string model that are dependent by the
** foam's combinatorics (contracts in fixq.h).
**
** sum_b c_b grad A_b = 0 over the movable vertices is what dependence
** means. Each edge adds to the gradient s_e = sum_b c_b w_(b,e) times its
** own geometric term (w the edge's weights in the cells' index,
** string_model.h), and at a vertex whose position is free the three or
** more edge terms are in general position, so a combination that is zero
** for every position has s_e = 0 on every edge with a free end. With the
** weights +-1 of two bodies on an edge this says c equal (opposite
** weights) or opposite (equal weights); one body with a target on an edge
** (the other side free, no cell, or a body without one) says c = 0.
** Solving these with a union-find with parities leaves c = +-1 on a
** component that nothing forces to 0: the sum of those bodies' signed
** areas is then constant (the torus's area, or the area inside fixed
** edges) and the targets are dependent, for any positions. Conservative
** where the rule is not sure: an edge with an end on a constraint or
** boundary, with more than two bodies, or with unequal weights forces its
** bodies to 0 (their dependence, if any, is left to the numerical solve);
** edges whose ends are both fixed say nothing.
*/
#include "fixq.h"

#include <string.h>

#include "string_model.h"

static int32_t find(int32_t *par, uint8_t *odd, int32_t x) {
  /* root of x, and odd[x] its parity relative to the root (path halving
  ** keeps both) */
  int p = 0;
  int32_t r = x;
  while (par[r] != r) {
    p ^= odd[r];
    r = par[r];
  }
  /* compress: point x's path at r with the accumulated parities */
  int32_t y = x;
  int q = p;
  while (par[y] != y) {
    int32_t next = par[y];
    int oy = odd[y];
    par[y] = r;
    odd[y] = (uint8_t)q;
    q ^= oy;
    y = next;
  }
  return r;
}

int tds_fixq_dependent(tds_ctx *ctx, const tds_surf *s, const tds_fixq *fq, tds_id *first,
                       int32_t *count) {
  *first = TDS_NONE;
  *count = 0;
  const tds_mesh *m = &s->m;
  const tds_strings *st = s->str;
  if (!st || !st->eb_start || st->idx_ne != m->ne || m->nb == 0) return TDS_OK;
  int32_t nb = m->nb;
  int32_t *par = tds_malloc(&ctx->alloc, (size_t)nb * sizeof *par);
  uint8_t *odd = tds_calloc(&ctx->alloc, (size_t)nb, sizeof *odd);
  uint8_t *zero = tds_calloc(&ctx->alloc, (size_t)nb, sizeof *zero);
  if (!par || !odd || !zero) {
    tds_free(&ctx->alloc, par);
    tds_free(&ctx->alloc, odd);
    tds_free(&ctx->alloc, zero);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  for (int32_t b = 0; b < nb; b++) par[b] = b;
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    int movable = 0, sure = 1;
    for (int c = 0; c < 2; c++) {
      tds_id v = m->ev[e][c];
      if (m->vflags[v] & TDS_FIXED) continue;
      movable = 1;
      if ((m->vcon && m->vcon[v]) || (m->vbdry && m->vbdry[v] != TDS_NONE)) sure = 0;
    }
    if (!movable) continue;
    int32_t k0 = st->eb_start[e], k1 = st->eb_start[e + 1], nt = 0, kt[2] = {0, 0};
    int others = 0; /* a side with no target: free */
    for (int32_t k = k0; k < k1; k++) {
      if (st->eb_w[k] == 0) continue;
      if (fq->bq[st->eb_body[k]] < 0) {
        others = 1;
        continue;
      }
      if (nt < 2) kt[nt] = k;
      nt++;
    }
    if (nt == 2 && sure && !others && (st->eb_w[kt[0]] == st->eb_w[kt[1]] ||
                                      st->eb_w[kt[0]] == -st->eb_w[kt[1]])) {
      int32_t a = st->eb_body[kt[0]], b = st->eb_body[kt[1]];
      int want = st->eb_w[kt[0]] == st->eb_w[kt[1]]; /* c_a = -c_b: parity 1 */
      int32_t ra = find(par, odd, a), rb = find(par, odd, b);
      int pa = odd[a], pb = odd[b]; /* relative to the roots (a root's is 0) */
      if (ra != rb) {
        par[ra] = rb;
        odd[ra] = (uint8_t)(pa ^ pb ^ want);
        zero[rb] |= zero[ra];
      } else if ((pa ^ pb) != want) {
        zero[ra] = 1; /* c = -c: the component is 0 */
      }
      continue;
    }
    for (int32_t k = k0; k < k1; k++)
      if (st->eb_w[k] != 0 && fq->bq[st->eb_body[k]] >= 0)
        zero[find(par, odd, st->eb_body[k])] = 1;
  }
  /* the first body with a target whose component is free, and its size */
  tds_id root = TDS_NONE;
  for (int32_t b = 0; b < nb && root == TDS_NONE; b++)
    if (fq->bq[b] >= 0 && !zero[find(par, odd, b)]) root = find(par, odd, b), *first = b;
  if (root != TDS_NONE)
    for (int32_t b = 0; b < nb; b++)
      if (fq->bq[b] >= 0 && find(par, odd, b) == root) (*count)++;
  tds_free(&ctx->alloc, par);
  tds_free(&ctx->alloc, odd);
  tds_free(&ctx->alloc, zero);
  return TDS_OK;
}
