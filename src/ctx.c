/* ctx.c: error context, output sinks and allocation helpers. */
#include "tds.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int tds_contract_err(tds_ctx *ctx, const char *file, int line, const char *cond) {
  return tds_seterr(ctx, TDS_EBUG, "%s:%d: broken contract: %s", file, line, cond);
}

void tds_contract_abort(const char *file, int line, const char *cond) {
  fprintf(stderr, "%s:%d: broken contract: %s\n", file, line, cond);
  fflush(stderr);
  abort();
}

void tds_ctx_init(tds_ctx *ctx) {
  memset(ctx, 0, sizeof *ctx);
}

int tds_seterr(tds_ctx *ctx, int rc, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(ctx->errmsg, sizeof ctx->errmsg, fmt, ap);
  va_end(ap);
  return rc;
}

static void emit(tds_out_fn fn, void *ud, FILE *dflt, const char *fmt,
                 va_list ap) {
  char buf[2048];
  vsnprintf(buf, sizeof buf, fmt, ap);
  if (fn)
    fn(ud, buf);
  else {
    fputs(buf, dflt);
    fflush(dflt);
  }
}

void tds_printf(tds_ctx *ctx, const char *fmt, ...) {
  va_list ap;
  if (ctx->quiet) return;
  va_start(ap, fmt);
  emit(ctx->out, ctx->out_ud, stdout, fmt, ap);
  va_end(ap);
}

void tds_warnf(tds_ctx *ctx, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  emit(ctx->warn, ctx->warn_ud, stderr, fmt, ap);
  va_end(ap);
}

static void *sys_alloc(void *ud, void *ptr, size_t n) {
  (void)ud;
  if (n == 0) {
    free(ptr);
    return NULL;
  }
  return realloc(ptr, n);
}

/* Always inlined and never a tail call, so that the hook's caller is the
** public helper and the helper's caller the allocation site (the
** out-of-memory test tells sites apart by these return addresses). */
static inline __attribute__((always_inline)) void *call(const tds_alloc *a, void *p,
                                                        size_t n) {
  if (!a || !a->fn) return sys_alloc(NULL, p, n);
  void *q = a->fn(a->ud, p, n);
  __asm__ volatile("" ::: "memory"); /* keeps this frame on the stack */
  return q;
}

void *tds_malloc(const tds_alloc *a, size_t n) {
  return call(a, NULL, n ? n : 1);
}

void *tds_calloc(const tds_alloc *a, size_t n, size_t size) {
  if (n == 0 || size == 0) n = size = 1;
  if (n > SIZE_MAX / size) return NULL;
  void *p = call(a, NULL, n * size);
  if (p) memset(p, 0, n * size);
  return p;
}

void *tds_realloc(const tds_alloc *a, void *p, size_t n) {
  return call(a, p, n ? n : 1);
}

void *tds_reallocarray(const tds_alloc *a, void *p, size_t n, size_t size) {
  if (n == 0 || size == 0) n = size = 1;
  if (n > SIZE_MAX / size) return NULL;
  return call(a, p, n * size);
}

void tds_free(const tds_alloc *a, void *p) {
  if (p) call(a, p, 0);
}

char *tds_strdup(const tds_alloc *a, const char *s) {
  if (!s) return NULL;
  size_t n = strlen(s) + 1;
  char *d = call(a, NULL, n);
  if (d) memcpy(d, s, n);
  return d;
}

/* The block from the hook has n + 64 + sizeof(void *) bytes; the pointer
** it returned is stored just below the aligned address. */
void *tds_calloc_aligned(const tds_alloc *a, size_t n) {
  if (n > SIZE_MAX - 128) return NULL;
  char *raw = call(a, NULL, n + 64 + sizeof(void *));
  if (!raw) return NULL;
  uintptr_t u = ((uintptr_t)raw + sizeof(void *) + 63) & ~(uintptr_t)63;
  char *p = raw + (u - (uintptr_t)raw);
  memcpy(p - sizeof(void *), &raw, sizeof raw);
  memset(p, 0, n);
  return p;
}

void tds_free_aligned(const tds_alloc *a, void *p) {
  if (!p) return;
  void *raw;
  memcpy(&raw, (char *)p - sizeof(void *), sizeof raw);
  call(a, raw, 0);
}

int tds_grow(const tds_alloc *a, void **p, size_t size, int32_t *cap, int32_t need) {
  if (need <= *cap) return TDS_OK;
  size_t ncap = *cap > 0 ? (size_t)*cap : 16;
  while (ncap < (size_t)need) ncap *= 2;
  if (ncap > INT32_MAX / 4) return TDS_ENOMEM;
  void *q = call(a, *p, ncap * size);
  if (!q) return TDS_ENOMEM;
  memset((char *)q + (size_t)*cap * size, 0, (ncap - (size_t)*cap) * size);
  *p = q;
  *cap = (int32_t)ncap;
  return TDS_OK;
}
