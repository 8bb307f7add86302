/*
** tds.h: shared types, status codes and the error context of the core.
**
** The core (every src/ file that is not lua_*.c, repl.c or main.c) never
** includes lua.h, never exits and keeps no globals. Functions return a
** status code; on failure the message is in ctx->errmsg (SQLite style).
*/
#ifndef TDS_H
#define TDS_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#define TDS_VERSION "0.1.0"

typedef int32_t tds_id;    /* element index, 0-based in C; TDS_NONE if absent */
#define TDS_NONE (-1)

/* An oriented reference packs an index and a reversal bit (Evolver's sign). */
#define TDS_OREF(id, rev) (((id) << 1) | ((rev) ? 1 : 0))
#define TDS_OID(r) ((r) >> 1)
#define TDS_OREV(r) ((r) & 1)
#define TDS_OFLIP(r) ((r) ^ 1)

enum {
  TDS_OK = 0,
  TDS_ENOMEM,   /* allocation failed */
  TDS_EIO,      /* file could not be read or written */
  TDS_ESYNTAX,  /* malformed input (datafile, expression) */
  TDS_ETOPO,    /* topology operation refused or mesh inconsistent */
  TDS_ERANGE,   /* argument out of range, element does not exist */
  TDS_EINTR,    /* interrupted by the user (Ctrl-C) */
  TDS_ENUM,     /* numerical failure (NaN, singular system) */
  TDS_EBUG      /* a contract of the core was broken (TDS_REQUIRE) */
};

/* Runtime contract checks, compiled in with -DTDS_CHECKS (the unit tests,
** `make test-asan` and the fuzzers; not the program, so `g` runs at full
** speed). Both evaluate nothing without TDS_CHECKS.
**
** TDS_REQUIRE(ctx, cond), in a function that returns a status: if cond is
** false, the function returns TDS_EBUG with "file:line: broken contract:
** cond" in ctx->errmsg (the caller sees an error, the process goes on).
** Use it at the entry of the public functions that take a ctx.
**
** TDS_ASSERT(cond), anywhere else (no ctx or no status to return): if cond
** is false, print "file:line: broken contract: cond" on stderr and abort()
** (a fuzzer or the test run reports it with the stack). */
#ifdef TDS_CHECKS
#define TDS_REQUIRE(ctx, cond)                                              \
  do {                                                                      \
    if (!(cond)) return tds_contract_err((ctx), __FILE__, __LINE__, #cond); \
  } while (0)
#define TDS_ASSERT(cond) \
  ((cond) ? (void)0 : tds_contract_abort(__FILE__, __LINE__, #cond))
#else
#define TDS_REQUIRE(ctx, cond) ((void)0)
#define TDS_ASSERT(cond) ((void)0)
#endif
struct tds_ctx;
/* The failure paths of TDS_REQUIRE and TDS_ASSERT (always compiled, so
** checked and unchecked objects link together). */
int tds_contract_err(struct tds_ctx *ctx, const char *file, int line, const char *cond);
void tds_contract_abort(const char *file, int line, const char *cond)
    __attribute__((noreturn));

/* The allocator hook (like lua_Alloc): one function with realloc's
** contract. ptr NULL allocates n bytes; n == 0 frees ptr and returns NULL;
** otherwise ptr is resized to n bytes. On failure it returns NULL and ptr
** stays valid. ud is the hook's own state. fn NULL means the C library.
**
** Every allocation of the core goes through a hook: the one in the ctx
** (ctx->alloc) for memory a call uses and releases, the one a mesh carries
** (m->alloc; a surface's is s->m.alloc) for memory the mesh or surface
** keeps, and the one an object (expression, pair set, sparse matrix, ...)
** was made with, which it keeps to free itself. A surface must be used
** with contexts that have the same hook as the surface (both are the C
** library unless a test installs one; doc/design.md "Memory"). */
typedef void *(*tds_alloc_fn)(void *ud, void *ptr, size_t n);
typedef struct tds_alloc {
  tds_alloc_fn fn;
  void *ud;
} tds_alloc;

/* Where progress lines and warnings go; the REPL and tests may capture them. */
typedef void (*tds_out_fn)(void *ud, const char *text);

struct tds_progress;                 /* progress.h */

typedef struct tds_ctx {
  char errmsg[1024];                 /* message of the last failure */
  volatile sig_atomic_t interrupt;   /* set asynchronously (SIGINT); polled */
  tds_out_fn out;                    /* progress output; NULL = stdout */
  void *out_ud;
  tds_out_fn warn;                   /* warnings; NULL = stderr */
  void *warn_ud;
  int quiet;                         /* suppress progress lines */
  /* Called after every iteration of a long command (g, pg) on the thread
  ** running it, between iterations (the surface is consistent); energy is
  ** that iteration's. NULL = none. The live view publishes through it. */
  void (*step)(void *ud, double energy);
  void *step_ud;
  struct tds_progress *progress;     /* live line and history, or NULL */
  tds_alloc alloc;                   /* allocator hook (zero: C library) */
} tds_ctx;

/* Initialise a context with default sinks. */
void tds_ctx_init(tds_ctx *ctx);

/* Store a formatted message in ctx->errmsg and return rc. */
int tds_seterr(tds_ctx *ctx, int rc, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Print a formatted progress line (or any text) through ctx->out. */
void tds_printf(tds_ctx *ctx, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Emit a formatted warning through ctx->warn. */
void tds_warnf(tds_ctx *ctx, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Nonzero when two hooks are the same (same function and state). */
static inline int tds_alloc_same(const tds_alloc *a, const tds_alloc *b) {
  return a->fn == b->fn && a->ud == b->ud;
}

/* The allocation helpers; a NULL or zero-initialised `a` is the C library.
** tds_malloc, tds_calloc (zero-filled; n*size checked) and tds_realloc
** return NULL on failure (tds_realloc leaves p valid); a zero size
** allocates one byte, so NULL always means failure. tds_free(a, NULL) is a
** no-op. tds_strdup copies a string (NULL on failure or if s is NULL). */
void *tds_malloc(const tds_alloc *a, size_t n);
void *tds_calloc(const tds_alloc *a, size_t n, size_t size);
void *tds_realloc(const tds_alloc *a, void *p, size_t n);
void tds_free(const tds_alloc *a, void *p);
char *tds_strdup(const tds_alloc *a, const char *s);
/* tds_realloc of n elements of `size` bytes (n*size checked). */
void *tds_reallocarray(const tds_alloc *a, void *p, size_t n, size_t size);

/* n zero-filled bytes on a 64-byte boundary (a cache line), NULL on
** failure; release with tds_free_aligned (NULL is a no-op). */
void *tds_calloc_aligned(const tds_alloc *a, size_t n);
void tds_free_aligned(const tds_alloc *a, void *p);

/* Grow *p (element size `size`) from capacity *cap to at least `need`
** elements, zero-filling the new part. Returns TDS_OK or TDS_ENOMEM (on
** failure *p and *cap are untouched). */
int tds_grow(const tds_alloc *a, void **p, size_t size, int32_t *cap, int32_t need);

#endif
