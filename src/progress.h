/*
** progress.h: the live progress line of long runs and the iteration
** history of the session (for `plot`).
**
** A tds_progress is owned by the program (the Lua state) and hung on
** ctx->progress; without one the iteration loops behave as before (one
** line per iteration unless quiet, nothing recorded). The loops call
** tds_progress_begin, then tds_progress_step after every iteration, which
** records it and, when the live line is on (a terminal, not quiet, not
** verbose), redraws one line ending in '\r' at most four times a second;
** it returns nonzero when the caller should skip its per-iteration line.
** tds_progress_end erases the live line.
*/
#ifndef TDS_PROGRESS_H
#define TDS_PROGRESS_H

#include "tds.h"

typedef struct tds_progress {
  int tty;            /* output is a terminal (set by the program) */
  int verbose;        /* per-iteration lines even on a terminal */
  /* the current run */
  char kind;          /* 'g' or 'p' (pg) */
  int live;           /* the live line is in charge of this run */
  int64_t total;      /* iterations asked for (0: until converged) */
  double t0, tdraw;   /* start, last redraw (seconds, monotonic) */
  int64_t skipped;    /* per-iteration lines the live line replaced */
  int width;          /* characters of the line on screen */
  /* the history: session iteration number, kind, energy and scale (g) or
  ** r (pg); thinned to every other entry when cap is reached */
  int64_t count;      /* iterations recorded this session */
  int64_t stride;     /* record every stride-th iteration (1, 2, 4, ...) */
  int32_t n, cap;
  double *iter, *energy, *value;
  char *kinds;
  tds_alloc alloc;    /* of the history (zero: C library; free keeps it) */
} tds_progress;

void tds_progress_init(tds_progress *p);
void tds_progress_free(tds_progress *p);
/* Forget the history (a new surface). */
void tds_progress_clear(tds_progress *p);

/* Start a run of `total` iterations (0: unknown) of kind 'g' or 'p'. */
void tds_progress_begin(tds_ctx *ctx, char kind, int64_t total);

/* Iteration k (1-based) of the run is done with this energy and scale
** (g) or r (pg). Returns nonzero when the live line shows it. */
int tds_progress_step(tds_ctx *ctx, int64_t k, double energy, double value);

/* Erase the live line (before a message of its own line); it is drawn
** again at the next redraw. */
void tds_progress_erase(tds_ctx *ctx);

/* End the run: erase the live line. Returns the number of per-iteration
** lines it replaced (the caller may print the last one). */
int64_t tds_progress_end(tds_ctx *ctx);

/* The line drawn for iteration k after `secs` seconds (for tests too). */
void tds_progress_format(char *buf, size_t n, char kind, int64_t k,
                         int64_t total, double energy, double value,
                         double secs);

#endif
