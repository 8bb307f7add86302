/* newton_asm.c: the Newton system assembled straight into its unknowns
** (newton_int.h, tds_nsys_assemble).
**
** tds_nsys_build's general path assembles the xyz Hessian as triplets,
** then restricts it to the motion spaces and to the normals (two more
** triplet passes, each a sort). Here the restriction comes first: each
** movable vertex k gets its unknowns' directions in space, D_k (3 x c_k,
** the motion basis times the normal columns), before the assembly, and
** every element Hessian is projected at once, D_k^T h_kl D_l, into a CSC
** matrix whose pattern is built from the edges (vertex k's unknowns
** couple with those of its edge neighbours and its own). No triplets, no
** sort: one pass over the elements. The curvature of the level sets and
** boundaries (hess.h, tds_hess_reduce), which needs the gradient, is
** added to the diagonal blocks afterwards.
**
** An element that couples two vertices without an edge between them
** (none of the built-in terms does) makes the assembly report a miss;
** the caller then takes the general path. */
#include <math.h>
#include <string.h>

#include "eval.h"
#include "fixq.h"
#include "motion.h"
#include "newton_int.h"
#include "vec3.h"

typedef struct pat {
  const int32_t *vk;      /* vertex slot -> movable index k, or -1 */
  const int32_t *ustart;  /* k -> first unknown (ustart[nvm] = m) */
  double (*D)[3][3];      /* k -> D[i][a]: dx_i per unit of its unknown a */
  int32_t *nbstart;       /* k -> range of its neighbours in nb, noff */
  int32_t *nb;            /* neighbours l <= k, ascending; the last is k */
  int32_t *noff;          /* rows of nb[i]'s unknowns before it in k's columns */
  int32_t *colptr, *rowind;
  double *val;
  int miss;               /* an element coupled vertices without an edge */
} pat;

static void pat_free(const tds_alloc *al, pat *p) {
  tds_free(al, p->nbstart);
  tds_free(al, p->nb);
  tds_free(al, p->noff);
}

/* Add w D_k^T h_cd D_l to the upper blocks (k <= l) of the element with
** corners vs (tds_hess_acc.add). */
static void add_elem(tds_hess_acc *ha, const tds_id *vs, int kind, double w,
                     double (*h)[9]) {
  pat *p = ha->user;
  for (int c = 0; c < kind; c++) {
    int32_t k = p->vk[vs[c]];
    if (k < 0) continue;
    int ck = p->ustart[k + 1] - p->ustart[k];
    if (!ck) continue;
    const double(*Dk)[3] = p->D[k];
    for (int d = 0; d < kind; d++) {
      int32_t l = p->vk[vs[d]];
      if (l < k) continue; /* the transposed block comes from (d, c) */
      int cl = p->ustart[l + 1] - p->ustart[l];
      if (!cl) continue;
      int32_t i = p->nbstart[l];
      while (i < p->nbstart[l + 1] && p->nb[i] != k) i++;
      if (i == p->nbstart[l + 1]) {
        p->miss = 1;
        continue;
      }
      const double(*Dl)[3] = p->D[l];
      for (int b = 0; b < cl; b++) {
        double g[3];
        for (int r = 0; r < 3; r++)
          g[r] = h[3 * c + r][3 * d] * Dl[0][b] + h[3 * c + r][3 * d + 1] * Dl[1][b] +
                 h[3 * c + r][3 * d + 2] * Dl[2][b];
        double *col = p->val + p->colptr[p->ustart[l] + b] + p->noff[i];
        int na = k == l ? b + 1 : ck;
        for (int a = 0; a < na; a++)
          col[a] += w * (Dk[0][a] * g[0] + Dk[1][a] * g[1] + Dk[2][a] * g[2]);
      }
    }
  }
}

