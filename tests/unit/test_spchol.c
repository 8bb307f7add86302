/* test_spchol.c: the sparse Cholesky with a reused analysis (spchol.h).
** Matrices: weighted graph Laplacians of an m x m grid plus a positive
** diagonal (seeded random weights in [0.5, 1.5] and shifts in [0.01,
** 0.02]: positive definite, condition number below 1e4), refactored
** with new values on the same pattern; a singular Laplacian (free ends),
** an indefinite matrix, non-finite entries, a changed pattern and the
** empty matrix; and conjugate gradients preconditioned with the factors
** of a nearby matrix. Tolerances: a backward-stable Cholesky solve has a
** residual of a few ulps times ||A|| ||x||; 1e-13 relative (to
** ||A||_F ||x||) allows for the 900 x 900 sums. */
#include <stdlib.h>

#include "check.h"
#include "spchol.h"

static unsigned seed_ = 2024;
static double urand(void) { /* [0, 1) */
  seed_ = seed_ * 1103515245u + 12345u;
  return (double)(seed_ >> 8) / (1 << 24);
}

/* The grid Laplacian's upper triangle with weights w (one per edge, in
** the order made here) and diagonal shifts d (NULL: none). */
static void grid(int m, const double *w, const double *d, tds_spmat *out) {
  int n = m * m, e = 0;
  double *diag = calloc(n, sizeof *diag);
  tds_sptrip t = {.nrow = n, .ncol = n};
  for (int i = 0; i < m; i++)
    for (int j = 0; j < m; j++) {
      int a = i * m + j;
      int nb[2] = {j + 1 < m ? a + 1 : -1, i + 1 < m ? a + m : -1};
      for (int k = 0; k < 2; k++) {
        if (nb[k] < 0) continue;
        tds_sptrip_add(&t, a, nb[k], -w[e]);
        diag[a] += w[e];
        diag[nb[k]] += w[e];
        e++;
      }
    }
  for (int a = 0; a < n; a++) tds_sptrip_add(&t, a, a, diag[a] + (d ? d[a] : 0));
  tds_spmat_from_trip(&t, 1, out);
  tds_sptrip_free(&t);
  free(diag);
}

static double norm(int n, const double *x) {
  double s = 0;
  for (int i = 0; i < n; i++) s += x[i] * x[i];
  return sqrt(s);
}

static double fnorm(const tds_spmat *A) {
  double s = 0;
  for (int j = 0; j < A->ncol; j++)
    for (int k = A->colptr[j]; k < A->colptr[j + 1]; k++)
      s += (A->rowind[k] == j ? 1 : 2) * A->val[k] * A->val[k];
  return sqrt(s);
}

/* ||A x - b|| / (||A||_F ||x||) */
static double backward(const tds_spmat *A, const double *x, const double *b) {
  int n = A->nrow;
  double *r = malloc(n * sizeof *r);
  tds_spmat_mulv(A, x, r);
  for (int i = 0; i < n; i++) r[i] -= b[i];
  double e = norm(n, r) / (fnorm(A) * norm(n, x));
  free(r);
  return e;
}

enum { M = 30, N = M * M, NE = 2 * M * (M - 1) };

static void random_values(double *w, double *d) {
  for (int e = 0; e < NE; e++) w[e] = 0.5 + urand();
  for (int a = 0; a < N; a++) d[a] = 0.01 + 0.01 * urand();
}

/* Factor several matrices of one pattern after one analysis: each solve
** has a direct solve's backward error, and its x is the one b was made
** from (the condition number is below 1e4: 1e-9 relative). */
static void spchol_refactor(void) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  static double w[NE], d[N], xs[N], b[N], x[N];
  random_values(w, d);
  tds_spmat A = {0};
  grid(M, w, d, &A);
  tds_spchol *f = NULL;
  CHECK(tds_spchol_analyse(&ctx, &A, 0, &f) == TDS_OK);
  for (int round = 0; round < 3 && f; round++) {
    if (round) { /* new values, same pattern */
      tds_spmat B = {0};
      random_values(w, d);
      grid(M, w, d, &B);
      memcpy(A.val, B.val, A.colptr[N] * sizeof *A.val);
      tds_spmat_free(&B);
    }
    CHECK(tds_spchol_factor(&ctx, f, &A) == TDS_OK);
    for (int i = 0; i < N; i++) xs[i] = urand() - 0.5;
    tds_spmat_mulv(&A, xs, b);
    memcpy(x, b, sizeof x);
    CHECK(tds_spchol_solve(&ctx, f, x) == TDS_OK);
    CHECK(backward(&A, x, b) <= 1e-13);
    double err = 0;
    for (int i = 0; i < N; i++) err = fmax(err, fabs(x[i] - xs[i]));
    CHECK(err <= 1e-9);
  }
  tds_spchol_free(f);
  tds_spmat_free(&A);
}

