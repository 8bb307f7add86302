/* wfile.c: all-or-nothing file writing (contract in wfile.h). */
#define _XOPEN_SOURCE 700 /* realpath */
#include "wfile.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#ifndef O_NOFOLLOW
#define O_NOFOLLOW 0
#endif
#ifndef O_CLOEXEC
#define O_CLOEXEC 0
#endif

static void release(tds_wfile *w) {
  tds_free(&w->alloc, w->path);
  tds_free(&w->alloc, w->tmp);
  w->path = w->tmp = NULL;
  w->f = NULL;
}

/* The directory part of path ("." if none), from allocator a. */
static char *dir_of(const tds_alloc *a, const char *path) {
  const char *slash = strrchr(path, '/');
  if (!slash) return tds_strdup(a, ".");
  if (slash == path) return tds_strdup(a, "/");
  size_t n = (size_t)(slash - path);
  char *d = tds_malloc(a, n + 1);
  if (d) {
    memcpy(d, path, n);
    d[n] = 0;
  }
  return d;
}

/* May this process replace an existing file of mode st? root may write
** anything, so for root a file without any write bit counts as read-only
** (what a user marks 0444 must not be replaced silently). */
static int writable(const char *path, const struct stat *st) {
  if (geteuid() == 0) return (st->st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) != 0;
  return access(path, W_OK) == 0;
}

int tds_wfile_open(tds_ctx *ctx, tds_wfile *w, const char *path) {
  memset(w, 0, sizeof *w);
  w->alloc = ctx->alloc;
  if (!*path) return tds_seterr(ctx, TDS_EIO, "cannot write '': empty file name");
  struct stat st;
  mode_t mode = 0666; /* the umask applies to a new file */
  int exists = 0;
  if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode)) {
    /* write through the link: the file it names is replaced */
    char real[PATH_MAX];
    if (realpath(path, real)) {
      w->path = tds_strdup(&w->alloc, real);
      if (!w->path) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    } else if (errno != ENOENT) {
      return tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", path, strerror(errno));
    }
  }
  if (!w->path) w->path = tds_strdup(&w->alloc, path);
  if (!w->path) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  if (stat(w->path, &st) == 0) {
    exists = 1;
    if (!S_ISREG(st.st_mode)) {
      release(w);
      return tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", path,
                        S_ISDIR(st.st_mode) ? "it is a directory" : "not a regular file");
    }
    if (!writable(w->path, &st)) {
      release(w);
      return tds_seterr(ctx, TDS_EIO, "cannot write '%s': the file is read-only", path);
    }
    mode = st.st_mode & 07777;
  }
  char *dir = dir_of(&w->alloc, w->path);
  const char *base = strrchr(w->path, '/');
  base = base ? base + 1 : w->path;
  size_t n = (dir ? strlen(dir) : 0) + strlen(base) + 64;
  w->tmp = dir ? tds_malloc(&w->alloc, n) : NULL;
  if (!w->tmp) {
    tds_free(&w->alloc, dir);
    release(w);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  struct timespec ts;
  clock_gettime(CLOCK_REALTIME, &ts);
  int fd = -1, err = 0;
  for (int attempt = 0; attempt < 100 && fd < 0; attempt++) {
    snprintf(w->tmp, n, "%s/.%s.%ld-%lx-%d.tmp", dir, base, (long)getpid(),
             (unsigned long)ts.tv_nsec ^ (unsigned long)(uintptr_t)w, attempt);
    fd = open(w->tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, exists ? 0600 : mode);
    err = errno;
    if (fd < 0 && err != EEXIST) break;
  }
  tds_free(&w->alloc, dir);
  if (fd < 0) {
    int rc = tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", path, strerror(err));
    release(w);
    return rc;
  }
  /* the new file gets the old one's permission bits (after the exclusive
  ** create, so no one else could open it meanwhile) */
  /* and, where allowed (root), its owner; elsewhere the writer owns it */
  if (exists && (st.st_uid != geteuid() || st.st_gid != getegid()) &&
      fchown(fd, st.st_uid, st.st_gid) != 0) {
    /* not permitted: the file stays the writer's */
  }
  if (exists && fchmod(fd, mode) != 0) {
    int e = errno;
    close(fd);
    unlink(w->tmp);
    int rc = tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", path, strerror(e));
    release(w);
    return rc;
  }
  w->f = fdopen(fd, "w");
  if (!w->f) {
    int e = errno;
    close(fd);
    unlink(w->tmp);
    release(w);
    return tds_seterr(ctx, TDS_ENOMEM, "cannot write '%s': %s", path, strerror(e));
  }
  return TDS_OK;
}

void tds_wfile_abort(tds_wfile *w) {
  if (w->f) fclose(w->f);
  if (w->tmp) unlink(w->tmp);
  release(w);
}

/* The temporary is gone (failed or renamed): forget its name. */
static void drop_tmp(tds_wfile *w, int remove) {
  if (remove) unlink(w->tmp);
  tds_free(&w->alloc, w->tmp);
  w->tmp = NULL;
}

int tds_wfile_close(tds_ctx *ctx, tds_wfile *w) {
  if (!w->f) return TDS_OK;
  int err = 0;
  if (fflush(w->f) != 0 || ferror(w->f)) err = errno ? errno : EIO;
  if (!err && fsync(fileno(w->f)) != 0) err = errno;
  if (fclose(w->f) != 0 && !err) err = errno;
  w->f = NULL;
  if (!err) return TDS_OK;
  drop_tmp(w, 1);
  return tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", w->path, strerror(err));
}

int tds_wfile_commit(tds_ctx *ctx, tds_wfile *w) {
  int rc = tds_wfile_close(ctx, w);
  if (rc != TDS_OK) return rc;
  if (!w->tmp) return tds_seterr(ctx, TDS_EIO, "cannot write '%s': nothing to commit", w->path);
  if (rename(w->tmp, w->path) != 0) {
    int e = errno;
    drop_tmp(w, 1);
    return tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", w->path, strerror(e));
  }
  drop_tmp(w, 0);
  /* make the rename itself durable (the folder's name on the stack, so
  ** that running out of memory cannot skip it) */
  char dir[PATH_MAX];
  const char *slash = strrchr(w->path, '/');
  size_t n = slash ? (size_t)(slash - w->path) : 0;
  if (slash == w->path) n = 1; /* "/" */
  if (n < sizeof dir) {
    memcpy(dir, slash ? w->path : ".", slash ? n : 1);
    dir[slash ? n : 1] = 0;
    int dfd = open(dir, O_RDONLY | O_CLOEXEC);
    if (dfd >= 0) {
      fsync(dfd);
      close(dfd);
    }
  }
  return TDS_OK;
}
