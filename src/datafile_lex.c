/*
** datafile_lex.c: the datafile preprocessor (contract in datafile_int.h).
** Turns raw text into logical lines, one at a time: comments become a
** space, backslash-newline joins lines, #define lines define macros, and
** macro names (case sensitive, whole identifiers outside strings and
** numbers) are replaced by their bodies, rescanned, as separate tokens.
**
** Substitution is textual, as in Evolver: only where a body would merge
** with its neighbours into one token is a space put between them. So
** with "#define M -2" and "#define W 2", the vertex line "1 5 M 0" and
** "1 5 -W 0" both read as coordinates 5 -2 0, and "parameter a = 1 M" is
** -1 (all verified with evolver-nox-d 2.70).
**
** Every byte of output goes through put(), which enforces the line length
** limit, so exponential macro bodies and 10 MB lines end in a message,
** not in memory exhaustion. Recursion is refused when a macro is met
** inside its own expansion.
*/
#include "datafile_int.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

void df_lex_init(df_lex *lx, tds_ctx *ctx, const char *name, const char *text,
                 size_t n) {
  memset(lx, 0, sizeof *lx);
  lx->ctx = ctx;
  lx->name = name;
  lx->src = text;
  lx->n = n;
  lx->line = 1;
}

void df_lex_free(df_lex *lx) {
  for (int i = 0; i < lx->nmac; i++) {
    tds_free(&lx->ctx->alloc, lx->mac[i].name);
    tds_free(&lx->ctx->alloc, lx->mac[i].body);
  }
  tds_free(&lx->ctx->alloc, lx->mac);
  tds_free(&lx->ctx->alloc, lx->buf);
  tds_free(&lx->ctx->alloc, lx->bp);
  lx->mac = NULL;
  lx->buf = NULL;
  lx->bp = NULL;
  lx->nmac = lx->capmac = lx->nbp = lx->capbp = 0;
  lx->len = lx->cap = 0;
}

