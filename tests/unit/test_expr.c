/* test_expr.c: the expression compiler and evaluator (src/expr.h). */
#include "check.h"
#include "expr.h"

#include <stdlib.h>

/* ---- helpers ---- */

static const double NOVARS[TDS_NVARS] = {0, 0, 0, 0, 0, 0};

/* Compile s with flags (no parameters); NULL (and a failed check) on error. */
static tds_expr *comp(const char *s, int flags) {
  tds_ctx ctx;
  tds_expr_env env = {.flags = flags, NULL, NULL};
  tds_expr *e = NULL;
  tds_ctx_init(&ctx);
  int rc = tds_expr_parse(&ctx, s, NULL, &env, &e);
  CHECK(rc == TDS_OK);
  if (rc) printf("  parse '%s': %s\n", s, ctx.errmsg);
  return e;
}

/* Value of a variable-free expression. */
static double val(const char *s) {
  tds_expr *e = comp(s, 0);
  if (!e) return NAN;
  double v = tds_expr_eval(e, NULL, NOVARS);
  tds_expr_free(e);
  return v;
}

/* Parse expecting failure; returns the message in buf. */
static int perr(const char *s, int flags, char *buf, size_t cap) {
  tds_ctx ctx;
  tds_expr_env env = {.flags = flags, NULL, NULL};
  tds_expr *e = (tds_expr *)&ctx;   /* must be reset to NULL */
  tds_ctx_init(&ctx);
  int rc = tds_expr_parse(&ctx, s, NULL, &env, &e);
  CHECK(e == NULL);
  snprintf(buf, cap, "%s", ctx.errmsg);
  return rc;
}

static int has(const char *msg, const char *part) { return strstr(msg, part) != NULL; }

/* Two parameters, case-insensitive: alpha -> slot 0, wallt -> slot 3. */
static int lookup2(void *ud, const char *name, size_t len) {
  (void)ud;
  static const char *names[] = {"alpha", "wallt"};
  static const int slots[] = {0, 3};
  for (int k = 0; k < 2; k++) {
    size_t i = 0;
    while (i < len && names[k][i] &&
           (name[i] | 0x20) == names[k][i])
      i++;
    if (i == len && !names[k][i]) return slots[k];
  }
  return -1;
}

/* Gradient against central differences of the value, Hessian against
   central differences of the gradient, both with h = 1e-5. The error of a
   central difference is O(h^2 |f'''|) ~ 1e-10 plus rounding O(eps |f| / h)
   ~ 1e-11 for the O(1) functions and points used here, so a relative
   tolerance of 1e-6 has a wide margin yet catches any wrong formula. */
static void fd_check(const char *s, int flags, const double *params,
                     const double x0[TDS_NVARS]) {
  tds_ctx ctx;
  tds_expr_env env = {.flags = flags, lookup2, NULL};
  tds_expr *e = NULL;
  tds_ctx_init(&ctx);
  if (tds_expr_parse(&ctx, s, NULL, &env, &e) != TDS_OK) {
    printf("  parse '%s': %s\n", s, ctx.errmsg);
    CHECK(0);
    return;
  }
  const double h = 1e-5;
  int failed0 = check_failed_;
  double g[TDS_NDIFF], g2[TDS_NDIFF], H[TDS_NDIFF][TDS_NDIFF];
  double v0 = tds_expr_eval(e, params, x0);
  double v1 = tds_expr_eval_grad(e, params, x0, g);
  double v2 = tds_expr_eval_hess(e, params, x0, g2, H);
  CHECK(isfinite(v0));
  CHECK(v0 == v1 && v0 == v2);
  for (int i = 0; i < TDS_NDIFF; i++) {
    double xp[TDS_NVARS], xm[TDS_NVARS], gp[TDS_NDIFF], gm[TDS_NDIFF];
    memcpy(xp, x0, sizeof xp);
    memcpy(xm, x0, sizeof xm);
    xp[i] += h;
    xm[i] -= h;
    double fd = (tds_expr_eval(e, params, xp) - tds_expr_eval(e, params, xm)) / (2 * h);
    CHECK_NEAR(g[i], fd, 1e-6);
    CHECK(g[i] == g2[i]);
    tds_expr_eval_grad(e, params, xp, gp);
    tds_expr_eval_grad(e, params, xm, gm);
    for (int j = 0; j < TDS_NDIFF; j++) {
      CHECK_NEAR(H[j][i], (gp[j] - gm[j]) / (2 * h), 1e-6);
      CHECK(H[i][j] == H[j][i]);
    }
  }
  if (check_failed_ > failed0) printf("  in '%s'\n", s);
  tds_expr_free(e);
}

