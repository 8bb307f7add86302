/*
** datafile.h: reading and writing Surface Evolver datafiles (.fe, .dmp).
**
** The reader takes the datafile format of Evolver's manual (datafile.htm):
** a top section of declarations (PARAMETER, CONSTRAINT, BOUNDARY,
** QUANTITY, GRAVITY_CONSTANT, ...), then the VERTICES, EDGES, FACES and
** BODIES sections, then an optional READ section of commands, which is
** kept verbatim in s->read_text (the Lua layer runs it after loading,
** lua/evorun.lua). Lexical rules: keywords are
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
#ifndef TDS_DF_MAXLINE /* the fuzz build lowers the two expansion limits */
#define TDS_DF_MAXLINE (4u << 20)   /* bytes of a logical line after macros */
#endif
#define TDS_DF_MAXMACRO 4096        /* bytes of one macro body */
#define TDS_DF_MACRODEPTH 64        /* nested macro expansions */
#define TDS_DF_MAXID (1 << 26)      /* largest element id */
#ifndef TDS_DF_MAXTOTAL
#define TDS_DF_MAXTOTAL (64u << 20) /* bytes produced by macro expansion */
#endif

/* Load the datafile at path into s, which must be empty (freshly
** initialised: no elements, parameters or model). On success returns
** TDS_OK; if the file has a read section, its text is kept in s->read_text
** and one line saying so goes to tds_warnf. On failure returns TDS_EIO
** (cannot read), TDS_ESYNTAX (malformed or unsupported input), TDS_ERANGE /
** TDS_ETOPO (references that do not exist or do not fit) or TDS_ENOMEM,
** with "path:line: message" in ctx->errmsg, and s is emptied again
** (tds_surf_free), so a failed load leaves nothing behind. The loaded
** surface takes Evolver's line search (s->evolver_ls = 1), so a ported
** script's `g` takes Evolver's steps; the caller may switch it off. */
int tds_datafile_load(tds_ctx *ctx, tds_surf *s, const char *path);

/* The same from text[0..len) (need not be NUL-terminated; may contain any
** bytes). name is used in messages (e.g. "test.fe"). */
int tds_datafile_load_buffer(tds_ctx *ctx, tds_surf *s, const char *name,
                             const char *text, size_t len);

/* Evolver's `addload`: the datafile at path (or text[0..len)) added to
** the surface s, which may hold anything (not the string model). The new
** elements are numbered after the existing slots (their file ids become
** `original`; KEEP_ORIGINALS is not obeyed), top-section declarations
** replace existing ones of the same number or name (parameters, constraints,
** boundaries, quantities, settings), user attributes already defined must
** agree in type, and the file's read section is ignored (not run, not
** kept). All or nothing: on any failure s is bit for bit as before, with
** "path:line: message" in ctx->errmsg and the statuses of the load. */
int tds_datafile_addload(tds_ctx *ctx, tds_surf *s, const char *path);
int tds_datafile_addload_buffer(tds_ctx *ctx, tds_surf *s, const char *name,
                                const char *text, size_t len);

/* Evolver's `replace_load`: every element of s goes, then path is
** addloaded (ids start at 1 again; parameters, constraints, quantities
** and attributes not redeclared stay). All or nothing like addload. */
int tds_datafile_replace_load(tds_ctx *ctx, tds_surf *s, const char *path);

/* Evolver's run-time `define constraint|boundary|quantity ...`: one
** top-section declaration in text[0..len), given as in a datafile, added
** to the live surface s. Messages are "name:LINE: ..." with the text's
** first line numbered `line`. Nothing is added unless the whole text is
** one valid declaration (a new GLOBAL constraint is then applied to every
** vertex, as at load). Same statuses as tds_datafile_load_buffer. */
int tds_datafile_define(tds_ctx *ctx, tds_surf *s, const char *name, int line,
                        const char *text, size_t len);

/* Write s as a datafile Evolver reads back to the same element counts and
** energy: parameters with their current values, constraints, boundaries
** and quantities with their formula texts, the elements with their
** attributes (every facet as a three-edge face, ids kept, dead slots left
** out), bodies, gravity and model settings, then s->read_text as the read
** section. Writes path.tmp and renames it to path, so a failed dump never
** destroys an existing file. TDS_OK, or TDS_EIO with a message. */
int tds_datafile_dump(tds_ctx *ctx, tds_surf *s, const char *path);
/* As tds_datafile_dump with `read` (NULL: none) as the read section. */
int tds_datafile_dump_read(tds_ctx *ctx, tds_surf *s, const char *path, const char *read);

/* The plain element lists of s as a datafile (write_fe): `header` (the
** caller's top section: parameters, constraints in Evolver syntax; NULL
** for none), the gravity constant and user attribute definitions, the
** elements exactly as tds_datafile_dump writes them, and `read` as the
** read section (NULL: none). Written the same all-or-nothing way. */
int tds_datafile_write_fe(tds_ctx *ctx, tds_surf *s, const char *path, const char *header,
                          const char *read);

/* Whether path names a datafile: extension .fe or .dmp (any case) -> 1;
** .tds or .lua -> 0; anything else: 1 if the file starts (after comments
** and #define lines) with a datafile keyword such as VERTICES, PARAMETER
** or CONSTRAINT that is not followed by '{', '(' or '=' (Lua), else 0. An
** unreadable file counts as not a datafile (the Lua loader reports it). */
int tds_datafile_detect(const char *path);

#endif
