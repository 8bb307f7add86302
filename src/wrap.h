/*
** wrap.h: torus wraps of edges (the torus model, torus.h).
**
** An edge's wrap says how it crosses the unit cell: lattice counts k[0..2],
** one per period vector, so the true head of the edge seen from its tail is
** x[head] + k[0] period[0] + k[1] period[1] + k[2] period[2]. Evolver's
** datafile writes each count as * (0), + (1) or - (-1); refining and other
** operations may produce larger counts. Packed in one int32 per edge
** (tds_mesh.ewrap), 10 signed bits per period, 0 meaning no wrap, so that
** the column needs no special default and a non-torus mesh reads zeros.
*/
#ifndef TDS_WRAP_H
#define TDS_WRAP_H

#include <stdint.h>

#define TDS_WRAP_MAX 511 /* largest count one field holds */

static inline int32_t tds_wrap_pack(const int k[3]) {
  uint32_t w = 0;
  for (int i = 0; i < 3; i++) w |= ((uint32_t)k[i] & 1023u) << (10 * i);
  return (int32_t)w;
}

static inline void tds_wrap_unpack(int32_t w, int k[3]) {
  for (int i = 0; i < 3; i++) {
    int v = (int)(((uint32_t)w >> (10 * i)) & 1023u);
    k[i] = v >= 512 ? v - 1024 : v;
  }
}

/* a + b (counts added; the caller keeps them within TDS_WRAP_MAX). */
static inline int32_t tds_wrap_add(int32_t a, int32_t b) {
  int ka[3], kb[3];
  tds_wrap_unpack(a, ka);
  tds_wrap_unpack(b, kb);
  for (int i = 0; i < 3; i++) ka[i] += kb[i];
  return tds_wrap_pack(ka);
}

static inline int32_t tds_wrap_neg(int32_t a) {
  int k[3];
  tds_wrap_unpack(a, k);
  for (int i = 0; i < 3; i++) k[i] = -k[i];
  return tds_wrap_pack(k);
}

/* Nonzero when a + b would leave the representable range. */
static inline int tds_wrap_overflows(int32_t a, int32_t b) {
  int ka[3], kb[3];
  tds_wrap_unpack(a, ka);
  tds_wrap_unpack(b, kb);
  for (int i = 0; i < 3; i++)
    if (ka[i] + kb[i] > TDS_WRAP_MAX || ka[i] + kb[i] < -TDS_WRAP_MAX) return 1;
  return 0;
}

/* d = the translation of wrap w: sum of k[i] period[i]. Written out, not
** a loop: gcc -O2 keeps a loop of three, storing d one by one, and the
** caller's vectorised code then loads d in pairs, each load straddling two
** stores (a store-forwarding stall, some 15 cycles). */
static inline void tds_wrap_vec(const double (*period)[3], int32_t w, double d[3]) {
  int k[3];
  tds_wrap_unpack(w, k);
  d[0] = k[0] * period[0][0] + k[1] * period[1][0] + k[2] * period[2][0];
  d[1] = k[0] * period[0][1] + k[1] * period[1][1] + k[2] * period[2][1];
  d[2] = k[0] * period[0][2] + k[1] * period[1][2] + k[2] * period[2][2];
}

#endif
