/* eval_torus.c: the torus model's facet pass (facet tension, the bodies'
** lifted volumes and prescribed pressures) without Hessians, the hot loop
** of g on a periodic foam.
**
** The same numbers, in the same order, as eval.c's general assembly with
** facet_area fused with the lifted tds_mk_volume_zshift (s_tension and
** s_volume_lift): per facet the area to the energy (weight: the
** tension), then per side j (0 front, 1 back) the facet's volume
** translated by its body's lift, +-1 to the body's volume (and its fixq
** gradient through fixq.h's emap) and -+p to the energy for a body with
** a prescribed pressure.
**
** What costs there is not the arithmetic but the bookkeeping around it:
** unpacking four packed wraps per facet (two corners, two lifts), each
** times the periods, and the general loop's sink lists. Here the wraps a
** facet uses are numbered once per topology (the plan: a byte per corner
** and side into a table of the distinct wraps, rarely more than a few
** dozen), the table's translations are computed once per evaluation, and
** the sides are plain code. Each translation is the same expression as
** gather.h's (k0 p0 + k1 p1 + k2 p2, negated for an edge used backwards:
** the negation is exact), so the corners, and everything after them, are
** the general loop's bit for bit.
*/
#include "eval.h"

#include "geom.h"
#include "torus.h"
#include "vec3.h"

#define TDS_TPLAN_MAX 255 /* distinct wraps a plan numbers (a byte each) */

/* The plan (surf.h's tplan): code[f] = {corner 1, corner 2, side 0's
** lift, side 1's lift}, each an index into wrap[] (0: no translation). */
struct tds_tplan {
  uint64_t gen; /* topo_gen it was made for */
  int32_t nf;
  int nw;
  int32_t wrap[TDS_TPLAN_MAX];
  uint8_t code[][4];
};

/* The index of packed wrap w in p->wrap, added if new; -1 when full. */
static int code_of(struct tds_tplan *p, int32_t w) {
  for (int i = 0; i < p->nw; i++)
    if (p->wrap[i] == w) return i;
  if (p->nw == TDS_TPLAN_MAX) return -1;
  p->wrap[p->nw] = w;
  return p->nw++;
}

/* s->tplan for the mesh as it is (s->tlift current): 1, or 0 when it
** cannot be made (out of memory, too many distinct wraps). */
static int make_plan(tds_surf *s) {
  tds_mesh *m = &s->m;
  struct tds_tplan *p = s->tplan;
  if (p && p->gen == m->topo_gen && p->nf == m->nf) return 1;
  if (!p || p->nf < m->nf) {
    tds_free(&m->alloc, p);
    s->tplan = p = tds_malloc(&m->alloc, sizeof *p + (size_t)(m->nf > 0 ? m->nf : 1) * 4);
    if (!p) return 0;
  }
  p->gen = 0; /* not valid until made */
  p->nf = m->nf;
  p->nw = 1;
  p->wrap[0] = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    const int32_t *fe = m->fe[f];
    int32_t w1 = m->ewrap[TDS_OID(fe[0])], w2 = m->ewrap[TDS_OID(fe[2])];
    int32_t w[4] = {TDS_OREV(fe[0]) ? tds_wrap_neg(w1) : w1,
                    TDS_OREV(fe[2]) ? w2 : tds_wrap_neg(w2), s->tlift[2 * f],
                    s->tlift[2 * f + 1]};
    for (int k = 0; k < 4; k++) {
      int c = code_of(p, w[k]);
      if (c < 0) return 0;
      p->code[f][k] = (uint8_t)c;
    }
  }
  p->gen = m->topo_gen;
  return 1;
}

/* One side of facet f: body bd, sign +-1, lift tz along z. geom.h's
** geom_volume_zshift written out on the facet's shared parts (zsum =
** a_z + b_z + c_z, Nz, and per corner k dy[k], dx[k], the differences of
** the next two corners' y and x), so that its gradient stays in
** registers: through an array the scatter's loads straddled the
** kernel's stores, which costs a stall each (a quarter of the pass). */
static inline __attribute__((always_inline)) void
side(tds_surf *s, tds_eval_out *out, const int32_t *emap, tds_id f, int j, tds_id bd,
     double sign, double tz, double zsum, double Nz, const double dy[3], const double dx[3],
     double *vtotal) {
  tds_mesh *m = &s->m;
  tds_fixq *fq = out->fq;
  int32_t q = fq ? fq->bq[bd] : -1;
  int press = (m->bflags[bd] & TDS_PRESSURE) != 0;
  double zs = zsum + 3 * tz;
  double V = zs * Nz / 6;
  m->bvol[bd] += sign * V;
  double w = press ? -sign * m->bpressure[bd] : 0;
  if (press) *vtotal += w * V; /* the general loop's pressure sink: the same value */
  if (!(q >= 0 || (press && out->grad))) return;
  double zs6 = zs / 6, nz6 = Nz / 6;
  double gx[3] = {zs6 * dy[0], zs6 * dy[1], zs6 * dy[2]};
  double gy[3] = {zs6 * dx[0], zs6 * dx[1], zs6 * dx[2]};
  const tds_id *vs = m->fv[f];
  if (q >= 0 && emap) { /* unrolled, so that nothing goes through memory */
    const int32_t *mp = emap + 6 * f + 3 * j;
    double *e0 = fq->g[mp[0]], *e1 = fq->g[mp[1]], *e2 = fq->g[mp[2]];
    e0[0] += sign * gx[0], e0[1] += sign * gy[0], e0[2] += sign * nz6;
    e1[0] += sign * gx[1], e1[1] += sign * gy[1], e1[2] += sign * nz6;
    e2[0] += sign * gx[2], e2[1] += sign * gy[2], e2[2] += sign * nz6;
  } else if (q >= 0) {
    for (int k = 0; k < 3; k++) {
      double gc[3] = {sign * gx[k], sign * gy[k], sign * nz6};
      tds_fixq_add(fq, vs[k], q, gc);
    }
  }
  for (int k = 0; press && out->grad && k < 3; k++) {
    double gc[3] = {gx[k], gy[k], nz6};
    v3_axpy(out->grad[vs[k]], w, gc);
  }
}

