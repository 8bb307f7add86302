/* newton_eig.c: ritz, the eigenvalues of H w = lambda M w on the
** constraints nearest a shift (newton.h), by subspace iteration with the
** shift-inverted operator T = (H - shift M)^-1 M (applied through the
** bordered factorisation, so T x satisfies the constraints) and
** Rayleigh-Ritz in the M inner product, where T is self-adjoint. A block
** of p > n vectors finds repeated eigenvalues (symmetric shapes have
** many), which a single-vector Lanczos would miss. The start is seeded
** (the same run gives the same numbers). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "newton_int.h"
#include "recalc.h"
#include "snap.h"

/* LAPACK: eigenvalues and vectors of a dense symmetric matrix. */
void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info);

static double mdot(const tds_nsys *n, const double *Mx, const double *y) {
  double s = 0;
  for (int32_t i = 0; i < n->m; i++) s += Mx[i] * y[i];
  return s;
}

/* M-orthonormalise the p columns of X (m each, column-major) by two
** passes of modified Gram-Schmidt; a column that vanishes is replaced by
** a seeded random one and orthonormalised again. MX: scratch. */
static void orthonormal(const tds_nsys *n, double *X, int p, double *MX, unsigned *seed) {
  int32_t m = n->m;
  for (int c = 0; c < p; c++) {
    double *x = X + (size_t)c * m;
    for (int tries = 0; tries < 3; tries++) {
      for (int pass = 0; pass < 2; pass++)
        for (int l = 0; l < c; l++) {
          double d = mdot(n, MX + (size_t)l * m, x);
          const double *q = X + (size_t)l * m;
          for (int32_t i = 0; i < m; i++) x[i] -= d * q[i];
        }
      tds_nsys_metric(n, x, MX + (size_t)c * m);
      double nn = mdot(n, MX + (size_t)c * m, x);
      if (nn > 1e-28) {
        double inv = 1 / sqrt(nn);
        for (int32_t i = 0; i < m; i++) {
          x[i] *= inv;
          MX[(size_t)c * m + i] *= inv;
        }
        break;
      }
      for (int32_t i = 0; i < m; i++) {
        *seed = *seed * 1103515245u + 12345u;
        x[i] = (double)(*seed >> 8) / (1 << 24) - 0.5;
      }
    }
  }
}

/* Y = T X: for each column, solve K [y; z] = [M x; 0]. */
static int apply_T(tds_ctx *ctx, const tds_nsys *n, tds_la *f, const double *MX, double *Y,
                   int p, double *rhs) {
  int32_t m = n->m;
  for (int c = 0; c < p; c++) {
    memcpy(rhs, MX + (size_t)c * m, (size_t)m * sizeof *rhs);
    for (int32_t q = 0; q < n->nq; q++) rhs[m + q] = 0;
    int rc = tds_la_solve(ctx, f, rhs, 0);
    if (rc != TDS_OK) return rc;
    memcpy(Y + (size_t)c * m, rhs, (size_t)m * sizeof *rhs);
  }
  return TDS_OK;
}

/* Factor K - shift [M 0; 0 0], nudging the shift off an eigenvalue. */
static int factor_at(tds_ctx *ctx, const tds_nsys *n, double eps, double *shift, tds_la **f,
                     tds_inertia *in, tds_inertia *first) {
  for (int tries = 0;; tries++) {
    tds_spmat K = {0};
    int rc = tds_nsys_kkt(ctx, n, *shift, &K);
    if (rc == TDS_OK) rc = tds_la_factor(ctx, &K, eps, f);
    tds_spmat_free(&K);
    if (rc != TDS_OK) return rc;
    *in = tds_la_inertia(*f);
    in->neg -= n->nq;
    in->pos -= n->nq;
    if (in->neg < 0 || in->pos < 0) {
      tds_la_free(*f);
      *f = NULL;
      return tds_seterr(ctx, TDS_ENUM, "ritz: the constraints' gradients are dependent (or hessian_epsilon is "
                         "so large that their pivots count as zero)");
    }
    if (tries == 0 && first) *first = *in;
    if (!in->zero || tries == 3) return TDS_OK;
    tds_la_free(*f);
    *f = NULL;
    *shift += 1e-9 * (1 + fabs(*shift)); /* on an eigenvalue: move off it */
  }
}