/* The pattern: vertex k's columns hold the unknowns of its edge
** neighbours below it, then its own up to the diagonal. TDS_OK or
** TDS_ENOMEM. */
static int pat_build(tds_ctx *ctx, const tds_mesh *m, int32_t nvm, pat *p, int32_t *nnz) {
  const tds_alloc *al = &ctx->alloc;
  const int32_t *vk = p->vk, *us = p->ustart;
  p->nbstart = tds_calloc(al, (size_t)nvm + 2, sizeof *p->nbstart);
  if (!p->nbstart) return TDS_ENOMEM;
  int32_t *cnt = p->nbstart + 1;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    int32_t a = vk[m->ev[e][0]], b = vk[m->ev[e][1]];
    if (a < 0 || b < 0 || a == b || us[a + 1] == us[a] || us[b + 1] == us[b]) continue;
    cnt[a > b ? a : b]++;
  }
  for (int32_t k = 0; k < nvm; k++) cnt[k] += us[k + 1] > us[k]; /* itself */
  for (int32_t k = 0; k < nvm; k++) p->nbstart[k + 1] += p->nbstart[k];
  int32_t tot = p->nbstart[nvm];
  p->nb = tds_malloc(al, ((size_t)tot + 1) * sizeof *p->nb);
  p->noff = tds_malloc(al, ((size_t)tot + 1) * sizeof *p->noff);
  if (!p->nb || !p->noff) return TDS_ENOMEM;
  int32_t *fill = p->noff; /* scratch: next free place per vertex */
  for (int32_t k = 0; k < nvm; k++) fill[k] = p->nbstart[k];
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    int32_t a = vk[m->ev[e][0]], b = vk[m->ev[e][1]];
    if (a < 0 || b < 0 || a == b || us[a + 1] == us[a] || us[b + 1] == us[b]) continue;
    if (a > b) p->nb[fill[a]++] = b;
    else p->nb[fill[b]++] = a;
  }
  for (int32_t k = 0; k < nvm; k++)
    if (us[k + 1] > us[k]) p->nb[fill[k]++] = k;
  /* sort each list (short: insertion), drop repeats (parallel edges) */
  int32_t out = 0, start = 0;
  for (int32_t k = 0; k < nvm; k++) {
    int32_t lo = start, hi = p->nbstart[k + 1];
    start = hi;
    for (int32_t i = lo + 1; i < hi; i++)
      for (int32_t j = i; j > lo && p->nb[j] < p->nb[j - 1]; j--) {
        int32_t t = p->nb[j];
        p->nb[j] = p->nb[j - 1];
        p->nb[j - 1] = t;
      }
    p->nbstart[k] = out;
    for (int32_t i = lo; i < hi; i++)
      if (i == lo || p->nb[i] != p->nb[i - 1]) p->nb[out++] = p->nb[i];
  }
  p->nbstart[nvm] = out;
  /* offsets and the column pointers */
  int64_t n = 0;
  int32_t mm = us[nvm];
  p->colptr = tds_malloc(al, ((size_t)mm + 1) * sizeof *p->colptr);
  if (!p->colptr) return TDS_ENOMEM;
  for (int32_t k = 0; k < nvm; k++) {
    int32_t off = 0;
    for (int32_t i = p->nbstart[k]; i < p->nbstart[k + 1]; i++) {
      p->noff[i] = off;
      off += us[p->nb[i] + 1] - us[p->nb[i]];
    }
    int32_t below = off - (us[k + 1] - us[k]); /* rows before its own */
    for (int32_t b = us[k]; b < us[k + 1]; b++) {
      p->colptr[b] = (int32_t)n;
      n += below + (b - us[k]) + 1;
      if (n > INT32_MAX) return TDS_ERANGE;
    }
  }
  p->colptr[mm] = (int32_t)n;
  *nnz = (int32_t)n;
  p->rowind = tds_malloc(al, ((size_t)n + 1) * sizeof *p->rowind);
  p->val = tds_calloc(al, (size_t)n + 1, sizeof *p->val);
  if (!p->rowind || !p->val) return TDS_ENOMEM;
  for (int32_t k = 0; k < nvm; k++)
    for (int32_t b = us[k]; b < us[k + 1]; b++) {
      int32_t e = p->colptr[b];
      for (int32_t i = p->nbstart[k]; i < p->nbstart[k + 1]; i++) {
        int32_t l = p->nb[i], end = l == k ? b + 1 : us[l + 1];
        for (int32_t r = us[l]; r < end; r++) p->rowind[e++] = r;
      }
    }
  return TDS_OK;
}

/* A vertex on no constraint and no boundary: its motion basis is the
** identity, with no curvature (tds_hess_vertex_space's answer, quicker). */
static int plain(const tds_mesh *m, tds_id v) {
  return m->vcon[v] == 0 && m->vbdry[v] == TDS_NONE;
}

