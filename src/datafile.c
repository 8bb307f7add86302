/*
** datafile.c: the Surface Evolver datafile reader (contract in datafile.h).
**
** The preprocessor (datafile_lex.c) hands over logical lines; this file
** parses them with a cursor. In the top section tokens may cross line ends
** ("energy:" on one line, "e1: ..." on the next); element lines are one
** logical line each. Expressions are parsed straight from the line with
** tds_expr_parse (longest expression, TDS_EXPR_DATAFILE for the
** signed-number rule), so they never run past the end of their line.
** Faces are collected and built when their section ends, after reserving
** facet slots up to the highest face id, so split-off facets come after
** every declared id.
*/
#define TDS_DATAFILE_INTERNAL
#include "datafile.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "model.h"
#include "motion.h"
#include "topo.h"

enum { S_HEADER = 0, S_VERTICES, S_EDGES, S_FACES, S_BODIES };
static const char *const section_name[] = {"top", "VERTICES", "EDGES", "FACES",
                                           "BODIES"};

typedef struct face_rec {
  tds_id id;          /* 0-based */
  int line;
  int n;
  int32_t off;        /* first oriented edge in df.oe */
  tds_face_attr at;
} face_rec;

typedef struct df {
  tds_ctx *ctx;
  tds_surf *s;
  df_lex lx;
  const char *name;
  const char *p;       /* cursor in lx.buf */
  int eof;             /* no more logical lines */
  int section;
  int seen_vertices;
  int64_t maxid;       /* largest element id accepted for this file */
  face_rec *faces;
  int32_t nfaces, capfaces;
  int32_t *oe;
  int32_t noe, capoe;
  tds_id maxface;      /* highest face slot + 1 */
  int density_given;
  int has_read;
  size_t read_at;
  int split;           /* several values in a row: element lines, matrices */
} df;

/* ---- characters and messages ---- */

