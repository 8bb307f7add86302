/*
** expr_eval.c: evaluation of compiled expressions (see expr.h).
**
** The program is flat postfix code with relative jumps for ?:, so the
** evaluators are loops over a fixed local stack (no recursion, no
** allocation). The value path carries doubles only. The derivative paths
** carry per slot the value, the gradient and the packed upper triangle of
** the Hessian, over the "active" variables only (those x y z p1 p2 that
** occur, e.nact <= 5), and apply the chain rule per opcode from the
** operation's partial derivatives (forward mode, exact).
*/
#define TDS_EXPR_INTERNAL
#include "expr.h"

#include <math.h>
#include <string.h>

/* ---- values (shared with constant folding) ---- */

static inline double truth(int c) { return c ? 1.0 : 0.0; }

static inline double imod(double a, double b) {
  double fa = floor(a), fb = floor(b);
  return fa - floor(fa / fb) * fb;
}

static inline double apply(int op, double a, double b) {
  switch (op) {
  case TDS_OP_NEG: return -a;
  case TDS_OP_NOT: return truth(a == 0);
  case TDS_OP_ABS: return fabs(a);
  case TDS_OP_SQR: return a * a;
  case TDS_OP_SQRT: return sqrt(a);
  case TDS_OP_SIN: return sin(a);
  case TDS_OP_COS: return cos(a);
  case TDS_OP_TAN: return tan(a);
  case TDS_OP_ASIN: return asin(a);
  case TDS_OP_ACOS: return acos(a);
  case TDS_OP_ATAN: return atan(a);
  case TDS_OP_LOG: return log(a);
  case TDS_OP_EXP: return exp(a);
  case TDS_OP_SINH: return sinh(a);
  case TDS_OP_COSH: return cosh(a);
  case TDS_OP_TANH: return tanh(a);
  case TDS_OP_ASINH: return asinh(a);
  case TDS_OP_ACOSH: return acosh(a);
  case TDS_OP_ATANH: return atanh(a);
  case TDS_OP_CEIL: return ceil(a);
  case TDS_OP_FLOOR: return floor(a);
  case TDS_OP_ADD: return a + b;
  case TDS_OP_SUB: return a - b;
  case TDS_OP_MUL: return a * b;
  case TDS_OP_DIV: return a / b;
  case TDS_OP_MOD: return a - floor(a / b) * b;
  case TDS_OP_IMOD: return imod(a, b);
  case TDS_OP_IDIV: return trunc(trunc(a) / trunc(b));
  case TDS_OP_POW: return pow(a, b);
  case TDS_OP_ATAN2: return atan2(a, b);
  case TDS_OP_MIN: return b < a ? b : a;
  case TDS_OP_MAX: return b > a ? b : a;
  case TDS_OP_EQ: return truth(a == b);
  case TDS_OP_NE: return truth(a != b);
  case TDS_OP_LT: return truth(a < b);
  case TDS_OP_GT: return truth(a > b);
  case TDS_OP_LE: return truth(a <= b);
  case TDS_OP_GE: return truth(a >= b);
  case TDS_OP_AND: return truth(a != 0 && b != 0);
  case TDS_OP_OR: return truth(a != 0 || b != 0);
  default: return NAN;
  }
}

/* Apply op to constants; the evaluator's exact semantics (constant folding). */
double tds_expr_fold(int op, double a, double b) { return apply(op, a, b); }

/* Evaluate the value only. */
double tds_expr_eval(const tds_expr *e, const double *params,
                     const double vars[TDS_NVARS]) {
  double st[TDS_EXPR_MAXSTACK];
  int sp = -1;
  const tds_instr *c = e->code;
  for (int pc = 0, n = e->ncode; pc < n; pc++) {
    int op = c[pc].op;
    switch (op) {
    case TDS_OP_PUSHK: st[++sp] = e->k[c[pc].arg]; break;
    case TDS_OP_PUSHV: st[++sp] = vars[c[pc].arg]; break;
    case TDS_OP_PUSHP: st[++sp] = params[c[pc].arg]; break;
    case TDS_OP_JZ: if (st[sp--] == 0) pc += c[pc].arg; break;
    case TDS_OP_JMP: pc += c[pc].arg; break;
    case TDS_OP_ADD: sp--; st[sp] += st[sp + 1]; break;
    case TDS_OP_SUB: sp--; st[sp] -= st[sp + 1]; break;
    case TDS_OP_MUL: sp--; st[sp] *= st[sp + 1]; break;
    case TDS_OP_DIV: sp--; st[sp] /= st[sp + 1]; break;
    case TDS_OP_NEG: st[sp] = -st[sp]; break;
    case TDS_OP_SQR: st[sp] *= st[sp]; break;
    default:
      if (op >= TDS_OP_BINARY0) {
        sp--;
        st[sp] = apply(op, st[sp], st[sp + 1]);
      } else {
        st[sp] = apply(op, st[sp], 0);
      }
    }
  }
  return st[0];
}