int tds_nsys_assemble(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_nsys *out,
                      int *miss) {
  memset(out, 0, sizeof *out);
  out->alloc = ctx->alloc;
  *miss = 0;
  const tds_alloc *al = &ctx->alloc;
  tds_mesh *m = &s->m;
  tds_fixq fq = {0};
  pat p = {0};
  vnorm *vn = NULL;
  int32_t *vk = NULL, *vert = NULL, *ustart = NULL;
  double (*W)[3][3] = NULL, (*D)[3][3] = NULL, (*grad)[3] = NULL, *qw = NULL;
  int rc = tds_fixq_build(ctx, s, &fq);
  if (rc != TDS_OK) return rc;
  int32_t nq = out->nq = fq.nq;
  size_t nv1 = (size_t)m->nv + 1;
  vk = tds_malloc(al, nv1 * sizeof *vk);
  vert = tds_malloc(al, nv1 * sizeof *vert);
  vn = tds_malloc(al, nv1 * sizeof *vn);
  grad = tds_calloc(al, nv1, sizeof *grad);
  qw = tds_calloc(al, (size_t)nq + 1, sizeof *qw);
  out->mult = tds_calloc(al, (size_t)nq + 1, sizeof *out->mult);
  out->value = tds_calloc(al, (size_t)nq + 1, sizeof *out->value);
  out->target = tds_calloc(al, (size_t)nq + 1, sizeof *out->target);
  if (!vk || !vert || !vn || !grad || !qw || !out->mult || !out->value || !out->target)
    goto nomem;
  int32_t nvm = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    vk[v] = tds_vertex_free(s, v) ? nvm : -1;
    if (vk[v] >= 0) vert[nvm++] = v;
  }
  for (int32_t q = 0; q < nq; q++) {
    out->mult[q] = fq.qbody[q] != TDS_NONE ? m->bpressure[fq.qbody[q]]
                                           : s->quant[fq.qquant[q]].pressure;
    qw[q] = -out->mult[q];
  }
  /* the unknowns: motion basis B times normal columns W */
  W = tds_malloc(al, ((size_t)nvm + 1) * sizeof *W);
  D = tds_calloc(al, (size_t)nvm + 1, sizeof *D);
  ustart = tds_malloc(al, ((size_t)nvm + 2) * sizeof *ustart);
  if (!W || !D || !ustart) goto nomem;
  if ((rc = tds_hess_normals(ctx, s, o, vn)) != TDS_OK) goto fail;
  ustart[0] = 0;
  for (int32_t k = 0; k < nvm; k++) {
    static const double zero[3] = {0, 0, 0};
    double B[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, C[3][3];
    int d = plain(m, vert[k]) ? 3 : tds_hess_vertex_space(s, vert[k], zero, B, C);
    int c = d == 0 ? 0 : tds_normal_columns(&vn[vert[k]], (const double(*)[3])B, d, !o->normal, W[k]);
    for (int i = 0; i < 3; i++)
      for (int b = 0; b < c; b++) {
        double x = 0;
        for (int a = 0; a < d; a++) x += B[i][a] * W[k][a][b];
        D[k][i][b] = x;
      }
    ustart[k + 1] = ustart[k] + c;
  }
  int32_t mm = out->m = ustart[nvm];
  p.vk = vk;
  p.ustart = ustart;
  p.D = D;
  int32_t nnz = 0;
  if ((rc = pat_build(ctx, m, nvm, &p, &nnz)) != TDS_OK) {
    if (rc == TDS_ENOMEM) goto nomem;
    rc = tds_seterr(ctx, TDS_ERANGE, "hessian: the matrix is too big");
    goto fail;
  }
  /* the assembly */
  tds_hess_acc acc = {.ew = 1, .qw = qw, .add = add_elem, .user = &p};
  tds_eval_out eo = {.grad = grad, .fq = nq ? &fq : NULL, .hess = &acc};
  if ((rc = tds_eval(ctx, s, &eo)) != TDS_OK) goto fail;
  if (p.miss) {
    *miss = 1;
    goto fail;
  }
  out->energy = eo.energy;
  for (int32_t q = 0; q < nq; q++) {
    out->value[q] = fq.value[q];
    out->target[q] = fq.target[q];
  }
  out->vert = tds_malloc(al, ((size_t)mm + 1) * sizeof *out->vert);
  out->mv = tds_calloc(al, (size_t)mm + 1, sizeof *out->mv);
  out->dx = tds_calloc(al, (size_t)mm + 1, sizeof *out->dx);
  out->grad = tds_calloc(al, (size_t)mm + 1, sizeof *out->grad);
  if (!out->vert || !out->mv || !out->dx || !out->grad) goto nomem;
  /* per vertex: the Lagrangian's gradient f, the curvature block, the
  ** unknowns' gradient and directions */
  int32_t *acnt = tds_calloc(al, (size_t)nq + 2, sizeof *acnt);
  if (!acnt) goto nomem;
  for (int32_t k = 0; k < nvm; k++) {
    tds_id v = vert[k];
    int c = ustart[k + 1] - ustart[k];
    if (!c) continue;
    double f[3];
    v3_copy(f, grad[v]);
    if (v < fq.nv)
      for (int32_t e = fq.start[v]; e < fq.start[v + 1]; e++) {
        v3_axpy(f, qw[fq.eq[e]], fq.g[e]);
        acnt[fq.eq[e] + 1] += c;
      }
    double B[3][3], C[3][3] = {{0}};
    int d = plain(m, v) ? 3 : tds_hess_vertex_space(s, v, f, B, C);
    int32_t self = p.nbstart[k + 1] - 1;
    for (int b = 0; b < c; b++) {
      int32_t j = ustart[k] + b;
      out->vert[j] = v;
      for (int i = 0; i < 3; i++) out->dx[j][i] = D[k][i][b];
      out->grad[j] = v3_dot(out->dx[j], f);
      if (m->vbdry[v] != TDS_NONE)
        for (int a = 0; a < d; a++) out->mv[j][a] = W[k][a][b];
      else
        v3_copy(out->mv[j], out->dx[j]);
      double *col = p.val + p.colptr[j] + p.noff[self];
      for (int a = 0; a <= b; a++) {
        double x = 0;
        for (int r = 0; r < d; r++)
          for (int t = 0; t < d; t++) x += W[k][r][a] * C[r][t] * W[k][t][b];
        col[a] += x;
      }
    }
  }
  /* A = D^T (grad Q_q), column by column in the unknowns' order */
  for (int32_t q = 0; q < nq; q++) acnt[q + 1] += acnt[q];
  out->A = (tds_spmat){.nrow = mm, .ncol = nq, .alloc = ctx->alloc};
  out->A.colptr = tds_malloc(al, ((size_t)nq + 1) * sizeof *out->A.colptr);
  out->A.rowind = tds_malloc(al, ((size_t)acnt[nq] + 1) * sizeof *out->A.rowind);
  out->A.val = tds_malloc(al, ((size_t)acnt[nq] + 1) * sizeof *out->A.val);
  if (!out->A.colptr || !out->A.rowind || !out->A.val) {
    tds_free(al, acnt);
    goto nomem;
  }
  memcpy(out->A.colptr, acnt, ((size_t)nq + 1) * sizeof *acnt);
  for (int32_t k = 0; k < nvm; k++) {
    tds_id v = vert[k];
    if (v >= fq.nv) continue;
    for (int32_t e = fq.start[v]; e < fq.start[v + 1]; e++)
      for (int32_t j = ustart[k]; j < ustart[k + 1]; j++) {
        int32_t at = acnt[fq.eq[e]]++;
        out->A.rowind[at] = j;
        out->A.val[at] = v3_dot(out->dx[j], fq.g[e]);
      }
  }
  tds_free(al, acnt);
  out->H = (tds_spmat){.nrow = mm, .ncol = mm, .upper = 1, .colptr = p.colptr,
                       .rowind = p.rowind, .val = p.val, .alloc = ctx->alloc};
  p.colptr = p.rowind = NULL;
  p.val = NULL;
  if (o->linear_metric &&
      (rc = tds_nsys_build_metric(ctx, s, o->metric_mix, o->normal_perp, vk, ustart, out)) != TDS_OK)
    goto fail;
  rc = TDS_OK;
  goto done;
nomem:
  rc = tds_seterr(ctx, TDS_ENOMEM, "hessian: out of memory");
fail:
  tds_nsys_free(out);
done:
  tds_free(al, p.colptr);
  tds_free(al, p.rowind);
  tds_free(al, p.val);
  pat_free(al, &p);
  tds_fixq_free(&fq);
  tds_free(al, vk);
  tds_free(al, vert);
  tds_free(al, vn);
  tds_free(al, grad);
  tds_free(al, qw);
  tds_free(al, W);
  tds_free(al, D);
  tds_free(al, ustart);
  return rc;
}
