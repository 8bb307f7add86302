/* test_la.c: the sparse symmetric factorisation (la.h): inertia and
** solves of small matrices whose answers are known exactly: definite,
** indefinite, singular, a KKT matrix with a zero block, and seeded random
** matrices built as Q D Q^T with chosen signs in D (Sylvester's law fixes
** the inertia). Solve tolerances: the residual of a backward-stable LDL^T
** solve is a few ulps times ||A|| ||x||; 1e-12 relative leaves room for
** the conditioning of these matrices (condition numbers below 1e3). */
#include <stdlib.h>

#include "check.h"
#include "la.h"

/* Dense symmetric n x n (row-major) to upper CSC, keeping zeros off. */
static void to_sp(int n, const double *a, tds_spmat *out) {
  tds_sptrip t = {.nrow = n, .ncol = n};
  for (int j = 0; j < n; j++)
    for (int i = 0; i <= j; i++)
      if (a[i * n + j] != 0 || i == j) tds_sptrip_add(&t, i, j, a[i * n + j]);
  tds_spmat_from_trip(&t, 1, out);
  tds_sptrip_free(&t);
}

/* Factor dense a; check inertia; solve a x = a*xs and compare with xs. */
static int factor_check(int n, const double *a, int neg, int zero, int pos, int solve) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  tds_spmat A = {0};
  to_sp(n, a, &A);
  tds_la *f = NULL;
  int rc = tds_la_factor(&ctx, &A, 0, &f);
  CHECK(rc == TDS_OK);
  if (rc != TDS_OK) return tds_spmat_free(&A), 0;
  tds_inertia in = tds_la_inertia(f);
  CHECK(in.neg == neg);
  CHECK(in.zero == zero);
  CHECK(in.pos == pos);
  if (solve) {
    double *xs = malloc(n * sizeof *xs), *b = malloc(n * sizeof *b);
    for (int i = 0; i < n; i++) xs[i] = 1.0 + 0.37 * i - 0.05 * i * i;
    tds_spmat_mulv(&A, xs, b);
    CHECK(tds_la_solve(&ctx, f, b, 0) == TDS_OK);
    double err = 0, nx = 0;
    for (int i = 0; i < n; i++) {
      err = fmax(err, fabs(b[i] - xs[i]));
      nx = fmax(nx, fabs(xs[i]));
    }
    CHECK_NEAR(err / nx, 0, 1e-12);
    free(xs);
    free(b);
  } else {
    double b[64] = {0};
    b[0] = 1;
    CHECK(tds_la_solve(&ctx, f, b, 0) == TDS_ENUM);
    CHECK(strstr(ctx.errmsg, "singular") != NULL);
  }
  tds_la_free(f);
  tds_spmat_free(&A);
  return 1;
}

static void la_definite(void) {
  /* the 1D Laplacian: eigenvalues 2 - 2 cos(k pi / 6) > 0 */
  double a[25] = {0};
  for (int i = 0; i < 5; i++) {
    a[i * 5 + i] = 2;
    if (i) a[i * 5 + i - 1] = a[(i - 1) * 5 + i] = -1;
  }
  factor_check(5, a, 0, 0, 5, 1);
}

static void la_indefinite(void) {
  /* [[1 2][2 1]]: eigenvalues 3 and -1; a zero diagonal needs a 2x2 pivot */
  double a[4] = {1, 2, 2, 1};
  factor_check(2, a, 1, 0, 1, 1);
  double b[9] = {0, 1, 0, 1, 0, 0, 0, 0, -3}; /* eigenvalues 1, -1, -3 */
  factor_check(3, b, 2, 0, 1, 1);
}

static void la_singular(void) {
  /* the Laplacian with free ends (Neumann): constants are its null space */
  double a[16] = {1, -1, 0, 0, -1, 2, -1, 0, 0, -1, 2, -1, 0, 0, -1, 1};
  factor_check(4, a, 0, 1, 3, 0);
  /* rank one: x x^T, eigenvalues |x|^2, 0, 0 */
  double x[3] = {1, 2, -1}, b[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) b[i * 3 + j] = x[i] * x[j];
  factor_check(3, b, 0, 2, 1, 0);
}