/* ---- derivatives ---- */

#define NH (TDS_NDIFF * (TDS_NDIFF + 1) / 2)

typedef struct slot {
  double v;
  double g[TDS_NDIFF];
  double h[NH];   /* upper triangle, row by row, over the active variables */
} slot;

static void zero_derivs(slot *s, int n, int nh, int want_h) {
  memset(s->g, 0, (size_t)n * sizeof(double));
  if (want_h) memset(s->h, 0, (size_t)nh * sizeof(double));
}

/* s <- f(s) with f' = f1, f'' = f2. */
static void chain1(slot *s, int n, int want_h, double f1, double f2) {
  if (want_h) {
    int k = 0;
    for (int i = 0; i < n; i++)
      for (int j = i; j < n; j++, k++)
        s->h[k] = f1 * s->h[k] + f2 * s->g[i] * s->g[j];
  }
  for (int i = 0; i < n; i++) s->g[i] *= f1;
}

/* a <- f(a, b) with first partials fa fb and second faa fab fbb; a partial
   of an operand whose derivatives are identically zero must be passed as 0
   (it may be inf or NaN where the operand is constant). */
static void chain2(slot *a, const slot *b, int n, int want_h, double fa,
                   double fb, double faa, double fab, double fbb) {
  if (want_h) {
    int k = 0;
    for (int i = 0; i < n; i++)
      for (int j = i; j < n; j++, k++)
        a->h[k] = fa * a->h[k] + fb * b->h[k] + faa * a->g[i] * a->g[j] +
                  fbb * b->g[i] * b->g[j] +
                  fab * (a->g[i] * b->g[j] + b->g[i] * a->g[j]);
  }
  for (int i = 0; i < n; i++) a->g[i] = fa * a->g[i] + fb * b->g[i];
}

/* Value f of a unary op and its derivatives f1, f2; returns 0 if the op has
   zero derivative everywhere. */
static int d_unary(int op, double x, double *f, double *f1, double *f2) {
  double t, u;
  *f = apply(op, x, 0);
  switch (op) {
  case TDS_OP_NEG: *f1 = -1; *f2 = 0; return 1;
  case TDS_OP_ABS: *f1 = x > 0 ? 1 : x < 0 ? -1 : 0; *f2 = 0; return 1;
  case TDS_OP_SQR: *f1 = 2 * x; *f2 = 2; return 1;
  case TDS_OP_SQRT: *f1 = 0.5 / *f; *f2 = -0.25 / (x * *f); return 1;
  case TDS_OP_SIN: *f1 = cos(x); *f2 = -*f; return 1;
  case TDS_OP_COS: *f1 = -sin(x); *f2 = -*f; return 1;
  case TDS_OP_TAN: t = *f; *f1 = 1 + t * t; *f2 = 2 * t * *f1; return 1;
  case TDS_OP_ASIN:
  case TDS_OP_ACOS:
    u = 1 - x * x;
    t = op == TDS_OP_ASIN ? 1 : -1;
    *f1 = t / sqrt(u); *f2 = t * x / (u * sqrt(u)); return 1;
  case TDS_OP_ATAN: u = 1 + x * x; *f1 = 1 / u; *f2 = -2 * x / (u * u); return 1;
  case TDS_OP_LOG: *f1 = 1 / x; *f2 = -1 / (x * x); return 1;
  case TDS_OP_EXP: *f1 = *f; *f2 = *f; return 1;
  case TDS_OP_SINH: *f1 = cosh(x); *f2 = *f; return 1;
  case TDS_OP_COSH: *f1 = sinh(x); *f2 = *f; return 1;
  case TDS_OP_TANH: t = *f; *f1 = 1 - t * t; *f2 = -2 * t * *f1; return 1;
  case TDS_OP_ASINH: u = x * x + 1; *f1 = 1 / sqrt(u); *f2 = -x / (u * sqrt(u)); return 1;
  case TDS_OP_ACOSH: u = x * x - 1; *f1 = 1 / sqrt(u); *f2 = -x / (u * sqrt(u)); return 1;
  case TDS_OP_ATANH: u = 1 - x * x; *f1 = 1 / u; *f2 = 2 * x / (u * u); return 1;
  default: *f1 = *f2 = 0; return 0;   /* NOT CEIL FLOOR */
  }
}

