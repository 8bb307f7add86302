/*
** datafile_read.c: the datafile reader's cursor over logical lines, its
** messages, and the readers of words, integers, values and expressions
** (contracts in datafile_int.h).
**
** In the top section tokens may cross line ends ("energy:" on one line,
** "e1: ..." on the next); element lines are one logical line each.
** Expressions are parsed straight from the line with tds_expr_parse
** (longest expression, TDS_EXPR_DATAFILE for the signed-number rule), so
** they never run past the end of their line.
*/
#include "datafile_int.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "model.h"

/* ---- messages ---- */

int df_line_of(const df *d, const char *at) {
  if (!at || !d->lx.buf || at < d->lx.buf || at > d->lx.buf + d->lx.len)
    return d->eof ? d->lx.line : d->lx.line0;
  return df_lex_line_at(&d->lx, (size_t)(at - d->lx.buf));
}

static int vderr(df *d, int line, int rc, const char *fmt, va_list ap) {
  char msg[800];
  vsnprintf(msg, sizeof msg, fmt, ap);
  tds_seterr(d->ctx, rc, "%s:%d: %s", d->name, line, msg);
  return rc;
}

int df_err(df *d, const char *at, int rc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vderr(d, df_line_of(d, at), rc, fmt, ap);
  va_end(ap);
  return rc;
}

int df_err_line(df *d, int line, int rc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vderr(d, line, rc, fmt, ap);
  va_end(ap);
  return rc;
}

int df_core(df *d, int line, int rc, const char *what) {
  char msg[sizeof d->ctx->errmsg];
  memcpy(msg, d->ctx->errmsg, sizeof msg);
  msg[sizeof msg - 1] = 0;
  if (what && *what)
    tds_seterr(d->ctx, rc ? rc : TDS_ESYNTAX, "%s:%d: %s: %.700s", d->name, line,
               what, msg);
  else
    tds_seterr(d->ctx, rc ? rc : TDS_ESYNTAX, "%s:%d: %.700s", d->name, line, msg);
  return rc ? rc : TDS_ESYNTAX;
}

const char *df_describe(const char *p, char *buf, size_t cap) {
  if (!*p) {
    snprintf(buf, cap, "end of line");
    return buf;
  }
  size_t n = 0;
  if (is_alnum((unsigned char)*p) || *p == '.') {
    while (n < 30 && (is_alnum((unsigned char)p[n]) || p[n] == '.')) n++;
  } else {
    n = 1;
  }
  char q[40];
  size_t j = 0;
  for (size_t i = 0; i < n; i++) {
    unsigned char c = (unsigned char)p[i];
    if (c < ' ' || c >= 127) {
      if (n == 1) {
        snprintf(buf, cap, "character '\\x%02x'", c);
        return buf;
      }
      c = '?';
    }
    q[j++] = (char)c;
  }
  q[j] = 0;
  snprintf(buf, cap, "'%s%s'", q, n == 30 ? "..." : "");
  return buf;
}

const char *df_upper(const char *w, char *buf, size_t cap) {
  size_t i = 0;
  for (; w[i] && i + 1 < cap; i++)
    buf[i] = (w[i] >= 'a' && w[i] <= 'z') ? (char)(w[i] - 32) : w[i];
  buf[i] = 0;
  return buf;
}

/* ---- cursor ---- */

void df_ws(df *d) {
  while (is_ws((unsigned char)*d->p)) d->p++;
}

int df_at_eol(df *d) {
  df_ws(d);
  return *d->p == 0;
}

int df_next_line(df *d) {
  if (d->eof) return 0;
  int r = df_lex_next(&d->lx);
  d->p = d->lx.buf ? d->lx.buf : "";
  if (r == 0) d->eof = 1;
  return r;
}

int df_more(df *d, int *have) {
  for (;;) {
    df_ws(d);
    if (*d->p) {
      *have = 1;
      return TDS_OK;
    }
    int r = df_next_line(d);
    if (r < 0) return -r;
    if (r == 0) {
      *have = 0;
      return TDS_OK;
    }
  }
}

size_t df_word_len(const char *p) {
  size_t n = 0;
  if (!is_alpha((unsigned char)p[0])) return 0;
  while (is_alnum((unsigned char)p[n])) n++;
  return n;
}

int df_word_eq(const char *p, size_t n, const char *w) {
  return strlen(w) == n && strncasecmp(p, w, n) == 0;
}

