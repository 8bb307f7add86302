/*
** datafile_int.h: internals of the datafile reader, shared by its files
** only (the public contract is datafile.h):
**   datafile.c           driver: load entry points, section dispatch,
**                        finishing touches, cleanup on failure, detection
**   datafile_lex.c       preprocessor: raw text -> logical lines
**   datafile_read.c      cursor over logical lines, messages, values
**   datafile_header.c    top-section keywords, the "not supported" table
**   datafile_define.c    DEFINE kind ATTRIBUTE (user attributes)
**   datafile_elements.c  VERTICES, EDGES, FACES and BODIES lines
**
** Conventions of the parsing functions below: they return TDS_OK or a
** status after setting "name:line: message" in ctx->errmsg (some return
** the negated status of df_lex_next, which the driver turns positive);
** `what` names the thing being read for messages ("vertex 3", "PARAMETER
** r"); an `at` pointer into the current line gives the line a message is
** reported at (NULL: where the logical line starts).
*/
#ifndef TDS_DATAFILE_INT_H
#define TDS_DATAFILE_INT_H

#include <stdint.h>

#include "datafile.h"
#include "expr.h"
#include "topo.h"

/* ---- the preprocessor (datafile_lex.c) ----
** Turns the raw text into logical lines (comments removed, continuations
** joined, macros expanded), one at a time, so that a #define takes effect
** from its line on and the READ section is never preprocessed. */

typedef struct df_macro {
  char *name;             /* case kept: macro names are case sensitive */
  char *body;             /* comments removed, trimmed */
  size_t namelen;
} df_macro;

typedef struct df_lex {
  tds_ctx *ctx;
  const char *name;       /* file name for messages */
  const char *src;        /* raw text */
  size_t n;
  size_t pos;             /* raw offset of the next logical line */
  int line;               /* physical line at pos (1-based) */
  /* the current logical line */
  char *buf;              /* expanded text, NUL-terminated */
  size_t len, cap;
  int line0;              /* physical line where it starts */
  size_t raw0, raw1;      /* raw range it came from */
  struct { size_t off; int line; } *bp;  /* line breakpoints within buf */
  int nbp, capbp;
  /* macros */
  df_macro *mac;
  int nmac, capmac;
  size_t total;           /* bytes produced by macro expansion (bounded) */
  int depth;              /* current expansion depth */
  const df_macro *active[TDS_DF_MACRODEPTH]; /* macros being expanded */
} df_lex;

/* Set up a lexer over text[0..n). */
void df_lex_init(df_lex *lx, tds_ctx *ctx, const char *name, const char *text,
                 size_t n);
/* Release its memory. */
void df_lex_free(df_lex *lx);
/* Produce the next logical line in lx->buf. Returns 1 (a line, possibly
** blank), 0 at the end of the text, or a negative status -TDS_E* after
** setting "name:line: message" (unterminated comment or string, NUL
** byte, bad #define, recursive or too long macro expansion). */
int df_lex_next(df_lex *lx);
/* Physical line of offset off in the current logical line. */
int df_lex_line_at(const df_lex *lx, size_t off);
/* Offset where the raw text following the word READ begins, given that
** the current logical line starts with READ (falls back to the end of the
** line if READ came out of a macro). */
size_t df_lex_read_start(const df_lex *lx);

/* ---- characters ---- */

