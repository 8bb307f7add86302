/* progress.c: live progress line and iteration history (progress.h). */
#include "progress.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define HIST_CAP_MAX (1 << 20) /* entries kept before thinning */
#define REDRAW 0.25            /* seconds between redraws */

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void tds_progress_init(tds_progress *p) {
  memset(p, 0, sizeof *p);
  p->stride = 1;
}

void tds_progress_free(tds_progress *p) {
  tds_alloc al = p->alloc;
  tds_free(&al, p->iter);
  tds_free(&al, p->energy);
  tds_free(&al, p->value);
  tds_free(&al, p->kinds);
  int tty = p->tty, verbose = p->verbose;
  tds_progress_init(p);
  p->alloc = al;
  p->tty = tty;
  p->verbose = verbose;
}

void tds_progress_clear(tds_progress *p) {
  p->n = 0;
  p->count = 0;
  p->stride = 1;
}

/* Append one entry; on allocation failure the history just stops
** growing (it is a convenience, never a reason to fail a run). */
static void record(tds_progress *p, char kind, double energy, double value) {
  p->count++;
  if ((p->count - 1) % p->stride) return;
  if (p->n == p->cap) {
    if (p->cap >= HIST_CAP_MAX) {
      int32_t j = 0;
      for (int32_t i = 0; i < p->n; i += 2, j++) {
        p->iter[j] = p->iter[i];
        p->energy[j] = p->energy[i];
        p->value[j] = p->value[i];
        p->kinds[j] = p->kinds[i];
      }
      p->n = j;
      p->stride *= 2;
      if ((p->count - 1) % p->stride) return;
    } else {
      int32_t nc = p->cap ? 2 * p->cap : 1024;
      double *a = tds_realloc(&p->alloc, p->iter, (size_t)nc * sizeof *a);
      if (a) p->iter = a;
      double *b = a ? tds_realloc(&p->alloc, p->energy, (size_t)nc * sizeof *b) : NULL;
      if (b) p->energy = b;
      double *c = b ? tds_realloc(&p->alloc, p->value, (size_t)nc * sizeof *c) : NULL;
      if (c) p->value = c;
      char *d = c ? tds_realloc(&p->alloc, p->kinds, (size_t)nc) : NULL;
      if (!d) return;
      p->kinds = d;
      p->cap = nc;
    }
  }
  p->iter[p->n] = (double)p->count;
  p->energy[p->n] = energy;
  p->value[p->n] = value;
  p->kinds[p->n] = kind;
  p->n++;
}

void tds_progress_begin(tds_ctx *ctx, char kind, int64_t total) {
  tds_progress *p = ctx->progress;
  if (!p) return;
  p->kind = kind;
  p->total = total > 0 ? total : 0;
  p->live = p->tty && !p->verbose && !ctx->quiet;
  p->t0 = p->tdraw = now();
  p->skipped = 0;
  p->width = 0;
}

static void duration(char *buf, size_t n, double s) {
  if (s < 60) snprintf(buf, n, "%.0fs", s);
  else if (s < 3600) snprintf(buf, n, "%dm%02ds", (int)(s / 60), (int)fmod(s, 60));
  else snprintf(buf, n, "%dh%02dm", (int)(s / 3600), (int)fmod(s / 60, 60));
}

void tds_progress_format(char *buf, size_t n, char kind, int64_t k,
                         int64_t total, double energy, double value,
                         double secs) {
  char it[48], left[32] = "";
  if (total > 0) snprintf(it, sizeof it, "%lld/%lld", (long long)k, (long long)total);
  else snprintf(it, sizeof it, "%lld", (long long)k);
  double rate = secs > 0 ? (double)k / secs : 0;
  if (total > 0 && rate > 0) {
    char d[24];
    duration(d, sizeof d, (double)(total - k) / rate);
    snprintf(left, sizeof left, "  %s left", d);
  }
  snprintf(buf, n, "%s %s  energy %.12g  %s %.4g  %.3g it/s%s",
           kind == 'p' ? "pg" : "g", it, energy, kind == 'p' ? "r" : "scale",
           value, rate, left);
}

int tds_progress_step(tds_ctx *ctx, int64_t k, double energy, double value) {
  tds_progress *p = ctx->progress;
  if (!p) return 0;
  record(p, p->kind, energy, value);
  if (!p->live) return 0;
  p->skipped++;
  double t = now();
  if (t - p->tdraw >= REDRAW) {
    char line[256];
    tds_progress_format(line, sizeof line, p->kind, k, p->total, energy, value,
                        t - p->t0);
    int len = (int)strlen(line);
    int pad = p->width > len ? p->width - len : 0;
    tds_printf(ctx, "\r%s%*s", line, pad, "");
    p->width = len;
    p->tdraw = t;
  }
  return 1;
}

void tds_progress_erase(tds_ctx *ctx) {
  tds_progress *p = ctx->progress;
  if (p && p->live && p->width > 0) tds_printf(ctx, "\r%*s\r", p->width, "");
  if (p) p->width = 0;
}

int64_t tds_progress_end(tds_ctx *ctx) {
  tds_progress *p = ctx->progress;
  if (!p) return 0;
  tds_progress_erase(ctx);
  int64_t n = p->skipped;
  p->live = 0;
  p->skipped = 0;
  p->width = 0;
  return n;
}