int df_peek(df *d, const char *w) {
  df_ws(d);
  size_t n = df_word_len(d->p);
  return n && df_word_eq(d->p, n, w);
}

int df_accept(df *d, const char *w) {
  if (!df_peek(d, w)) return 0;
  d->p += strlen(w);
  return 1;
}

size_t df_take_word(df *d, char *buf, size_t cap) {
  df_ws(d);
  size_t n = df_word_len(d->p);
  size_t k = n < cap - 1 ? n : cap - 1;
  for (size_t i = 0; i < k; i++) {
    char c = d->p[i];
    buf[i] = (c >= 'A' && c <= 'Z') ? (char)(c + 32) : c;
  }
  buf[k] = 0;
  d->p += n;
  return n;
}

int df_looks_int(df *d) {
  df_ws(d);
  const char *p = d->p;
  if (*p == '+' || *p == '-') p++;
  return is_digit((unsigned char)*p);
}

/* Names that can start an expression besides parameters. */
static const char *const expr_words[] = {
    "abs", "sqr", "sqrt", "sin", "cos", "tan", "asin", "acos", "atan", "log",
    "exp", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh", "ceil", "floor",
    "atan2", "pow", "minimum", "maximum", "pi", "e", "g", "not", NULL};

int df_expr_word(const char *p, size_t n) {
  for (int i = 0; expr_words[i]; i++)
    if (df_word_eq(p, n, expr_words[i])) return 1;
  return 0;
}

int df_looks_value(df *d) {
  df_ws(d);
  int c = (unsigned char)*d->p;
  if (is_digit(c) || c == '.' || c == '+' || c == '-' || c == '(' || c == '!')
    return 1;
  size_t n = df_word_len(d->p);
  if (!n) return 0;
  if (df_expr_word(d->p, n)) return 1;
  return tds_surf_param_find(d->s, d->p, n) >= 0;
}

/* ---- integers, values, expressions ---- */

int df_read_int(df *d, int sign, const char *what, int64_t *v) {
  char b[64];
  df_ws(d);
  const char *a = d->p, *p = d->p;
  int neg = 0;
  if ((*p == '+' || *p == '-') && sign) {
    neg = *p == '-';
    p++;
  }
  if (!is_digit((unsigned char)*p))
    return df_err(d, a, TDS_ESYNTAX, "%s: expected %s, found %s", what,
                  sign ? "a signed integer" : "an integer", df_describe(a, b, sizeof b));
  int64_t x = 0;
  while (is_digit((unsigned char)*p)) {
    if (x <= 1000000000000000LL) x = x * 10 + (*p - '0');
    p++;
  }
  if (x > 1000000000000000LL) x = 1000000000000001LL;
  if (is_alpha((unsigned char)*p) || *p == '.')
    return df_err(d, a, TDS_ESYNTAX, "%s: expected %s, found %s", what,
                  sign ? "a signed integer" : "an integer", df_describe(a, b, sizeof b));
  d->p = p;
  *v = neg ? -x : x;
  return TDS_OK;
}

/* Parse the longest expression at the cursor (same line). In the top
** section an expression is one value and '-' is always an operator
** ("parameter c = 1 -2" is -1, as in Evolver); in lists (d->split) the
** signed-number rule of TDS_EXPR_DATAFILE separates values. */
static int parse_expr(df *d, int flags, tds_expr **out, const char *what) {
  char b[64];
  df_ws(d);
  const char *a = d->p;
  *out = NULL;
  if (!*a) return df_err(d, a, TDS_ESYNTAX, "%s: expected a value, found end of line", what);
  if (*a == '{' || *a == '}' || *a == '"' || *a == '=')
    return df_err(d, a, TDS_ESYNTAX, "%s: expected a value, found %s", what,
                  df_describe(a, b, sizeof b));
  size_t used = 0;
  int rc = tds_model_parse(d->ctx, d->s, a, &used, flags | (d->split ? TDS_EXPR_DATAFILE : 0),
                           out);
  if (rc != TDS_OK) return df_core(d, df_line_of(d, a), rc, what);
  d->p = a + used;
  return TDS_OK;
}