static inline int is_alpha(int c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static inline int is_digit(int c) { return c >= '0' && c <= '9'; }
static inline int is_alnum(int c) { return is_alpha(c) || is_digit(c); }
/* Whitespace of the datafile: ',' ':' ';' count as blanks. */
static inline int is_ws(int c) {
  return c == ' ' || c == '\t' || c == ',' || c == ':' || c == ';' ||
         c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/* ---- the parser state ---- */

/* Sections in the order a file must give them. */
enum { S_HEADER = 0, S_VERTICES, S_EDGES, S_FACES, S_BODIES };

/* A face as read, built when the FACES section ends (see df_build_faces). */
typedef struct df_face {
  tds_id id;          /* 0-based */
  int line;
  int n;              /* number of oriented edges */
  int32_t off;        /* first oriented edge in df.oe */
  tds_face_attr at;
  int32_t pv0, pv1;   /* its other attributes' values in df.pv */
  int64_t file;       /* its `original`: the file's id or ORIGINAL's value */
} df_face;

typedef struct df {
  tds_ctx *ctx;
  tds_surf *s;
  df_lex lx;
  const char *name;    /* file name for messages */
  const char *p;       /* cursor in lx.buf (never NULL) */
  int eof;             /* no more logical lines */
  int section;         /* S_* */
  int seen_vertices;
  int64_t maxid;       /* largest element id accepted for this file */
  df_face *faces;      /* faces of the FACES section, not built yet */
  int32_t nfaces, capfaces;
  int32_t *oe;         /* scratch: face edges, or one body's faces */
  int32_t noe, capoe;
  double *pv;          /* scratch: attribute values of element lines, as
                          [registry row, n, n values]... (datafile_elements.c) */
  int32_t npv, cappv;
  tds_id maxface;      /* highest face slot + 1 */
  int has_read;        /* a READ section follows ... */
  size_t read_at;      /* ... from this raw offset */
  int split;           /* several values in a row: element lines, matrices */
  int space_dim;       /* SPACE_DIMENSION given (0: not given) */
  int string_model;    /* STRING or SURFACE_DIMENSION 1 given */
  int torus_line;      /* line of TORUS / TORUS_FILLED (0: none) */
  int klein_line;      /* line of KLEIN_METRIC (0: none) */
  int periods_line;    /* line of PERIODS (0: none) */
  int periods_dim;     /* rows (and values per row) PERIODS had: 2 or 3 */
  /* Element ids: as Evolver, elements are numbered 1, 2, ... in the order
  ** the file gives them (the file's ids become `original`), unless the
  ** top section says KEEP_ORIGINALS (slot = the file's id - 1). */
  int keep_ids;
  int32_t *idmap[4];   /* per kind: file id -> slot + 1 (0: none yet) */
  int32_t capmap[4];
  int32_t nread[4];    /* elements of each kind read so far */
  int64_t fid;         /* the current element line's id in the file */
  int64_t orig;        /* its ORIGINAL value, or -1 */
  struct df_app *app;  /* append mode (addload): what to put back on failure */
  int32_t ne0;         /* edges before this file (addload): rings of the
                          file's edges are ordered at the end (ring.h) */
} df;

/* ---- append mode (datafile_append.c) ----
** df_app_begin saves what the file may change and numbers the new
** elements after the existing ones; df_app_detach(d, kind, slot) lets the
** file redeclare an existing constraint, boundary or quantity slot (1:
** done, its old definition kept aside; 0: not in append mode, or already
** redeclared by this file); df_app_end keeps the result (ok) or puts the
** surface back as it was. */
enum { DF_APP_CON, DF_APP_BDRY, DF_APP_QUANT };
int df_app_begin(df *d);
int df_app_detach(df *d, int kind, int slot);
void df_app_end(df *d, int ok);

/* Free the id maps (datafile_elements.c). */
void df_free_ids(df *d);

/* ---- the string model (datafile_string.c) ---- */

/* Build the faces of the FACES section as string-model cells (in id
** order). */
int df_string_faces(df *d);
/* Give body id the cells faces[0..n) (signed 1-based ids). */
int df_string_body(df *d, tds_id id, int n, const int32_t *faces);
/* When the elements start: refuse what the string model does not have yet
** (messages at the current line). */
int df_string_model(df *d);
/* METRIC (the cursor after the keyword at `at`): the string model's
** Riemannian metric into s->metric. */
int df_metric(df *d, const char *at);
/* When the vertices begin: KLEIN_METRIC and SYMMETRY_GROUP "genus2" only
** in the string model, other groups not in it. */
int df_klein_check(df *d);
/* At the end: check the cells. */
int df_string_finish(df *d);

/* ---- the torus model (datafile_torus.c) ---- */

/* TORUS (filled 0) or TORUS_FILLED (1): the cursor is after the word. */
int df_torus(df *d, int filled);
/* PERIODS: three rows of three expressions, each row on one line. */
int df_periods(df *d);
/* SYMMETRY_GROUP "name" (symgroup.h): the group's wraps through the torus
** model's machinery (m->torus 1, m->sym the group). */
int df_symmetry_group(df *d);
/* When the VERTICES section starts: PERIODS needs TORUS. */
int df_torus_start(df *d, const char *at);
/* The wrap signs after an edge's vertices (none: *wrap = 0): three of
** * + -; an error without TORUS. */
int df_edge_wrap(df *d, const char *what, int32_t *wrap);
/* After the elements: facets close in the torus, volumes settled to whole
** cells (torus.h), a warning for bodies that wrap round the torus. */
int df_torus_finish(df *d);

/* ---- messages (datafile_read.c) ---- */

/* Physical line of position at in the current logical line (NULL or
** outside it: where the line starts, or the last line at end of file). */
int df_line_of(const df *d, const char *at);
/* Set "name:line: message" (line of `at`, as df_line_of) and return rc. */
int df_err(df *d, const char *at, int rc, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* The same at a given physical line. */
int df_err_line(df *d, int line, int rc, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* Prefix the core's message in ctx->errmsg with "name:line: what: " (no
** "what: " if what is NULL or empty); rc 0 counts as TDS_ESYNTAX. */
int df_core(df *d, int line, int rc, const char *what);
/* A short printable description of the token at p ("'abc'", "end of
** line", "character '\x01'") in buf, for messages; returns buf. */
const char *df_describe(const char *p, char *buf, size_t cap);
/* w in upper case in buf (truncated to cap); returns buf. */
const char *df_upper(const char *w, char *buf, size_t cap);

/* ---- the cursor (datafile_read.c) ----
** Functions named "same line" stay within the current logical line;
** df_more and the df_header_* readers move to the following lines when
** the current one is used up, as tokens of the top section may. */

/* Skip blanks (same line). */
void df_ws(df *d);
/* Whether only blanks are left on the line (skips them). */
int df_at_eol(df *d);
/* Fetch the next logical line and put the cursor at its start. 1 = got
** one, 0 = end of file (then d->eof is set), else -status. */
int df_next_line(df *d);
/* Move to the next token, across line ends; *have = 0 at end of file. */
int df_more(df *d, int *have);
/* Length of the identifier at p (0 if none). */
size_t df_word_len(const char *p);
/* Whether p[0..n) is w, case-insensitively. */
int df_word_eq(const char *p, size_t n, const char *w);
/* Whether the word at the cursor (same line) is w, case-insensitively. */
int df_peek(df *d, const char *w);
/* df_peek, and if so step over it. */
int df_accept(df *d, const char *w);
/* Read the word at the cursor lowercased into buf (truncated); returns
** its length (0 if there is no word) and advances. */
size_t df_take_word(df *d, char *buf, size_t cap);
/* Whether an integer (optionally signed) starts at the cursor. */
int df_looks_int(df *d);
/* Whether the cursor (same line) starts a value rather than an attribute
** word: a number, sign, '(' or '!', a function or constant name of
** expressions, or a parameter. */
int df_looks_value(df *d);
/* Whether p[0..n) is a name expressions reserve (sqrt, pi, g, ...). */
int df_expr_word(const char *p, size_t n);

/* ---- values (datafile_read.c) ---- */

/* An integer (same line), signed if `sign`. Values beyond 1e15 read as
** 1e15 + 1 (callers range-check). */
int df_read_int(df *d, int sign, const char *what, int64_t *v);
/* A constant expression (same line) evaluated now; refuses non-finite
** values. In the top section '-' is always an operator; with d->split the
** signed-number rule separates values ("5 -1" is two). */
int df_read_value(df *d, double *v, const char *what);
/* A colour name (black, red, clear, ...) or value in -32768..32767. */
int df_read_color(df *d, int16_t *c, const char *what);
/* The top-section forms of df_read_int, df_read_value and an unevaluated
** expression parsed with `flags` (TDS_EXPR_*): the token may start on a
** following line. *e is NULL on failure, else the caller's. */
int df_header_int(df *d, int sign, const char *what, int64_t *v);
int df_header_value(df *d, double *v, const char *what);
int df_header_expr(df *d, int flags, tds_expr **e, const char *what);
/* The components "<letter>1 expr <letter>2 expr <letter>3 expr" of a
** vector (top section; any order; at least one; letter lowercase) into
** e[0..2]; a component whose entry is already set is refused as given
** twice, entries not given are left alone. On failure too, the caller
** owns and frees (df_free3) what e holds. */
int df_components(df *d, char letter, int flags, tds_expr *e[3], const char *what);
/* Free e[0..2] and set them to NULL. */
void df_free3(tds_expr *e[3]);

/* ---- top section (datafile_header.c) ---- */

/* Whether w (lowercase) is an Evolver keyword whose feature tds does not
** have yet (torus, quadratic, metric, ...). */
int df_unsupported(const char *w);
/* Refuse the unsupported keyword w found at `at`: "W is not supported
** yet". */
int df_not_supported(df *d, const char *at, const char *w);
/* Whether w (lowercase) is a top-section keyword, read or refused. */
int df_header_word(const char *w);
/* Read the top-section keyword w (lowercase, taken from `at`) and what
** belongs to it; unknown and unsupported keywords are refused. */
int df_header_keyword(df *d, const char *w, const char *at);

/* ---- user attributes (datafile_define.c) ---- */

/* Read "kind ATTRIBUTE name type [dim]..." after the word DEFINE (found
** at `at`) and define the attribute; other DEFINEs are refused as not
** supported yet. */
int df_define(df *d, const char *at);

/* ---- element sections (datafile_elements.c) ---- */

/* Read the element line at the cursor (starting with its id) of the
** current section (d->section > S_HEADER), up to the end of its
** declaration; the driver checks that nothing follows. Vertices, edges and
** bodies are declared at once, faces collected for df_build_faces. */
int df_element_line(df *d);
/* Build the collected faces (at the end of the FACES section), after
** reserving facet slots up to the highest face id so that split-off
** facets come after every declared id. */
int df_build_faces(df *d);

#endif
