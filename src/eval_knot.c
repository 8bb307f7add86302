/*
** eval_knot.c: assembly of the method rows that do not live on single
** elements (method.h's TDS_IT_*): knot energies over pairs of vertices or
** edges, the string curvature at vertices between two edges, Hooke
** springs whose constants are read per edge. Same contract as eval.c's
** loop: value times w to the total, gradient to the energy or to a fixq
** quantity, Hessian (where the row has one) to the accumulator.
**
** Pair sums are over ordered pairs, as Evolver's: a symmetric kernel is
** evaluated once per unordered pair with weight 2. The cost is quadratic
** in the number of vertices or edges (knots have a few hundred).
*/
#include "eval.h"

#include <math.h>
#include <string.h>

#include "attr.h"
#include "method.h"
#include "vec3.h"

typedef struct acc {
  tds_surf *s;
  tds_eval_out *out;
  double w;
  int32_t gq;
  double total;
} acc;

static double param(const tds_surf *s, const char *name, double dflt) {
  int k = tds_surf_param_find(s, name, strlen(name));
  return k >= 0 ? s->parval[k] : dflt;
}

/* Scatter value v (times weight ww = w or 2w) with gradient g at n corners vs. */
static void put(acc *A, const tds_id *vs, int n, double ww, double v, double (*g)[3],
                double (*h)[9]) {
  tds_eval_out *out = A->out;
  A->total += ww * v;
  if (!g) return;
  for (int c = 0; c < n; c++) {
    double gc[3] = {ww * g[c][0], ww * g[c][1], ww * g[c][2]};
    if (A->gq == -1) v3_axpy(out->grad[vs[c]], 1, gc);
    else if (A->gq >= 0) tds_fixq_add(out->fq, vs[c], A->gq, gc);
  }
  if (h && out->hess) {
    tds_hess_acc *ha = out->hess;
    double hw = A->gq == -1 ? ha->ew : A->gq >= 0 && ha->qw ? ha->qw[A->gq] : 0;
    tds_eval_scatter_hess(ha, vs, n, ww * hw, h);
  }
}

static int method_is_buck(const tds_method *row) { return row == &tds_methods[TDS_M_BUCK_KNOT]; }

static int live_v(const tds_mesh *m, tds_id v) { return !(m->vflags[v] & TDS_DEAD); }
static int live_e(const tds_mesh *m, tds_id e) { return !(m->eflags[e] & TDS_DEAD); }

static int vpair(tds_ctx *ctx, acc *A, const tds_method *row, double pw, int wantg,
                 int wanth) {
  const tds_mesh *m = &A->s->m;
  tds_mlocal L = {.pw = pw, .param = A->s->parval};
  double g[3][3], h[9][9];
  for (tds_id i = 0; i < m->nv; i++) {
    if (!live_v(m, i)) continue;
    for (tds_id j = i + 1; j < m->nv; j++) {
      if (!live_v(m, j)) continue;
      L.x[0] = m->x[i];
      L.x[1] = m->x[j];
      tds_id vs[2] = {i, j};
      double v = row->eval(&L, wantg ? g : NULL, wanth ? h : NULL);
      if (!isfinite(v))
        return tds_seterr(ctx, TDS_ENUM, "%s is not finite: vertices %d and %d coincide",
                          row->name, (int)i + 1, (int)j + 1);
      put(A, vs, 2, 2 * A->w, v, wantg ? g : NULL, wanth ? h : NULL);
    }
  }
  return TDS_OK;
}

static int epair(tds_ctx *ctx, acc *A, const tds_method *row, double pw, int wantg) {
  const tds_mesh *m = &A->s->m;
  int sym = (row->flags & TDS_MF_SYMPAIR) != 0;
  int disjoint = (row->flags & TDS_MF_DISJOINT) != 0;
  double g[4][3];
  for (tds_id i = 0; i < m->ne; i++) {
    if (!live_e(m, i)) continue;
    for (tds_id j = sym ? i + 1 : 0; j < m->ne; j++) {
      if (j == i || !live_e(m, j)) continue;
      const tds_id *a = m->ev[i], *b = m->ev[j];
      if (disjoint && (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]))
        continue;
      const double *y[4] = {m->x[a[0]], m->x[a[1]], m->x[b[0]], m->x[b[1]]};
      tds_id vs[4] = {a[0], a[1], b[0], b[1]};
      double v = row->eval4(y, pw, wantg ? g : NULL);
      if (!isfinite(v))
        return tds_seterr(ctx, TDS_ENUM,
                          "%s is not finite between edges %d and %d%s", row->name,
                          (int)i + 1, (int)j + 1,
                          method_is_buck(row) ? " (its denominator is not positive: the "
                                                "edges are long for their distance)"
                                              : "");
      put(A, vs, 4, sym ? 2 * A->w : A->w, v, wantg ? g : NULL, NULL);
    }
  }
  return TDS_OK;
}