int df_read_value(df *d, double *v, const char *what) {
  tds_expr *e;
  const char *a = d->p;
  int rc = parse_expr(d, TDS_EXPR_NOCOORD, &e, what);
  if (rc) return rc;
  double vars[TDS_NVARS] = {0};
  vars[TDS_G] = d->s->gravity;
  *v = tds_expr_eval(e, d->s->parval, vars);
  if (!isfinite(*v)) {
    char t[100];
    snprintf(t, sizeof t, "%s", tds_expr_text(e));
    tds_expr_free(e);
    return df_err(d, a, TDS_ESYNTAX, "%s: value of '%s' is not finite", what, t);
  }
  tds_expr_free(e);
  return TDS_OK;
}

static const struct { const char *name; int value; } colors[] = {
    {"black", 0}, {"blue", 1}, {"green", 2}, {"cyan", 3}, {"red", 4},
    {"magenta", 5}, {"brown", 6}, {"lightgray", 7}, {"lightgrey", 7},
    {"darkgray", 8}, {"darkgrey", 8}, {"lightblue", 9}, {"lightgreen", 10},
    {"lightcyan", 11}, {"lightred", 12}, {"lightmagenta", 13}, {"yellow", 14},
    {"white", 15}, {"clear", -1}, {"transparent", -1}, {NULL, 0}};

int df_read_color(df *d, int16_t *c, const char *what) {
  df_ws(d);
  size_t n = df_word_len(d->p);
  for (int i = 0; n && colors[i].name; i++)
    if (df_word_eq(d->p, n, colors[i].name)) {
      d->p += n;
      *c = (int16_t)colors[i].value;
      return TDS_OK;
    }
  double v;
  int rc = df_read_value(d, &v, what);
  if (rc) return rc;
  if (v < -32768 || v > 32767)
    return df_err(d, NULL, TDS_ESYNTAX, "%s: color %g out of range", what, v);
  *c = (int16_t)lround(v);
  return TDS_OK;
}

/* ---- the top-section forms: the token may start on a following line ---- */

/* Move to the next token; at end of file fail with "what: expected
** `thing`, found end of file". */
static int more_or_fail(df *d, const char *thing, const char *what) {
  int have, rc = df_more(d, &have);
  if (rc) return rc;
  if (!have)
    return df_err(d, NULL, TDS_ESYNTAX, "%s: expected %s, found end of file", what, thing);
  return TDS_OK;
}

int df_header_value(df *d, double *v, const char *what) {
  int rc = more_or_fail(d, "a value", what);
  return rc ? rc : df_read_value(d, v, what);
}

int df_header_expr(df *d, int flags, tds_expr **e, const char *what) {
  *e = NULL;
  int rc = more_or_fail(d, "an expression", what);
  return rc ? rc : parse_expr(d, flags, e, what);
}

int df_header_int(df *d, int sign, const char *what, int64_t *v) {
  int rc = more_or_fail(d, "an integer", what);
  return rc ? rc : df_read_int(d, sign, what, v);
}

/* ---- vectors of expressions ---- */

int df_components(df *d, char letter, int flags, tds_expr *e[3], const char *what) {
  int got = 0;
  for (;;) {
    int have, rc = df_more(d, &have);
    if (rc) return rc;
    if (!have) break;
    size_t n = df_word_len(d->p);
    if (n != 2 || (d->p[0] | 32) != letter || d->p[1] < '1' || d->p[1] > '3') {
      if (n == 2 && (d->p[0] | 32) == letter && d->p[1] >= '4' && d->p[1] <= '9')
        return df_err(d, d->p, TDS_ESYNTAX,
                      "%s: component %.2s needs more than 3 dimensions "
                      "(SPACE_DIMENSION is not supported yet)", what, d->p);
      break;
    }
    int k = d->p[1] - '1';
    const char *a = d->p;
    d->p += 2;
    if (e[k])
      return df_err(d, a, TDS_ESYNTAX, "%s: %c%d given twice", what, letter - 32, k + 1);
    char w2[300];
    snprintf(w2, sizeof w2, "%s %c%d", what, letter - 32, k + 1);
    if ((rc = df_header_expr(d, flags, &e[k], w2))) return rc;
    got++;
  }
  if (!got)
    return df_err(d, d->p, TDS_ESYNTAX, "%s: expected %c1, %c2, %c3 components", what,
                  letter - 32, letter - 32, letter - 32);
  return TDS_OK;
}

void df_free3(tds_expr *e[3]) {
  for (int i = 0; i < 3; i++) {
    tds_expr_free(e[i]);
    e[i] = NULL;
  }
}
