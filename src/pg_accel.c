/* pg_accel.c: Anderson acceleration (type II) of the pg fixed-point map
** X -> G(X), X the positions of the movable vertices (parameters for
** boundary vertices) and G(X) the positions after one plain iteration.
**
**   F_k = G(X_k) - X_k,   dF_j = F_{j+1} - F_j,   dG_j = G_{j+1} - G_j
**   gamma = argmin |F_k - sum_j gamma_j dF_j|   (the last m differences)
**   X_{k+1} = G(X_k) - sum_j gamma_j dG_j
**
** The Gram matrix of the dF columns is kept up to date one column per
** step (one sweep over the history computes the new column's products
** and dF^T F together), so a step costs two reads of the history.
** Safeguards (each clears the history; the step is then plain):
**   - a mixed vertex would land more than sqrt(lim2) from its plain move;
**   - |F| grew a hundredfold over the best since the last restart;
**   - no new best |F| for 4 m steps (stagnation);
**   - the small least-squares system is singular.
** The driver also clears the history after every flip (the map changed).
*/
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pg_int.h"

/* Vector arithmetic (GCC/Clang vector extensions): two lanes, unaligned
** loads (SSE2 on x86-64). Every sum below has a fixed order (eight
** partial sums, added in a fixed order), so the results do not depend on
** the instruction set. */
typedef double v2d __attribute__((vector_size(16), aligned(8)));

static inline v2d ld2(const double *p) {
  v2d v;
  memcpy(&v, p, sizeof v);
  return v;
}

static inline double hsum4(v2d a, v2d b, v2d c, v2d d) {
  v2d e = (a + b) + (c + d);
  return e[0] + e[1];
}

/* (a . b, a . c) over n entries. */
static inline __attribute__((always_inline)) void dot2_impl(const double *restrict a, const double *restrict b,
                 const double *restrict c, int32_t n, double *ab, double *ac) {
  v2d s0 = {0, 0}, s1 = s0, s2 = s0, s3 = s0, t0 = s0, t1 = s0, t2 = s0, t3 = s0;
  int32_t i = 0;
  for (; i + 8 <= n; i += 8) {
    v2d a0 = ld2(a + i), a1 = ld2(a + i + 2), a2 = ld2(a + i + 4), a3 = ld2(a + i + 6);
    s0 += a0 * ld2(b + i);
    s1 += a1 * ld2(b + i + 2);
    s2 += a2 * ld2(b + i + 4);
    s3 += a3 * ld2(b + i + 6);
    t0 += a0 * ld2(c + i);
    t1 += a1 * ld2(c + i + 2);
    t2 += a2 * ld2(c + i + 4);
    t3 += a3 * ld2(c + i + 6);
  }
  double s = hsum4(s0, s1, s2, s3), t = hsum4(t0, t1, t2, t3);
  for (; i < n; i++) {
    s += a[i] * b[i];
    t += a[i] * c[i];
  }
  *ab = s;
  *ac = t;
}

/* x = g - sum_c gam[c] col_c (the columns in order), n entries. */
static inline __attribute__((always_inline)) void mix_impl(double *restrict x, const double *restrict g,
                const double *cols, size_t stride, const double *gam, int h,
                int32_t n) {
  int32_t i = 0;
  for (; i + 8 <= n; i += 8) {
    v2d x0 = ld2(g + i), x1 = ld2(g + i + 2), x2 = ld2(g + i + 4), x3 = ld2(g + i + 6);
    for (int c = 0; c < h; c++) {
      const double *d = cols + (size_t)c * stride + i;
      v2d gc = {gam[c], gam[c]};
      x0 -= gc * ld2(d);
      x1 -= gc * ld2(d + 2);
      x2 -= gc * ld2(d + 4);
      x3 -= gc * ld2(d + 6);
    }
    memcpy(x + i, &x0, sizeof x0);
    memcpy(x + i + 2, &x1, sizeof x1);
    memcpy(x + i + 4, &x2, sizeof x2);
    memcpy(x + i + 6, &x3, sizeof x3);
  }
  for (; i < n; i++) {
    double t = g[i];
    for (int c = 0; c < h; c++) t -= gam[c] * cols[(size_t)c * stride + i];
    x[i] = t;
  }
}

