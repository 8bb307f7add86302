/*
** atomic.h: writing a file all at once or not at all.
**
** tds_afile_open creates "<path>.tmp" and opens it for writing; the caller
** writes through af->f. tds_afile_close flushes and closes it, reporting a
** write error; tds_afile_commit renames the temporary over path, so a
** reader sees either the old file or the complete new one. Several files
** can be closed first and committed together (export's per-body files).
** tds_afile_abort removes the temporary and releases everything; it is
** safe after any step, including after commit (then it only frees).
*/
#ifndef TDS_ATOMIC_H
#define TDS_ATOMIC_H

#include <stdio.h>

#include "tds.h"

typedef struct tds_afile {
  FILE *f;        /* open stream, NULL after close */
  char *path;     /* destination (owned copy) */
  char *tmp;      /* temporary path, NULL once renamed */
} tds_afile;

/* Open path's temporary for writing. TDS_OK, TDS_ENOMEM or TDS_EIO (the
** message names the file); on failure *af needs no abort. */
int tds_afile_open(tds_ctx *ctx, tds_afile *af, const char *path);
/* Close the stream. TDS_OK, or TDS_EIO if any write or the close failed. */
int tds_afile_close(tds_ctx *ctx, tds_afile *af);
/* Rename the closed temporary to the destination. TDS_OK or TDS_EIO. */
int tds_afile_commit(tds_ctx *ctx, tds_afile *af);
/* Close if open, remove the temporary if it still exists, free. */
void tds_afile_abort(tds_afile *af);

#endif
