/*
** fuzz_expr.c: libFuzzer harness of the expression compiler (expr.h).
**
** Input: byte 0 picks the parse flags (TDS_EXPR_*) and whether the parse
** stops at the longest prefix (consumed mode); bytes 1..8 seed the
** evaluation points; the rest is the expression text. A parse must either
** fail with a message or give a program whose value, gradient and Hessian
** evaluate without sanitizer reports at a few points, and the three
** evaluators must agree: the same value (or all NaN), the same gradient
** from eval_grad and eval_hess, a symmetric Hessian, zero derivatives for
** variables that do not occur, and a constant program that needs neither
** parameters nor variables; the polynomial degree is at least -1 and a
** degree-0 program has a zero gradient. The gradient is not compared with finite
** differences: expressions are arbitrary (floor, ?:, huge powers), so such
** a check would flag correct code.
*/
#include <math.h>
#include <strings.h>
#include <stdint.h>

#include "expr.h"
#include "fuzz_util.h"

static const char *const names[] = {"a", "b", "rad", "angle", "q.value", "height"};
enum { NPARAMS = 6 };

static int lookup(void *ud, const char *name, size_t len) {
  (void)ud;
  for (int i = 0; i < NPARAMS; i++)
    if (strlen(names[i]) == len && !strncasecmp(names[i], name, len)) return i;
  return -1;
}

/* Same double, both NaN, or both the same infinity. */
static int same(double a, double b) {
  return (isnan(a) && isnan(b)) || a == b;
}

static uint64_t rng;
static double next_value(void) {
  rng = rng * 6364136223846793005ull + 1442695040888963407ull;
  static const double specials[] = {0.0, 1.0, -1.0, 0.5, 2.0, -3.0, 1e-300, 1e300};
  unsigned r = (unsigned)(rng >> 33);
  if ((r & 7) == 0) return specials[(r >> 3) & 7];
  return ((double)(r >> 3) / (double)(1u << 28) - 0.5) * 8.0;
}

static void evaluate(const tds_expr *e) {
  int maxp = tds_expr_max_param(e);
  FUZZ_CHECK(maxp < NPARAMS, "parameter slot %d out of range", maxp);
  /* Exactly as many parameters as the program claims to need, so ASan
     catches a read beyond them. */
  double *params = maxp >= 0 ? malloc(sizeof(double) * (size_t)(maxp + 1)) : NULL;
  if (tds_expr_is_const(e)) {
    double v = tds_expr_eval(e, NULL, NULL);
    FUZZ_CHECK(maxp < 0 && !tds_expr_uses_params(e), "constant uses parameters");
    for (int var = 0; var < TDS_NVARS; var++)
      FUZZ_CHECK(!tds_expr_uses_var(e, var), "constant uses variable %d", var);
    (void)v;
  }
  /* Polynomial degree (for quadrature rules): at least -1, and a degree-0
     program has a zero gradient wherever its value is finite. */
  int degree = tds_expr_degree(e);
  FUZZ_CHECK(degree >= -1, "'%s': degree %d", tds_expr_text(e), degree);
  for (int point = 0; point < 4; point++) {
    double vars[TDS_NVARS];
    for (int i = 0; i < TDS_NVARS; i++) vars[i] = next_value();
    for (int i = 0; i <= maxp; i++) params[i] = next_value();
    double g1[TDS_NDIFF], g2[TDS_NDIFF], h[TDS_NDIFF][TDS_NDIFF];
    double v0 = tds_expr_eval(e, params, vars);
    double v1 = tds_expr_eval_grad(e, params, vars, g1);
    double v2 = tds_expr_eval_hess(e, params, vars, g2, h);
    FUZZ_CHECK(same(v0, v1) && same(v0, v2), "'%s': values %.17g %.17g %.17g",
               tds_expr_text(e), v0, v1, v2);
    for (int i = 0; i < TDS_NDIFF; i++) {
      if (degree == 0 && isfinite(v0))
        FUZZ_CHECK(g1[i] == 0, "'%s': degree 0 but d/d%d = %.17g", tds_expr_text(e), i, g1[i]);
      FUZZ_CHECK(same(g1[i], g2[i]), "'%s': d/d%d %.17g vs %.17g", tds_expr_text(e), i,
                 g1[i], g2[i]);
      if (!tds_expr_uses_var(e, i)) {
        FUZZ_CHECK(g1[i] == 0, "'%s': d/d%d = %g of an absent variable", tds_expr_text(e),
                   i, g1[i]);
        for (int j = 0; j < TDS_NDIFF; j++)
          FUZZ_CHECK(h[i][j] == 0 && h[j][i] == 0, "'%s': hessian %d %d of an absent variable",
                     tds_expr_text(e), i, j);
      }
      for (int j = 0; j < i; j++)
        FUZZ_CHECK(same(h[i][j], h[j][i]), "'%s': hessian not symmetric at %d %d: %.17g %.17g",
                   tds_expr_text(e), i, j, h[i][j], h[j][i]);
    }
  }
  free(params);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 9) return 0;
  int flags = data[0] & 15, prefix = data[0] & 16;
  rng = 0;
  for (int i = 1; i < 9; i++) rng = rng << 8 | data[i];
  size_t len = size - 9;
  char *text = malloc(len + 1);
  if (!text) return 0;
  memcpy(text, data + 9, len);
  text[len] = 0;
  tds_ctx ctx;
  tds_ctx_init(&ctx);
  ctx.out = ctx.warn = fuzz_no_output;
  tds_expr_env env = {flags, lookup, NULL};
  tds_expr *e = NULL;
  size_t consumed = 0;
  int rc = tds_expr_parse(&ctx, text, prefix ? &consumed : NULL, &env, &e);
  if (rc == TDS_OK) {
    FUZZ_CHECK(e != NULL, "parse succeeded without a program");
    FUZZ_CHECK(!prefix || consumed <= strlen(text), "consumed %zu of %zu", consumed,
               strlen(text));
    FUZZ_CHECK(tds_expr_ncode(e) >= 1, "empty program");
    evaluate(e);
    tds_expr_free(e);
  } else {
    FUZZ_CHECK(e == NULL && ctx.errmsg[0], "failed parse: rc %d, program %p, message '%s'",
               rc, (void *)e, ctx.errmsg);
  }
  free(text);
  return 0;
}
