/*
** expr_parse.c: lexer, recursive-descent parser and constant folder for
** Evolver expressions (see expr.h), emitting flat postfix code directly.
**
** Each parse function appends the code of its operand to the buffer and
** describes it in an `opnd` (where its code starts, whether it is a single
** folded constant, which variables it uses). An operator whose operands are
** all constant truncates their code and pushes the folded value; ?: with a
** constant condition keeps only the selected branch (jumps are relative,
** so code moves freely). Recursion is bounded by TDS_EXPR_MAXNEST; the
** evaluation stack depth is computed by one linear pass over the final code.
*/
#define TDS_EXPR_INTERNAL
#include "expr.h"

#include <locale.h>
#include <math.h>
#include <stdalign.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- tokens ---- */

enum {
  T_END, T_NUM, T_NAME, T_LP, T_RP, T_COMMA, T_COLON, T_QUEST, T_BAD,
  /* operators */
  T_PLUS, T_MINUS, T_STAR, T_SLASH, T_PERCENT, T_MOD, T_IMOD, T_IDIV, T_POW,
  T_EQ, T_NE, T_LT, T_GT, T_LE, T_GE, T_NOT, T_AND, T_OR, T_ASSIGN
};

typedef struct tok {
  int t;
  size_t pos, len;     /* byte range in the text */
  double num;          /* T_NUM */
  const char *bad;     /* why a T_BAD / T_NUM token is unusable, or NULL */
  int signnum;         /* '-' preceded by whitespace and followed by none */
} tok;

/* Operand descriptor. */
#define DIFFMASK 0x1f      /* x y z p1 p2 */
#define GBIT 0x20
#define PARAMBIT 0x40
typedef struct opnd {
  int start;     /* first instruction of its code */
  int isconst;   /* code is a single PUSHK */
  double val;    /* value when isconst */
  int deps;      /* variables (bits 0..5) and PARAMBIT */
  int dd;        /* may have a nonzero derivative */
} opnd;

typedef struct parser {
  tds_ctx *ctx;
  const tds_alloc *al;    /* ctx's allocator, or NULL (the C library) */
  const char *s;
  size_t n;
  int flags;
  const tds_expr_env *env;
  tok cur;
  size_t lexpos;       /* where the next token is lexed */
  size_t last_end;     /* end of the last consumed token */
  int nest;            /* recursion counter */
  int pdepth;          /* open parentheses (incl. argument lists) */
  int argdepth;        /* open function-argument lists */
  int qdepth;          /* pending '?' awaiting ':' */
  int rc;
  tds_instr *code;
  int32_t ncode, capcode;
  double *k;
  int32_t nk, capk;
} parser;

/* ---- error messages ---- */

/* Quote the expression: trimmed, control bytes shown as spaces and
   non-ASCII as '?', at most 60 characters then "...". */
static void quote(const parser *p, char *buf, size_t cap) {
  size_t a = 0, b = p->n, j = 0;
  while (a < b && (unsigned char)p->s[a] <= ' ') a++;
  while (b > a && (unsigned char)p->s[b - 1] <= ' ') b--;
  for (size_t i = a; i < b && j + 4 < cap; i++) {
    if (i - a >= 60) {
      memcpy(buf + j, "...", 3);
      j += 3;
      break;
    }
    unsigned char ch = (unsigned char)p->s[i];
    buf[j++] = ch < ' ' ? ' ' : ch >= 127 ? '?' : (char)ch;
  }
  buf[j] = 0;
}

