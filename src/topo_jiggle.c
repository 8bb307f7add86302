/* topo_jiggle.c: j / jiggle, a seeded random displacement of the free
** vertices (simulated annealing, shaking a surface out of a rut). */
#include "topo_edit.h"

#include <math.h>

#include "gather.h"
#include "motion.h"
#include "snap.h"
#include "vec3.h"

/* splitmix64: a full-period 64-bit generator; the stream depends only on
** the seed, so a jiggle is reproducible. */
static uint64_t next(uint64_t *st) {
  uint64_t z = (*st += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/* Uniform in (0, 1). */
static double uniform(uint64_t *st) {
  return ((double)(next(st) >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/* Standard normal (Box-Muller; one of the pair is used). */
static double gauss(uint64_t *st) {
  double u = uniform(st), v = uniform(st);
  return sqrt(-2 * log(u)) * cos(2 * TDS_PI * v);
}

static int jiggle(tds_ctx *ctx, tds_surf *s, double temp, uint64_t *rng, int32_t *n) {
  tds_mesh *m = &s->m;
  double sum = 0;
  int32_t ne = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    tds_corners C;
    tds_gather_edge(m, TDS_OREF(e, 0), &C);
    double d[3];
    v3_sub(d, C.x[1], C.x[0]);
    sum += v3_norm(d);
    ne++;
  }
  double sigma = ne ? temp * sum / ne : 0;
  int32_t cnt = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_alive(m->vflags, v) || (m->vflags[v] & TDS_FIXED) || m->vbdry[v] != TDS_NONE)
      continue;
    for (int k = 0; k < 3; k++) m->x[v][k] += sigma * gauss(rng);
    if (tds_motion_enforce(s, v) != TDS_OK)
      return tds_seterr(ctx, TDS_ENUM, "jiggle: vertex %d could not be projected back "
                        "onto its constraints", v + 1);
    cnt++;
  }
  m->coord_gen++;
  *n = cnt;
  return tds_surf_update(ctx, s);
}

int tds_jiggle(tds_ctx *ctx, tds_surf *s, double temp, uint64_t *rng, int32_t *n) {
  if (n) *n = 0;
  if (!isfinite(temp) || temp < 0)
    return tds_seterr(ctx, TDS_ERANGE, "jiggle: the temperature must be a finite "
                      "number >= 0, not %g", temp);
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  int32_t cnt = 0;
  uint64_t st = *rng;
  rc = tds_snap_end(ctx, s, &sn, jiggle(ctx, s, temp, &st, &cnt));
  if (rc == TDS_OK) *rng = st;
  if (n) *n = rc == TDS_OK ? cnt : 0;
  return rc;
}
