/* jiggle.c: random displacement of the vertices (see jiggle.h). */
#include "jiggle.h"

#include <math.h>

#include "gather.h"
#include "motion.h"
#include "snap.h"
#include "vec3.h"

/* splitmix64: a full-period 64-bit generator, one state word. */
static uint64_t next64(uint64_t *state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15u);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
  return z ^ (z >> 31);
}

double tds_rng_uniform(uint64_t *state) {
  return (double)(next64(state) >> 11) * 0x1.0p-53;
}

/* A standard normal number (Box-Muller; 1 - u keeps the log finite). */
static double normal(uint64_t *state) {
  double u = 1 - tds_rng_uniform(state), w = tds_rng_uniform(state);
  return sqrt(-2 * log(u)) * cos(2 * 3.14159265358979323846 * w);
}

static double mean_edge(const tds_mesh *m) {
  double sum = 0;
  int32_t n = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    tds_corners C;
    tds_gather_edge(m, TDS_OREF(e, 0), &C);
    double d[3];
    v3_sub(d, C.x[1], C.x[0]);
    sum += v3_norm(d);
    n++;
  }
  return n ? sum / n : 0;
}

static int jiggle(tds_ctx *ctx, tds_surf *s, double temperature, const uint8_t *sel,
                  int32_t *nmoved) {
  tds_mesh *m = &s->m;
  double sigma = temperature * mean_edge(m);
  int32_t moved = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_vertex_free(s, v) || m->vbdry[v] != TDS_NONE || (sel && !sel[v])) continue;
    for (int k = 0; k < 3; k++) m->x[v][k] += sigma * normal(&s->rng);
    if (tds_motion_enforce(s, v) != TDS_OK)
      return tds_seterr(ctx, TDS_ENUM, "jiggle: vertex %d could not be projected "
                        "back onto its constraints", (int)v + 1);
    moved++;
  }
  m->coord_gen++;
  if (nmoved) *nmoved = moved;
  return tds_surf_update(ctx, s);
}

int tds_jiggle(tds_ctx *ctx, tds_surf *s, double temperature, const uint8_t *sel,
               int32_t *nmoved) {
  if (!(temperature >= 0 && isfinite(temperature)))
    return tds_seterr(ctx, TDS_ERANGE, "jiggle: the temperature must be a finite "
                      "number >= 0, not %g", temperature);
  uint64_t rng = s->rng;
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc != TDS_OK) return rc;
  rc = tds_snap_end(ctx, s, &sn, jiggle(ctx, s, temperature, sel, nmoved));
  if (rc != TDS_OK) s->rng = rng;
  return rc;
}