/* Conjugate gradients on matrices near the factored one (every weight
** moved by up to 5%, a few entries more than the factored pattern):
** rtol 0 reaches a direct solve's backward error (1e-13 as above, with
** the stopping test's 1e-14 of ||b|| + ||A|| ||x||), rtol 1e-6 a
** residual of at most 1e-6 ||b||, and a limit of one iteration is
** reported (-1) with b left as it was; the same from a first guess. */
static void spchol_near(void) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  static double w[NE], d[N], w1[NE], xs[N], b[N], x[N], r[N], work[4 * N];
  random_values(w, d);
  tds_spmat A = {0}, B = {0};
  grid(M, w, d, &A);
  tds_spchol *f = NULL;
  CHECK(tds_spchol_analyse(&ctx, &A, 0, &f) == TDS_OK);
  CHECK(f && tds_spchol_factor(&ctx, f, &A) == TDS_OK);
  if (!f) return;
  for (int e = 0; e < NE; e++) w1[e] = w[e] * (1 + 0.1 * (urand() - 0.5));
  grid(M, w1, d, &B);
  for (int i = 0; i < N; i++) xs[i] = urand() - 0.5;
  tds_spmat_mulv(&B, xs, b);
  int its = -2;
  memcpy(x, b, sizeof x);
  CHECK(tds_spchol_solve_near(&ctx, f, &B, x, NULL, 0, work, 50, &its) == TDS_OK);
  CHECK(its > 0 && its <= 50);
  CHECK(backward(&B, x, b) <= 1e-13);
  memcpy(x, b, sizeof x);
  CHECK(tds_spchol_solve_near(&ctx, f, &B, x, NULL, 1e-6, work, 50, &its) == TDS_OK);
  CHECK(its >= 0);
  tds_spmat_mulv(&B, x, r);
  for (int i = 0; i < N; i++) r[i] -= b[i];
  CHECK(norm(N, r) <= 1e-6 * norm(N, b));
  memcpy(x, b, sizeof x);
  CHECK(tds_spchol_solve_near(&ctx, f, &B, x, NULL, 0, work, 1, &its) == TDS_OK);
  CHECK(its == -1);
  CHECK(memcmp(x, b, sizeof x) == 0);
  /* from a first guess x0: the exact solution needs no iteration (its
  ** residual is rounding, under the stopping test); one 1e-3 off reaches
  ** the same backward error; x0 is only read */
  static double x0[N];
  tds_spmat_mulv(&B, xs, b);
  memcpy(x0, xs, sizeof x0);
  memcpy(x, b, sizeof x);
  CHECK(tds_spchol_solve_near(&ctx, f, &B, x, x0, 0, work, 50, &its) == TDS_OK);
  CHECK(its == 0);
  CHECK(memcmp(x, xs, sizeof x) == 0);
  for (int i = 0; i < N; i++) x0[i] = xs[i] + 1e-3 * (urand() - 0.5);
  memcpy(r, x0, sizeof r);
  memcpy(x, b, sizeof x);
  CHECK(tds_spchol_solve_near(&ctx, f, &B, x, x0, 0, work, 50, &its) == TDS_OK);
  CHECK(its > 0 && its <= 50);
  CHECK(backward(&B, x, b) <= 1e-13);
  CHECK(memcmp(r, x0, sizeof r) == 0);
  /* on the factored matrix itself: no iteration */
  tds_spmat_mulv(&A, xs, b);
  memcpy(x, b, sizeof x);
  CHECK(tds_spchol_solve_near(&ctx, f, &A, x, NULL, 0, work, 50, &its) == TDS_OK);
  CHECK(its == 0);
  tds_spchol_free(f);
  tds_spmat_free(&A);
  tds_spmat_free(&B);
}

/* Refusals: a singular matrix (the grid Laplacian without shifts:
** constants are its null space), an indefinite one, a non-finite entry,
** a different pattern; a failed factorisation leaves nothing to solve
** with; the empty matrix factors and solves. */
static void spchol_refuse(void) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  static double w[NE], d[N], b[N];
  random_values(w, d);
  tds_spmat A = {0};
  grid(M, w, NULL, &A);
  tds_spchol *f = NULL;
  CHECK(tds_spchol_analyse(&ctx, &A, 0, &f) == TDS_OK);
  if (!f) return;
  CHECK(tds_spchol_factor(&ctx, f, &A) == TDS_ENUM);
  CHECK(strstr(ctx.errmsg, "singular") != NULL);
  b[0] = 1;
  CHECK(tds_spchol_solve(&ctx, f, b) == TDS_ERANGE);
  A.val[A.colptr[N] - 1] = -5; /* the last diagonal entry: indefinite */
  CHECK(tds_spchol_factor(&ctx, f, &A) == TDS_ENUM);
  A.val[0] = NAN;
  CHECK(tds_spchol_factor(&ctx, f, &A) == TDS_ENUM);
  CHECK(strstr(ctx.errmsg, "not finite") != NULL);
  tds_spmat B = {0};
  grid(M, w, d, &B);
  CHECK(tds_spchol_factor(&ctx, f, &B) == TDS_OK);
  tds_spmat_free(&B);
  grid(M - 1, w, d, &B); /* another size */
  CHECK(tds_spchol_factor(&ctx, f, &B) == TDS_ERANGE);
  CHECK(strstr(ctx.errmsg, "pattern") != NULL);
  tds_spmat_free(&B);
  tds_spchol_free(f);
  tds_spmat_free(&A);
  tds_spmat L = {.nrow = 2, .ncol = 2, .upper = 0};
  CHECK(tds_spchol_analyse(&ctx, &L, 0, &f) == TDS_ERANGE && f == NULL);
  tds_spmat E = {.nrow = 0, .ncol = 0, .upper = 1};
  int32_t cp = 0;
  E.colptr = &cp;
  CHECK(tds_spchol_analyse(&ctx, &E, 0, &f) == TDS_OK);
  CHECK(f && tds_spchol_factor(&ctx, f, &E) == TDS_OK);
  CHECK(f && tds_spchol_solve(&ctx, f, b) == TDS_OK);
  tds_spchol_free(f);
}

int main(void) {
  RUN(spchol_refactor);
  RUN(spchol_near);
  RUN(spchol_refuse);
  return check_done();
}