/* r += ten (d x n) / 2: a corner's part of geom_area's gradient, times
** the tension, as v3_cross, v3_scale and v3_axpy compute it. */
static inline __attribute__((always_inline)) void
add_area_grad(double *r, double ten, const double d[3], const double n[3]) {
  double x = d[1] * n[2] - d[2] * n[1];
  double y = d[2] * n[0] - d[0] * n[2];
  double z = d[0] * n[1] - d[1] * n[0];
  r[0] += ten * (x * 0.5);
  r[1] += ten * (y * 0.5);
  r[2] += ten * (z * 0.5);
}

int tds_eval_torus_facets(tds_surf *s, tds_eval_out *out) {
  tds_mesh *m = &s->m;
  if (!m->ewrap || !s->tlift || !make_plan(s)) return 0;
  const struct tds_tplan *p = s->tplan;
  double T[TDS_TPLAN_MAX][3]; /* the translations of the plan's wraps */
  for (int i = 0; i < p->nw; i++) {
    int k[3];
    tds_wrap_unpack(p->wrap[i], k);
    for (int j = 0; j < 3; j++)
      T[i][j] = k[0] * m->period[0][j] + k[1] * m->period[1][j] + k[2] * m->period[2][j];
  }
  tds_fixq *fq = out->fq;
  double (*grad)[3] = out->grad;
  const int32_t *emap = fq && fq->emap_kind == TDS_EL_FACET ? fq->emap : NULL;
  double tsum = 0, ttotal = 0, vtotal = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    uint32_t fl = m->fflags[f];
    if (fl & TDS_DEAD) continue;
    const tds_id *vs = m->fv[f];
    const uint8_t *cd = p->code[f];
    double y[3][3];
    const double *x0 = m->x[vs[0]], *x1 = m->x[vs[1]], *x2 = m->x[vs[2]];
    const double *t1 = T[cd[0]], *t2 = T[cd[1]];
    for (int j = 0; j < 3; j++) {
      y[0][j] = x0[j];
      y[1][j] = x1[j] + t1[j];
      y[2][j] = x2[j] + t2[j];
    }
    double A;
    double ten = m->ften[f];
    if (grad) { /* geom_area with its gradient, written out (see side()) */
      double ab[3], ac[3], N[3], n[3] = {0, 0, 0}, d[3];
      v3_sub(ab, y[1], y[0]);
      v3_sub(ac, y[2], y[0]);
      v3_cross(N, ab, ac);
      double len = v3_norm(N);
      if (len > 0) n[0] = N[0] / len, n[1] = N[1] / len, n[2] = N[2] / len;
      A = 0.5 * len;
      v3_sub(d, y[1], y[2]);
      add_area_grad(grad[vs[0]], ten, d, n);
      v3_sub(d, y[2], y[0]);
      add_area_grad(grad[vs[1]], ten, d, n);
      v3_sub(d, y[0], y[1]);
      add_area_grad(grad[vs[2]], ten, d, n);
    } else {
      A = geom_area(y[0], y[1], y[2], NULL);
    }
    tsum += A;
    ttotal += ten * A;
    if (fl & TDS_NONCONTENT) continue;
    /* geom_volume_zshift's parts that both sides share */
    double zsum = y[0][2] + y[1][2] + y[2][2];
    double Nz = (y[1][0] - y[0][0]) * (y[2][1] - y[0][1]) - (y[1][1] - y[0][1]) * (y[2][0] - y[0][0]);
    double dy[3] = {y[1][1] - y[2][1], y[2][1] - y[0][1], y[0][1] - y[1][1]};
    double dx[3] = {y[2][0] - y[1][0], y[0][0] - y[2][0], y[1][0] - y[0][0]};
    tds_id b0 = m->fb[f][0], b1 = m->fb[f][1];
    if (b0 != TDS_NONE) side(s, out, emap, f, 0, b0, 1.0, T[cd[2]][2], zsum, Nz, dy, dx, &vtotal);
    if (b1 != TDS_NONE) side(s, out, emap, f, 1, b1, -1.0, T[cd[3]][2], zsum, Nz, dy, dx, &vtotal);
  }
  out->energy += ttotal + vtotal;
  out->area += tsum;
  return 1;
}