static void la_kkt(void) {
  /* [H a; a^T 0] with H = I (3x3), a = (1 1 1): inertia (n+... ) = 3 pos
  ** from H on a's complement (2) plus one pair (+, -) from the border */
  double k[16] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 0};
  factor_check(4, k, 1, 0, 3, 1);
  /* H = diag(1, -1, 2): on a^T x = 0 with a = e2 it is diag(1, 2): the
  ** border adds one of each sign: (1 neg, 3 pos) */
  double k2[16] = {1, 0, 0, 0, 0, -1, 0, 1, 0, 0, 2, 0, 0, 1, 0, 0};
  factor_check(4, k2, 1, 0, 3, 1);
  /* a dependent border: two equal constraint columns make it singular */
  double k3[25] = {1, 0, 0, 1, 1, 0, 1, 0, 1, 1, 0, 0, 1, 1, 1,
                   1, 1, 1, 0, 0, 1, 1, 1, 0, 0};
  factor_check(5, k3, 1, 1, 3, 0);
}

/* Q D Q^T, Q a product of seeded random Householder reflections. */
static void la_random(void) {
  unsigned seed = 12345;
  for (int trial = 0; trial < 20; trial++) {
    int n = 3 + trial % 9;
    double d[16], Q[256], a[256], v[16];
    int neg = 0, pos = 0;
    for (int i = 0; i < n; i++) {
      seed = seed * 1103515245u + 12345u;
      double r = (double)(seed >> 8) / (1 << 24);
      d[i] = (r < 0.4 ? -1 : 1) * (0.5 + 2 * r);
      if (d[i] < 0) neg++;
      else pos++;
    }
    for (int i = 0; i < n * n; i++) Q[i] = (i / n == i % n);
    for (int h = 0; h < 3; h++) {
      double nv = 0;
      for (int i = 0; i < n; i++) {
        seed = seed * 1103515245u + 12345u;
        v[i] = (double)(seed >> 8) / (1 << 24) - 0.5;
        nv += v[i] * v[i];
      }
      for (int c = 0; c < n; c++) { /* Q = (I - 2 v v^T / |v|^2) Q */
        double s = 0;
        for (int i = 0; i < n; i++) s += v[i] * Q[i * n + c];
        for (int i = 0; i < n; i++) Q[i * n + c] -= 2 * s / nv * v[i];
      }
    }
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        double s = 0;
        for (int k = 0; k < n; k++) s += Q[i * n + k] * d[k] * Q[j * n + k];
        a[i * n + j] = s;
      }
    for (int i = 0; i < n; i++) /* exact symmetry */
      for (int j = 0; j < i; j++) a[i * n + j] = a[j * n + i];
    factor_check(n, a, neg, 0, pos, 1);
  }
}

static void la_bad_input(void) {
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  double a[4] = {1, NAN, NAN, 1};
  tds_spmat A = {0};
  to_sp(2, a, &A);
  tds_la *f = (tds_la *)&ctx;
  CHECK(tds_la_factor(&ctx, &A, 0, &f) == TDS_ENUM);
  CHECK(f == NULL);
  CHECK(strstr(ctx.errmsg, "not finite") != NULL);
  tds_spmat_free(&A);
  /* the empty matrix factors, with empty inertia */
  tds_spmat E = {.nrow = 0, .ncol = 0, .upper = 1};
  int32_t cp = 0;
  E.colptr = &cp;
  CHECK(tds_la_factor(&ctx, &E, 0, &f) == TDS_OK);
  CHECK(tds_la_inertia(f).neg + tds_la_inertia(f).zero + tds_la_inertia(f).pos == 0);
  tds_la_free(f);
}

int main(void) {
  RUN(la_definite);
  RUN(la_indefinite);
  RUN(la_singular);
  RUN(la_kkt);
  RUN(la_random);
  RUN(la_bad_input);
  return check_done();
}