/* Partials of a smooth binary op (ADD..ATAN2 except IMOD IDIV); la/lb say
   whether the operands carry derivatives (unneeded partials are skipped,
   they may be NaN). d[] = fa fb faa fab fbb. */
static double d_binary(int op, double a, double b, int la, int lb, double d[5]) {
  double f = apply(op, a, b), r;
  d[0] = d[1] = d[2] = d[3] = d[4] = 0;
  switch (op) {
  case TDS_OP_ADD: d[0] = 1; d[1] = 1; break;
  case TDS_OP_SUB: d[0] = 1; d[1] = -1; break;
  case TDS_OP_MUL: d[0] = b; d[1] = a; d[3] = 1; break;
  case TDS_OP_DIV:
    d[0] = 1 / b; d[1] = -f / b; d[3] = -1 / (b * b); d[4] = 2 * f / (b * b);
    break;
  case TDS_OP_MOD: d[0] = 1; d[1] = -floor(a / b); break;
  case TDS_OP_POW:
    if (la) {
      d[0] = b == 0 ? 0 : b * pow(a, b - 1);
      d[2] = (b == 0 || b == 1) ? 0 : b * (b - 1) * pow(a, b - 2);
    }
    if (lb) {
      r = log(a);
      d[1] = f * r;
      d[4] = f * r * r;
      if (la) d[3] = pow(a, b - 1) * (1 + b * r);
    }
    break;
  case TDS_OP_ATAN2:   /* atan2(a = y, b = x) */
    r = a * a + b * b;
    d[0] = b / r; d[1] = -a / r;
    d[2] = -2 * a * b / (r * r); d[4] = -d[2];
    d[3] = (a * a - b * b) / (r * r);
    break;
  default: break;
  }
  if (!la) d[0] = d[2] = d[3] = 0;
  if (!lb) d[1] = d[4] = d[3] = 0;
  return f;
}

static double run_deriv(const tds_expr *e, const double *params,
                        const double *vars, double grad[TDS_NDIFF],
                        double hess[TDS_NDIFF][TDS_NDIFF], int want_h) {
  slot st[TDS_EXPR_MAXSTACK];
  int sp = -1, n = e->nact, nh = n * (n + 1) / 2;
  const tds_instr *c = e->code;
  double d[5], f, f1, f2;
  for (int pc = 0, nc = e->ncode; pc < nc; pc++) {
    int op = c[pc].op, fl = c[pc].flags;
    slot *s;
    switch (op) {
    case TDS_OP_PUSHK:
    case TDS_OP_PUSHV:
    case TDS_OP_PUSHP:
      s = &st[++sp];
      zero_derivs(s, n, nh, want_h);
      if (op == TDS_OP_PUSHK) {
        s->v = e->k[c[pc].arg];
      } else if (op == TDS_OP_PUSHP) {
        s->v = params[c[pc].arg];
      } else {
        s->v = vars[c[pc].arg];
        if (c[pc].arg < TDS_NDIFF) s->g[e->loc[c[pc].arg]] = 1;
      }
      break;
    case TDS_OP_JZ: if (st[sp--].v == 0) pc += c[pc].arg; break;
    case TDS_OP_JMP: pc += c[pc].arg; break;
    default:
      if (op < TDS_OP_BINARY0) {
        s = &st[sp];
        if (!(fl & 1)) {
          s->v = apply(op, s->v, 0);
        } else if (d_unary(op, s->v, &f, &f1, &f2)) {
          chain1(s, n, want_h, f1, f2);
          s->v = f;
        } else {
          s->v = f;
          zero_derivs(s, n, nh, want_h);
        }
        break;
      }
      sp--;
      s = &st[sp];
      if (!fl) {
        s->v = apply(op, s->v, s[1].v);
      } else if (op == TDS_OP_MIN || op == TDS_OP_MAX) {
        if (op == TDS_OP_MIN ? s[1].v < s->v : s[1].v > s->v) *s = s[1];
      } else if (op <= TDS_OP_ATAN2 && op != TDS_OP_IMOD && op != TDS_OP_IDIV) {
        f = d_binary(op, s->v, s[1].v, fl & 1, fl & 2, d);
        chain2(s, &s[1], n, want_h, d[0], d[1], d[2], d[3], d[4]);
        s->v = f;
      } else {   /* IMOD IDIV comparisons and/or: zero derivative */
        s->v = apply(op, s->v, s[1].v);
        zero_derivs(s, n, nh, want_h);
      }
    }
  }
  for (int i = 0; i < TDS_NDIFF; i++) grad[i] = 0;
  for (int i = 0; i < n; i++) grad[e->act[i]] = st[0].g[i];
  if (want_h) {
    memset(hess, 0, sizeof(double) * TDS_NDIFF * TDS_NDIFF);
    int k = 0;
    for (int i = 0; i < n; i++)
      for (int j = i; j < n; j++, k++)
        hess[e->act[i]][e->act[j]] = hess[e->act[j]][e->act[i]] = st[0].h[k];
  }
  return st[0].v;
}