/* ---- tests ---- */

static void test_evolver_table(void) {
  /* expressions.md section 3 (verified in Evolver 2.70a) */
  CHECK_NEAR(val("2^3^2"), 64, 0);
  CHECK_NEAR(val("2**3**2"), 64, 0);
  CHECK_NEAR(val("-2^2"), -4, 0);
  CHECK_NEAR(val("(-2)^2"), 4, 0);
  CHECK_NEAR(val("2^-1"), 0.5, 0);
  CHECK_NEAR(val("1 + 2 * 3 ^ 2"), 19, 0);
  CHECK_NEAR(val("2^3*2"), 16, 0);
  CHECK_NEAR(val("10/4/2"), 1.25, 0);
  CHECK_NEAR(val("10-4-2"), 4, 0);
  CHECK_NEAR(val("7 % 3"), 1, 0);
  CHECK_NEAR(val("-7 % 3"), 2, 0);
  CHECK_NEAR(val("7 % -3"), -2, 0);
  CHECK_NEAR(val("7 mod 3"), 1, 0);
  CHECK_NEAR(val("7.5 imod 2"), 1, 0);
  CHECK_NEAR(val("-7.5 imod 2"), 0, 0);
  CHECK_NEAR(val("3 imod -2"), -1, 0);
  CHECK_NEAR(val("7 idiv 2"), 3, 0);
  CHECK_NEAR(val("-3.5 idiv 2.1"), -1, 0);
  CHECK_NEAR(val("-3 idiv 2"), -1, 0);
  CHECK_NEAR(val("1 < 2 < 3"), 0, 0);
  CHECK_NEAR(val("3 > 2 > 1"), 1, 0);
  CHECK_NEAR(val("not 0 + 1"), 0, 0);
  CHECK_NEAR(val("!1 + 1"), 0, 0);
  CHECK_NEAR(val("not 1 == 0"), 1, 0);
  CHECK_NEAR(val("1 and 0 or 1"), 1, 0);
  CHECK_NEAR(val("1 || 0 && 0"), 1, 0);
  CHECK_NEAR(val("2 and 3"), 1, 0);
  CHECK_NEAR(val("0 ? 2 : 3 + 10"), 13, 0);
  CHECK_NEAR(val("0 ? 2 : 0 ? 3 : 4"), 4, 0);
  CHECK_NEAR(val("1 ? 1 ? 5 : 6 : 7"), 5, 0);
  CHECK_NEAR(val("2 != 2"), 0, 0);
  CHECK_NEAR(val("2 <= 2 && 3 >= 4 == 0"), 1, 0);
  /* IEEE results instead of Evolver's errors (callers check isfinite) */
  CHECK(isinf(val("1/0")) && val("1/0") > 0);
  CHECK(isinf(val("log(0)")) && val("log(0)") < 0);
  CHECK(isnan(val("sqrt(-1)")));
  CHECK(isnan(val("acos(2)")));
}

