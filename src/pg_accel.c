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

int pg_accel_init(pg_accel *a, int32_t nstate, int depth) {
  memset(a, 0, sizeof *a);
  a->depth = depth;
  a->N = nstate;
  size_t N = (size_t)(nstate > 0 ? nstate : 1), m = (size_t)depth;
  a->X = tds_calloc(N, sizeof *a->X);
  a->G = tds_calloc(N, sizeof *a->G);
  a->Fprev = tds_calloc(N, sizeof *a->Fprev);
  a->Gprev = tds_calloc(N, sizeof *a->Gprev);
  a->dF = tds_calloc(N * m, sizeof *a->dF);
  a->dG = tds_calloc(N * m, sizeof *a->dG);
  a->M = tds_calloc(m * m, sizeof *a->M);
  a->Ms = tds_calloc(m * m, sizeof *a->Ms);
  a->gam = tds_calloc(m, sizeof *a->gam);
  if (!a->X || !a->G || !a->Fprev || !a->Gprev || !a->dF || !a->dG || !a->M ||
      !a->Ms || !a->gam) {
    pg_accel_free(a);
    return TDS_ENOMEM;
  }
  pg_accel_reset(a);
  a->cooldown = 2 * depth;
  return TDS_OK;
}

void pg_accel_free(pg_accel *a) {
  free(a->X);
  free(a->G);
  free(a->Fprev);
  free(a->Gprev);
  free(a->dF);
  free(a->dG);
  free(a->M);
  free(a->Ms);
  free(a->gam);
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
      const double *restrict dc = a->dF + (size_t)c * N;
      double s0 = 0, s1 = 0, t0 = 0, t1 = 0;
      int32_t i = 0;
      for (; i + 1 < N; i += 2) {
        s0 += dc[i] * dF[i];
        s1 += dc[i + 1] * dF[i + 1];
        t0 += dc[i] * Fp[i];
        t1 += dc[i + 1] * Fp[i + 1];
      }
      if (i < N) {
        s0 += dc[i] * dF[i];
        t0 += dc[i] * Fp[i];
      }
      a->M[c * m + col] = a->M[col * m + c] = s0 + s1;
      a->gam[c] = t0 + t1;
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
  /* gamma = argmin |F - dF gamma|: (dF^T dF + eps) gamma = dF^T F. */
  double tr = 0;
  for (int c = 0; c < h; c++) tr += a->M[c * m + c];
  for (int i = 0; i < h; i++) {
    for (int j = 0; j < h; j++) a->Ms[i * h + j] = a->M[i * m + j];
    a->Ms[i * h + i] += 1e-12 * tr + 1e-300;
  }
  if (tds_dense_solve(h, a->Ms, a->gam) != 0) {
    restart(a);
    memcpy(X, G, (size_t)N * sizeof *X);
    return 0;
  }
  memcpy(X, G, (size_t)N * sizeof *X);
  for (int c = 0; c < h; c++) {
    const double *restrict dG = a->dG + (size_t)c * N;
    double g = a->gam[c];
    for (int32_t i = 0; i < N; i++) X[i] -= g * dG[i];
  }
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