/* The same code for the widest vector unit (the same operations in the
** same order: the same bits); isa as pg_accel.isa. */

static void dot2_generic(const double *a, const double *b, const double *c,
                         int32_t n, double *ab, double *ac) {
  dot2_impl(a, b, c, n, ab, ac);
}

static void mix_generic(double *x, const double *g, const double *cols,
                        size_t stride, const double *gam, int h, int32_t n) {
  mix_impl(x, g, cols, stride, gam, h, n);
}

#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((target("avx2"))) static void dot2_avx2(const double *a, const double *b,
                                                      const double *c, int32_t n,
                                                      double *ab, double *ac) {
  dot2_impl(a, b, c, n, ab, ac);
}

__attribute__((target("avx2"))) static void mix_avx2(double *x, const double *g,
                                                     const double *cols, size_t stride,
                                                     const double *gam, int h, int32_t n) {
  mix_impl(x, g, cols, stride, gam, h, n);
}
#define HAVE_AVX2_PATH 1
#endif

static void dot2(int isa, const double *a, const double *b, const double *c,
                 int32_t n, double *ab, double *ac) {
  (void)isa;
#ifdef HAVE_AVX2_PATH
  if (isa > 0) {
    dot2_avx2(a, b, c, n, ab, ac);
    return;
  }
#endif
  dot2_generic(a, b, c, n, ab, ac);
}

static void mix(int isa, double *x, const double *g, const double *cols,
                size_t stride, const double *gam, int h, int32_t n) {
  (void)isa;
#ifdef HAVE_AVX2_PATH
  if (isa > 0) {
    mix_avx2(x, g, cols, stride, gam, h, n);
    return;
  }
#endif
  mix_generic(x, g, cols, stride, gam, h, n);
}

int pg_accel_init(pg_accel *a, const tds_alloc *al, int32_t nstate, int depth) {
  memset(a, 0, sizeof *a);
  if (al) a->al = *al;
  a->depth = depth;
  a->N = nstate;
  size_t N = (size_t)(nstate > 0 ? nstate : 1), m = (size_t)depth;
  a->X = tds_calloc(&a->al, N, sizeof *a->X);
  a->G = tds_calloc(&a->al, N, sizeof *a->G);
  a->Fprev = tds_calloc(&a->al, N, sizeof *a->Fprev);
  a->Gprev = tds_calloc(&a->al, N, sizeof *a->Gprev);
  a->dF = tds_calloc(&a->al, N * m, sizeof *a->dF);
  a->dG = tds_calloc(&a->al, N * m, sizeof *a->dG);
  a->M = tds_calloc(&a->al, m * m, sizeof *a->M);
  a->Ms = tds_calloc(&a->al, m * m, sizeof *a->Ms);
  a->gam = tds_calloc(&a->al, m, sizeof *a->gam);
  a->sc = tds_calloc(&a->al, m, sizeof *a->sc);
  if (!a->X || !a->G || !a->Fprev || !a->Gprev || !a->dF || !a->dG || !a->M ||
      !a->Ms || !a->gam || !a->sc) {
    pg_accel_free(a);
    return TDS_ENOMEM;
  }
  pg_accel_reset(a);
  a->cooldown = 2 * depth;
  a->isa = pg_pass_isa(1);
  return TDS_OK;
}

void pg_accel_free(pg_accel *a) {
  tds_alloc al = a->al;
  tds_free(&al, a->X);
  tds_free(&al, a->G);
  tds_free(&al, a->Fprev);
  tds_free(&al, a->Gprev);
  tds_free(&al, a->dF);
  tds_free(&al, a->dG);
  tds_free(&al, a->M);
  tds_free(&al, a->Ms);
  tds_free(&al, a->gam);
  tds_free(&al, a->sc);
  memset(a, 0, sizeof *a);
}

void pg_accel_reset(pg_accel *a) {
  a->hist = 0;
  a->head = 0;
  a->have_prev = 0;
  a->fbest = a->fref = INFINITY;
  a->kbest = a->steps;
}

static void restart(pg_accel *a) {
  pg_accel_reset(a);
  a->restarts++;
}