static void test_functions(void) {
  /* expressions.md section 4 */
  CHECK_NEAR(val("abs(-3)"), 3, 0);
  CHECK_NEAR(val("sqr(3)"), 9, 0);
  CHECK_NEAR(val("sqrt(2)"), 1.4142135623730951, 1e-15);
  CHECK_NEAR(val("atan2(1,-1)"), 2.35619449019234, 1e-14);
  CHECK_NEAR(val("log(e)"), 1, 1e-15);
  CHECK_NEAR(val("log(E)"), 1, 1e-15);
  CHECK_NEAR(val("cosh(1)"), 1.54308063481524, 1e-14);
  CHECK_NEAR(val("acosh(2)"), 1.31695789692482, 1e-14);
  CHECK_NEAR(val("pow(-2,3)"), -8, 0);
  CHECK_NEAR(val("(-2)^3"), -8, 0);
  CHECK_NEAR(val("ceil(2.1)"), 3, 0);
  CHECK_NEAR(val("floor(-2.1)"), -3, 0);
  CHECK_NEAR(val("maximum(3,4)"), 4, 0);
  CHECK_NEAR(val("minimum(3,4)"), 3, 0);
  CHECK_NEAR(val("pi"), 3.14159265358979, 1e-14);
  CHECK_NEAR(val("SIN(PI/2) + Cos(0)"), 2, 1e-15);
  CHECK_NEAR(val("tan(pi/4) + asin(1) - acos(0) + atan(1)*4 - pi"), 1, 1e-14);
  CHECK_NEAR(val("sinh(1) - (e - 1/e)/2"), 0, 1e-15);
  CHECK_NEAR(val("tanh(0.5) - sinh(0.5)/cosh(0.5)"), 0, 1e-15);
  CHECK_NEAR(val("asinh(sinh(0.7)) + atanh(tanh(0.3)) + exp(log(2))"), 3, 1e-14);
  /* numbers */
  CHECK_NEAR(val("0x1F"), 31, 0);
  CHECK_NEAR(val("0Xff"), 255, 0);
  CHECK_NEAR(val("101b"), 5, 0);
  CHECK_NEAR(val(".5 + 1. + 1e-3 + 5E+2 + 2.5e1"), 526.501, 1e-14);
  CHECK_NEAR(val("1e-999999"), 0, 0);
  CHECK_NEAR(val("7 MOD 3 + 7 Imod 2 + 7 IDIV 2"), 5, 0);
  CHECK_NEAR(val("1 /* a comment */ + 2 // another"), 3, 0);
}

static void test_folding_and_queries(void) {
  tds_expr *e = comp("2*pi/3", 0);
  if (e) {
    CHECK(tds_expr_ncode(e) == 1);
    CHECK(tds_expr_is_const(e));
    CHECK_NEAR(tds_expr_eval(e, NULL, NULL), 2 * 3.14159265358979323846 / 3, 1e-15);
    CHECK(strcmp(tds_expr_text(e), "2*pi/3") == 0);
    tds_expr_free(e);
  }
  e = comp("0 ? x : 2 + sqr(3)", 0);          /* constant condition: folded */
  if (e) {
    CHECK(tds_expr_ncode(e) == 1 && tds_expr_is_const(e));
    CHECK_NEAR(tds_expr_eval(e, NULL, NULL), 11, 0);
    tds_expr_free(e);
  }
  e = comp("1 < 2 ? x*(2+3) : y", 0);
  if (e) {
    CHECK(tds_expr_uses_var(e, TDS_X) && !tds_expr_uses_var(e, TDS_Y));
    CHECK(tds_expr_ncode(e) == 3);           /* x 5 * */
    double v[TDS_NVARS] = {2, 0, 0, 0, 0, 0};
    CHECK_NEAR(tds_expr_eval(e, NULL, v), 10, 0);
    tds_expr_free(e);
  }
  e = comp("  G*z + X1 ", 0);
  if (e) {
    CHECK(!tds_expr_is_const(e));
    CHECK(tds_expr_uses_var(e, TDS_G) && tds_expr_uses_var(e, TDS_Z));
    CHECK(tds_expr_uses_var(e, TDS_X) && !tds_expr_uses_var(e, TDS_Y));
    CHECK(!tds_expr_uses_params(e) && tds_expr_max_param(e) == -1);
    CHECK(strcmp(tds_expr_text(e), "G*z + X1") == 0);
    double v[TDS_NVARS] = {1, 2, 3, 0, 0, 9.8}, g[TDS_NDIFF];
    CHECK_NEAR(tds_expr_eval_grad(e, NULL, v, g), 30.4, 1e-14);
    CHECK(g[TDS_X] == 1 && g[TDS_Y] == 0 && g[TDS_Z] == 9.8);
    tds_expr_free(e);
  }
  /* a^0 folds to 1 (C's pow(a, 0) is 1 for every a): its gradient is 0
     even where a's derivative overflows; fuzz_expr found "x^1^6^0" giving
     value 1 with gradient NaN at x = 1e300 (0 * inf). */
  e = comp("x^1^6^0", 0);
  if (e) {
    CHECK(tds_expr_is_const(e) && tds_expr_degree(e) == 0);
    double v[TDS_NVARS] = {1e300, 0, 0, 0, 0, 0}, g[TDS_NDIFF], h[TDS_NDIFF][TDS_NDIFF];
    CHECK(tds_expr_eval_hess(e, NULL, v, g, h) == 1 && g[TDS_X] == 0 && h[0][0] == 0);
    tds_expr_free(e);
  }
  /* right-nested constants fold however deep the stack would be */
  char buf[2000] = "";
  for (int i = 0; i < 150; i++) strcat(buf, "1+(");
  strcat(buf, "1");
  for (int i = 0; i < 150; i++) strcat(buf, ")");
  CHECK_NEAR(val(buf), 151, 0);
}

