/* pairset.c: a set of unordered vertex pairs. */
#include "pairset.h"

#include <stdlib.h>
#include <string.h>

static uint64_t pkey(tds_id a, tds_id b) {
  uint64_t lo = (uint32_t)(a < b ? a : b), hi = (uint32_t)(a < b ? b : a);
  return (hi << 32 | lo) + 1; /* never 0 */
}

static size_t phash(uint64_t k, size_t cap) {
  k ^= k >> 33;
  k *= 0xff51afd7ed558ccdULL;
  k ^= k >> 33;
  return (size_t)k & (cap - 1);
}

static size_t pfind(const tds_pairset *ps, uint64_t k) {
  size_t i = phash(k, ps->cap);
  while (ps->key[i] && ps->key[i] != k) i = (i + 1) & (ps->cap - 1);
  return i;
}

int tds_pairset_init(tds_pairset *ps, const tds_alloc *a, size_t n) {
  ps->alloc = a ? *a : (tds_alloc){0};
  ps->cap = 16;
  while (ps->cap < 2 * n + 16) ps->cap *= 2;
  ps->key = tds_calloc(&ps->alloc, ps->cap, sizeof *ps->key);
  return ps->key ? TDS_OK : TDS_ENOMEM;
}

void tds_pairset_free(tds_pairset *ps) {
  tds_free(&ps->alloc, ps->key);
  ps->key = NULL;
  ps->cap = 0;
}

int tds_pairset_has(const tds_pairset *ps, tds_id a, tds_id b) {
  return ps->key[pfind(ps, pkey(a, b))] != 0;
}

void tds_pairset_add(tds_pairset *ps, tds_id a, tds_id b) {
  TDS_ASSERT(a >= 0 && b >= 0 && ps->key);
  uint64_t k = pkey(a, b);
  ps->key[pfind(ps, k)] = k;
}

/* Deletion with backward shift, so probe chains stay intact. */
void tds_pairset_remove(tds_pairset *ps, tds_id a, tds_id b) {
  size_t i = pfind(ps, pkey(a, b));
  if (!ps->key[i]) return;
  size_t j = i;
  for (;;) {
    ps->key[i] = 0;
    for (;;) {
      j = (j + 1) & (ps->cap - 1);
      if (!ps->key[j]) return;
      size_t h = phash(ps->key[j], ps->cap);
      /* the entry at j may stay if its home h lies cyclically in (i, j] */
      if (i <= j ? (i < h && h <= j) : (i < h || h <= j)) continue;
      break;
    }
    ps->key[i] = ps->key[j];
    i = j;
  }
}

void tds_pairset_clear(tds_pairset *ps) {
  if (ps->key) memset(ps->key, 0, ps->cap * sizeof *ps->key);
}