static int is_alpha(int c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static int is_digit(int c) { return c >= '0' && c <= '9'; }
static int is_alnum(int c) { return is_alpha(c) || is_digit(c); }
static int is_ws(int c) {
  return c == ' ' || c == '\t' || c == ',' || c == ':' || c == ';' ||
         c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

static int line_of(const df *d, const char *at) {
  if (!at || !d->lx.buf || at < d->lx.buf || at > d->lx.buf + d->lx.len)
    return d->eof ? d->lx.line : d->lx.line0;
  return df_lex_line_at(&d->lx, (size_t)(at - d->lx.buf));
}

static int derr(df *d, const char *at, int rc, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int derr_line(df *d, int line, int rc, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static int vderr(df *d, int line, int rc, const char *fmt, va_list ap) {
  char msg[800];
  vsnprintf(msg, sizeof msg, fmt, ap);
  tds_seterr(d->ctx, rc, "%s:%d: %s", d->name, line, msg);
  return rc;
}

/* Fail with "name:line: message" (line of position at in the current
** logical line; NULL: where the line starts). */
static int derr(df *d, const char *at, int rc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vderr(d, line_of(d, at), rc, fmt, ap);
  va_end(ap);
  return rc;
}

/* The same at a given physical line. */
static int derr_line(df *d, int line, int rc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vderr(d, line, rc, fmt, ap);
  va_end(ap);
  return rc;
}

/* Prefix the core's message in ctx->errmsg with "name:line: what: ". */
static int dcore(df *d, int line, int rc, const char *what) {
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

/* A short printable description of the token at p, for messages. */
static const char *describe(const char *p, char *buf, size_t cap) {
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

static const char *upper(const char *w, char *buf, size_t cap) {
  size_t i = 0;
  for (; w[i] && i + 1 < cap; i++)
    buf[i] = (w[i] >= 'a' && w[i] <= 'z') ? (char)(w[i] - 32) : w[i];
  buf[i] = 0;
  return buf;
}

/* ---- cursor ---- */

static void ws(df *d) {
  while (is_ws((unsigned char)*d->p)) d->p++;
}

static int at_eol(df *d) {
  ws(d);
  return *d->p == 0;
}

/* Fetch the next logical line. 1 = got one, 0 = end of file, else -rc. */
static int next_line(df *d) {
  if (d->eof) return 0;
  int r = df_lex_next(&d->lx);
  d->p = d->lx.buf ? d->lx.buf : "";
  if (r == 0) d->eof = 1;
  return r;
}

/* Move to the next token, across line ends. *have = 0 at end of file. */
static int more(df *d, int *have) {
  for (;;) {
    ws(d);
    if (*d->p) {
      *have = 1;
      return TDS_OK;
    }
    int r = next_line(d);
    if (r < 0) return -r;
    if (r == 0) {
      *have = 0;
      return TDS_OK;
    }
  }
}

static size_t word_len(const char *p) {
  size_t n = 0;
  if (!is_alpha((unsigned char)p[0])) return 0;
  while (is_alnum((unsigned char)p[n])) n++;
  return n;
}

static int word_eq(const char *p, size_t n, const char *w) {
  return strlen(w) == n && strncasecmp(p, w, n) == 0;
}

/* Whether the word at the cursor (same line) is w, case-insensitively. */
static int peek(df *d, const char *w) {
  ws(d);
  size_t n = word_len(d->p);
  return n && word_eq(d->p, n, w);
}

static int accept(df *d, const char *w) {
  if (!peek(d, w)) return 0;
  d->p += strlen(w);
  return 1;
}

/* Read the word at the cursor lowercased into buf (truncated); returns
** its length (0 if there is no word) and advances. */
static size_t take_word(df *d, char *buf, size_t cap) {
  ws(d);
  size_t n = word_len(d->p);
  size_t k = n < cap - 1 ? n : cap - 1;
  for (size_t i = 0; i < k; i++) {
    char c = d->p[i];
    buf[i] = (c >= 'A' && c <= 'Z') ? (char)(c + 32) : c;
  }
  buf[k] = 0;
  d->p += n;
  return n;
}

/* An integer (optionally signed) starts at the cursor. */
static int looks_int(df *d) {
  ws(d);
  const char *p = d->p;
  if (*p == '+' || *p == '-') p++;
  return is_digit((unsigned char)*p);
}

/* Read an integer; sign allowed if `sign`. Values beyond 1e15 read as
** 1e15 + 1 (callers range-check). */
static int read_int(df *d, int sign, const char *what, int64_t *v) {
  char b[64];
  ws(d);
  const char *a = d->p, *p = d->p;
  int neg = 0;
  if ((*p == '+' || *p == '-') && sign) {
    neg = *p == '-';
    p++;
  }
  if (!is_digit((unsigned char)*p))
    return derr(d, a, TDS_ESYNTAX, "%s: expected %s, found %s", what,
                sign ? "a signed integer" : "an integer", describe(a, b, sizeof b));
  int64_t x = 0;
  while (is_digit((unsigned char)*p)) {
    if (x <= 1000000000000000LL) x = x * 10 + (*p - '0');
    p++;
  }
  if (x > 1000000000000000LL) x = 1000000000000001LL;
  if (is_alpha((unsigned char)*p) || *p == '.')
    return derr(d, a, TDS_ESYNTAX, "%s: expected %s, found %s", what,
                sign ? "a signed integer" : "an integer", describe(a, b, sizeof b));
  d->p = p;
  *v = neg ? -x : x;
  return TDS_OK;
}

/* ---- expressions ---- */

/* Scratch copy of the rest of the line for a list context (see below). */
/* Parse the longest expression at the cursor (same line). In the top
** section an expression is one value and '-' is always an operator
** ("parameter c = 1 -2" is -1, as in Evolver); in lists (d->split) the
** signed-number rule of TDS_EXPR_DATAFILE separates values. */
static int parse_expr(df *d, int flags, tds_expr **out, const char *what) {
  char b[64];
  ws(d);
  const char *a = d->p;
  *out = NULL;
  if (!*a) return derr(d, a, TDS_ESYNTAX, "%s: expected a value, found end of line", what);
  if (*a == '{' || *a == '}' || *a == '"' || *a == '=')
    return derr(d, a, TDS_ESYNTAX, "%s: expected a value, found %s", what,
                describe(a, b, sizeof b));
  tds_expr_env env;
  tds_model_env(d->s, flags | (d->split ? TDS_EXPR_DATAFILE : 0), &env);
  size_t used = 0;
  int rc = tds_expr_parse(d->ctx, a, &used, &env, out);
  if (rc != TDS_OK) return dcore(d, line_of(d, a), rc, what);
  d->p = a + used;
  return TDS_OK;
}

/* A constant expression, evaluated now. */
static int read_value(df *d, double *v, const char *what) {
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
    return derr(d, a, TDS_ESYNTAX, "%s: value of '%s' is not finite", what, t);
  }
  tds_expr_free(e);
  return TDS_OK;
}

/* A value in the top section: it may start on the next line. */
static int header_value(df *d, double *v, const char *what) {
  int have, rc = more(d, &have);
  if (rc) return rc;
  if (!have) return derr(d, NULL, TDS_ESYNTAX, "%s: expected a value, found end of file", what);
  return read_value(d, v, what);
}

static int header_expr(df *d, int flags, tds_expr **e, const char *what) {
  int have, rc = more(d, &have);
  *e = NULL;
  if (rc) return rc;
  if (!have)
    return derr(d, NULL, TDS_ESYNTAX, "%s: expected an expression, found end of file", what);
  return parse_expr(d, flags, e, what);
}

static int header_int(df *d, int sign, const char *what, int64_t *v) {
  int have, rc = more(d, &have);
  if (rc) return rc;
  if (!have) return derr(d, NULL, TDS_ESYNTAX, "%s: expected an integer, found end of file", what);
  return read_int(d, sign, what, v);
}

/* Names that can start an expression besides parameters. */
static const char *const expr_words[] = {
    "abs", "sqr", "sqrt", "sin", "cos", "tan", "asin", "acos", "atan", "log",
    "exp", "sinh", "cosh", "tanh", "asinh", "acosh", "atanh", "ceil", "floor",
    "atan2", "pow", "minimum", "maximum", "pi", "e", "g", "not", NULL};

/* Whether the cursor (same line) starts a value rather than an attribute. */
static int looks_value(df *d) {
  ws(d);
  int c = (unsigned char)*d->p;
  if (is_digit(c) || c == '.' || c == '+' || c == '-' || c == '(' || c == '!')
    return 1;
  size_t n = word_len(d->p);
  if (!n) return 0;
  for (int i = 0; expr_words[i]; i++)
    if (word_eq(d->p, n, expr_words[i])) return 1;
  return tds_surf_param_find(d->s, d->p, n) >= 0;
}

static const struct { const char *name; int value; } colors[] = {
    {"black", 0}, {"blue", 1}, {"green", 2}, {"cyan", 3}, {"red", 4},
    {"magenta", 5}, {"brown", 6}, {"lightgray", 7}, {"lightgrey", 7},
    {"darkgray", 8}, {"darkgrey", 8}, {"lightblue", 9}, {"lightgreen", 10},
    {"lightcyan", 11}, {"lightred", 12}, {"lightmagenta", 13}, {"yellow", 14},
    {"white", 15}, {"clear", -1}, {"transparent", -1}, {NULL, 0}};

static int read_color(df *d, int16_t *c, const char *what) {
  ws(d);
  size_t n = word_len(d->p);
  for (int i = 0; n && colors[i].name; i++)
    if (word_eq(d->p, n, colors[i].name)) {
      d->p += n;
      *c = (int16_t)colors[i].value;
      return TDS_OK;
    }
  double v;
  int rc = read_value(d, &v, what);
  if (rc) return rc;
  if (v < -32768 || v > 32767) return derr(d, NULL, TDS_ESYNTAX, "%s: color %g out of range", what, v);
  *c = (int16_t)lround(v);
  return TDS_OK;
}

/* ---- keyword tables ---- */

/* Evolver keywords whose features the core does not have yet. */
static const char *const unsupported[] = {
    "torus", "torus_filled", "periods", "display_periods", "display_origin",
    "string", "quadratic", "lagrange", "lagrange_order", "simplex_representation",
    "symmetry_group", "metric", "conformal_metric", "klein_metric", "define",
    "method_instance", "optimizing_parameter", "optimising_parameter", "wulff",
    "phasefile", "diffusion", "pressure", "squared_curvature",
    "square_curvature", "mean_curvature_integral", "gauss_curvature",
    "squared_gaussian_curvature", "square_gaussian_curvature", "sqgauss",
    "insulating_knot_energy", "conducting_knot_energy", "mobility",
    "mobility_tensor", "integral_order", "integral_order_1d",
    "integral_order_2d", "runge_kutta", "homothety", "autopop", "autochop",
    "area_normalization", "approximate_curvature", "effective_area", "jiggle",
    "temperature", "length_method_name", "area_method_name",
    "volume_method_name", "hessian_special_normal_vector", "fixed_area",
    "area_fixed", "load_library", "interp_bdry_param",
    "view_transform_generators", "function", "procedure", "total_time",
    "gradient_mode", "parameter_file", "ideal_gas", "knot_energy",
    "conserved", "on_assign_call", "nonwall", "content_rank", "axial_point",
    "wrap", "phase", "actual_volume", "form_integrand", "k_form_order",
    "parameter_1", "element_modulus", "clip_coeff", NULL};

static int is_in(const char *w, const char *const *list) {
  for (int i = 0; list[i]; i++)
    if (!strcmp(w, list[i])) return 1;
  return 0;
}

static int not_supported(df *d, const char *at, const char *w) {
  char u[64];
  return derr(d, at, TDS_ESYNTAX, "%s is not supported yet", upper(w, u, sizeof u));
}

/* ---- top section ---- */

static int h_parameter(df *d, const char *kw) {
  (void)kw;
  int have, rc = more(d, &have);
  if (rc) return rc;
  const char *a = d->p;
  char name[256], b[64];
  size_t n = word_len(d->p);
  if (!n)
    return derr(d, a, TDS_ESYNTAX, "PARAMETER: expected a name, found %s",
                describe(a, b, sizeof b));
  if (n >= sizeof name) return derr(d, a, TDS_ESYNTAX, "PARAMETER: name too long");
  memcpy(name, a, n);
  name[n] = 0;
  d->p += n;
  for (int i = 0; expr_words[i]; i++)
    if (!strcasecmp(name, expr_words[i]))
      return derr(d, a, TDS_ESYNTAX, "PARAMETER: '%s' is a reserved name", name);
  static const char *const coord[] = {"x", "y", "z", "w", "x1", "x2", "x3",
                                      "x4", "p1", "p2", NULL};
  for (int i = 0; coord[i]; i++)
    if (!strcasecmp(name, coord[i]))
      return derr(d, a, TDS_ESYNTAX, "PARAMETER: '%s' is a reserved name", name);
  ws(d);
  if (*d->p == '=') d->p++;
  char what[300];
  snprintf(what, sizeof what, "PARAMETER %s", name);
  double v;
  if ((rc = header_value(d, &v, what))) return rc;
  if (peek(d, "on_assign_call")) return not_supported(d, d->p, "on_assign_call");
  if (peek(d, "pdelta") || peek(d, "pscale"))
    return not_supported(d, d->p, "optimizing_parameter");
  if (tds_surf_param_set(d->s, name, v) < 0)
    return derr(d, NULL, TDS_ENOMEM, "out of memory");
  return TDS_OK;
}

/* Components "<letter>1 expr <letter>2 expr <letter>3 expr" (any order,
** each at most once; at least one). */
static int components(df *d, char letter, int flags, tds_expr *e[3],
                      const char *what) {
  int got = 0;
  for (;;) {
    int have, rc = more(d, &have);
    if (rc) return rc;
    if (!have) break;
    size_t n = word_len(d->p);
    if (n != 2 || (d->p[0] | 32) != letter || d->p[1] < '1' || d->p[1] > '3') {
      if (n == 2 && (d->p[0] | 32) == letter && d->p[1] >= '4' && d->p[1] <= '9')
        return derr(d, d->p, TDS_ESYNTAX,
                    "%s: component %.2s needs more than 3 dimensions "
                    "(SPACE_DIMENSION is not supported yet)", what, d->p);
      break;
    }
    int k = d->p[1] - '1';
    const char *a = d->p;
    d->p += 2;
    if (e[k])
      return derr(d, a, TDS_ESYNTAX, "%s: %c%d given twice", what, letter - 32, k + 1);
    char w2[300];
    snprintf(w2, sizeof w2, "%s %c%d", what, letter - 32, k + 1);
    if ((rc = header_expr(d, flags, &e[k], w2))) return rc;
    got++;
  }
  if (!got)
    return derr(d, d->p, TDS_ESYNTAX, "%s: expected %c1, %c2, %c3 components", what,
                letter - 32, letter - 32, letter - 32);
  return TDS_OK;
}

static void free3(tds_expr *e[3]) {
  for (int i = 0; i < 3; i++) {
    tds_expr_free(e[i]);
    e[i] = NULL;
  }
}

/* Optional ENERGY and CONTENT integrands of a constraint or boundary. */
static int integrals(df *d, tds_expr *en[3], tds_expr *ct[3], int flags,
                     const char *what) {
  for (;;) {
    int have, rc = more(d, &have);
    if (rc || !have) return rc;
    const char *a = d->p;
    char w2[300];
    if (accept(d, "energy")) {
      if (en[0] || en[1] || en[2])
        return derr(d, a, TDS_ESYNTAX, "%s: ENERGY given twice", what);
      snprintf(w2, sizeof w2, "%s ENERGY", what);
      if ((rc = components(d, 'e', flags, en, w2))) return rc;
    } else if (accept(d, "content")) {
      if (ct[0] || ct[1] || ct[2])
        return derr(d, a, TDS_ESYNTAX, "%s: CONTENT given twice", what);
      snprintf(w2, sizeof w2, "%s CONTENT", what);
      if ((rc = components(d, 'c', flags, ct, w2))) return rc;
    } else {
      return TDS_OK;
    }
  }
}

static int h_constraint(df *d, const char *kw) {
  (void)kw;
  int64_t n;
  int rc = header_int(d, 0, "CONSTRAINT", &n);
  if (rc) return rc;
  if (n < 1 || n > 1000000000)
    return derr(d, NULL, TDS_ESYNTAX, "CONSTRAINT: number %lld out of range", (long long)n);
  char what[64], w[64];
  snprintf(what, sizeof what, "constraint %lld", (long long)n);
  if (tds_surf_con_slot(d->s, (int)n) >= 0)
    return derr(d, NULL, TDS_ESYNTAX, "%s is declared twice", what);
  int flags = 0;
  for (;;) {
    int have;
    if ((rc = more(d, &have))) return rc;
    if (!have) return derr(d, NULL, TDS_ESYNTAX, "%s: expected FORMULA, found end of file", what);
    const char *a = d->p;
    take_word(d, w, sizeof w);
    if (!strcmp(w, "global")) flags |= TDS_CON_GLOBAL;
    else if (!strcmp(w, "convex")) flags |= TDS_CON_CONVEX;
    else if (!strcmp(w, "nonnegative")) flags |= TDS_CON_NONNEG;
    else if (!strcmp(w, "nonpositive")) flags |= TDS_CON_NONPOS;
    else if (!strcmp(w, "formula") || !strcmp(w, "function") || !strcmp(w, "equation"))
      break;
    else if (is_in(w, unsupported)) {
      char u[64];
      return derr(d, a, TDS_ESYNTAX, "%s: %s is not supported yet", what, upper(w, u, sizeof u));
    } else {
      char b[64];
      d->p = a;
      return derr(d, a, TDS_ESYNTAX, "%s: expected FORMULA, found %s", what,
                  describe(a, b, sizeof b));
    }
  }
  if ((flags & TDS_CON_NONNEG) && (flags & TDS_CON_NONPOS))
    return derr(d, NULL, TDS_ESYNTAX, "%s: both NONNEGATIVE and NONPOSITIVE", what);
  tds_expr *f = NULL, *en[3] = {0}, *ct[3] = {0};
  char w2[80];
  snprintf(w2, sizeof w2, "%s FORMULA", what);
  if ((rc = header_expr(d, TDS_EXPR_FORMULA, &f, w2)) ||
      (rc = integrals(d, en, ct, 0, what))) {
    tds_expr_free(f);
    free3(en);
    free3(ct);
    return rc;
  }
  int line = line_of(d, NULL);
  rc = tds_model_constraint(d->ctx, d->s, (int)n, flags, f, en, ct);
  return rc ? dcore(d, line, rc, NULL) : TDS_OK;
}

static int h_boundary(df *d, const char *kw) {
  (void)kw;
  int64_t n, k;
  int rc = header_int(d, 0, "BOUNDARY", &n);
  if (rc) return rc;
  if (n < 1 || n > 1000000000)
    return derr(d, NULL, TDS_ESYNTAX, "BOUNDARY: number %lld out of range", (long long)n);
  char what[64];
  snprintf(what, sizeof what, "boundary %lld", (long long)n);
  if (tds_model_boundary_slot(d->s, (int)n) >= 0)
    return derr(d, NULL, TDS_ESYNTAX, "%s is declared twice", what);
  int have;
  if ((rc = more(d, &have))) return rc;
  if (!have || !accept(d, "parameters")) {
    char b[64];
    return derr(d, d->p, TDS_ESYNTAX, "%s: expected PARAMETERS, found %s", what,
                describe(d->p, b, sizeof b));
  }
  if ((rc = header_int(d, 0, what, &k))) return rc;
  if (k < 1 || k > 2)
    return derr(d, NULL, TDS_ESYNTAX, "%s: %lld parameters (1 or 2 are supported)",
                what, (long long)k);
  int flags = 0;
  if ((rc = more(d, &have))) return rc;
  if (have && accept(d, "convex")) flags |= TDS_CON_CONVEX;
  tds_expr *x[3] = {0}, *en[3] = {0}, *ct[3] = {0};
  rc = components(d, 'x', TDS_EXPR_PARAMS, x, what);
  if (!rc && (!x[0] || !x[1] || !x[2]))
    rc = derr(d, d->p, TDS_ESYNTAX, "%s: needs X1, X2 and X3", what);
  if (!rc) rc = integrals(d, en, ct, 0, what);
  if (rc) {
    free3(x);
    free3(en);
    free3(ct);
    return rc;
  }
  int line = line_of(d, NULL);
  rc = tds_model_boundary(d->ctx, d->s, (int)n, (int)k, flags, x, en, ct);
  return rc ? dcore(d, line, rc, NULL) : TDS_OK;
}

typedef struct meth {
  int method;
  int global;
  double modulus;
  tds_expr *in[3];
  int line;
} meth;

static int h_quantity(df *d, const char *kw) {
  (void)kw;
  int have, rc = more(d, &have);
  if (rc) return rc;
  const char *a = d->p;
  char name[128], w[64], b[64];
  size_t n = word_len(d->p);
  if (!n)
    return derr(d, a, TDS_ESYNTAX, "QUANTITY: expected a name, found %s",
                describe(a, b, sizeof b));
  if (n >= sizeof name) return derr(d, a, TDS_ESYNTAX, "QUANTITY: name too long");
  memcpy(name, a, n);
  name[n] = 0;
  d->p += n;
  int qline = line_of(d, a);
  char what[160];
  snprintf(what, sizeof what, "quantity %s", name);
  int sameline = !at_eol(d);
  if ((rc = more(d, &have))) return rc;
  static const char *const kinds[] = {"energy", "fixed", "info_only", "conserved", NULL};
  size_t wl = have ? word_len(d->p) : 0;
  int kind = -1;
  for (int i = 0; kinds[i] && wl; i++)
    if (word_eq(d->p, wl, kinds[i])) kind = i;
  if (kind < 0) {
    if (!sameline) return TDS_OK; /* "quantity name;" forward declaration */
    return derr(d, d->p, TDS_ESYNTAX,
                "%s: expected ENERGY, FIXED = value or INFO_ONLY, found %s", what,
                describe(d->p, b, sizeof b));
  }
  if (tds_model_quantity_find(d->s, name) >= 0)
    return derr_line(d, qline, TDS_ESYNTAX, "%s is declared twice", what);
  if (kind == 3) return not_supported(d, d->p, "conserved");
  d->p += wl;
  double target = 0, modulus = 1, lagrange = 0, volconst = 0;
  int qkind = kind == 0 ? TDS_Q_ENERGY : kind == 1 ? TDS_Q_FIXED : TDS_Q_INFO;
  if (kind == 1) {
    ws(d);
    if (*d->p == '=') d->p++;
    if ((rc = header_value(d, &target, what))) return rc;
  }
  meth ms[4];
  int nm = 0;
  memset(ms, 0, sizeof ms);
  for (;;) {
    if ((rc = more(d, &have))) goto fail;
    if (!have) break;
    const char *at = d->p;
    take_word(d, w, sizeof w);
    if (!strcmp(w, "lagrange_multiplier")) {
      rc = header_value(d, &lagrange, what);
    } else if (!strcmp(w, "tolerance")) {
      double tol;
      rc = header_value(d, &tol, what);
    } else if (!strcmp(w, "volconst")) {
      rc = header_value(d, &volconst, what);
    } else if (!strcmp(w, "modulus")) {
      rc = header_value(d, nm ? &ms[nm - 1].modulus : &modulus, what);
    } else if (!strcmp(w, "method") || !strcmp(w, "global_method")) {
      if (nm == 4) {
        rc = derr(d, at, TDS_ESYNTAX, "%s: at most 4 methods are supported", what);
        goto fail;
      }
      int gm = w[0] == 'g';
      if ((rc = more(d, &have))) goto fail;
      const char *ma = d->p;
      char mname[64];
      if (!have || !take_word(d, mname, sizeof mname)) {
        rc = derr(d, ma, TDS_ESYNTAX, "%s: expected a method name, found %s", what,
                  describe(ma, b, sizeof b));
        goto fail;
      }
      int mi = tds_method_by_name(mname);
      if (mi < 0) {
        char u[64];
        rc = derr(d, ma, TDS_ESYNTAX, "method %s is not supported yet", upper(mname, u, sizeof u));
        goto fail;
      }
      meth *m = &ms[nm++];
      m->method = mi;
      m->global = gm;
      m->modulus = 1;
      m->line = line_of(d, ma);
      if (!gm && accept(d, "global")) m->global = 1;
    } else if (!strcmp(w, "global")) {
      if (!nm) {
        rc = derr(d, at, TDS_ESYNTAX, "%s: GLOBAL before any METHOD", what);
        goto fail;
      }
      ms[nm - 1].global = 1;
    } else if (!strcmp(w, "scalar_integrand") || !strcmp(w, "vector_integrand")) {
      if (!nm) {
        rc = derr(d, at, TDS_ESYNTAX, "%s: %s before any METHOD", what, w);
        goto fail;
      }
      meth *m = &ms[nm - 1];
      if (m->in[0] || m->in[1] || m->in[2]) {
        rc = derr(d, at, TDS_ESYNTAX, "%s: method has two integrands", what);
        goto fail;
      }
      if (w[0] == 's')
        rc = header_expr(d, 0, &m->in[0], what);
      else
        rc = components(d, 'q', 0, m->in, what);
    } else if (is_in(w, unsupported)) {
      rc = not_supported(d, at, w);
    } else {
      d->p = at;
      break;
    }
    if (rc) goto fail;
  }
  if (!nm) {
    rc = derr(d, d->p, TDS_ESYNTAX, "%s: no METHOD given", what);
    goto fail;
  }
  for (int i = 0; i < nm; i++)
    if (!ms[i].global) {
      char u[64];
      rc = derr_line(d, ms[i].line, TDS_ESYNTAX,
                "%s: method %s without GLOBAL (applied to listed elements) is "
                "not supported yet", what, upper(tds_method_names[ms[i].method], u, sizeof u));
      goto fail;
    }
  int idx;
  rc = tds_model_quantity(d->ctx, d->s, name, qkind, modulus, target, &idx);
  if (rc) {
    rc = dcore(d, qline, rc, NULL);
    goto fail;
  }
  d->s->quant[idx].pressure = lagrange;
  d->s->quant[idx].volconst = volconst;
  for (int i = 0; i < nm; i++) {
    rc = tds_model_method(d->ctx, d->s, idx, ms[i].method, ms[i].modulus, ms[i].in);
    memset(ms[i].in, 0, sizeof ms[i].in); /* taken, also on failure */
    if (rc) {
      rc = dcore(d, ms[i].line, rc, NULL);
      goto fail;
    }
  }
  return TDS_OK;
fail:
  for (int i = 0; i < 4; i++) free3(ms[i].in);
  return rc;
}

static int h_gravity(df *d, const char *kw) {
  (void)kw;
  return header_value(d, &d->s->gravity, "GRAVITY_CONSTANT");
}

static int h_gap(df *d, const char *kw) {
  char u[64];
  return header_value(d, &d->s->gap_constant, upper(kw, u, sizeof u));
}

static int h_symmetric(df *d, const char *kw) {
  (void)kw;
  d->s->symmetric_content = 1;
  return TDS_OK;
}

static int h_contol(df *d, const char *kw) {
  (void)kw;
  double v;
  int rc = header_value(d, &v, "CONSTRAINT_TOLERANCE");
  if (rc) return rc;
  if (v <= 0) return derr(d, NULL, TDS_ESYNTAX, "CONSTRAINT_TOLERANCE must be positive");
  d->s->constraint_tol = v;
  return TDS_OK;
}

static int h_dimension(df *d, const char *kw) {
  int64_t n;
  char u[64];
  upper(kw, u, sizeof u);
  int rc = header_int(d, 0, u, &n);
  if (rc) return rc;
  int want = kw[1] == 'p' ? 3 : 2; /* space_dimension 3, surface_dimension 2 */
  if (n != want)
    return derr(d, NULL, TDS_ESYNTAX, "%s %lld is not supported yet", u, (long long)n);
  return TDS_OK;
}

static int h_nothing(df *d, const char *kw) {
  (void)d;
  (void)kw;
  return TDS_OK;
}

static int h_scale(df *d, const char *kw) {
  (void)kw;
  double v;
  int rc = header_value(d, &v, "SCALE");
  if (rc) return rc;
  if (v < 0) return derr(d, NULL, TDS_ESYNTAX, "SCALE must not be negative");
  d->s->scale = v;
  if (accept(d, "fixed")) d->s->fixed_scale = 1;
  return TDS_OK;
}

static int h_scale_limit(df *d, const char *kw) {
  (void)kw;
  double v;
  int rc = header_value(d, &v, "SCALE_LIMIT");
  if (rc) return rc;
  if (v <= 0) return derr(d, NULL, TDS_ESYNTAX, "SCALE_LIMIT must be positive");
  d->s->scale_limit = v;
  return TDS_OK;
}

/* A keyword followed by one ignored number (dump hints, warnings). */
static int h_ignore1(df *d, const char *kw) {
  double v;
  char u[64];
  return header_value(d, &v, upper(kw, u, sizeof u));
}

/* VIEW_MATRIX: 16 numbers, display only. */
static int h_view_matrix(df *d, const char *kw) {
  (void)kw;
  int rc = TDS_OK;
  d->split = 1;
  for (int i = 0; i < 16 && !rc; i++) {
    double v;
    rc = header_value(d, &v, "VIEW_MATRIX");
  }
  d->split = 0;
  return rc;
}

/* slice_coeff = { a, b, c, d } (written by Evolver's dump), display only. */
static int h_slice(df *d, const char *kw) {
  (void)kw;
  int have, rc = more(d, &have);
  if (rc) return rc;
  if (have && *d->p == '=') d->p++;
  if ((rc = more(d, &have))) return rc;
  int brace = have && *d->p == '{';
  if (brace) d->p++;
  d->split = 1;
  for (int i = 0; i < 4 && !rc; i++) {
    double v;
    rc = header_value(d, &v, "SLICE_COEFF");
  }
  d->split = 0;
  if (rc) return rc;
  if (brace) {
    if ((rc = more(d, &have))) return rc;
    if (!have || *d->p != '}') {
      char b[64];
      return derr(d, d->p, TDS_ESYNTAX, "SLICE_COEFF: expected '}', found %s",
                  describe(d->p, b, sizeof b));
    }
    d->p++;
  }
  return TDS_OK;
}

/* VIEW_TRANSFORMS n, then n matrices each optionally preceded by COLOR c
** or SWAP_COLORS; display only. */
static int h_view_transforms(df *d, const char *kw) {
  (void)kw;
  int64_t n;
  int rc = header_int(d, 0, "VIEW_TRANSFORMS", &n);
  if (rc) return rc;
  if (n > 100000) return derr(d, NULL, TDS_ESYNTAX, "VIEW_TRANSFORMS: too many (%lld)", (long long)n);
  for (int64_t t = 0; t < n; t++) {
    int have;
    for (;;) {
      if ((rc = more(d, &have))) return rc;
      if (have && accept(d, "swap_colors")) continue;
      if (have && accept(d, "color")) {
        int16_t c;
        if ((rc = more(d, &have)) || (rc = read_color(d, &c, "VIEW_TRANSFORMS"))) return rc;
        continue;
      }
      break;
    }
    d->split = 1;
    for (int i = 0; i < 16 && !rc; i++) {
      double v;
      rc = header_value(d, &v, "VIEW_TRANSFORMS");
    }
    d->split = 0;
    if (rc) return rc;
  }
  return TDS_OK;
}

/* EVOLVER_VERSION "x" */
static int h_version(df *d, const char *kw) {
  (void)kw;
  int have, rc = more(d, &have);
  if (rc) return rc;
  if (!have || *d->p != '"') {
    char b[64];
    return derr(d, d->p, TDS_ESYNTAX, "EVOLVER_VERSION: expected a quoted version, found %s",
                describe(d->p, b, sizeof b));
  }
  const char *q = strchr(d->p + 1, '"');
  d->p = q ? q + 1 : d->p + strlen(d->p);
  return TDS_OK;
}

typedef int (*hdr_fn)(df *d, const char *kw);
static const struct {
  const char *name;
  hdr_fn fn;
} header_kw[] = {
    {"parameter", h_parameter},
    {"constraint", h_constraint},
    {"boundary", h_boundary},
    {"quantity", h_quantity},
    {"gravity_constant", h_gravity},
    {"spring_constant", h_gap},
    {"gap_constant", h_gap},
    {"symmetric_content", h_symmetric},
    {"constraint_tolerance", h_contol},
    {"space_dimension", h_dimension},
    {"surface_dimension", h_dimension},
    {"soapfilm", h_nothing},
    {"linear", h_nothing},
    {"keep_originals", h_nothing},
    {"keep_macros", h_nothing},
    {"everything_quantities", h_nothing},
    {"merit_factor", h_nothing},
    {"scale", h_scale},
    {"scale_limit", h_scale_limit},
    {"vertices_predicted", h_ignore1},
    {"edges_predicted", h_ignore1},
    {"facets_predicted", h_ignore1},
    {"facetedges_predicted", h_ignore1},
    {"bodies_predicted", h_ignore1},
    {"quantities_predicted", h_ignore1},
    {"method_instances_predicted", h_ignore1},
    {"suppress_warning", h_ignore1},
    {"unsuppress_warning", h_ignore1},
    {"zoom_vertex", h_ignore1},
    {"zoom_radius", h_ignore1},
    {"view_matrix", h_view_matrix},
    {"slice_coeff", h_slice},
    {"view_transforms", h_view_transforms},
    {"evolver_version", h_version},
    {NULL, NULL}};

static hdr_fn header_fn(const char *w) {
  for (int i = 0; header_kw[i].name; i++)
    if (!strcmp(w, header_kw[i].name)) return header_kw[i].fn;
  return NULL;
}

/* ---- element sections ---- */

/* Attribute words that may follow element data (for "unknown attribute"
** versus "not supported yet" messages, and to end value lists). */
static int unknown_attr(df *d, const char *at, const char *w, const char *what) {
  char u[64];
  if (is_in(w, unsupported))
    return derr(d, at, TDS_ESYNTAX, "%s: %s is not supported yet", what, upper(w, u, sizeof u));
  if (tds_model_quantity_find(d->s, w) >= 0)
    return derr(d, at, TDS_ESYNTAX,
                "%s: named quantities on single elements (%s) are not supported yet",
                what, w);
  if (!*w) {
    char b[64];
    return derr(d, at, TDS_ESYNTAX, "%s: unexpected %s", what, describe(at, b, sizeof b));
  }
  return derr(d, at, TDS_ESYNTAX, "%s: unknown attribute '%s'", what, w);
}

/* CONSTRAINT(S) c1 c2 ...: *rev set if a number is negative. */
static int con_list(df *d, const char *what, tds_cmask *mask, int *rev) {
  int n = 0;
  while (looks_int(d)) {
    int64_t c;
    const char *a = d->p;
    int rc = read_int(d, 1, what, &c);
    if (rc) return rc;
    if (c < 0) {
      if (rev) *rev = 1;
      c = -c;
    }
    int slot = c > 0 && c <= 1000000000 ? tds_surf_con_slot(d->s, (int)c) : -1;
    if (slot < 0)
      return derr(d, a, TDS_ERANGE, "%s: constraint %lld is not defined", what, (long long)c);
    *mask |= (tds_cmask)1 << slot;
    n++;
  }
  if (!n) {
    char b[64];
    return derr(d, d->p, TDS_ESYNTAX, "%s: expected constraint numbers, found %s", what,
                describe(d->p, b, sizeof b));
  }
  return TDS_OK;
}

static int bdry_ref(df *d, const char *what, int32_t *slot) {
  int64_t b;
  const char *a = d->p;
  int rc = read_int(d, 0, what, &b);
  if (rc) return rc;
  *slot = b > 0 && b <= 1000000000 ? tds_model_boundary_slot(d->s, (int)b) : -1;
  if (*slot < 0)
    return derr(d, a, TDS_ERANGE, "%s: boundary %lld is not defined", what, (long long)b);
  return TDS_OK;
}

/* The element id at the start of a line. */
static int element_id(df *d, const char *kind, tds_id *id) {
  int64_t v;
  const char *a = d->p;
  char what[32];
  snprintf(what, sizeof what, "%s id", kind);
  int rc = read_int(d, 0, what, &v);
  if (rc) return rc;
  if (v < 1 || v > d->maxid)
    return derr(d, a, TDS_ERANGE, "%s id %lld is out of range (1 to %lld)", kind,
                (long long)v, (long long)d->maxid);
  *id = (tds_id)(v - 1);
  return TDS_OK;
}

/* Make room for slot id of `kind`, growing geometrically. (Workaround:
** tds_mesh_claim reserves exactly id + 1 slots, so claiming ids one by one
** would reallocate every column each time.) */
static int room_for(df *d, int kind, tds_id id) {
  const tds_mesh *m = &d->s->m;
  int32_t cap = kind == TDS_VERTEX ? m->capv : kind == TDS_EDGE ? m->cape
              : kind == TDS_FACET ? m->capf : m->capb;
  if (id < cap) return TDS_OK;
  int64_t want = (int64_t)cap + cap / 2;
  if (want < id + 1) want = (int64_t)id + 1;
  if (want < 64) want = 64;
  if (want > d->maxid) want = d->maxid;
  if (tds_mesh_reserve(&d->s->m, kind, (int32_t)want) != TDS_OK)
    return derr(d, NULL, TDS_ENOMEM, "out of memory");
  return TDS_OK;
}

static int vertex_line(df *d) {
  tds_id id;
  int rc = element_id(d, "vertex", &id);
  if (rc) return rc;
  char what[48], w[64];
  snprintf(what, sizeof what, "vertex %d", id + 1);
  double val[3];
  int nval = 0;
  while (looks_value(d)) {
    if (nval == 3)
      return derr(d, d->p, TDS_ESYNTAX, "%s: more than 3 coordinates "
                  "(SPACE_DIMENSION is not supported yet)", what);
    if ((rc = read_value(d, &val[nval], what))) return rc;
    nval++;
  }
  uint32_t flags = 0;
  tds_cmask con = 0;
  int32_t bd = TDS_NONE;
  const char *bdat = NULL;
  while (!at_eol(d)) {
    const char *at = d->p;
    take_word(d, w, sizeof w);
    if (!strcmp(w, "fixed")) {
      flags |= TDS_FIXED;
    } else if (!strcmp(w, "bare")) {
      flags |= TDS_BARE;
    } else if (!strcmp(w, "constraint") || !strcmp(w, "constraints")) {
      rc = con_list(d, what, &con, NULL);
    } else if (!strcmp(w, "boundary")) {
      bdat = at;
      rc = bdry_ref(d, what, &bd);
    } else if (!strcmp(w, "color") || !strcmp(w, "colour")) {
      int16_t c;
      rc = read_color(d, &c, what); /* vertices have no colour: display only */
    } else if (!strcmp(w, "original")) {
      int64_t o;
      rc = read_int(d, 0, what, &o);
    } else {
      return unknown_attr(d, at, w, what);
    }
    if (rc) return rc;
  }
  double x[3] = {0, 0, 0}, p[2] = {0, 0};
  if (bd != TDS_NONE) {
    int np = d->s->bdry[bd].nparams;
    if (con)
      return derr(d, bdat, TDS_ESYNTAX, "%s: a vertex on a boundary cannot also be on a constraint", what);
    if (nval != np)
      return derr(d, NULL, TDS_ESYNTAX, "%s on boundary %d needs %d parameter%s, got %d",
                  what, d->s->bdry[bd].number, np, np > 1 ? "s" : "", nval);
    for (int k = 0; k < np; k++) p[k] = val[k];
  } else {
    if (nval != 3)
      return derr(d, NULL, TDS_ESYNTAX, "%s needs 3 coordinates, got %d", what, nval);
    for (int k = 0; k < 3; k++) x[k] = val[k];
  }
  int line = line_of(d, NULL);
  if ((rc = room_for(d, TDS_VERTEX, id))) return rc;
  rc = tds_decl_vertex(d->ctx, d->s, id, x, bd, p, flags, con);
  return rc ? dcore(d, line, rc, NULL) : TDS_OK;
}

static int edge_line(df *d) {
  tds_id id;
  int rc = element_id(d, "edge", &id);
  if (rc) return rc;
  char what[48], w[64], b[64];
  snprintf(what, sizeof what, "edge %d", id + 1);
  int64_t ends[2];
  for (int k = 0; k < 2; k++) {
    if ((rc = read_int(d, 0, what, &ends[k]))) return rc;
    if (ends[k] < 1 || ends[k] > d->s->m.nv || !tds_alive(d->s->m.vflags, (tds_id)(ends[k] - 1)))
      return derr(d, NULL, TDS_ERANGE, "%s refers to vertex %lld, which does not exist",
                  what, (long long)ends[k]);
  }
  ws(d);
  if (looks_int(d))
    return derr(d, d->p, TDS_ESYNTAX,
                "%s: a third vertex (QUADRATIC midpoint) is not supported yet", what);
  if (*d->p == '*' || *d->p == '+' || *d->p == '-')
    return derr(d, d->p, TDS_ESYNTAX, "%s: torus wrap signs (TORUS) are not supported yet", what);
  uint32_t flags = 0;
  tds_cmask con = 0;
  int rev = 0;
  int32_t bd = TDS_NONE;
  double ten = 0;
  int16_t color = 0;
  while (!at_eol(d)) {
    const char *at = d->p;
    if (!take_word(d, w, sizeof w))
      return derr(d, at, TDS_ESYNTAX, "%s: unexpected %s", what, describe(at, b, sizeof b));
    if (!strcmp(w, "fixed")) {
      flags |= TDS_FIXED;
    } else if (!strcmp(w, "no_refine") || !strcmp(w, "norefine")) {
      flags |= TDS_NO_REFINE;
    } else if (!strcmp(w, "bare")) {
      flags |= TDS_BARE;
    } else if (!strcmp(w, "noncontent")) {
      flags |= TDS_NONCONTENT;
    } else if (!strcmp(w, "constraint") || !strcmp(w, "constraints")) {
      rc = con_list(d, what, &con, &rev);
    } else if (!strcmp(w, "boundary")) {
      rc = bdry_ref(d, what, &bd);
    } else if (!strcmp(w, "tension") || !strcmp(w, "density")) {
      rc = read_value(d, &ten, what);
    } else if (!strcmp(w, "color") || !strcmp(w, "colour")) {
      rc = read_color(d, &color, what);
    } else if (!strcmp(w, "original")) {
      int64_t o;
      rc = read_int(d, 0, what, &o);
    } else {
      return unknown_attr(d, at, w, what);
    }
    if (rc) return rc;
  }
  if (rev) flags |= TDS_CONREV;
  int line = line_of(d, NULL);
  if ((rc = room_for(d, TDS_EDGE, id))) return rc;
  rc = tds_decl_edge(d->ctx, d->s, id, (tds_id)ends[0] - 1, (tds_id)ends[1] - 1, flags,
                     con, bd, ten, color);
  return rc ? dcore(d, line, rc, NULL) : TDS_OK;
}

static int face_line(df *d) {
  tds_id id;
  int rc = element_id(d, "face", &id);
  if (rc) return rc;
  char what[48], w[64], b[64];
  snprintf(what, sizeof what, "face %d", id + 1);
  int32_t off = d->noe;
  int n = 0;
  while (looks_int(d)) {
    int64_t e;
    const char *a = d->p;
    if ((rc = read_int(d, 1, what, &e))) return rc;
    int64_t ae = e < 0 ? -e : e;
    if (e == 0 || ae > d->s->m.ne || !tds_alive(d->s->m.eflags, (tds_id)(ae - 1)))
      return derr(d, a, TDS_ERANGE, "%s refers to edge %lld, which does not exist", what,
                  (long long)ae);
    if (tds_grow((void **)&d->oe, sizeof *d->oe, &d->capoe, d->noe + 1))
      return derr(d, a, TDS_ENOMEM, "out of memory");
    d->oe[d->noe++] = TDS_OREF((tds_id)(ae - 1), e < 0);
    n++;
  }
  tds_face_attr at = {0};
  at.tension = 1;
  while (!at_eol(d)) {
    const char *a = d->p;
    if (!take_word(d, w, sizeof w))
      return derr(d, a, TDS_ESYNTAX, "%s: unexpected %s", what, describe(a, b, sizeof b));
    if (!strcmp(w, "fixed")) {
      at.flags |= TDS_FIXED;
    } else if (!strcmp(w, "no_refine") || !strcmp(w, "norefine")) {
      at.flags |= TDS_NO_REFINE;
    } else if (!strcmp(w, "nodisplay") || !strcmp(w, "no_display")) {
      at.flags |= TDS_NODISPLAY;
    } else if (!strcmp(w, "noncontent")) {
      at.flags |= TDS_NONCONTENT;
    } else if (!strcmp(w, "constraint") || !strcmp(w, "constraints")) {
      rc = con_list(d, what, &at.con, NULL);
    } else if (!strcmp(w, "tension") || !strcmp(w, "density")) {
      rc = read_value(d, &at.tension, what);
    } else if (!strcmp(w, "color") || !strcmp(w, "colour") || !strcmp(w, "frontcolor")) {
      rc = read_color(d, &at.color, what);
    } else if (!strcmp(w, "backcolor")) {
      int16_t c; /* one colour per facet in tds: the back colour is dropped */
      rc = read_color(d, &c, what);
    } else if (!strcmp(w, "original")) {
      int64_t o;
      rc = read_int(d, 0, what, &o);
    } else if (!strcmp(w, "boundary")) {
      return derr(d, a, TDS_ESYNTAX, "%s: faces on a BOUNDARY are not supported yet", what);
    } else {
      return unknown_attr(d, a, w, what);
    }
    if (rc) return rc;
  }
  if (n < 3)
    return derr(d, NULL, TDS_ETOPO, "%s has %d edge%s; at least 3 are needed", what, n,
                n == 1 ? "" : "s");
  if (tds_grow((void **)&d->faces, sizeof *d->faces, &d->capfaces, d->nfaces + 1))
    return derr(d, NULL, TDS_ENOMEM, "out of memory");
  face_rec *r = &d->faces[d->nfaces++];
  r->id = id;
  r->line = line_of(d, NULL);
  r->n = n;
  r->off = off;
  r->at = at;
  if (id + 1 > d->maxface) d->maxface = id + 1;
  return TDS_OK;
}

/* Build the collected faces (end of the FACES section). */
static int build_faces(df *d) {
  if (d->nfaces == 0) return TDS_OK;
  tds_mesh *m = &d->s->m;
  /* Reserve for the split-off elements at once (tds_build_face reserves
  ** exactly what each face needs, which is quadratic over many faces). */
  int64_t nv = m->nv, ne = m->ne, nf = d->maxface;
  for (int32_t i = 0; i < d->nfaces; i++)
    if (d->faces[i].n > 3) {
      nv += 1;
      ne += d->faces[i].n;
      nf += d->faces[i].n - 1;
    }
  if (nv > INT32_MAX / 8 || ne > INT32_MAX / 8 || nf > INT32_MAX / 8 ||
      tds_mesh_reserve(m, TDS_VERTEX, (int32_t)nv) ||
      tds_mesh_reserve(m, TDS_EDGE, (int32_t)ne) ||
      tds_mesh_reserve(m, TDS_FACET, (int32_t)nf) ||
      tds_mesh_extend_dead(m, TDS_FACET, d->maxface))
    return derr(d, NULL, TDS_ENOMEM, "out of memory");
  for (int32_t i = 0; i < d->nfaces; i++) {
    face_rec *r = &d->faces[i];
    int rc = tds_build_face(d->ctx, d->s, r->id, r->n, d->oe + r->off, &r->at);
    if (rc) return dcore(d, r->line, rc, NULL);
  }
  d->nfaces = 0;
  return TDS_OK;
}

static int body_line(df *d) {
  tds_id id;
  int rc = element_id(d, "body", &id);
  if (rc) return rc;
  char what[48], w[64], b[64];
  snprintf(what, sizeof what, "body %d", id + 1);
  int32_t off = d->noe;
  int n = 0;
  while (looks_int(d)) {
    int64_t f;
    const char *a = d->p;
    if ((rc = read_int(d, 1, what, &f))) return rc;
    int64_t af = f < 0 ? -f : f;
    if (f == 0 || af > d->s->m.nf || !tds_alive(d->s->m.fflags, (tds_id)(af - 1)) ||
        d->s->m.forig[af - 1] != (tds_id)(af - 1))
      return derr(d, a, TDS_ERANGE, "%s refers to face %lld, which does not exist", what,
                  (long long)af);
    if (tds_grow((void **)&d->oe, sizeof *d->oe, &d->capoe, d->noe + 1))
      return derr(d, a, TDS_ENOMEM, "out of memory");
    d->oe[d->noe++] = (int32_t)f;
    n++;
  }
  double volume = 0, volconst = 0, density = 0, pressure = 0, lagrange = 0;
  int has_vol = 0, has_vc = 0, has_den = 0, has_pr = 0, has_lm = 0;
  while (!at_eol(d)) {
    const char *a = d->p;
    if (!take_word(d, w, sizeof w))
      return derr(d, a, TDS_ESYNTAX, "%s: unexpected %s", what, describe(a, b, sizeof b));
    if (!strcmp(w, "volume")) {
      rc = read_value(d, &volume, what);
      has_vol = 1;
    } else if (!strcmp(w, "volconst")) {
      rc = read_value(d, &volconst, what);
      has_vc = 1;
    } else if (!strcmp(w, "density")) {
      rc = read_value(d, &density, what);
      has_den = 1;
    } else if (!strcmp(w, "pressure")) {
      rc = read_value(d, &pressure, what);
      has_pr = 1;
    } else if (!strcmp(w, "lagrange_multiplier")) {
      rc = read_value(d, &lagrange, what);
      has_lm = 1;
    } else if (!strcmp(w, "centerofmass")) {
      /* display option of Evolver's dumps */
    } else if (!strcmp(w, "original")) {
      int64_t o;
      rc = read_int(d, 0, what, &o);
    } else {
      return unknown_attr(d, a, w, what);
    }
    if (rc) return rc;
  }
  if (has_vol && has_pr)
    return derr(d, NULL, TDS_ESYNTAX, "%s: give either VOLUME or PRESSURE, not both", what);
  int line = line_of(d, NULL);
  if ((rc = room_for(d, TDS_BODY, id))) return rc;
  rc = tds_decl_body(d->ctx, d->s, id, n, d->oe + off);
  d->noe = off;
  if (rc) return dcore(d, line, rc, NULL);
  tds_mesh *m = &d->s->m;
  if (has_vol) {
    m->btarget[id] = volume;
    m->bflags[id] |= TDS_TARGET;
    if (has_lm) m->bpressure[id] = lagrange;
  }
  if (has_pr) {
    m->bpressure[id] = pressure;
    m->bflags[id] |= TDS_PRESSURE;
  }
  if (has_vc) {
    m->bvolconst[id] = volconst;
    m->bflags[id] |= TDS_VOLCONST;
  }
  if (has_den) {
    m->bdensity[id] = density;
    d->density_given = 1;
  }
  return TDS_OK;
}

/* ---- driver ---- */

static int end_section(df *d) {
  int rc = d->section == S_FACES ? build_faces(d) : TDS_OK;
  d->noe = 0;
  return rc;
}

static int section_of(const char *w) {
  if (!strcmp(w, "vertices")) return S_VERTICES;
  if (!strcmp(w, "edges")) return S_EDGES;
  if (!strcmp(w, "faces") || !strcmp(w, "facets")) return S_FACES;
  if (!strcmp(w, "bodies")) return S_BODIES;
  return -1;
}

/* Start section sec at the keyword at `at`. */
static int begin_section(df *d, int sec, const char *at) {
  if (sec == d->section)
    return derr(d, at, TDS_ESYNTAX, "%s section given twice", section_name[sec]);
  if (sec < d->section)
    return derr(d, at, TDS_ESYNTAX, "%s section after the %s section", section_name[sec],
                section_name[d->section]);
  if (sec > S_VERTICES && !d->seen_vertices)
    return derr(d, at, TDS_ESYNTAX, "%s section before the VERTICES section",
                section_name[sec]);
  int rc = end_section(d);
  if (rc) return rc;
  d->section = sec;
  if (sec == S_VERTICES) d->seen_vertices = 1;
  if (!at_eol(d)) {
    char b[64];
    return derr(d, d->p, TDS_ESYNTAX, "unexpected %s after %s", describe(d->p, b, sizeof b),
                section_name[sec]);
  }
  return TDS_OK;
}

/* Whether the rest of text has anything but whitespace and comments. */
static int has_commands(const char *s, size_t n) {
  size_t i = 0;
  while (i < n) {
    if (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r') {
      i++;
    } else if (i + 1 < n && s[i] == '/' && s[i + 1] == '/') {
      while (i < n && s[i] != '\n') i++;
    } else if (i + 1 < n && s[i] == '/' && s[i + 1] == '*') {
      i += 2;
      while (i + 1 < n && !(s[i] == '*' && s[i + 1] == '/')) i++;
      i += 2;
    } else {
      return 1;
    }
  }
  return 0;
}

static int parse(df *d) {
  char w[64], b[64];
  for (;;) {
    int have, rc;
    if (d->section == S_HEADER) {
      if ((rc = more(d, &have))) return rc;
    } else {
      /* element sections: one element per logical line */
      while (at_eol(d)) {
        int r = next_line(d);
        if (r < 0) return -r;
        if (r == 0) break;
      }
      have = !at_eol(d);
    }
    if (!have) break;
    const char *at = d->p;
    if (d->section != S_HEADER && is_digit((unsigned char)*d->p)) {
      d->split = 1;
      switch (d->section) {
      case S_VERTICES: rc = vertex_line(d); break;
      case S_EDGES: rc = edge_line(d); break;
      case S_FACES: rc = face_line(d); break;
      default: rc = body_line(d); break;
      }
      d->split = 0;
      if (rc) return rc;
      if (!at_eol(d))
        return derr(d, d->p, TDS_ESYNTAX, "unexpected %s", describe(d->p, b, sizeof b));
      continue;
    }
    if (!take_word(d, w, sizeof w)) {
      if (d->section == S_HEADER)
        return derr(d, at, TDS_ESYNTAX, "expected a keyword, found %s", describe(at, b, sizeof b));
      return derr(d, at, TDS_ESYNTAX, "%s section: expected an element id, found %s",
                  section_name[d->section], describe(at, b, sizeof b));
    }
    int sec = section_of(w);
    if (sec >= 0) {
      if ((rc = begin_section(d, sec, at))) return rc;
      continue;
    }
    if (!strcmp(w, "read")) {
      if ((rc = end_section(d))) return rc;
      d->has_read = 1;
      d->read_at = df_lex_read_start(&d->lx);
      return TDS_OK;
    }
    hdr_fn fn = header_fn(w);
    if (d->section != S_HEADER) {
      char u[64];
      if (fn || is_in(w, unsupported))
        return derr(d, at, TDS_ESYNTAX, "%s must come before the VERTICES section",
                    upper(w, u, sizeof u));
      return derr(d, at, TDS_ESYNTAX, "%s section: expected an element id, found %s",
                  section_name[d->section], describe(at, b, sizeof b));
    }
    if (fn) {
      if ((rc = fn(d, w))) return rc;
    } else if (is_in(w, unsupported)) {
      return not_supported(d, at, w);
    } else {
      return derr(d, at, TDS_ESYNTAX, "unknown keyword %s", describe(at, b, sizeof b));
    }
  }
  return end_section(d);
}

/* After parsing: global constraints, gravity, consistency. */
static int finish(df *d) {
  tds_surf *s = d->s;
  tds_mesh *m = &s->m;
  if (!d->seen_vertices)
    return derr(d, NULL, TDS_ESYNTAX, "no VERTICES section (is this a datafile?)");
  tds_cmask global = 0;
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (s->con[c].number && (s->con[c].flags & TDS_CON_GLOBAL))
      global |= (tds_cmask)1 << c;
  if (global)
    for (tds_id v = 0; v < m->nv; v++) {
      if (!tds_alive(m->vflags, v) || (m->vcon[v] & global) == global) continue;
      m->vcon[v] |= global;
      if (m->vbdry[v] == TDS_NONE && tds_motion_enforce(s, v) != TDS_OK)
        tds_warnf(d->ctx, "%s: vertex %d: projection onto its constraints did not converge\n",
                  d->name, v + 1);
    }
  s->gravity_on = d->density_given;
  if (tds_mesh_check(d->ctx, m) != TDS_OK) {
    char msg[sizeof d->ctx->errmsg];
    memcpy(msg, d->ctx->errmsg, sizeof msg);
    msg[sizeof msg - 1] = 0;
    return tds_seterr(d->ctx, TDS_ETOPO, "%s: inconsistent surface: %.900s", d->name, msg);
  }
  if (d->has_read) {
    const char *r = d->lx.src + d->read_at;
    size_t n = d->lx.n - d->read_at;
    if (has_commands(r, n)) {
      s->read_text = malloc(n + 1);
      if (!s->read_text) return tds_seterr(d->ctx, TDS_ENOMEM, "out of memory");
      memcpy(s->read_text, r, n);
      s->read_text[n] = 0;
      tds_warnf(d->ctx, "%s: read section kept, not run (Evolver command language "
                "is not translated yet)\n", d->name);
    }
  }
  m->topo_gen++;
  m->coord_gen++;
  return TDS_OK;
}

static int surface_empty(const tds_surf *s) {
  if (s->m.nv || s->m.ne || s->m.nf || s->m.nb || s->npar || s->nbdry || s->nquant ||
      s->read_text)
    return 0;
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (s->con[c].number) return 0;
  return 1;
}

int tds_datafile_load_buffer(tds_ctx *ctx, tds_surf *s, const char *name,
                             const char *text, size_t len) {
  if (!name) name = "(datafile)";
  if (!surface_empty(s))
    return tds_seterr(ctx, TDS_ERANGE,
                      "%s: a surface is already loaded; datafiles load into an "
                      "empty surface", name);
  if (len > TDS_DF_MAXFILE)
    return tds_seterr(ctx, TDS_ESYNTAX, "%s: file too large (more than %u bytes)", name,
                      TDS_DF_MAXFILE);
  df d;
  memset(&d, 0, sizeof d);
  d.ctx = ctx;
  d.s = s;
  d.name = name;
  d.p = "";
  int64_t lim = 1000000 + 16 * (int64_t)len;
  d.maxid = lim < TDS_DF_MAXID ? lim : TDS_DF_MAXID;
  df_lex_init(&d.lx, ctx, name, text ? text : "", text ? len : 0);
  int rc = parse(&d);
  if (rc == TDS_OK) rc = finish(&d);
  df_lex_free(&d.lx);
  free(d.faces);
  free(d.oe);
  if (rc != TDS_OK) {
    if (rc < 0) rc = -rc;
    tds_surf_free(s); /* leaves ctx->errmsg alone */
  }
  return rc;
}

int tds_datafile_load(tds_ctx *ctx, tds_surf *s, const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return tds_seterr(ctx, TDS_EIO, "cannot open '%s': %s", path, strerror(errno));
  size_t cap = 1 << 16, n = 0;
  char *buf = malloc(cap);
  int rc = TDS_OK;
  while (buf) {
    if (n == cap) {
      if (cap > TDS_DF_MAXFILE) break;
      char *nb = realloc(buf, cap * 2);
      if (!nb) {
        free(buf);
        buf = NULL;
        break;
      }
      buf = nb;
      cap *= 2;
    }
    size_t got = fread(buf + n, 1, cap - n, f);
    n += got;
    if (got == 0) break;
  }
  if (!buf) {
    rc = tds_seterr(ctx, TDS_ENOMEM, "%s: out of memory", path);
  } else if (ferror(f)) {
    rc = tds_seterr(ctx, TDS_EIO, "cannot read '%s': %s", path, strerror(errno));
  } else if (n > TDS_DF_MAXFILE) {
    rc = tds_seterr(ctx, TDS_ESYNTAX, "%s: file too large (more than %u bytes)", path,
                    TDS_DF_MAXFILE);
  }
  fclose(f);
  if (rc == TDS_OK) rc = tds_datafile_load_buffer(ctx, s, path, buf, n);
  free(buf);
  return rc;
}

/* ---- detection ---- */

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), k = strlen(suffix);
  return n >= k && strcasecmp(s + n - k, suffix) == 0;
}

int tds_datafile_detect(const char *path) {
  if (ends_with(path, ".fe") || ends_with(path, ".dmp")) return 1;
  if (ends_with(path, ".tds") || ends_with(path, ".lua")) return 0;
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  char buf[8192];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = 0;
  size_t i = 0;
  for (;;) { /* skip whitespace, comments and # lines */
    while (i < n && is_ws((unsigned char)buf[i])) i++;
    if (i + 1 < n && buf[i] == '/' && buf[i + 1] == '/') {
      while (i < n && buf[i] != '\n') i++;
    } else if (i + 1 < n && buf[i] == '/' && buf[i + 1] == '*') {
      i += 2;
      while (i + 1 < n && !(buf[i] == '*' && buf[i + 1] == '/')) i++;
      i += 2;
    } else if (i < n && buf[i] == '#') {
      while (i < n && buf[i] != '\n') i++;
    } else {
      break;
    }
  }
  if (i >= n) return 0;
  size_t wl = word_len(buf + i);
  if (!wl || wl >= 64) return 0;
  char w[64];
  for (size_t k = 0; k < wl; k++) w[k] = (char)(buf[i + k] | (is_alpha((unsigned char)buf[i + k]) ? 32 : 0));
  w[wl] = 0;
  size_t j = i + wl;
  while (j < n && (buf[j] == ' ' || buf[j] == '\t')) j++;
  if (j < n && (buf[j] == '{' || buf[j] == '(' || buf[j] == '=' || buf[j] == '.' ||
                buf[j] == '[' || buf[j] == '"'))
    return 0;
  return section_of(w) >= 0 || header_fn(w) != NULL || is_in(w, unsupported);
}