static int lerr(df_lex *lx, int rc, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static int lerr(df_lex *lx, int rc, int line, const char *fmt, ...) {
  char msg[700];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  tds_seterr(lx->ctx, rc, "%s:%d: %s", lx->name, line, msg);
  return -rc;
}

/* Append one byte to the logical line. */
static int put(df_lex *lx, char c) {
  /* Only expanded text counts: a large file without macros is bounded by
  ** TDS_DF_MAXFILE, while a few nested #defines can multiply a 3 KB file
  ** into gigabytes. */
  if (lx->depth && ++lx->total > TDS_DF_MAXTOTAL)
    return lerr(lx, TDS_ESYNTAX, lx->line0,
                "macro expansion produces more than %u bytes", TDS_DF_MAXTOTAL);
  if (lx->len + 2 > lx->cap) {
    if (lx->len + 2 > TDS_DF_MAXLINE)
      return lerr(lx, TDS_ESYNTAX, lx->line0,
                  "line too long (more than %u bytes%s)", TDS_DF_MAXLINE,
                  lx->depth ? " after macro expansion" : "");
    size_t cap = lx->cap ? lx->cap * 2 : 256;
    if (cap > TDS_DF_MAXLINE) cap = TDS_DF_MAXLINE;
    char *b = tds_realloc(&lx->ctx->alloc, lx->buf, cap);
    if (!b) return lerr(lx, TDS_ENOMEM, lx->line0, "out of memory");
    lx->buf = b;
    lx->cap = cap;
  }
  lx->buf[lx->len++] = c;
  lx->buf[lx->len] = 0;
  return 0;
}

static int put_n(df_lex *lx, const char *s, size_t n) {
  for (size_t i = 0; i < n; i++) {
    int rc = put(lx, s[i]);
    if (rc) return rc;
  }
  return 0;
}

/* Record that the text from offset len on comes from physical line `line`. */
static int breakpoint(df_lex *lx) {
  if (lx->nbp > 0 && lx->bp[lx->nbp - 1].line == lx->line) return 0;
  if (tds_grow(&lx->ctx->alloc, (void **)&lx->bp, sizeof *lx->bp, &lx->capbp, lx->nbp + 1))
    return lerr(lx, TDS_ENOMEM, lx->line, "out of memory");
  lx->bp[lx->nbp].off = lx->len;
  lx->bp[lx->nbp].line = lx->line;
  lx->nbp++;
  return 0;
}

int df_lex_line_at(const df_lex *lx, size_t off) {
  int line = lx->line0;
  for (int i = 0; i < lx->nbp && lx->bp[i].off <= off; i++) line = lx->bp[i].line;
  return line;
}

/* Index of the macro named s[0..n) (the latest definition), or -1. */
static int find_macro(const df_lex *lx, const char *s, size_t n) {
  for (int i = lx->nmac - 1; i >= 0; i--)
    if (lx->mac[i].namelen == n && memcmp(lx->mac[i].name, s, n) == 0)
      return i;
  return -1;
}

static int scan_body(df_lex *lx, const char *s, size_t n);

/* Whether characters a and b written side by side would merge into one
** token (a name or number, or an operator such as ** <= &&). */
static int glues(int a, int b) {
  int wa = is_alnum(a) || a == '.', wb = is_alnum(b) || b == '.';
  if (wa && wb) return 1;
  return strchr("*<>=!&|", a) && a && strchr("*=&|", b) && b;
}

/* Emit identifier s[0..n), expanding it if it names a macro. `next` is
** the character that follows it in its source. */
static int ident(df_lex *lx, const char *s, size_t n, int expand, int next) {
  int mi = expand ? find_macro(lx, s, n) : -1;
  const df_macro *m = mi >= 0 ? &lx->mac[mi] : NULL;
  if (!m) return put_n(lx, s, n);
  for (int i = 0; i < lx->depth; i++)
    if (lx->active[i] == m)
      return lerr(lx, TDS_ESYNTAX, lx->line,
                  i == lx->depth - 1 ? "macro %s expands to itself"
                                     : "macro %s expands to itself (through %s)",
                  m->name, lx->active[lx->depth - 1]->name);
  if (lx->depth >= TDS_DF_MACRODEPTH)
    return lerr(lx, TDS_ESYNTAX, lx->line,
                "macros nested more than %d deep (expanding %s)",
                TDS_DF_MACRODEPTH, m->name);
  const char *b = m->body;
  int rc = 0;
  if (lx->len && glues((unsigned char)lx->buf[lx->len - 1], (unsigned char)b[0]))
    rc = put(lx, ' '); /* keep it a separate token */
  if (rc) return rc;
  lx->active[lx->depth++] = m;
  rc = scan_body(lx, b, strlen(b));
  lx->depth--;
  if (rc) return rc;
  if (lx->len && glues((unsigned char)lx->buf[lx->len - 1], next)) return put(lx, ' ');
  return 0;
}

/* Length of the number-like token at s (C's pp-number): digits, letters,
** '.', and a sign right after an exponent letter of a decimal number. */
static size_t number_len(const char *s, size_t n) {
  size_t i = 0;
  int hex = n > 1 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
  while (i < n) {
    int c = (unsigned char)s[i];
    if (is_alnum(c) || c == '.') {
      i++;
    } else if ((c == '+' || c == '-') && !hex && i > 0 &&
               (s[i - 1] == 'e' || s[i - 1] == 'E') && i + 1 < n &&
               is_digit((unsigned char)s[i + 1])) {
      i++;
    } else {
      break;
    }
  }
  return i;
}

/* Length of the string literal at s (s[0] == '"'), or 0 if unterminated
** before the end or a newline. */
static size_t string_len(const char *s, size_t n) {
  for (size_t i = 1; i < n; i++) {
    if (s[i] == '\n') return 0;
    if (s[i] == '\\' && i + 1 < n && s[i + 1] != '\n') {
      i++;
      continue;
    }
    if (s[i] == '"') return i + 1;
  }
  return 0;
}

/* Rescan a macro body (no comments or newlines left in it). */
static int scan_body(df_lex *lx, const char *s, size_t n) {
  size_t i = 0;
  int rc = 0;
  while (i < n && !rc) {
    int c = (unsigned char)s[i];
    if (is_alpha(c)) {
      size_t j = i + 1;
      while (j < n && is_alnum((unsigned char)s[j])) j++;
      rc = ident(lx, s + i, j - i, 1, j < n ? (unsigned char)s[j] : ' ');
      i = j;
    } else if (is_digit(c) || (c == '.' && i + 1 < n && is_digit((unsigned char)s[i + 1]))) {
      size_t k = number_len(s + i, n - i);
      rc = put_n(lx, s + i, k);
      i += k;
    } else if (c == '"') {
      size_t k = string_len(s + i, n - i);
      if (!k) k = n - i;
      rc = put_n(lx, s + i, k);
      i += k;
    } else {
      rc = put(lx, (char)c);
      i++;
    }
  }
  return rc;
}

/* Skip a C comment at lx->pos ("/" "*"); counts newlines. */
static int skip_block_comment(df_lex *lx) {
  int start = lx->line;
  size_t i = lx->pos + 2;
  while (i + 1 < lx->n && !(lx->src[i] == '*' && lx->src[i + 1] == '/')) {
    if (lx->src[i] == '\n') lx->line++;
    i++;
  }
  if (i + 1 >= lx->n) {
    lx->pos = lx->n;
    return lerr(lx, TDS_ESYNTAX, start, "unterminated comment (/* without */)");
  }
  lx->pos = i + 2;
  return 0;
}

/* Scan raw text into the logical line until its end; expand macros unless
** `expand` is 0 (a #define body). */
static int scan_raw(df_lex *lx, int expand) {
  const char *s = lx->src;
  int rc = 0;
  while (lx->pos < lx->n && !rc) {
    size_t i = lx->pos;
    int c = (unsigned char)s[i];
    int c1 = i + 1 < lx->n ? (unsigned char)s[i + 1] : -1;
    if (c == '\n') {
      lx->pos++;
      lx->line++;
      break;
    } else if (c == '\\' && (c1 == '\n' || (c1 == '\r' && i + 2 < lx->n && s[i + 2] == '\n'))) {
      lx->pos += c1 == '\n' ? 2 : 3;
      lx->line++;
      rc = put(lx, ' ');
      if (!rc) rc = breakpoint(lx);
    } else if (c == '/' && c1 == '/') {
      while (lx->pos < lx->n && s[lx->pos] != '\n') lx->pos++;
    } else if (c == '/' && c1 == '*') {
      rc = skip_block_comment(lx);
      if (!rc) rc = put(lx, ' ');
      if (!rc) rc = breakpoint(lx);
    } else if (c == 0) {
      return lerr(lx, TDS_ESYNTAX, lx->line,
                  "NUL byte in the file (this is not a text datafile)");
    } else if (c == '"') {
      size_t k = string_len(s + i, lx->n - i);
      if (!k) return lerr(lx, TDS_ESYNTAX, lx->line, "unterminated string");
      rc = put_n(lx, s + i, k);
      lx->pos += k;
    } else if (is_alpha(c)) {
      size_t j = i + 1;
      while (j < lx->n && is_alnum((unsigned char)s[j])) j++;
      lx->pos = j;
      rc = ident(lx, s + i, j - i, expand, j < lx->n ? (unsigned char)s[j] : ' ');
    } else if (is_digit(c) || (c == '.' && c1 >= 0 && is_digit(c1))) {
      size_t k = number_len(s + i, lx->n - i);
      rc = put_n(lx, s + i, k);
      lx->pos += k;
    } else if (c == '\r' || c == '\f' || c == '\v') {
      rc = put(lx, ' ');
      lx->pos++;
    } else {
      rc = put(lx, (char)c);
      lx->pos++;
    }
  }
  return rc;
}

/* A '#' line: #define NAME body. The logical line becomes blank. */
static int directive(df_lex *lx, size_t hash) {
  const char *s = lx->src;
  size_t i = hash + 1;
  while (i < lx->n && (s[i] == ' ' || s[i] == '\t')) i++;
  size_t w = i;
  while (i < lx->n && is_alnum((unsigned char)s[i])) i++;
  size_t wl = i - w;
  if (wl == 6 && strncasecmp(s + w, "define", 6) == 0) {
    while (i < lx->n && (s[i] == ' ' || s[i] == '\t')) i++;
    size_t nm = i;
    if (i < lx->n && is_alpha((unsigned char)s[i])) {
      i++;
      while (i < lx->n && is_alnum((unsigned char)s[i])) i++;
    }
    size_t nl = i - nm;
    if (nl == 0)
      return lerr(lx, TDS_ESYNTAX, lx->line, "#define needs a macro name");
    if (nl > 200)
      return lerr(lx, TDS_ESYNTAX, lx->line, "macro name too long");
    lx->pos = i;
    int rc = scan_raw(lx, 0);
    if (rc) return rc;
    size_t a = 0, b = lx->len;
    while (a < b && (lx->buf[a] == ' ' || lx->buf[a] == '\t')) a++;
    while (b > a && (lx->buf[b - 1] == ' ' || lx->buf[b - 1] == '\t')) b--;
    if (b - a > TDS_DF_MAXMACRO)
      return lerr(lx, TDS_ESYNTAX, lx->line0,
                  "macro %.*s: body longer than %d characters", (int)nl, s + nm,
                  TDS_DF_MAXMACRO);
    int mi = find_macro(lx, s + nm, nl);
    df_macro *m = mi >= 0 ? &lx->mac[mi] : NULL;
    if (!m) {
      if (tds_grow(&lx->ctx->alloc, (void **)&lx->mac, sizeof *lx->mac, &lx->capmac, lx->nmac + 1))
        return lerr(lx, TDS_ENOMEM, lx->line0, "out of memory");
      m = &lx->mac[lx->nmac];
      memset(m, 0, sizeof *m);
      m->name = tds_malloc(&lx->ctx->alloc, nl + 1);
      if (!m->name) return lerr(lx, TDS_ENOMEM, lx->line0, "out of memory");
      memcpy(m->name, s + nm, nl);
      m->name[nl] = 0;
      m->namelen = nl;
      lx->nmac++;
    }
    char *body = tds_malloc(&lx->ctx->alloc, b - a + 1);
    if (!body) return lerr(lx, TDS_ENOMEM, lx->line0, "out of memory");
    memcpy(body, lx->buf + a, b - a);
    body[b - a] = 0;
    tds_free(&lx->ctx->alloc, m->body);
    m->body = body;
    lx->len = 0;
    lx->buf[0] = 0;
    lx->nbp = 0;
    return 0;
  }
  if (wl == 7 && strncasecmp(s + w, "include", 7) == 0)
    return lerr(lx, TDS_ESYNTAX, lx->line, "#INCLUDE is not supported yet");
  return lerr(lx, TDS_ESYNTAX, lx->line, "unknown directive '#%.*s'",
              (int)(wl > 40 ? 40 : wl), s + w);
}

int df_lex_next(df_lex *lx) {
  lx->len = 0;
  lx->nbp = 0;
  lx->depth = 0;
  if (!lx->buf) {
    int rc = put(lx, ' ');
    if (rc) return rc;
    lx->len = 0;
  }
  lx->buf[0] = 0;
  if (lx->pos >= lx->n) return 0;
  if (lx->ctx->interrupt) { /* Ctrl-C while loading a large file */
    lx->ctx->interrupt = 0;
    return lerr(lx, TDS_EINTR, lx->line, "interrupted while loading");
  }
  lx->line0 = lx->line;
  lx->raw0 = lx->pos;
  size_t i = lx->pos;
  while (i < lx->n && (lx->src[i] == ' ' || lx->src[i] == '\t')) i++;
  int rc = (i < lx->n && lx->src[i] == '#') ? directive(lx, i) : scan_raw(lx, 1);
  lx->raw1 = lx->pos;
  return rc ? rc : 1;
}

size_t df_lex_read_start(const df_lex *lx) {
  const char *s = lx->src;
  size_t i = lx->raw0;
  for (;;) {
    while (i < lx->raw1 && (s[i] == ' ' || s[i] == '\t' || s[i] == ',' ||
                            s[i] == ';' || s[i] == ':' || s[i] == '\r'))
      i++;
    if (i + 1 < lx->raw1 && s[i] == '/' && s[i + 1] == '*') {
      i += 2;
      while (i + 1 < lx->raw1 && !(s[i] == '*' && s[i + 1] == '/')) i++;
      i += 2;
      continue;
    }
    break;
  }
  if (i + 4 <= lx->raw1 && strncasecmp(s + i, "read", 4) == 0 &&
      (i + 4 == lx->n || !is_alnum((unsigned char)s[i + 4])))
    return i + 4;
  return lx->raw1;
}