static int fail(parser *p, size_t pos, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int fail(parser *p, size_t pos, const char *fmt, ...) {
  char q[80], what[200];
  va_list ap;
  if (p->rc) return p->rc;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  quote(p, q, sizeof q);
  p->rc = TDS_ESYNTAX;
  if (p->ctx)
    tds_seterr(p->ctx, TDS_ESYNTAX, "expression '%s': %s at column %zu", q,
               what, pos + 1);
  return p->rc;
}

static int nomem(parser *p) {
  if (p->rc) return p->rc;
  p->rc = TDS_ENOMEM;
  if (p->ctx) tds_seterr(p->ctx, TDS_ENOMEM, "expression: out of memory");
  return p->rc;
}

/* Describe a token for "unexpected ..." into buf. */
static void describe(const parser *p, const tok *t, char *buf, size_t cap) {
  if (t->t == T_END) {
    snprintf(buf, cap, "end of expression");
    return;
  }
  if (t->t == T_BAD && t->len == 1) {
    unsigned char ch = (unsigned char)p->s[t->pos];
    if (ch < ' ' || ch >= 127)
      snprintf(buf, cap, "character '\\x%02x'", ch);
    else
      snprintf(buf, cap, "character '%c'", ch);
    return;
  }
  char q[24];
  size_t j = 0;
  for (size_t i = 0; i < t->len && j < 20; i++) {
    unsigned char ch = (unsigned char)p->s[t->pos + i];
    q[j++] = ch < ' ' ? ' ' : ch >= 127 ? '?' : (char)ch;
  }
  q[j] = 0;
  snprintf(buf, cap, "'%s%s'", q, t->len > 20 ? "..." : "");
}

static int unexpected(parser *p) {
  char d[64];
  if (p->cur.t == T_BAD && p->cur.bad)
    return fail(p, p->cur.pos, "%s", p->cur.bad);
  describe(p, &p->cur, d, sizeof d);
  return fail(p, p->cur.pos, "unexpected %s", d);
}

/* ---- lexer ---- */

static int is_alpha(int c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static int is_digit(int c) { return c >= '0' && c <= '9'; }
static int is_alnum(int c) { return is_alpha(c) || is_digit(c); }
static int is_hex(int c) {
  return is_digit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}
static int lower(int c) { return c >= 'A' && c <= 'Z' ? c + 32 : c; }

static int is_space(const parser *p, int c) {
  if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v')
    return 1;
  if (!(p->flags & TDS_EXPR_DATAFILE)) return 0;
  if (c == ';') return 1;
  if (c == ',') return p->argdepth == 0;
  if (c == ':') return p->qdepth == 0;
  return 0;
}

/* Skip whitespace and comments from i; returns the new position, or
   (size_t)-1 for an unterminated comment starting at *bad. */
static size_t skip_space(const parser *p, size_t i, size_t *bad) {
  const char *s = p->s;
  for (;;) {
    if (i < p->n && is_space(p, (unsigned char)s[i])) {
      i++;
    } else if (i + 1 < p->n && s[i] == '\\' && (s[i + 1] == '\n' || s[i + 1] == '\r')) {
      i += 2;
    } else if (i + 1 < p->n && s[i] == '/' && s[i + 1] == '/') {
      while (i < p->n && s[i] != '\n') i++;
    } else if (i + 1 < p->n && s[i] == '/' && s[i + 1] == '*') {
      size_t j = i + 2;
      while (j + 1 < p->n && !(s[j] == '*' && s[j + 1] == '/')) j++;
      if (j + 1 >= p->n) {
        *bad = i;
        return (size_t)-1;
      }
      i = j + 2;
    } else {
      return i;
    }
  }
}

/* Convert the decimal literal s[0..len) with strtod (correct rounding),
   independent of the C locale's decimal point. */
static double decimal_value(const tds_alloc *al, const char *s, size_t len, int *ok) {
  char small[128], *buf = len < sizeof small ? small : tds_malloc(al, len + 1);
  double v = 0;
  char *end;
  *ok = 0;
  if (!buf) return 0;
  memcpy(buf, s, len);
  buf[len] = 0;
  v = strtod(buf, &end);
  if ((size_t)(end - buf) != len) {
    const char *dp = localeconv()->decimal_point;
    char *dot = strchr(buf, '.');
    if (dot && dp && dp[0] && !dp[1]) *dot = dp[0];
    v = strtod(buf, &end);
  }
  *ok = (size_t)(end - buf) == len;
  if (buf != small) tds_free(al, buf);
  return v;
}

/* Lex a number starting at i into t. */
static void lex_number(const parser *p, size_t i, tok *t) {
  const char *s = p->s;
  size_t j = i;
  t->t = T_NUM;
  t->pos = i;
  if (s[i] == '0' && i + 2 < p->n && (s[i + 1] == 'x' || s[i + 1] == 'X') &&
      is_hex((unsigned char)s[i + 2])) {
    double v = 0;
    for (j = i + 2; j < p->n && is_hex((unsigned char)s[j]); j++) {
      int c = lower((unsigned char)s[j]);
      v = v * 16 + (is_digit(c) ? c - '0' : c - 'a' + 10);
    }
    t->num = v;
    t->len = j - i;
    if (!isfinite(v)) t->bad = "number out of range";
    return;
  }
  while (j < p->n && (s[j] == '0' || s[j] == '1')) j++;
  if (j > i && j < p->n && (s[j] == 'b' || s[j] == 'B') &&
      !(j + 1 < p->n && (is_alnum((unsigned char)s[j + 1]) || s[j + 1] == '.'))) {
    double v = 0;
    for (size_t m = i; m < j; m++) v = v * 2 + (s[m] - '0');
    t->num = v;
    t->len = j + 1 - i;
    if (!isfinite(v)) t->bad = "number out of range";
    return;
  }
  j = i;
  while (j < p->n && is_digit((unsigned char)s[j])) j++;
  if (j < p->n && s[j] == '.') {
    j++;
    while (j < p->n && is_digit((unsigned char)s[j])) j++;
  }
  if (j < p->n && (s[j] == 'e' || s[j] == 'E')) {
    size_t m = j + 1;
    if (m < p->n && (s[m] == '+' || s[m] == '-')) m++;
    if (m < p->n && is_digit((unsigned char)s[m])) {
      while (m < p->n && is_digit((unsigned char)s[m])) m++;
      j = m;
    }
  }
  int ok;
  t->len = j - i;
  t->num = decimal_value(p->al, s + i, t->len, &ok);
  if (!ok)
    t->bad = "cannot read number";
  else if (!isfinite(t->num))
    t->bad = "number out of range";
}

/* Reserved words that are operators. */
typedef struct kw { const char *name; int t; } kw;
static const kw opwords[] = {
  {"mod", T_MOD}, {"imod", T_IMOD}, {"idiv", T_IDIV}, {"and", T_AND},
  {"or", T_OR}, {"not", T_NOT}, {NULL, 0}
};

static int name_is(const char *s, size_t len, const char *w) {
  size_t i = 0;
  for (; i < len; i++)
    if (!w[i] || lower((unsigned char)s[i]) != w[i]) return 0;
  return w[i] == 0;
}

/* Lex the token at p->lexpos into p->cur. */
static void lex(parser *p) {
  size_t bad = 0, i = skip_space(p, p->lexpos, &bad);
  tok *t = &p->cur;
  const char *s = p->s;
  memset(t, 0, sizeof *t);
  if (i == (size_t)-1) {
    t->t = T_BAD;
    t->pos = bad;
    t->len = 2;
    t->bad = "unterminated comment";
    p->lexpos = p->n;
    return;
  }
  t->pos = i;
  t->len = 1;
  if (i >= p->n) {
    t->t = T_END;
    t->len = 0;
    p->lexpos = i;
    return;
  }
  int c = (unsigned char)s[i], c1 = i + 1 < p->n ? (unsigned char)s[i + 1] : 0;
  if (is_digit(c) || (c == '.' && is_digit(c1))) {
    lex_number(p, i, t);
  } else if (is_alpha(c)) {
    size_t j = i + 1;
    while (j < p->n && is_alnum((unsigned char)s[j])) j++;
    t->t = T_NAME;
    t->len = j - i;
    for (const kw *w = opwords; w->name; w++)
      if (name_is(s + i, t->len, w->name)) t->t = w->t;
    /* dotted names (q.value) go to the lookup as one name */
    while (t->t == T_NAME && j + 1 < p->n && s[j] == '.' &&
           is_alpha((unsigned char)s[j + 1])) {
      j += 2;
      while (j < p->n && is_alnum((unsigned char)s[j])) j++;
      t->len = j - i;
    }
  } else {
    int two = 0;
    switch (c) {
    case '+': t->t = T_PLUS; break;
    case '-': t->t = T_MINUS; break;
    case '*': if (c1 == '*') { t->t = T_POW; two = 1; } else t->t = T_STAR; break;
    case '/': t->t = T_SLASH; break;
    case '%': t->t = T_PERCENT; break;
    case '^': t->t = T_POW; break;
    case '(': t->t = T_LP; break;
    case ')': t->t = T_RP; break;
    case ',': t->t = T_COMMA; break;
    case ':': t->t = T_COLON; break;
    case '?': t->t = T_QUEST; break;
    case '=': if (c1 == '=') { t->t = T_EQ; two = 1; } else t->t = T_ASSIGN; break;
    case '!': if (c1 == '=') { t->t = T_NE; two = 1; } else t->t = T_NOT; break;
    case '<': if (c1 == '=') { t->t = T_LE; two = 1; } else t->t = T_LT; break;
    case '>': if (c1 == '=') { t->t = T_GE; two = 1; } else t->t = T_GT; break;
    case '&': if (c1 == '&') { t->t = T_AND; two = 1; } else t->t = T_BAD; break;
    case '|': if (c1 == '|') { t->t = T_OR; two = 1; } else t->t = T_BAD; break;
    default: t->t = T_BAD; break;
    }
    t->len = two ? 2 : 1;
    if (t->t == T_MINUS && i > 0 && is_space(p, (unsigned char)s[i - 1]) &&
        i + 1 < p->n && !is_space(p, c1) && c1 != '-' && c1 != '+')
      t->signnum = 1;
  }
  p->lexpos = t->pos + t->len;
}

/* Consume the current token and lex the next one. */
static void advance(parser *p) {
  p->last_end = p->cur.pos + p->cur.len;
  lex(p);
}

/* ---- code emission ---- */

static int emit(parser *p, int op, int flags, int32_t arg) {
  if (p->rc) return p->rc;
  if (tds_grow(p->al, (void **)&p->code, sizeof *p->code, &p->capcode, p->ncode + 1))
    return nomem(p);
  p->code[p->ncode].op = (uint8_t)op;
  p->code[p->ncode].flags = (uint8_t)flags;
  p->code[p->ncode].arg = arg;
  p->ncode++;
  return TDS_OK;
}

/* Truncate the code to o->start and push constant v; o becomes it. */
static int emit_const(parser *p, opnd *o, int start, double v) {
  if (p->rc) return p->rc;
  p->ncode = start;
  if (tds_grow(p->al, (void **)&p->k, sizeof *p->k, &p->capk, p->nk + 1))
    return nomem(p);
  p->k[p->nk] = v;
  o->start = start;
  o->isconst = 1;
  o->val = v;
  o->deps = 0;
  o->dd = 0;
  return emit(p, TDS_OP_PUSHK, 0, p->nk++);
}

static int zero_deriv_op(int op) {
  return op == TDS_OP_NOT || op == TDS_OP_CEIL || op == TDS_OP_FLOOR ||
         op == TDS_OP_IMOD || op == TDS_OP_IDIV || op >= TDS_OP_EQ;
}

/* Apply unary op to operand a (its code is at the end of the buffer). */
static int unop(parser *p, int op, opnd *a) {
  if (p->rc) return p->rc;
  if (a->isconst) return emit_const(p, a, a->start, tds_expr_fold(op, a->val, 0));
  emit(p, op, a->dd ? 1 : 0, 0);
  a->isconst = 0;
  if (zero_deriv_op(op)) a->dd = 0;
  return p->rc;
}

/* Apply binary op to a and b (b's code follows a's); result in a. */
static int binop(parser *p, int op, opnd *a, const opnd *b) {
  if (p->rc) return p->rc;
  if (a->isconst && b->isconst)
    return emit_const(p, a, a->start, tds_expr_fold(op, a->val, b->val));
  if (op == TDS_OP_POW && b->isconst && b->val == 0)     /* a^0 is 1 for every a (pow), */
    return emit_const(p, a, a->start, 1);   /* also where a's derivative overflows */
  if (op == TDS_OP_POW && b->isconst && b->val == 2) {   /* x^2 -> sqr */
    p->ncode = b->start;
    return unop(p, TDS_OP_SQR, a);
  }
  emit(p, op, (a->dd ? 1 : 0) | (b->dd ? 2 : 0), 0);
  a->isconst = 0;
  a->deps |= b->deps;
  if (op == TDS_OP_MIN || op == TDS_OP_MAX)
    a->dd = a->dd || b->dd;
  else
    a->dd = zero_deriv_op(op) ? 0 : (a->dd || b->dd);
  return p->rc;
}

/* ---- parser ---- */

static int parse_expr(parser *p, opnd *o);
static int parse_ternary(parser *p, opnd *o);

static int enter(parser *p) {
  if (++p->nest > TDS_EXPR_MAXNEST)
    return fail(p, p->cur.pos, "expression nested too deeply (more than %d levels)",
                TDS_EXPR_MAXNEST);
  return TDS_OK;
}

/* Built-in names. */
enum { B_FUNC1, B_FUNC2, B_CONST, B_VAR };
typedef struct builtin { const char *name; int kind, code; } builtin;
static const builtin builtins[] = {
  {"abs", B_FUNC1, TDS_OP_ABS}, {"sqr", B_FUNC1, TDS_OP_SQR},
  {"sqrt", B_FUNC1, TDS_OP_SQRT}, {"sin", B_FUNC1, TDS_OP_SIN},
  {"cos", B_FUNC1, TDS_OP_COS}, {"tan", B_FUNC1, TDS_OP_TAN},
  {"asin", B_FUNC1, TDS_OP_ASIN}, {"acos", B_FUNC1, TDS_OP_ACOS},
  {"atan", B_FUNC1, TDS_OP_ATAN}, {"log", B_FUNC1, TDS_OP_LOG},
  {"exp", B_FUNC1, TDS_OP_EXP}, {"sinh", B_FUNC1, TDS_OP_SINH},
  {"cosh", B_FUNC1, TDS_OP_COSH}, {"tanh", B_FUNC1, TDS_OP_TANH},
  {"asinh", B_FUNC1, TDS_OP_ASINH}, {"acosh", B_FUNC1, TDS_OP_ACOSH},
  {"atanh", B_FUNC1, TDS_OP_ATANH}, {"ceil", B_FUNC1, TDS_OP_CEIL},
  {"floor", B_FUNC1, TDS_OP_FLOOR}, {"atan2", B_FUNC2, TDS_OP_ATAN2},
  {"pow", B_FUNC2, TDS_OP_POW}, {"minimum", B_FUNC2, TDS_OP_MIN},
  {"maximum", B_FUNC2, TDS_OP_MAX}, {"pi", B_CONST, 0}, {"e", B_CONST, 1},
  {"x", B_VAR, TDS_X}, {"y", B_VAR, TDS_Y}, {"z", B_VAR, TDS_Z},
  {"x1", B_VAR, TDS_X}, {"x2", B_VAR, TDS_Y}, {"x3", B_VAR, TDS_Z},
  {"p1", B_VAR, TDS_P1}, {"p2", B_VAR, TDS_P2}, {"g", B_VAR, TDS_G},
  {NULL, 0, 0}
};

static const builtin *find_builtin(const char *s, size_t len) {
  for (const builtin *b = builtins; b->name; b++)
    if (name_is(s, len, b->name)) return b;
  return NULL;
}

/* name(args): the current token is the function name. */
static int parse_call(parser *p, const builtin *b, opnd *o) {
  size_t namepos = p->cur.pos, namelen = p->cur.len;
  const char *name = b->name;
  int nargs = b->kind == B_FUNC2 ? 2 : 1;
  opnd a2;
  advance(p);
  if (p->cur.t != T_LP)
    return fail(p, p->cur.pos, "expected '(' after '%.*s'", (int)namelen,
                p->s + namepos);
  p->pdepth++;
  p->argdepth++;
  advance(p);
  if (enter(p) || parse_expr(p, o)) return p->rc;
  if (nargs == 2) {
    if (p->cur.t == T_RP)
      return fail(p, p->cur.pos, "%s needs 2 arguments", name);
    if (p->cur.t != T_COMMA) return fail(p, p->cur.pos, "missing ','");
    advance(p);
    if (parse_expr(p, &a2)) return p->rc;
  }
  p->nest--;
  if (p->cur.t == T_COMMA)
    return fail(p, p->cur.pos, "%s takes %d argument%s", name, nargs,
                nargs > 1 ? "s" : "");
  if (p->cur.t != T_RP) return fail(p, p->cur.pos, "missing ')'");
  p->pdepth--;
  p->argdepth--;
  advance(p);
  return nargs == 2 ? binop(p, b->code, o, &a2) : unop(p, b->code, o);
}

static int parse_name(parser *p, opnd *o) {
  const char *nm = p->s + p->cur.pos;
  size_t len = p->cur.len, pos = p->cur.pos;
  const builtin *b = find_builtin(nm, len);
  o->start = p->ncode;
  o->isconst = 0;
  o->deps = o->dd = 0;
  if (b && (b->kind == B_FUNC1 || b->kind == B_FUNC2)) return parse_call(p, b, o);
  if (b && b->kind == B_CONST) {
    advance(p);
    return emit_const(p, o, p->ncode, b->code == 0 ? 3.14159265358979323846
                                                   : 2.71828182845904523536);
  }
  if (b && b->code != TDS_G && (p->flags & TDS_EXPR_NOCOORD))
    return fail(p, pos, "%.*s is not allowed here", (int)len, nm);
  if (b && ((b->code != TDS_P1 && b->code != TDS_P2) || (p->flags & TDS_EXPR_PARAMS))) {
    advance(p);
    o->deps = 1 << b->code;
    o->dd = b->code < TDS_NDIFF;
    return emit(p, TDS_OP_PUSHV, 0, b->code);
  }
  int slot = p->env && p->env->lookup ? p->env->lookup(p->env->ud, nm, len) : -1;
  if (slot >= 0 || slot <= TDS_EXPR_ATTR(0)) {
    advance(p);
    o->deps = PARAMBIT;
    return emit(p, TDS_OP_PUSHP, 0, slot >= 0 ? slot : slot + 1);
  }
  if (b)
    return fail(p, pos, "%.*s is only allowed in boundary parametrisations",
                (int)len, nm);
  if (name_is(nm, len, "max") || name_is(nm, len, "min"))
    return fail(p, pos, "unknown name '%.*s' (use %.*simum(a,b))", (int)len, nm,
                (int)len, nm);
  const char *why = p->env && p->env->why ? p->env->why(p->env->ud) : NULL;
  if (why) return fail(p, pos, "%s", why);
  return fail(p, pos, "unknown name '%.*s'", len > 40 ? 40 : (int)len, nm);
}

static int parse_primary(parser *p, opnd *o) {
  o->start = p->ncode;
  switch (p->cur.t) {
  case T_NUM:
    if (p->cur.bad) return fail(p, p->cur.pos, "%s", p->cur.bad);
    {
      double v = p->cur.num;
      advance(p);
      return emit_const(p, o, p->ncode, v);
    }
  case T_NAME: return parse_name(p, o);
  case T_LP:
    p->pdepth++;
    advance(p);
    if (enter(p) || parse_expr(p, o)) return p->rc;
    p->nest--;
    if (p->cur.t != T_RP) return fail(p, p->cur.pos, "missing ')'");
    p->pdepth--;
    advance(p);
    return TDS_OK;
  case T_END:
    if (p->last_end == 0) return fail(p, p->cur.pos, "empty expression");
    return unexpected(p);
  default: return unexpected(p);
  }
}

/* pow := primary { ('^'|'**') ['-'|'+'] primary }  (left associative) */
static int parse_pow(parser *p, opnd *o) {
  if (parse_primary(p, o)) return p->rc;
  while (p->cur.t == T_POW) {
    opnd b;
    int neg = 0;
    advance(p);
    if (p->cur.t == T_MINUS || p->cur.t == T_PLUS) {
      neg = p->cur.t == T_MINUS;
      advance(p);
    }
    if (parse_primary(p, &b)) return p->rc;
    if (neg && unop(p, TDS_OP_NEG, &b)) return p->rc;
    if (binop(p, TDS_OP_POW, o, &b)) return p->rc;
  }
  return TDS_OK;
}

/* unary := ('-'|'+') unary | pow */
static int parse_unary(parser *p, opnd *o) {
  if (p->cur.t == T_MINUS || p->cur.t == T_PLUS) {
    int neg = p->cur.t == T_MINUS;
    advance(p);
    if (enter(p) || parse_unary(p, o)) return p->rc;
    p->nest--;
    return neg ? unop(p, TDS_OP_NEG, o) : TDS_OK;
  }
  return parse_pow(p, o);
}

static int mulop(int t) {
  switch (t) {
  case T_STAR: return TDS_OP_MUL;
  case T_SLASH: return TDS_OP_DIV;
  case T_PERCENT: case T_MOD: return TDS_OP_MOD;
  case T_IMOD: return TDS_OP_IMOD;
  case T_IDIV: return TDS_OP_IDIV;
  default: return -1;
  }
}

static int parse_mul(parser *p, opnd *o) {
  int op;
  if (parse_unary(p, o)) return p->rc;
  while ((op = mulop(p->cur.t)) >= 0) {
    opnd b;
    advance(p);
    if (parse_unary(p, &b) || binop(p, op, o, &b)) return p->rc;
  }
  return TDS_OK;
}

/* The datafile signed-number rule, as evolver-nox-d 2.70 reads element
   lines: after a complete operand, a '-' preceded by whitespace and not
   followed by whitespace starts a new value ("5 -1 0", "5 -rad 0" and
   "5 -(2) 0" are three values), while '+' never does ("5 +1" is 6). */
static int sign_breaks(const parser *p) {
  return (p->flags & TDS_EXPR_DATAFILE) && p->pdepth == 0 && p->cur.signnum;
}

static int parse_add(parser *p, opnd *o) {
  if (parse_mul(p, o)) return p->rc;
  while ((p->cur.t == T_PLUS || p->cur.t == T_MINUS) && !sign_breaks(p)) {
    int op = p->cur.t == T_PLUS ? TDS_OP_ADD : TDS_OP_SUB;
    opnd b;
    advance(p);
    if (parse_mul(p, &b) || binop(p, op, o, &b)) return p->rc;
  }
  return TDS_OK;
}

static int relop(int t) {
  switch (t) {
  case T_EQ: return TDS_OP_EQ;
  case T_NE: return TDS_OP_NE;
  case T_LT: return TDS_OP_LT;
  case T_GT: return TDS_OP_GT;
  case T_LE: return TDS_OP_LE;
  case T_GE: return TDS_OP_GE;
  default: return -1;
  }
}

/* rel := add [ relop rel ]  (right associative) */
static int parse_rel(parser *p, opnd *o) {
  int op;
  if (parse_add(p, o)) return p->rc;
  if ((op = relop(p->cur.t)) >= 0) {
    opnd b;
    advance(p);
    if (enter(p) || parse_rel(p, &b)) return p->rc;
    p->nest--;
    return binop(p, op, o, &b);
  }
  return TDS_OK;
}

/* not := ('not'|'!') not | rel */
static int parse_not(parser *p, opnd *o) {
  if (p->cur.t == T_NOT) {
    advance(p);
    if (enter(p) || parse_not(p, o)) return p->rc;
    p->nest--;
    return unop(p, TDS_OP_NOT, o);
  }
  return parse_rel(p, o);
}

static int parse_and(parser *p, opnd *o) {
  if (parse_not(p, o)) return p->rc;
  while (p->cur.t == T_AND) {
    opnd b;
    advance(p);
    if (parse_not(p, &b) || binop(p, TDS_OP_AND, o, &b)) return p->rc;
  }
  return TDS_OK;
}

static int parse_or(parser *p, opnd *o) {
  if (parse_and(p, o)) return p->rc;
  while (p->cur.t == T_OR) {
    opnd b;
    advance(p);
    if (parse_and(p, &b) || binop(p, TDS_OP_OR, o, &b)) return p->rc;
  }
  return TDS_OK;
}

/* Move code [from, p->ncode) down to `to`. */
static void move_code(parser *p, int to, int from) {
  memmove(p->code + to, p->code + from,
          (size_t)(p->ncode - from) * sizeof *p->code);
  p->ncode = to + (p->ncode - from);
}

/* ternary := or [ '?' ternary ':' ternary ] */
static int parse_ternary(parser *p, opnd *o) {
  opnd t, f;
  if (parse_or(p, o)) return p->rc;
  if (p->cur.t != T_QUEST) return TDS_OK;
  int jz = p->ncode;
  if (emit(p, TDS_OP_JZ, 0, 0)) return p->rc;
  p->qdepth++;
  advance(p);
  if (enter(p) || parse_ternary(p, &t)) return p->rc;
  int jmp = p->ncode;
  if (emit(p, TDS_OP_JMP, 0, 0)) return p->rc;
  if (p->cur.t != T_COLON) return fail(p, p->cur.pos, "missing ':'");
  p->qdepth--;
  advance(p);
  if (parse_ternary(p, &f)) return p->rc;
  p->nest--;
  p->code[jz].arg = jmp - jz;
  p->code[jmp].arg = p->ncode - jmp - 1;
  if (o->isconst) {          /* keep only the selected branch */
    opnd *sel = o->val != 0 ? &t : &f;
    if (o->val != 0) p->ncode = jmp;
    move_code(p, o->start, sel->start);
    sel->start = o->start;
    *o = *sel;
    return TDS_OK;
  }
  o->isconst = 0;
  o->deps |= t.deps | f.deps;
  o->dd = t.dd || f.dd;
  return TDS_OK;
}

/* expr := ternary { '=' ternary }   ('=' only with TDS_EXPR_FORMULA) */
static int parse_expr(parser *p, opnd *o) {
  if (parse_ternary(p, o)) return p->rc;
  while (p->cur.t == T_ASSIGN) {
    opnd b;
    if (!(p->flags & TDS_EXPR_FORMULA))
      return fail(p, p->cur.pos,
                  "'=' is only allowed in formulas (use '==' to compare)");
    advance(p);
    if (parse_ternary(p, &b) || binop(p, TDS_OP_SUB, o, &b)) return p->rc;
  }
  return TDS_OK;
}

/* ---- assembling the program ---- */

static size_t align_up(size_t n) {
  size_t a = alignof(max_align_t);
  return (n + a - 1) / a * a;
}

/* Build the final tds_expr (one allocation) from the parser's code. */
static int finish(parser *p, size_t a, size_t b, tds_expr **out) {
  int depth = 0, maxd = 0, nk = 0, varmask = 0, maxparam = -1, minparam = 0;
  for (int i = 0; i < p->ncode; i++) {
    int op = p->code[i].op;
    if (op <= TDS_OP_PUSHP) depth++;
    else if (op == TDS_OP_JZ || op == TDS_OP_JMP || op >= TDS_OP_BINARY0) depth--;
    if (depth > maxd) maxd = depth;
    if (op == TDS_OP_PUSHK) nk++;
    if (op == TDS_OP_PUSHV) varmask |= 1 << p->code[i].arg;
    if (op == TDS_OP_PUSHP && p->code[i].arg > maxparam) maxparam = p->code[i].arg;
    if (op == TDS_OP_PUSHP && p->code[i].arg < minparam) minparam = p->code[i].arg;
  }
  if (maxd > TDS_EXPR_MAXSTACK)
    return fail(p, a, "expression too complex (needs %d evaluation stack "
                "slots, at most %d)", maxd, TDS_EXPR_MAXSTACK);
  size_t off_k = align_up(sizeof(tds_expr));
  size_t off_code = align_up(off_k + (size_t)nk * sizeof(double));
  size_t off_text = off_code + (size_t)p->ncode * sizeof(tds_instr);
  char *mem = tds_malloc(p->al, off_text + (b - a) + 1);
  if (!mem) return nomem(p);
  tds_expr *e = (tds_expr *)mem;
  double *k = (double *)(mem + off_k);
  tds_instr *code = (tds_instr *)(mem + off_code);
  char *text = mem + off_text;
  memset(e, 0, sizeof *e);
  nk = 0;
  for (int i = 0; i < p->ncode; i++) {
    code[i] = p->code[i];
    if (code[i].op == TDS_OP_PUSHK) {
      k[nk] = p->k[code[i].arg];
      code[i].arg = nk++;
    }
  }
  memcpy(text, p->s + a, b - a);
  text[b - a] = 0;
  e->code = code;
  e->k = k;
  e->text = text;
  e->ncode = p->ncode;
  e->nk = nk;
  e->maxstack = maxd;
  e->varmask = varmask;
  e->maxparam = maxparam;
  e->minparam = minparam;
  if (p->al) e->alloc = *p->al;
  for (int v = 0; v < TDS_NDIFF; v++) {
    e->loc[v] = -1;
    if (varmask & (1 << v)) {
      e->loc[v] = e->nact;
      e->act[e->nact++] = v;
    }
  }
  *out = e;
  return TDS_OK;
}

/* Parse and compile one expression (contract in expr.h). */
int tds_expr_parse(tds_ctx *ctx, const char *text, size_t *consumed,
                   const tds_expr_env *env, tds_expr **out) {
  parser p;
  opnd o;
  TDS_ASSERT(out != NULL);
  memset(&p, 0, sizeof p);
  *out = NULL;
  p.ctx = ctx;
  p.al = ctx ? &ctx->alloc : NULL;
  p.s = text ? text : "";
  p.n = strlen(p.s);
  p.env = env;
  p.flags = env ? env->flags : 0;
  lex(&p);
  size_t first = p.cur.pos;
  p.last_end = 0;
  if (parse_expr(&p, &o) == TDS_OK &&
      ((!consumed && p.cur.t != T_END) || (p.cur.t == T_BAD && p.cur.bad)))
    unexpected(&p);
  if (p.rc == TDS_OK) finish(&p, first, p.last_end, out);
  if (p.rc == TDS_OK && consumed) *consumed = p.cur.pos;
  tds_free(p.al, p.code);
  tds_free(p.al, p.k);
  return p.rc;
}

/* Free a compiled expression (one block). */
void tds_expr_free(tds_expr *e) {
  if (e) {
    tds_alloc a = e->alloc;
    tds_free(&a, e);
  }
}

/* Source text (trimmed), owned by e. */
const char *tds_expr_text(const tds_expr *e) { return e->text; }

/* 1 if no variable and no parameter occurs. */
int tds_expr_is_const(const tds_expr *e) {
  return e->varmask == 0 && e->maxparam < 0 && e->minparam == 0;
}

/* 1 if variable var (TDS_X..TDS_G) occurs. */
int tds_expr_uses_var(const tds_expr *e, int var) {
  return var >= 0 && var < TDS_NVARS && (e->varmask >> var & 1);
}

/* 1 if any parameter occurs. */
int tds_expr_uses_params(const tds_expr *e) { return e->maxparam >= 0; }

/* 1 if an element attribute occurs. */
int tds_expr_uses_attrs(const tds_expr *e) { return e->minparam < 0; }

/* Highest parameter slot used, or -1. */
int tds_expr_max_param(const tds_expr *e) { return e->maxparam; }

/* Number of instructions. */
int tds_expr_ncode(const tds_expr *e) { return e->ncode; }
