/*
** expr.h: Surface Evolver's expression language, compiled once to a flat
** postfix program and evaluated with value, gradient or Hessian.
**
** Grammar and quirks: doc reference expressions.md (sections 1-4). Summary,
** high to low precedence: ^ ** (left assoc; a unary sign may follow) ·
** unary - + · * / % mod imod idiv · + - · == != < > <= >= (right assoc) ·
** not ! · and && · or || · ?: · '=' (a low-precedence minus, only with
** TDS_EXPR_FORMULA). Comparisons and logic yield 0/1.
**
** Lexical decisions where Evolver is silent or odd:
**  - numbers: 3, 1.5, .5, 1., 1e-3, 5E+2, hex 0x1F, binary 101b (Evolver's).
**    Fortran "1.5D2" is NOT an exponent: it reads as 1.5 followed by the
**    name D2 (as Evolver really does). A literal that overflows (1e999) is
**    an error; one that underflows reads as 0.
**  - C comments (slash-star ... star-slash) and // ... are skipped, as is a backslash-newline.
**  - TDS_EXPR_DATAFILE: ',' ':' ';' are whitespace, except that ',' separates
**    arguments inside a function call and ':' is the ternary colon while a
**    '?' is pending. The signed-number rule applies only outside
**    parentheses ("(1 -1)" is 0, not an error).
**  - names: keywords, functions, constants and x y z x1 x2 x3 p1 p2 G are
**    case-insensitive and reserved; any other name (also a dotted one like
**    "q.value") goes to env->lookup. G is allowed under TDS_EXPR_NOCOORD.
**  - the ':=' prefix, arrays, strings, attributes and aggregates of the
**    command language are not part of this compiler.
*/
#ifndef TDS_EXPR_H
#define TDS_EXPR_H

#include <stddef.h>

#include "tds.h"

enum { TDS_X = 0, TDS_Y, TDS_Z, TDS_P1, TDS_P2, TDS_NDIFF = 5, TDS_G = 5, TDS_NVARS = 6 };
/* vars[0..4] are differentiable: x y z p1 p2; vars[5] is G, the gravity
   constant (not differentiated). */

typedef struct tds_expr tds_expr;           /* opaque compiled program */

typedef struct tds_expr_env {
  int flags;                                 /* TDS_EXPR_* below */
  /* Parameter lookup: returns a slot >= 0 for a known parameter name
     (case-insensitive match is the callback's job), or -1. NULL = no
     parameters. name is NOT NUL-terminated: use len. */
  int (*lookup)(void *ud, const char *name, size_t len);
  void *ud;
  /* Optional: why the last lookup that returned -1 failed ("a facet
     attribute, ..."), appended to the unknown-name error, or NULL. */
  const char *(*why)(void *ud);
} tds_expr_env;

/* A lookup may also return TDS_EXPR_ATTR(j) (j >= 0): the name is an
   element attribute in slot j (xattr.h), compiled as a read of
   params[-1-j]. The caller then passes a params pointer with the slots in
   front of it, filled for the element being evaluated. */
#define TDS_EXPR_ATTR(j) (-2 - (j))

enum {
  TDS_EXPR_FORMULA  = 1,  /* '=' is a low-precedence minus (level-set formulas): "x^2+y^2 = R^2" */
  TDS_EXPR_DATAFILE = 2,  /* datafile lexing: the signed-number rule (after a complete operand, a
                             '-' preceded by whitespace and not followed by whitespace starts a NEW
                             expression: "1 -1 0" and "1 -a 0" are three, "1 - 1 0" is two, "1 +1" is
                             one), and ',' ':' ';' are whitespace */
  TDS_EXPR_PARAMS   = 4,  /* p1, p2 (also P1, P2) are allowed (boundary parametrisations) */
  TDS_EXPR_NOCOORD  = 8   /* constant context: x y z p1 p2 are errors ("x is not allowed here") */
};

/* Limits: parser nesting (parentheses, unary/not/comparison/ternary chains)
   and evaluation stack slots. Deeper expressions are refused with
   TDS_ESYNTAX. */
#define TDS_EXPR_MAXNEST 200
#define TDS_EXPR_MAXSTACK 64

/* Parse one expression from text (NUL-terminated). If consumed is NULL the
   whole text must be one expression (trailing tokens are an error).
   Otherwise parse the LONGEST legal expression starting at text (leading
   whitespace skipped), stop before the first token that cannot continue it
   (an identifier after a complete operand, a number after a complete
   operand, a closing brace, end of text, etc.), and store in *consumed the
   number of characters used (including the leading whitespace; it points at
   the first unused token).
   On error returns TDS_ESYNTAX with ctx->errmsg like:
     "expression 'x^2 + * 3': unexpected '*' at column 7"  (column is 1-based within text)
     "expression 'sin(x': missing ')' at column 6"
     "expression 'foo + 1': unknown name 'foo' at column 1"
   and *out is NULL. Returns TDS_ENOMEM on allocation failure. The caller
   owns *out (free with tds_expr_free). env may be NULL (flags 0). ctx
   may be NULL (no message; the C library allocates); otherwise memory
   comes from ctx->alloc, and the expression keeps that hook to free
   itself. */
int tds_expr_parse(tds_ctx *ctx, const char *text, size_t *consumed,
                   const tds_expr_env *env, tds_expr **out);

