/* ctx.c: error context, output sinks and allocation helpers. */
#include "tds.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

void *tds_calloc(size_t n, size_t size) {
  if (n == 0 || size == 0) n = size = 1;
  return calloc(n, size);
}

int tds_grow(void **p, size_t size, int32_t *cap, int32_t need) {
  if (need <= *cap) return TDS_OK;
  size_t ncap = *cap > 0 ? (size_t)*cap : 16;
  while (ncap < (size_t)need) ncap *= 2;
  if (ncap > INT32_MAX / 4) return TDS_ENOMEM;
  void *q = realloc(*p, ncap * size);
  if (!q) return TDS_ENOMEM;
  memset((char *)q + (size_t)*cap * size, 0, (ncap - (size_t)*cap) * size);
  *p = q;
  *cap = (int32_t)ncap;
  return TDS_OK;
}
