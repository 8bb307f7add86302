/*
** snap.h: a copy of everything a command may change, so that a failing
** command puts the surface back exactly as it was (commands are
** all-or-nothing; doc/reliability.md).
**
** A snapshot holds the whole mesh (coordinates, topology, flags, body
** pressures and volumes), the quantities' values and multipliers, the
** scale, the iteration counter, the last totals and the conjugate-gradient
** history. The model (parameters, constraints, quantities' definitions) is
** not copied: commands do not change it.
*/
#ifndef TDS_SNAP_H
#define TDS_SNAP_H

#include "surf.h"

typedef struct tds_snap {
  int taken;
  tds_mesh m;
  double scale, energy, area, cg_norm2;
  int64_t iterations;
  uint64_t placed_gen;      /* recalc state of the coordinates (recalc.h) */
  int nquant;
  double (*quant)[2];       /* value, pressure of each quantity */
  int32_t cg_nv;
  uint64_t cg_topo;
  double (*cg_dir)[3], (*cg_prev)[3];
  struct tds_strings *str;  /* the string model's cells, or NULL */
  tds_alloc alloc;          /* the surface's allocator */
} tds_snap;

/* Copy the surface's changeable state into sn. TDS_OK or TDS_ENOMEM
** (then sn holds nothing). */
int tds_snap_take(tds_ctx *ctx, const tds_surf *s, tds_snap *sn);

/* Put the surface back to the snapshot and release it. Generation counters
** move forward (never back), so caches built meanwhile are seen as stale. */
void tds_snap_restore(tds_surf *s, tds_snap *sn);

/* End a command that took sn: on success (TDS_OK) or interruption
** (TDS_EINTR: the completed steps are kept) release the snapshot; on any
** other failure put the surface back and add "; the surface is as before
** the command" to the message. Returns rc. */
int tds_snap_end(tds_ctx *ctx, tds_surf *s, tds_snap *sn, int rc);

/* Run a selection command fn(ctx, s, sel, &count) all or nothing under a
** snapshot: *n gets the count on success, 0 on failure (n may be NULL). */
typedef int (*tds_snap_cmd)(tds_ctx *ctx, tds_surf *s, const uint8_t *sel, int32_t *n);
int tds_snap_run(tds_ctx *ctx, tds_surf *s, tds_snap_cmd fn, const uint8_t *sel, int32_t *n);

/* Release a snapshot that is not needed (the command succeeded). */
void tds_snap_free(tds_snap *sn);

/* TDS_OK if the surface equals the snapshot bit for bit (live elements,
** their attributes, coordinates, pressures, quantities, scale, iteration
** count); otherwise TDS_ENUM with ctx->errmsg naming the first difference. */
int tds_snap_same(tds_ctx *ctx, const tds_surf *s, const tds_snap *sn);

/* TDS_OK if the state is finite: every coordinate, boundary parameter,
** tension, surface parameter, body target, pressure, density and volconst,
** quantity target and multiplier, the gravity constant, scale and scale
** limit; with `derived`, also what the last evaluation computed (energy,
** area, body volumes, quantity values), which a model can make non-finite
** at a legal shape (1/x at x = 0), so only a command that succeeded
** vouches for it. Otherwise TDS_ENUM naming the first that is not. */
int tds_surf_all_finite(tds_ctx *ctx, const tds_surf *s, int derived);

#endif
