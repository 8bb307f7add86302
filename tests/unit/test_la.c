/* test_la.c: the sparse symmetric factorisation (la.h): inertia and
** solves of small matrices whose answers are known exactly: definite,
** indefinite, singular, a KKT matrix with a zero block, and seeded random
** matrices built as Q D Q^T with chosen signs in D (Sylvester's law fixes
** the inertia). Solve tolerances: the residual of a backward-stable LDL^T
** solve is a few ulps times ||A|| ||x||; 1e-12 relative leaves room for
** the conditioning of these matrices (condition numbers below 1e3).
** la_chol: the Cholesky path (la_chol.h) on the N x N grid Laplacian
** (Dirichlet), whose eigenvalues are known in closed form: shifted, its
** inertia is exact, whichever path serves. */
#include <stdlib.h>

#include "check.h"
#include "la.h"
#include "la_chol.h"

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

/* The 5-point Laplacian of an N x N grid minus c I, upper CSC;
** eigenvalues 4 - 2 cos(j pi / (N + 1)) - 2 cos(k pi / (N + 1)) - c. */
static void grid(int N, double c, tds_spmat *out) {
  tds_sptrip t = {.nrow = N * N, .ncol = N * N};
  for (int i = 0; i < N; i++)
    for (int j = 0; j < N; j++) {
      int v = i * N + j;
      tds_sptrip_add(&t, v, v, 4 - c);
      if (j + 1 < N) tds_sptrip_add(&t, v, v + 1, -1);
      if (i + 1 < N) tds_sptrip_add(&t, v, v + N, -1);
    }
  tds_spmat_from_trip(&t, 1, out);
  tds_sptrip_free(&t);
}

static void la_chol(void) {
  const int N = 40, n = N * N;
  const double pi = acos(-1.0);
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  /* shifts: 0 (definite), and values between eigenvalues (indefinite,
  ** MUMPS's path); the exact count below each from the closed form */
  const double shifts[] = {0, 0.05, 0.5, 1.91, 3.3, 5.55};
  for (size_t si = 0; si < sizeof shifts / sizeof *shifts; si++) {
    double c = shifts[si], gap = HUGE_VAL;
    int below = 0;
    for (int j = 1; j <= N; j++)
      for (int k = 1; k <= N; k++) {
        double ev = 4 - 2 * cos(j * pi / (N + 1)) - 2 * cos(k * pi / (N + 1));
        below += ev < c;
        gap = fmin(gap, fabs(ev - c));
      }
    CHECK(gap > 1e-4); /* no eigenvalue at the shift: the count is clear */
    tds_spmat A = {0};
    grid(N, c, &A);
    tds_chol *ch = (tds_chol *)&ctx;
    int rc = tds_chol_factor(&ctx, &A, 1e-10, &ch);
    CHECK(rc == (below ? TDS_ERANGE : TDS_OK));
    CHECK((ch != NULL) == (rc == TDS_OK));
    tds_la *f = NULL;
    CHECK(tds_la_factor(&ctx, &A, 0, &f) == TDS_OK);
    if (f) {
      tds_inertia in = tds_la_inertia(f);
      CHECK(in.neg == below);
      CHECK(in.zero == 0);
      CHECK(in.pos == n - below);
    }
    /* solves, both ways: residual at rounding (cond < 1e3 here) */
    double *xs = malloc(n * sizeof *xs), *b = malloc(n * sizeof *b), *b2 = malloc(n * sizeof *b2);
    for (int i = 0; i < n; i++) xs[i] = sin(0.37 * i) + 0.1 * (i % 7);
    tds_spmat_mulv(&A, xs, b);
    memcpy(b2, b, n * sizeof *b);
    if (ch) CHECK(tds_chol_solve(&ctx, ch, b2) == TDS_OK);
    if (f) CHECK(tds_la_solve(&ctx, f, b, 0) == TDS_OK);
    double err = 0, err2 = 0;
    for (int i = 0; i < n; i++) {
      err = fmax(err, fabs(b[i] - xs[i]));
      if (ch) err2 = fmax(err2, fabs(b2[i] - xs[i]));
    }
    CHECK_NEAR(err, 0, 1e-10);
    CHECK_NEAR(err2, 0, 1e-10);
    free(xs);
    free(b);
    free(b2);
    tds_chol_free(ch);
    tds_la_free(f);
    tds_spmat_free(&A);
  }
  /* definite (eigenvalues 2 and 5e-14) but with a pivot below eps |A|:
  ** not Cholesky's; MUMPS counts the zero pivot */
  double d[4] = {1, 1, 1, 1 + 1e-13};
  tds_spmat D = {0};
  to_sp(2, d, &D);
  tds_chol *ch = NULL;
  CHECK(tds_chol_factor(&ctx, &D, 1e-10, &ch) == TDS_ERANGE && ch == NULL);
  tds_spmat_free(&D);
  factor_check(2, d, 0, 1, 1, 0);
  /* a zero diagonal (a KKT border) is not Cholesky's either */
  double k[9] = {2, 0, 1, 0, 2, 1, 1, 1, 0};
  tds_spmat K = {0};
  to_sp(3, k, &K);
  CHECK(tds_chol_factor(&ctx, &K, 1e-10, &ch) == TDS_ERANGE && ch == NULL);
  tds_spmat_free(&K);
}

int main(void) {
  RUN(la_definite);
  RUN(la_indefinite);
  RUN(la_singular);
  RUN(la_kkt);
  RUN(la_random);
  RUN(la_bad_input);
  RUN(la_chol);
  return check_done();
}