static void test_formula(void) {
  tds_expr *e = comp("x^2 + y^2 = 4", TDS_EXPR_FORMULA);
  if (e) {
    double v[TDS_NVARS] = {1, 1, 0, 0, 0, 0}, g[TDS_NDIFF];
    CHECK_NEAR(tds_expr_eval(e, NULL, v), -2, 0);
    CHECK_NEAR(tds_expr_eval_grad(e, NULL, v, g), -2, 0);
    CHECK(g[0] == 2 && g[1] == 2 && g[2] == 0 && g[3] == 0 && g[4] == 0);
    tds_expr_free(e);
  }
  e = comp("x = 1 + 2", TDS_EXPR_FORMULA);
  if (e) {
    double v[TDS_NVARS] = {5, 0, 0, 0, 0, 0};
    CHECK_NEAR(tds_expr_eval(e, NULL, v), 2, 0);
    tds_expr_free(e);
  }
  e = comp("z = x > 0 ? 1 : 2 = 1", TDS_EXPR_FORMULA);   /* left assoc */
  if (e) {
    double v[TDS_NVARS] = {1, 0, 7, 0, 0, 0};
    CHECK_NEAR(tds_expr_eval(e, NULL, v), 5, 0);
    tds_expr_free(e);
  }
  char msg[1024];
  CHECK(perr("x = 1", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(has(msg, "'=' is only allowed in formulas") && has(msg, "column 3"));
  CHECK_NEAR(val("3 == 3"), 1, 0);
}

static void test_derivatives(void) {
  double x0[TDS_NVARS] = {0.7, -0.4, 1.3, 1.1, 0.6, 9.8};
  double par[4] = {1.7, 0, 0, -0.35};
  fd_check("sin(x*y) + z^3/(1+x^2) - sqrt(x^2+y^2+z^2)", 0, par, x0);
  fd_check("atan2(y,x)", 0, par, x0);
  double x1[TDS_NVARS] = {-0.8, 0.5, 0, 0, 0, 0};
  fd_check("atan2(y,x) + atan2(x*y, y-x)", 0, par, x1);
  fd_check("exp(-x)*cos(p1)", TDS_EXPR_PARAMS, par, x0);
  fd_check("x > 0.5 ? x^2*y : sin(y)/x", 0, par, x0);
  x1[0] = 0.3;
  fd_check("x > 0.5 ? x^2*y : sin(y)/x", 0, par, x1);
  fd_check("pow(z, x) + x^y*z + 2^(x*y) + (1+x^2)^-1.5 + x^0 + y^1", 0, par, x0);
  fd_check("log(z*x) + tanh(z) + asinh(x) - acos(y/2) + asin(z/3)*atan(x)"
           " + cosh(y)*sinh(z) + tan(x) + acosh(1+x^2) + atanh(y/2) + abs(y-z)"
           " - abs(x) + sqr(x-y)",
           0, par, x0);
  fd_check("minimum(x*y, z) + maximum(x, y^2) + (x*z) % 0.3 + floor(x)*y"
           " + (y < x)*z + ceil(z)",
           0, par, x0);
  fd_check("alpha*p1^2*cos(p2) + WallT*x*y*z*p2 + G*y", TDS_EXPR_PARAMS, par, x0);
  /* the Hessian of a simple case, exactly */
  tds_expr *e = comp("x^2*y + 3*y*z", 0);
  if (e) {
    double v[TDS_NVARS] = {2, 3, 5, 0, 0, 0}, g[5], H[5][5];
    CHECK_NEAR(tds_expr_eval_hess(e, NULL, v, g, H), 57, 0);
    CHECK(g[0] == 12 && g[1] == 19 && g[2] == 9 && g[3] == 0);
    CHECK(H[0][0] == 6 && H[0][1] == 4 && H[1][0] == 4 && H[0][2] == 0);
    CHECK(H[1][2] == 3 && H[2][1] == 3 && H[1][1] == 0 && H[2][2] == 0);
    CHECK(H[3][3] == 0 && H[4][0] == 0);
    tds_expr_free(e);
  }
  /* a constant exponent leaves negative bases differentiable */
  e = comp("x^3", 0);
  if (e) {
    double v[TDS_NVARS] = {-2, 0, 0, 0, 0, 0}, g[5], H[5][5];
    CHECK_NEAR(tds_expr_eval_hess(e, NULL, v, g, H), -8, 0);
    CHECK_NEAR(g[0], 12, 1e-15);
    CHECK_NEAR(H[0][0], -12, 1e-15);
    tds_expr_free(e);
  }
}

static void test_params(void) {
  tds_ctx ctx;
  tds_expr_env env = {.flags = 0, lookup2, NULL};
  tds_expr *e = NULL;
  tds_ctx_init(&ctx);
  CHECK(tds_expr_parse(&ctx, "ALPHA*x + wallt^2", NULL, &env, &e) == TDS_OK);
  if (!e) return;
  CHECK(tds_expr_uses_params(e) && !tds_expr_is_const(e));
  CHECK(tds_expr_max_param(e) == 3);
  double par[4] = {2, 0, 0, 3}, v[TDS_NVARS] = {5, 0, 0, 0, 0, 0}, g[5];
  CHECK_NEAR(tds_expr_eval(e, par, v), 19, 0);
  par[0] = -1;                                  /* no recompilation */
  par[3] = 0.5;
  CHECK_NEAR(tds_expr_eval(e, par, v), -4.75, 0);
  tds_expr_eval_grad(e, par, v, g);
  CHECK(g[0] == -1 && g[1] == 0);               /* parameters are not variables */
  tds_expr_free(e);
  /* parameters alone are not folded */
  CHECK(tds_expr_parse(&ctx, "2*alpha + 1", NULL, &env, &e) == TDS_OK);
  if (e) {
    CHECK(tds_expr_max_param(e) == 0 && !tds_expr_is_const(e));
    CHECK_NEAR(tds_expr_eval(e, par, NULL), -1, 0);
    tds_expr_free(e);
  }
  /* p1, p2 need TDS_EXPR_PARAMS */
  char msg[1024];
  CHECK(perr("cos(p1)", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(has(msg, "p1 is only allowed in boundary parametrisations at column 5"));
  env.flags = TDS_EXPR_PARAMS;
  CHECK(tds_expr_parse(&ctx, "cos(P1) + p2", NULL, &env, &e) == TDS_OK);
  if (e) {
    CHECK(tds_expr_uses_var(e, TDS_P1) && tds_expr_uses_var(e, TDS_P2));
    double w[TDS_NVARS] = {0, 0, 0, 0, 2, 0};
    CHECK_NEAR(tds_expr_eval(e, NULL, w), 3, 0);
    tds_expr_free(e);
  }
  /* constant context */
  CHECK(perr("x+1", TDS_EXPR_NOCOORD, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(strcmp(msg, "expression 'x+1': x is not allowed here at column 1") == 0);
  CHECK(perr("2*p1", TDS_EXPR_NOCOORD | TDS_EXPR_PARAMS, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(has(msg, "p1 is not allowed here at column 3"));
  CHECK(perr("max(1,2)", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(has(msg, "unknown name 'max' (use maximum(a,b))"));
}

/* Parse consecutive expressions from s in datafile mode; values into v. */
static int parse_seq(const char *s, int flags, double *v, int max, size_t *rest) {
  tds_ctx ctx;
  tds_expr_env env = {.flags = flags, lookup2, NULL};
  double par[4] = {0, 0, 0, 2};
  double xv[TDS_NVARS] = {0, 3, 0, 0, 0, 0};
  size_t off = 0;
  int n = 0;
  tds_ctx_init(&ctx);
  while (n < max) {
    size_t i = off;
    while (s[i] == ' ') i++;
    if (!s[i] || strncmp(s + i, "fixed", 5) == 0) break;
    size_t used = 0;
    tds_expr *e = NULL;
    if (tds_expr_parse(&ctx, s + off, &used, &env, &e) != TDS_OK) {
      printf("  '%s': %s\n", s + off, ctx.errmsg);
      return -1;
    }
    v[n++] = tds_expr_eval(e, par, xv);
    tds_expr_free(e);
    off += used;
  }
  if (rest) *rest = off;
  return n;
}

static void test_datafile(void) {
  int D = TDS_EXPR_DATAFILE;
  double v[8];
  size_t rest = 0;
  CHECK(parse_seq("1 -1 0", D, v, 8, &rest) == 3);
  CHECK(v[0] == 1 && v[1] == -1 && v[2] == 0 && rest == 6);
  CHECK(parse_seq("1 - 1 0", D, v, 8, NULL) == 2);
  CHECK(v[0] == 0 && v[1] == 0);
  /* '+' never starts a value (evolver-nox-d reads "5 +1 0" as 6 and 0) */
  CHECK(parse_seq("1 +2 -.5", D, v, 8, NULL) == 2);
  CHECK(v[0] == 3 && v[1] == -0.5);
  CHECK(parse_seq("1,-1,2", D, v, 8, NULL) == 3);
  CHECK(v[0] == 1 && v[1] == -1 && v[2] == 2);
  CHECK(parse_seq("(1 -1) 2*3", D, v, 8, NULL) == 2);    /* rule off inside () */
  CHECK(v[0] == 0 && v[1] == 6);
  /* any '-' after a space and before a non-space starts a value, as
     evolver-nox-d reads "5 -rad 0" and "5 -(2) 0" (x is 0 here) */
  CHECK(parse_seq("1 -x 2", D, v, 8, NULL) == 3);
  CHECK(v[0] == 1 && v[1] == 0 && v[2] == 2);
  CHECK(parse_seq("5 -(2) 0", D, v, 8, NULL) == 3);
  CHECK(v[0] == 5 && v[1] == -2 && v[2] == 0);
  CHECK(parse_seq("-(WALLT*y) 4", D, v, 8, NULL) == 2);
  CHECK(v[0] == -6 && v[1] == 4);
  CHECK(parse_seq(", 3", D, v, 8, NULL) == 1 && v[0] == 3);
  CHECK(parse_seq("atan2(1, -1) maximum(2,3);", D, v, 8, NULL) == 2);
  CHECK_NEAR(v[0], 2.35619449019234, 1e-14);
  CHECK(v[1] == 3);
  CHECK(parse_seq("y > 1 ? 10 : 20 5", D, v, 8, NULL) == 2);   /* ':' after '?' */
  CHECK(v[0] == 10 && v[1] == 5);
  CHECK(parse_seq("2*pi/3 fixed", D, v, 8, &rest) == 1);
  CHECK(rest == 7);
  CHECK_NEAR(v[0], 2.0943951023931953, 1e-15);
  /* without datafile mode "1 -1" is one expression */
  CHECK(parse_seq("1 -1 0", 0, v, 8, NULL) == 2 && v[0] == 0 && v[1] == 0);

  /* consumed points at the first unused token; the text is trimmed */
  tds_ctx ctx;
  tds_expr_env env = {.flags = D, NULL, NULL};
  tds_expr *e = NULL;
  size_t used = 0;
  tds_ctx_init(&ctx);
  CHECK(tds_expr_parse(&ctx, "  2*pi/3   fixed", &used, &env, &e) == TDS_OK);
  CHECK(used == 11);
  if (e) {
    CHECK(strcmp(tds_expr_text(e), "2*pi/3") == 0);
    tds_expr_free(e);
  }
  CHECK(tds_expr_parse(&ctx, "x+1) rest", &used, &env, &e) == TDS_OK && used == 3);
  tds_expr_free(e);
  CHECK(tds_expr_parse(&ctx, "x+1 }", &used, &env, &e) == TDS_OK && used == 4);
  tds_expr_free(e);
  CHECK(tds_expr_parse(&ctx, "1.5D2", &used, &env, &e) == TDS_OK && used == 3);
  tds_expr_free(e);                           /* Fortran exponent not honoured */
  CHECK(tds_expr_parse(&ctx, "3 x", &used, &env, &e) == TDS_OK && used == 2);
  tds_expr_free(e);
  CHECK(tds_expr_parse(&ctx, "3 mod 2", &used, &env, &e) == TDS_OK && used == 7);
  tds_expr_free(e);
  e = NULL;
  CHECK(tds_expr_parse(&ctx, "3 = 1", &used, &env, &e) == TDS_ESYNTAX && !e);
}

static void test_errors(void) {
  char msg[1024];
  CHECK(perr("x^2 + * 3", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(strcmp(msg, "expression 'x^2 + * 3': unexpected '*' at column 7") == 0);
  CHECK(perr("sin(x", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(strcmp(msg, "expression 'sin(x': missing ')' at column 6") == 0);
  CHECK(perr("foo + 1", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(strcmp(msg, "expression 'foo + 1': unknown name 'foo' at column 1") == 0);
  CHECK(perr("(1+2", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "missing ')' at column 5"));
  CHECK(perr("((1+2)", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "missing ')'"));
  CHECK(perr("1+2)", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "unexpected ')' at column 4"));
  CHECK(perr("", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(strcmp(msg, "expression '': empty expression at column 1") == 0);
  CHECK(perr("   ", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "empty expression"));
  CHECK(perr("1 +", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(strcmp(msg, "expression '1 +': unexpected end of expression at column 4") == 0);
  CHECK(perr("\x01\xff", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(has(msg, "unexpected character '\\x01' at column 1"));
  CHECK(perr("1 2", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "unexpected '2' at column 3"));
  CHECK(perr("sin 1", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "expected '(' after 'sin'"));
  CHECK(perr("atan2(1)", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "atan2 needs 2 arguments"));
  CHECK(perr("sin(1,2)", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "sin takes 1 argument"));
  CHECK(perr("1 ? 2", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "missing ':' at column 6"));
  CHECK(perr("1 & 2", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "unexpected character '&'"));
  CHECK(perr("1e999999", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "number out of range"));
  CHECK(perr("1 + /* open", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "unterminated comment"));
  CHECK(perr("1.5D2", 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "unexpected 'D2'"));
  CHECK(perr("2 +\n* 3", 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(strcmp(msg, "expression '2 + * 3': unexpected '*' at column 5") == 0);
  /* a NULL ctx is tolerated */
  tds_expr *e = NULL;
  CHECK(tds_expr_parse(NULL, "1 +", NULL, NULL, &e) == TDS_ESYNTAX && !e);
}

static void test_robustness(void) {
  char msg[1024];
  size_t n = 100000;
  char *s = malloc(n + 1);
  if (!s) return;
  /* a valid 100000-character sum evaluates (left chain: stack depth 2) */
  for (size_t i = 0; i < n; i += 2) {
    s[i] = 'x';
    s[i + 1] = '+';
  }
  s[0] = '1';        /* "1+x+x+...+x " */
  s[n - 1] = ' ';
  s[n] = 0;
  tds_expr *e = comp(s, 0);
  if (e) {
    double v[TDS_NVARS] = {2, 0, 0, 0, 0, 0}, g[5], H[5][5];
    CHECK_NEAR(tds_expr_eval(e, NULL, v), 2.0 * (double)(n / 2 - 1) + 1, 0);
    CHECK_NEAR(tds_expr_eval_hess(e, NULL, v, g, H), 2.0 * (double)(n / 2 - 1) + 1, 0);
    CHECK(g[0] == (double)(n / 2 - 1) && H[0][0] == 0);
    tds_expr_free(e);
  }
  /* a broken one: message quotes at most 60 characters */
  s[n - 1] = '+';
  CHECK(perr(s, 0, msg, sizeof msg) == TDS_ESYNTAX);
  CHECK(has(msg, "x+x+...': unexpected end of expression at column 100001"));
  CHECK(strlen(msg) < 200);
  /* 10000 nested parentheses: clean error, no stack overflow */
  size_t depth = 10000;
  for (size_t i = 0; i < depth; i++) s[i] = '(';
  s[depth] = '1';
  for (size_t i = 0; i < depth; i++) s[depth + 1 + i] = ')';
  s[2 * depth + 1] = 0;
  CHECK(perr(s, 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "nested too deeply"));
  for (size_t i = 0; i < depth; i++) s[i] = '-';
  s[depth] = '1';
  s[depth + 1] = 0;
  CHECK(perr(s, 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "nested too deeply"));
  /* within the nesting limit but beyond 64 stack slots */
  s[0] = 0;
  for (int i = 0; i < 100; i++) strcat(s, "x+(");
  strcat(s, "x");
  for (int i = 0; i < 100; i++) strcat(s, ")");
  CHECK(perr(s, 0, msg, sizeof msg) == TDS_ESYNTAX && has(msg, "too complex"));
  /* 60 levels still work */
  s[0] = 0;
  for (int i = 0; i < 60; i++) strcat(s, "x+(");
  strcat(s, "x");
  for (int i = 0; i < 60; i++) strcat(s, ")");
  e = comp(s, 0);
  if (e) {
    double v[TDS_NVARS] = {1, 0, 0, 0, 0, 0}, g[5], H[5][5];
    CHECK_NEAR(tds_expr_eval_hess(e, NULL, v, g, H), 61, 0);
    CHECK(g[0] == 61);
    tds_expr_free(e);
  }
  /* pseudo-random garbage never crashes (any status, message set on error) */
  unsigned seed = 12345;
  const char alpha[] = "xyz01.e+-*/^()?:,!=<>&|% \t\x01\xff" "abcsinpmodG";
  for (int trial = 0; trial < 20000; trial++) {
    int len = (int)(seed % 24);
    for (int i = 0; i < len; i++) {
      seed = seed * 1103515245u + 12345u;
      s[i] = alpha[(seed >> 16) % (sizeof alpha - 1)];
    }
    s[len] = 0;
    seed = seed * 1103515245u + 12345u;
    tds_ctx ctx;
    tds_expr_env env = {.flags = (int)(seed >> 16) & 15, lookup2, NULL};
    size_t used = 0;
    tds_ctx_init(&ctx);
    e = NULL;
    int rc = tds_expr_parse(&ctx, s, (seed >> 20) & 1 ? &used : NULL, &env, &e);
    if (rc == TDS_OK) {
      double par[4] = {1, 1, 1, 1}, v[TDS_NVARS] = {0.3, 0.2, 0.1, 0.4, 0.5, 1}, g[5], H[5][5];
      tds_expr_eval(e, par, v);
      tds_expr_eval_hess(e, par, v, g, H);
      CHECK(used <= (size_t)len);
      tds_expr_free(e);
    } else {
      CHECK(rc == TDS_ESYNTAX && e == NULL && strncmp(ctx.errmsg, "expression '", 12) == 0);
    }
  }
  free(s);
}

int main(void) {
  RUN(test_evolver_table);
  RUN(test_functions);
  RUN(test_folding_and_queries);
  RUN(test_formula);
  RUN(test_derivatives);
  RUN(test_params);
  RUN(test_datafile);
  RUN(test_errors);
  RUN(test_robustness);
  return check_done();
}