/* Vertices with exactly two live edges: corners (far end of the first,
** v, far end of the second), the edges taken in id order. */
static int vstar(tds_ctx *ctx, acc *A, const tds_method *row, int wantg, int wanth) {
  const tds_mesh *m = &A->s->m;
  int32_t *cnt = tds_calloc(&ctx->alloc, (size_t)m->nv + 1, 3 * sizeof *cnt);
  if (!cnt) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (tds_id e = 0; e < m->ne; e++) {
    if (!live_e(m, e)) continue;
    for (int k = 0; k < 2; k++) {
      int32_t *c = &cnt[3 * m->ev[e][k]];
      if (c[0] < 2) c[1 + c[0]] = m->ev[e][!k];
      c[0]++;
    }
  }
  tds_mlocal L = {.param = A->s->parval};
  double g[3][3], h[9][9];
  for (tds_id v = 0; v < m->nv; v++) {
    const int32_t *c = &cnt[3 * v];
    if (!live_v(m, v) || c[0] != 2) continue;
    tds_id vs[3] = {c[1], v, c[2]};
    for (int k = 0; k < 3; k++) L.x[k] = m->x[vs[k]];
    double val = row->eval(&L, wantg ? g : NULL, wanth ? h : NULL);
    put(A, vs, 3, A->w, val, wantg ? g : NULL, wanth ? h : NULL);
  }
  tds_free(&ctx->alloc, cnt);
  return TDS_OK;
}

/* Hooke springs: hooke_energy's length is the parameter hooke_length (0
** when not defined, as evolver-nox-d), hooke2_energy's the edge attribute
** hooke_size (0 when not defined). */
static void hooke(acc *A, int method, int wantg, int wanth) {
  tds_surf *s = A->s;
  const tds_mesh *m = &s->m;
  const tds_method *row = &tds_methods[method];
  tds_mlocal L = {.param = s->parval};
  const double *size = NULL;
  int stride = 1;
  if (method == TDS_M_HOOKE) {
    L.k = param(s, "hooke_length", 0);
    L.pw = param(s, "hooke_power", 2);
  } else {
    L.pw = param(s, "hooke2_power", 2);
    tds_attr a;
    if (tds_attr_find(m, TDS_EDGE, "hooke_size", &a) && a.col >= 0 && a.size == 1) {
      size = m->ucol[TDS_EDGE][a.col].v;
      stride = m->ucol[TDS_EDGE][a.col].size;
    }
  }
  double g[3][3], h[9][9];
  for (tds_id e = 0; e < m->ne; e++) {
    if (!live_e(m, e)) continue;
    if (method == TDS_M_HOOKE2) L.k = size ? size[(size_t)e * stride] : 0;
    L.x[0] = m->x[m->ev[e][0]];
    L.x[1] = m->x[m->ev[e][1]];
    double v = row->eval(&L, wantg ? g : NULL, wanth ? h : NULL);
    put(A, m->ev[e], 2, A->w, v, wantg ? g : NULL, wanth ? h : NULL);
  }
}

int tds_eval_global_row(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, int method, double w,
                        int32_t gq, double *total) {
  const tds_method *row = &tds_methods[method];
  acc A = {s, out, w, gq, 0};
  int wantg = gq != -2 || out->hess;
  int wanth = out->hess != NULL;
  if (!out->grad && gq == -1) A.gq = -2, wantg = out->hess != NULL;
  int rc = TDS_OK;
  double kp = param(s, "knot_power", 2);
  switch (row->iter) {
  case TDS_IT_VPAIR:
    rc = vpair(ctx, &A, row, kp, wantg, wanth);
    break;
  case TDS_IT_EPAIR:
    if (wanth)
      return tds_seterr(ctx, TDS_ERANGE,
                        "method %s has no Hessian (nor in Evolver): use g, not hessian",
                        row->name);
    /* edge_knot_energy and circle_knot_energy have power 2 whatever
    ** knot_power says (measured: Evolver's values do not change) */
    if (method == TDS_M_CIRCLE_KNOT || method == TDS_M_EDGE_KNOT) kp = 2;
    rc = epair(ctx, &A, row, kp, wantg);
    break;
  case TDS_IT_VSTAR: {
    double cp = param(s, "curvature_power", 2);
    if (cp != 2)
      return tds_seterr(ctx, TDS_ERANGE,
                        "method %s: curvature_power %g is not supported yet (only 2)",
                        row->name, cp);
    rc = vstar(ctx, &A, row, wantg, wanth);
    break;
  }
  case TDS_IT_EDGE_K:
    hooke(&A, method, wantg, wanth);
    break;
  default:
    return tds_seterr(ctx, TDS_ERANGE, "method %s: not a global row", row->name);
  }
  *total = A.total;
  return rc;
}
