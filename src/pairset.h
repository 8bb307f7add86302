/*
** pairset.h: a set of unordered vertex pairs (undirected edges), open
** addressing with linear probing. Used by the flip passes to refuse a flip
** that would create an edge that already exists.
*/
#ifndef TDS_PAIRSET_H
#define TDS_PAIRSET_H

#include <stdint.h>

#include "tds.h"

typedef struct tds_pairset {
  uint64_t *key; /* 0 = empty slot */
  size_t cap;    /* a power of two, at least twice the pairs held */
  tds_alloc alloc;
} tds_pairset;

/* A set sized for up to n pairs, allocated through a (kept to free it).
** TDS_OK or TDS_ENOMEM. */
int tds_pairset_init(tds_pairset *ps, const tds_alloc *a, size_t n);
void tds_pairset_free(tds_pairset *ps);
int tds_pairset_has(const tds_pairset *ps, tds_id a, tds_id b);
/* Insert {a, b}; the set must have room (fewer than n pairs held). */
void tds_pairset_add(tds_pairset *ps, tds_id a, tds_id b);
void tds_pairset_remove(tds_pairset *ps, tds_id a, tds_id b);
/* Remove every pair. */
void tds_pairset_clear(tds_pairset *ps);

#endif
