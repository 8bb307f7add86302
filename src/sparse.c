/* sparse.c: triplets to CSC, lookup and product (sparse.h). */
#include "sparse.h"

#include <stdlib.h>
#include <string.h>


int tds_sptrip_add(tds_sptrip *t, int32_t i, int32_t j, double v) {
  TDS_ASSERT(i >= 0 && i < t->nrow && j >= 0 && j < t->ncol);
  if (t->n == t->cap) {
    int64_t cap = t->cap ? 2 * t->cap : 1024;
    int32_t *ni = tds_realloc(&t->alloc, t->i, (size_t)cap * sizeof *ni);
    if (!ni) return -1;
    t->i = ni;
    int32_t *nj = tds_realloc(&t->alloc, t->j, (size_t)cap * sizeof *nj);
    if (!nj) return -1;
    t->j = nj;
    double *nv = tds_realloc(&t->alloc, t->v, (size_t)cap * sizeof *nv);
    if (!nv) return -1;
    t->v = nv;
    t->cap = cap;
  }
  t->i[t->n] = i;
  t->j[t->n] = j;
  t->v[t->n] = v;
  t->n++;
  return 0;
}

void tds_sptrip_free(tds_sptrip *t) {
  tds_alloc a = t->alloc;
  tds_free(&a, t->i);
  tds_free(&a, t->j);
  tds_free(&a, t->v);
  memset(t, 0, sizeof *t);
  t->alloc = a;
}

void tds_spmat_free(tds_spmat *a) {
  tds_alloc al = a->alloc;
  tds_free(&al, a->colptr);
  tds_free(&al, a->rowind);
  tds_free(&al, a->val);
  memset(a, 0, sizeof *a);
  a->alloc = al;
}

typedef struct rv {
  int32_t r;
  double v;
} rv;

static int by_row(const void *a, const void *b) {
  int32_t x = ((const rv *)a)->r, y = ((const rv *)b)->r;
  return (x > y) - (x < y);
}

int tds_spmat_from_trip(const tds_sptrip *t, int upper, tds_spmat *out) {
  memset(out, 0, sizeof *out);
  out->alloc = t->alloc;
  out->nrow = t->nrow;
  out->ncol = t->ncol;
  out->upper = upper;
  int32_t nc = t->ncol;
  int64_t *cnt = tds_calloc(&out->alloc, (size_t)nc + 1, sizeof *cnt);
  rv *e = tds_malloc(&out->alloc, ((size_t)t->n + 1) * sizeof *e);
  out->colptr = tds_calloc(&out->alloc, (size_t)nc + 1, sizeof *out->colptr);
  if (!cnt || !e || !out->colptr) goto nomem;
  /* bucket by column (after mapping to the upper half) */
  for (int64_t k = 0; k < t->n; k++) {
    int32_t j = t->j[k];
    if (upper && t->i[k] > j) j = t->i[k];
    cnt[j + 1]++;
  }
  for (int32_t j = 0; j < nc; j++) cnt[j + 1] += cnt[j];
  int64_t *pos = tds_calloc(&out->alloc, (size_t)nc + 1, sizeof *pos);
  if (!pos) goto nomem;
  memcpy(pos, cnt, ((size_t)nc + 1) * sizeof *pos);
  for (int64_t k = 0; k < t->n; k++) {
    int32_t i = t->i[k], j = t->j[k];
    if (upper && i > j) {
      int32_t s = i;
      i = j;
      j = s;
    }
    e[pos[j]++] = (rv){i, t->v[k]};
  }
  tds_free(&out->alloc, pos);
  /* sort each column by row and sum repeats, compacting in place */
  int64_t n = 0;
  for (int32_t j = 0; j < nc; j++) {
    rv *c = e + cnt[j];
    int64_t len = cnt[j + 1] - cnt[j];
    if (len <= 48) { /* short columns (a mesh's): insertion sort */
      for (int64_t a = 1; a < len; a++) {
        rv x = c[a];
        int64_t b = a;
        for (; b > 0 && c[b - 1].r > x.r; b--) c[b] = c[b - 1];
        c[b] = x;
      }
    } else {
      qsort(c, (size_t)len, sizeof *c, by_row);
    }
    int64_t start = n;
    for (int64_t k = 0; k < len; k++) {
      if (n > start && e[n - 1].r == c[k].r) e[n - 1].v += c[k].v;
      else e[n++] = c[k];
    }
    if (n > INT32_MAX) goto nomem;
    out->colptr[j + 1] = (int32_t)n;
  }
  out->rowind = tds_malloc(&out->alloc, ((size_t)n + 1) * sizeof *out->rowind);
  out->val = tds_malloc(&out->alloc, ((size_t)n + 1) * sizeof *out->val);
  if (!out->rowind || !out->val) goto nomem;
  for (int64_t k = 0; k < n; k++) {
    out->rowind[k] = e[k].r;
    out->val[k] = e[k].v;
  }
  tds_free(&out->alloc, cnt);
  tds_free(&out->alloc, e);
  return 0;
nomem:
  tds_free(&out->alloc, cnt);
  tds_free(&out->alloc, e);
  tds_spmat_free(out);
  return -1;
}

double tds_spmat_get(const tds_spmat *a, int32_t i, int32_t j) {
  TDS_ASSERT(i >= 0 && i < a->nrow && j >= 0 && j < a->ncol);
  if (a->upper && i > j) {
    int32_t s = i;
    i = j;
    j = s;
  }
  int32_t lo = a->colptr[j], hi = a->colptr[j + 1];
  while (lo < hi) {
    int32_t mid = lo + (hi - lo) / 2;
    if (a->rowind[mid] < i) lo = mid + 1;
    else hi = mid;
  }
  return lo < a->colptr[j + 1] && a->rowind[lo] == i ? a->val[lo] : 0;
}

void tds_spmat_mulv(const tds_spmat *a, const double *x, double *y) {
  memset(y, 0, (size_t)a->nrow * sizeof *y);
  if (!a->upper) {
    for (int32_t j = 0; j < a->ncol; j++)
      for (int32_t k = a->colptr[j]; k < a->colptr[j + 1]; k++)
        y[a->rowind[k]] += a->val[k] * x[j];
    return;
  }
  /* Upper triangle: row j's terms of column j summed in a register (y[j]
  ** is 0 until column j, whose rows are at most j: the same sums in the
  ** same order as adding to y[j] in memory, without its latency) */
  for (int32_t j = 0; j < a->ncol; j++) {
    double xj = x[j], yj = 0;
    for (int32_t k = a->colptr[j]; k < a->colptr[j + 1]; k++) {
      int32_t i = a->rowind[k];
      double v = a->val[k];
      if (i != j) {
        y[i] += v * xj;
        yj += v * x[i];
      } else {
        yj += v * xj;
      }
    }
    y[j] += yj;
  }
}
