/* atomic.c: temporary file + rename (contract in atomic.h). */
#include "atomic.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

int tds_afile_open(tds_ctx *ctx, tds_afile *af, const char *path) {
  size_t n = strlen(path);
  af->f = NULL;
  af->path = malloc(n + 1);
  af->tmp = malloc(n + 5);
  if (!af->path || !af->tmp) {
    free(af->path);
    free(af->tmp);
    af->path = af->tmp = NULL;
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  memcpy(af->path, path, n + 1);
  memcpy(af->tmp, path, n);
  memcpy(af->tmp + n, ".tmp", 5);
  af->f = fopen(af->tmp, "wb");
  if (!af->f) {
    int rc = tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", af->tmp, strerror(errno));
    free(af->path);
    free(af->tmp);
    af->path = af->tmp = NULL;
    return rc;
  }
  return TDS_OK;
}

int tds_afile_close(tds_ctx *ctx, tds_afile *af) {
  if (!af->f) return TDS_OK;
  int err = ferror(af->f);
  int saved = errno;
  if (fclose(af->f) != 0 && !err) {
    err = 1;
    saved = errno;
  }
  af->f = NULL;
  if (err)
    return tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", af->tmp,
                      saved ? strerror(saved) : "write error");
  return TDS_OK;
}

int tds_afile_commit(tds_ctx *ctx, tds_afile *af) {
  if (rename(af->tmp, af->path) != 0)
    return tds_seterr(ctx, TDS_EIO, "cannot rename '%s' to '%s': %s", af->tmp,
                      af->path, strerror(errno));
  free(af->tmp);
  af->tmp = NULL;
  return TDS_OK;
}

void tds_afile_abort(tds_afile *af) {
  if (af->f) fclose(af->f);
  af->f = NULL;
  if (af->tmp) remove(af->tmp);
  free(af->tmp);
  free(af->path);
  af->tmp = af->path = NULL;
}