/* Free a compiled expression (NULL is fine). */
void tds_expr_free(tds_expr *e);
/* The source text it was compiled from (trimmed); owned by e. */
const char *tds_expr_text(const tds_expr *e);
/* 1 if e uses no variable (x y z p1 p2 G), no parameter and no attribute: it then folded to
   a single constant and may be evaluated with params = vars = NULL. */
int tds_expr_is_const(const tds_expr *e);
/* 1 if variable var (TDS_X..TDS_G) occurs (after constant folding). */
int tds_expr_uses_var(const tds_expr *e, int var);
/* 1 if any parameter occurs. */
int tds_expr_uses_params(const tds_expr *e);
/* 1 if any element attribute (TDS_EXPR_ATTR) occurs. */
int tds_expr_uses_attrs(const tds_expr *e);
/* Highest parameter slot used, or -1: params must hold that many + 1. */
int tds_expr_max_param(const tds_expr *e);
/* Number of instructions of the compiled program (1 for a folded
   constant); for tests and diagnostics. */
int tds_expr_ncode(const tds_expr *e);

/* Evaluate. params[slot] holds parameter values; vars[TDS_NVARS] the
   variables (either may be NULL when the expression does not use it).
   Results follow IEEE arithmetic (1/0 = inf, sqrt(-1) = NaN): callers check
   isfinite. No allocation; safe to call concurrently on one e. */
double tds_expr_eval(const tds_expr *e, const double *params, const double vars[TDS_NVARS]);
/* Value and gradient with respect to vars[0..4] (exact, forward mode).
   Non-smooth points: floor ceil imod idiv comparisons logic have zero
   derivative, abs uses sign(x) (0 at 0), % differentiates x - floor(x/y)*y
   with floor held constant, ?: minimum maximum follow the selected branch. */
double tds_expr_eval_grad(const tds_expr *e, const double *params, const double vars[TDS_NVARS],
                          double grad[TDS_NDIFF]);
/* Value, gradient and Hessian (full symmetric 5x5) with respect to vars[0..4]. */
double tds_expr_eval_hess(const tds_expr *e, const double *params, const double vars[TDS_NVARS],
                          double grad[TDS_NDIFF], double hess[TDS_NDIFF][TDS_NDIFF]);

/* Polynomial degree in x y z p1 p2 (parameters and G count as constants),
   or -1 if the expression is not a polynomial (functions, division by a
   variable, ?:, ...). Used to pick exact quadrature rules. */
int tds_expr_degree(const tds_expr *e);

#ifdef TDS_EXPR_INTERNAL
/* Shared by expr_parse.c and expr_eval.c only. */
#include <stdint.h>

enum {
  /* stack pushes and jumps */
  TDS_OP_PUSHK, TDS_OP_PUSHV, TDS_OP_PUSHP, TDS_OP_JZ, TDS_OP_JMP,
  /* unary: replace the top slot */
  TDS_OP_NEG, TDS_OP_NOT, TDS_OP_ABS, TDS_OP_SQR, TDS_OP_SQRT, TDS_OP_SIN,
  TDS_OP_COS, TDS_OP_TAN, TDS_OP_ASIN, TDS_OP_ACOS, TDS_OP_ATAN, TDS_OP_LOG,
  TDS_OP_EXP, TDS_OP_SINH, TDS_OP_COSH, TDS_OP_TANH, TDS_OP_ASINH,
  TDS_OP_ACOSH, TDS_OP_ATANH, TDS_OP_CEIL, TDS_OP_FLOOR,
  /* binary: pop two, push one */
  TDS_OP_ADD, TDS_OP_SUB, TDS_OP_MUL, TDS_OP_DIV, TDS_OP_MOD, TDS_OP_IMOD,
  TDS_OP_IDIV, TDS_OP_POW, TDS_OP_ATAN2, TDS_OP_MIN, TDS_OP_MAX, TDS_OP_EQ,
  TDS_OP_NE, TDS_OP_LT, TDS_OP_GT, TDS_OP_LE, TDS_OP_GE, TDS_OP_AND,
  TDS_OP_OR,
  TDS_OP_COUNT
};
#define TDS_OP_UNARY0 TDS_OP_NEG
#define TDS_OP_BINARY0 TDS_OP_ADD

/* One instruction. arg: constant index (PUSHK), variable (PUSHV), parameter
   slot (PUSHP), relative jump (JZ/JMP: next pc = pc + 1 + arg). flags on
   unary/binary ops: bit 0 = the (left) operand may have a nonzero
   derivative, bit 1 = the right operand may. */
typedef struct tds_instr {
  uint8_t op, flags;
  int32_t arg;
} tds_instr;

struct tds_expr {
  const tds_instr *code;
  const double *k;        /* constants */
  const char *text;
  int ncode, nk;
  int maxstack;           /* slots the evaluator needs */
  int varmask;            /* bit v: variable v occurs */
  int maxparam;           /* -1 if none */
  int minparam;           /* lowest slot read; < 0: element attributes */
  int nact;               /* differentiable variables that occur ... */
  int act[TDS_NDIFF];     /* ... local derivative index -> variable */
  int loc[TDS_NDIFF];     /* variable -> local index, -1 if absent */
  tds_alloc alloc;        /* the allocator of this block (the ctx's) */
};

/* Apply a unary or binary opcode to constant operands (b ignored for unary
   ops), with exactly the evaluator's semantics; used for constant folding. */
double tds_expr_fold(int op, double a, double b);
#endif

#endif