/* The start of ritz and eigenprobe's inverse iteration: a snapshot of s,
** s recalculated if stale, the system built. On failure the snapshot is
** ended (s as before) and the error returned. */
static int begin(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, tds_snap *sn,
                 tds_nsys *n) {
  int rc = tds_snap_take(ctx, s, sn);
  if (rc != TDS_OK) return rc;
  if ((rc = tds_recalc_if_stale(ctx, s)) == TDS_OK) rc = tds_nsys_build(ctx, s, o, n);
  return rc == TDS_OK ? TDS_OK : tds_snap_end(ctx, s, sn, rc);
}

int tds_newton_ritz(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double shift,
                    int32_t nwant, double *vals, int32_t *got, tds_inertia *in_out,
                    double (*vec)[3], int *iters, double *change_out) {
  *got = 0;
  *iters = 0;
  if (nwant < 0) return tds_seterr(ctx, TDS_ERANGE, "ritz: the count must not be negative");
  if (isinf(shift)) return tds_seterr(ctx, TDS_ERANGE, "ritz: the shift must be finite");
  tds_snap sn;
  tds_nsys n;
  int rc = begin(ctx, s, o, &sn, &n);
  if (rc != TDS_OK) return rc;
  tds_la *f = NULL;
  double *X = NULL, *Y = NULL, *MX = NULL, *rhs = NULL, *G = NULL, *th = NULL, *work = NULL,
         *prev = NULL, *row = NULL, *lam = NULL;
  int *ord = NULL;
  int32_t m = n.m, dim = n.m - n.nq;
  int user_shift = !isnan(shift);
  tds_inertia in, first;
  if (!user_shift) { /* below every eigenvalue: step down until none is below */
    shift = -1;
    for (int k = 0;; k++) {
      rc = factor_at(ctx, &n, o->epsilon, &shift, &f, &in, NULL);
      if (rc != TDS_OK) goto done;
      if (in.neg == 0 || k == 60) break;
      tds_la_free(f);
      f = NULL;
      shift *= 4;
    }
  } else {
    rc = factor_at(ctx, &n, o->epsilon, &shift, &f, &in, &first);
    if (rc != TDS_OK) goto done;
    in = first; /* the counts at the shift itself, as Evolver prints them */
  }
  *in_out = in;
  int32_t nn = nwant < dim ? nwant : (dim > 0 ? dim : 0);
  if (nn == 0) goto done;
  int p = nn + (nn < 8 ? 8 : nn);
  if (p > dim) p = dim;
  X = tds_malloc(&ctx->alloc, (size_t)m * p * sizeof *X);
  Y = tds_malloc(&ctx->alloc, (size_t)m * p * sizeof *Y);
  MX = tds_malloc(&ctx->alloc, (size_t)m * p * sizeof *MX);
  rhs = tds_malloc(&ctx->alloc, ((size_t)m + n.nq + 1) * sizeof *rhs);
  G = tds_malloc(&ctx->alloc, (size_t)p * p * sizeof *G);
  th = tds_malloc(&ctx->alloc, (size_t)p * sizeof *th);
  prev = tds_malloc(&ctx->alloc, (size_t)p * sizeof *prev);
  row = tds_malloc(&ctx->alloc, (size_t)p * sizeof *row);
  lam = tds_malloc(&ctx->alloc, (size_t)p * sizeof *lam);
  ord = tds_malloc(&ctx->alloc, (size_t)p * sizeof *ord);
  int lwork = 8 * p + 64;
  work = tds_malloc(&ctx->alloc, (size_t)lwork * sizeof *work);
  if (!X || !Y || !MX || !rhs || !G || !th || !prev || !work || !row || !lam || !ord) {
    rc = tds_seterr(ctx, TDS_ENOMEM, "ritz: out of memory");
    goto done;
  }
  unsigned seed = 1;
  for (size_t i = 0; i < (size_t)m * p; i++) {
    seed = seed * 1103515245u + 12345u;
    Y[i] = (double)(seed >> 8) / (1 << 24) - 0.5;
  }
  /* into the constraint space: X = T Y, orthonormal */
  for (int c = 0; c < p; c++) tds_nsys_metric(&n, Y + (size_t)c * m, MX + (size_t)c * m);
  if ((rc = apply_T(ctx, &n, f, MX, X, p, rhs)) != TDS_OK) goto done;
  orthonormal(&n, X, p, MX, &seed);
  double change = INFINITY;
  int it;
  for (it = 1; it <= 3000; it++) {
    if ((rc = apply_T(ctx, &n, f, MX, Y, p, rhs)) != TDS_OK) goto done;
    for (int a = 0; a < p; a++) /* G = X^T M Y, symmetrised */
      for (int b = 0; b <= a; b++) {
        double g = 0.5 * (mdot(&n, MX + (size_t)a * m, Y + (size_t)b * m) +
                          mdot(&n, MX + (size_t)b * m, Y + (size_t)a * m));
        G[a * p + b] = G[b * p + a] = g;
      }
    int info = 0;
    dsyev_("V", "U", &p, G, &p, th, work, &lwork, &info);
    if (info != 0) {
      rc = tds_seterr(ctx, TDS_ENUM, "ritz: the small eigenproblem failed (%d)", info);
      goto done;
    }
    /* order by |theta| descending: the nearest eigenvalues first */
    for (int a = 0; a < p; a++) ord[a] = a;
    for (int a = 1; a < p; a++)
      for (int b = a; b > 0 && fabs(th[ord[b]]) > fabs(th[ord[b - 1]]); b--) {
        int tmp = ord[b];
        ord[b] = ord[b - 1];
        ord[b - 1] = tmp;
      }
    /* X = Y S (columns in that order) */
    for (int32_t i = 0; i < m; i++) {
      double *r = row;
      for (int c = 0; c < p; c++) {
        double v = 0;
        for (int a = 0; a < p; a++) v += Y[(size_t)a * m + i] * G[ord[c] * p + a];
        r[c] = v;
      }
      for (int c = 0; c < p; c++) X[(size_t)c * m + i] = r[c];
    }
    change = 0;
    for (int c = 0; c < nn; c++) {
      double t = th[ord[c]];
      lam[c] = t != 0 ? shift + 1 / t : (double)INFINITY;
      if (it > 1) change += fabs(lam[c] - prev[c]);
      prev[c] = lam[c];
    }
    orthonormal(&n, X, p, MX, &seed);
    double scale = 0;
    for (int c = 0; c < nn; c++) scale = fmax(scale, fabs(lam[c]));
    if (it > 2 && change <= 1e-13 * (scale > 1 ? scale : 1) * nn) break;
  }
  if (it > 3000) it = 3000;
  *iters = it;
  if (change_out) *change_out = change;
  for (int c = 0; c < nn; c++) vals[c] = prev[c];
  *got = nn;
  /* the eigenvector of vals[0]: X's first column is the Ritz vector of
  ** the nearest (before the last orthonormalisation, same direction) */
  if (vec) {
    for (int32_t j = 0; j < m; j++)
      for (int i = 0; i < 3; i++) vec[n.vert[j]][i] += X[j] * n.dx[j][i];
  }
done:
  tds_la_free(f);
  tds_free(&ctx->alloc, X);
  tds_free(&ctx->alloc, Y);
  tds_free(&ctx->alloc, MX);
  tds_free(&ctx->alloc, rhs);
  tds_free(&ctx->alloc, G);
  tds_free(&ctx->alloc, th);
  tds_free(&ctx->alloc, prev);
  tds_free(&ctx->alloc, work);
  tds_free(&ctx->alloc, row);
  tds_free(&ctx->alloc, lam);
  tds_free(&ctx->alloc, ord);
  tds_nsys_free(&n);
  if (rc != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  tds_snap_free(&sn);
  return TDS_OK;
}

int tds_newton_invit(tds_ctx *ctx, tds_surf *s, const tds_newton_opts *o, double c, int maxit,
                     double *val, tds_inertia *in_out, double (*vec)[3], int *iters) {
  *iters = 0;
  *val = NAN;
  if (!isfinite(c)) return tds_seterr(ctx, TDS_ERANGE, "eigenprobe: the probe value is not finite");
  if (maxit < 0) return tds_seterr(ctx, TDS_ERANGE, "eigenprobe: the iteration count must not be negative");
  tds_snap sn;
  tds_nsys n;
  int rc = begin(ctx, s, o, &sn, &n);
  if (rc != TDS_OK) return rc;
  tds_la *f = NULL;
  int32_t m = n.m;
  double *x = tds_malloc(&ctx->alloc, ((size_t)m + 1) * sizeof *x);
  double *Mx = tds_malloc(&ctx->alloc, ((size_t)m + 1) * sizeof *Mx);
  double *y = tds_malloc(&ctx->alloc, ((size_t)m + n.nq + 1) * sizeof *y);
  if (!x || !Mx || !y) {
    rc = tds_seterr(ctx, TDS_ENOMEM, "eigenprobe: out of memory");
    goto done;
  }
  /* the counts at c itself (the eigenprobe line), then the factor used,
  ** moved off c when c is an eigenvalue */
  tds_inertia in, first;
  double shift = c;
  if ((rc = factor_at(ctx, &n, o->epsilon, &shift, &f, &in, &first)) != TDS_OK) goto done;
  in = first;
  *in_out = in;
  tds_printf(ctx, "Eigencounts:    %d <,  %d ==,  %d > \n", (int)in.neg, (int)in.zero,
             (int)in.pos);
  if (m - n.nq <= 0 || maxit == 0) goto done;
  /* seeded start, taken into the constraint space by one application */
  unsigned seed = 7;
  for (int32_t i = 0; i < m; i++) {
    seed = seed * 1103515245u + 12345u;
    x[i] = (double)(seed >> 8) / (1 << 24) - 0.5;
  }
  double prev = NAN, ev = NAN;
  for (int it = 0;; it++) {
    /* y = T x, ev = shift + x'Mx / x'My; then x = y normalised */
    tds_nsys_metric(&n, x, Mx);
    memcpy(y, Mx, (size_t)m * sizeof *y);
    for (int32_t q = 0; q < n.nq; q++) y[m + q] = 0;
    if ((rc = tds_la_solve(ctx, f, y, 0)) != TDS_OK) goto done;
    double xMx = 0, xMy = 0;
    for (int32_t i = 0; i < m; i++) {
      xMx += Mx[i] * x[i];
      xMy += Mx[i] * y[i];
    }
    if (it > 0) { /* the start is not in the constraint space: no estimate */
      ev = xMy != 0 ? shift + xMx / xMy : (double)INFINITY;
      int last = it - 1 == maxit || fabs(ev - prev) <= 1e-13 * fmax(1, fabs(ev));
      if (it == 1 || (it - 1) % 10 == 0 || last)
        tds_printf(ctx, "%d  ev = %20.15f\n", it - 1, ev);
      prev = ev;
      *iters = it - 1;
      if (last) break;
    }
    tds_nsys_metric(&n, y, Mx);
    double nn = 0;
    for (int32_t i = 0; i < m; i++) nn += Mx[i] * y[i];
    if (!(nn > 0) || !isfinite(nn)) {
      rc = tds_seterr(ctx, TDS_ENUM, "eigenprobe: the inverse iteration broke down");
      goto done;
    }
    for (int32_t i = 0; i < m; i++) x[i] = y[i] / sqrt(nn);
  }
  *val = ev;
  /* downhill: the eigenvector's sign makes the energy fall to first order */
  double slope = 0;
  for (int32_t i = 0; i < m; i++) slope += n.grad[i] * x[i];
  double sg = slope > 0 ? -1 : 1;
  if (vec)
    for (int32_t j = 0; j < m; j++)
      for (int i = 0; i < 3; i++) vec[n.vert[j]][i] += sg * x[j] * n.dx[j][i];
done:
  tds_la_free(f);
  tds_free(&ctx->alloc, x);
  tds_free(&ctx->alloc, Mx);
  tds_free(&ctx->alloc, y);
  tds_nsys_free(&n);
  if (rc != TDS_OK) return tds_snap_end(ctx, s, &sn, rc);
  tds_snap_free(&sn);
  return TDS_OK;
}