/* Value and gradient with respect to vars[0..4]. */
double tds_expr_eval_grad(const tds_expr *e, const double *params,
                          const double vars[TDS_NVARS],
                          double grad[TDS_NDIFF]) {
  return run_deriv(e, params, vars, grad, NULL, 0);
}

/* Value, gradient and full symmetric Hessian with respect to vars[0..4]. */
double tds_expr_eval_hess(const tds_expr *e, const double *params,
                          const double vars[TDS_NVARS], double grad[TDS_NDIFF],
                          double hess[TDS_NDIFF][TDS_NDIFF]) {
  return run_deriv(e, params, vars, grad, hess, 1);
}

int tds_expr_degree(const tds_expr *e) {
  int st[TDS_EXPR_MAXSTACK + 1], sp = 0; /* -1: not a polynomial */
  double kv[TDS_EXPR_MAXSTACK + 1];      /* constant value of a degree-0 slot */
  int kc[TDS_EXPR_MAXSTACK + 1];         /* 1: slot is a known constant */
  for (int pc = 0; pc < e->ncode; pc++) {
    const tds_instr *in = &e->code[pc];
    switch (in->op) {
    case TDS_OP_PUSHK:
      st[sp] = 0, kc[sp] = 1, kv[sp] = e->k[in->arg], sp++;
      break;
    case TDS_OP_PUSHP:
      st[sp] = 0, kc[sp] = 0, sp++;
      break;
    case TDS_OP_PUSHV: /* G is a constant of the integration */
      st[sp] = in->arg == TDS_G ? 0 : 1, kc[sp] = 0, sp++;
      break;
    case TDS_OP_NEG:
      kv[sp - 1] = -kv[sp - 1];
      break;
    case TDS_OP_SQR:
      st[sp - 1] = st[sp - 1] < 0 ? -1 : 2 * st[sp - 1];
      kc[sp - 1] = 0;
      break;
    case TDS_OP_ADD: case TDS_OP_SUB: case TDS_OP_MUL: case TDS_OP_DIV:
    case TDS_OP_POW: {
      int a = st[sp - 2], b = st[sp - 1], r;
      if (a < 0 || b < 0) r = -1;
      else if (in->op == TDS_OP_MUL) r = a + b;
      else if (in->op == TDS_OP_DIV) r = b == 0 ? a : -1;
      else if (in->op == TDS_OP_POW) {
        double n = kv[sp - 1];
        r = b == 0 && kc[sp - 1] && n >= 0 && n <= 16 && n == (int)n ? a * (int)n
            : (a == 0 && b == 0) ? 0 : -1;
      } else r = a > b ? a : b;
      sp--;
      st[sp - 1] = r;
      kc[sp - 1] = 0;
      break;
    }
    default: /* any other function of a non-constant is not a polynomial */
      if (in->op >= TDS_OP_BINARY0) {
        sp--;
        st[sp - 1] = (st[sp - 1] == 0 && st[sp] == 0) ? 0 : -1;
      } else if (in->op >= TDS_OP_UNARY0) {
        st[sp - 1] = st[sp - 1] == 0 ? 0 : -1;
      } else {
        return -1; /* jumps: ?: is piecewise */
      }
      kc[sp - 1] = 0;
    }
  }
  return sp == 1 ? st[0] : -1;
}
