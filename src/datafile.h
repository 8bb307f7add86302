/*
** datafile.h: reading and writing Surface Evolver datafiles (.fe, .dmp).
**
** The reader takes the datafile format of Evolver's manual (datafile.htm):
** a top section of declarations (PARAMETER, CONSTRAINT, BOUNDARY,
** QUANTITY, GRAVITY_CONSTANT, ...), then the VERTICES, EDGES, FACES and
** BODIES sections, then an optional READ section of commands, which is
** kept verbatim in s->read_text and not run. Lexical rules: keywords are
** case-insensitive, // and C comments, backslash-newline joins lines,
** ',' ':' ';' are whitespace, `#define NAME text` macros (names are case
** sensitive, plain text substitution, rescanned), constant expressions
** wherever a number goes, and Evolver's rule for values in a row: in
** element lines "5 -1 0" and "5 -rad 0" are three values, "5 - 1 0" and
** "5 +1 0" two; in the top section '-' is always an operator (details in
** doc/datafile.md). Element ids of the file are kept as they
** are (user id = slot + 1; gaps stay dead slots); faces of more than three
** edges are split around a centre vertex, with the extra facets numbered
** after the highest face id, as Evolver does.
**
** Features of Evolver the core does not model yet (torus, string model,
** quadratic, metrics, extra attributes, per-element quantities, ...) are
** refused with "FILE:LINE: TORUS is not supported yet" -- never skipped.
** Every error is "FILE:LINE: message" in ctx->errmsg with a nonzero
** status; no input crashes the reader (limits below).
**
** The core's rules apply: no Lua, no globals, status codes.
*/
#ifndef TDS_DATAFILE_H
#define TDS_DATAFILE_H

#include <stddef.h>

#include "surf.h"

/* Limits of the reader (inputs beyond them are refused with a message). */
#define TDS_DF_MAXFILE (256u << 20) /* bytes of a datafile */
#define TDS_DF_MAXLINE (4u << 20)   /* bytes of a logical line after macros */
#define TDS_DF_MAXMACRO 4096        /* bytes of one macro body */
#define TDS_DF_MACRODEPTH 64        /* nested macro expansions */
#define TDS_DF_MAXID (1 << 26)      /* largest element id */
#define TDS_DF_MAXTOTAL (512u << 20) /* bytes produced by the preprocessor */

/* Load the datafile at path into s, which must be empty (freshly
** initialised: no elements, parameters or model). On success returns
** TDS_OK; if the file has a read section, its text is kept in s->read_text
** and one line saying so goes to tds_warnf. On failure returns TDS_EIO
** (cannot read), TDS_ESYNTAX (malformed or unsupported input), TDS_ERANGE /
** TDS_ETOPO (references that do not exist or do not fit) or TDS_ENOMEM,
** with "path:line: message" in ctx->errmsg, and s is emptied again
** (tds_surf_free), so a failed load leaves nothing behind. */
int tds_datafile_load(tds_ctx *ctx, tds_surf *s, const char *path);

/* The same from text[0..len) (need not be NUL-terminated; may contain any
** bytes). name is used in messages (e.g. "test.fe"). */
int tds_datafile_load_buffer(tds_ctx *ctx, tds_surf *s, const char *name,
                             const char *text, size_t len);

/* Write s as a datafile Evolver reads back to the same element counts and
** energy: parameters with their current values, constraints, boundaries
** and quantities with their formula texts, the elements with their
** attributes (every facet as a three-edge face, ids kept, dead slots left
** out), bodies, gravity and model settings, then s->read_text as the read
** section. Writes path.tmp and renames it to path, so a failed dump never
** destroys an existing file. TDS_OK, or TDS_EIO with a message. */
int tds_datafile_dump(tds_ctx *ctx, tds_surf *s, const char *path);

/* Whether path names a datafile: extension .fe or .dmp (any case) -> 1;
** .tds or .lua -> 0; anything else: 1 if the file starts (after comments
** and #define lines) with a datafile keyword such as VERTICES, PARAMETER
** or CONSTRAINT that is not followed by '{', '(' or '=' (Lua), else 0. An
** unreadable file counts as not a datafile (the Lua loader reports it). */
int tds_datafile_detect(const char *path);

#ifdef TDS_DATAFILE_INTERNAL
/* Shared by datafile.c and datafile_lex.c only: the preprocessor, which
** turns the raw text into logical lines (comments removed, continuations
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
  size_t total;           /* bytes produced so far (bounded) */
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
#endif

#endif