int pg_accel_mix(pg_accel *a, double lim2) {
  const int32_t N = a->N;
  const int m = a->depth;
  double *restrict X = a->X;
  const double *restrict G = a->G;
  double fn = 0;
  for (int32_t i = 0; i < N; i++) {
    double f = G[i] - X[i];
    fn += f * f;
  }
  a->steps++;
  if (a->cool > 0) { /* plain steps after a stagnation */
    a->cool--;
    memcpy(X, G, (size_t)N * sizeof *X);
    return 0;
  }
  if (fn < a->fbest) a->fbest = fn;
  if (fn < 0.25 * a->fref) { /* |F| halved: progress */
    a->fref = fn;
    a->kbest = a->steps;
    if (a->hist > 0) a->cooldown = 2 * m; /* the history helps again */
  } else if (fn > 1e4 * a->fbest) { /* diverging: start over from here */
    restart(a);
    a->fbest = a->fref = fn;
    a->kbest = a->steps;
  } else if (a->steps - a->kbest > 3 * (int64_t)m) {
    /* Stagnating (far from the solution the map is too nonlinear for
    ** the history): plain steps for a while, longer after each failure. */
    restart(a);
    a->cool = a->cooldown;
    a->cooldown = a->cooldown < 8 * m ? 2 * a->cooldown : 8 * m;
    a->fbest = a->fref = INFINITY;
    a->kbest = a->steps + a->cool;
    memcpy(X, G, (size_t)N * sizeof *X);
    return 0;
  }
  if (a->have_prev) {
    /* New column: dF = F - Fprev, dG = G - Gprev; then Fprev, Gprev. */
    int col = a->head;
    double *restrict dF = a->dF + (size_t)col * N;
    double *restrict dG = a->dG + (size_t)col * N;
    double *restrict Fp = a->Fprev, *restrict Gp = a->Gprev;
    for (int32_t i = 0; i < N; i++) {
      double f = G[i] - X[i];
      dF[i] = f - Fp[i];
      dG[i] = G[i] - Gp[i];
      Fp[i] = f;
      Gp[i] = G[i];
    }
    a->head = (a->head + 1) % m;
    if (a->hist < m) a->hist++;
    /* One sweep: M[c][col] = dF_c . dF_col and gam[c] = dF_c . F. */
    for (int c = 0; c < a->hist; c++) {
      double mc, gc;
      dot2(a->isa, a->dF + (size_t)c * N, dF, Fp, N, &mc, &gc);
      a->M[c * m + col] = a->M[col * m + c] = mc;
      a->gam[c] = gc;
    }
  } else {
    for (int32_t i = 0; i < N; i++) {
      a->Fprev[i] = G[i] - X[i];
      a->Gprev[i] = G[i];
    }
  }
  a->have_prev = 1;
  int h = a->hist;
  if (h == 0) {
    memcpy(X, G, (size_t)N * sizeof *X);
    return 0;
  }
  /* gamma = argmin |F - dF gamma|: the normal equations, with the columns
  ** scaled to unit length (the columns' lengths span many orders of
  ** magnitude as the run converges) and a small relative ridge. */
  double *sc = a->sc;
  for (int c = 0; c < h; c++) {
    double d = a->M[c * m + c];
    sc[c] = d > 0 ? 1 / sqrt(d) : 0;
  }
  double rhs[64];
  for (int i = 0; i < h; i++) {
    for (int j = 0; j < h; j++) a->Ms[i * h + j] = a->M[i * m + j] * sc[i] * sc[j];
    a->Ms[i * h + i] = 1 + 1e-10;
    rhs[i] = a->gam[i] * sc[i];
  }
  if (tds_dense_solve(h, a->Ms, rhs) != 0) {
    restart(a);
    memcpy(X, G, (size_t)N * sizeof *X);
    return 0;
  }
  for (int c = 0; c < h; c++) a->gam[c] = rhs[c] * sc[c];
  mix(a->isa, X, G, a->dG, (size_t)N, a->gam, h, N);
  /* No vertex may jump far from its plain move. */
  for (int32_t j = 0; j + 2 < N; j += 3) {
    double dx = X[j] - G[j], dy = X[j + 1] - G[j + 1], dz = X[j + 2] - G[j + 2];
    if (!(dx * dx + dy * dy + dz * dz <= lim2)) {
      restart(a);
      memcpy(X, G, (size_t)N * sizeof *X);
      return 0;
    }
  }
  return 1;
}
