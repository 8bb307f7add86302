/*
** wfile.h: the one way tds writes a file that matters (datafiles, dumps,
** write_fe): all or nothing.
**
** The text goes to a new temporary file in the target's directory, created
** exclusively (O_CREAT|O_EXCL|O_NOFOLLOW, a unique name, so a planted file
** or symlink is never followed or overwritten), with the target's
** permission bits (and owner, where the process may set it); it is
** flushed and fsync'ed, then renamed over the
** target, and the directory is synced. A target that is a symlink is
** resolved, so the file it points to is replaced and the link kept. On any
** failure (no space, file-size limit, read-only place, I/O error) the
** temporary file is removed, the old file is untouched, and the message
** names the target and the reason.
**
** A target that exists but is not writable (no write permission bit for
** the user; for root: no write bit at all, e.g. mode 0444) or is not a
** regular file is refused before anything is written.
*/
#ifndef TDS_WFILE_H
#define TDS_WFILE_H

#include <stdio.h>

#include "tds.h"

typedef struct tds_wfile {
  FILE *f;        /* write the content here */
  char *path;     /* the target (symlinks resolved) */
  char *tmp;      /* the temporary file */
  tds_alloc alloc; /* of path and tmp (the ctx's at open) */
} tds_wfile;

/* Start writing `path`. TDS_OK with w->f open, or TDS_EIO / TDS_ENOMEM
** with a message (nothing created). */
int tds_wfile_open(tds_ctx *ctx, tds_wfile *w, const char *path);

/* Check the stream, flush and fsync it, close it. TDS_OK, or TDS_EIO with a
** message and the temporary file removed. Several files can be closed
** first and committed together (export's per-body files). */
int tds_wfile_close(tds_ctx *ctx, tds_wfile *w);

/* Close if still open, then rename over the target and sync the folder.
** TDS_OK, or TDS_EIO with a message and the temporary file removed.
** w->path stays readable until tds_wfile_abort. */
int tds_wfile_commit(tds_ctx *ctx, tds_wfile *w);

/* Finish with w: close it and remove the temporary file if it was not
** committed, and free everything. Safe after any step, also after commit
** (then it only frees). */
void tds_wfile_abort(tds_wfile *w);

#endif
