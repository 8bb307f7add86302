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

/* One side of facet f: body bd, sign +-1, lift tz along z; corners x. */
static inline __attribute__((always_inline)) void
side(tds_surf *s, tds_eval_out *out, const int32_t *emap, tds_id f, int j, tds_id bd,
     double sign, double tz, const double *const x[3], double *vtotal) {
  tds_mesh *m = &s->m;
  tds_fixq *fq = out->fq;
  int32_t q = fq ? fq->bq[bd] : -1;
  int press = (m->bflags[bd] & TDS_PRESSURE) != 0;
  double gv[3][3];
  double V = geom_volume_zshift(x[0], x[1], x[2], tz, q >= 0 || (press && out->grad) ? gv : NULL);
  m->bvol[bd] += sign * V;
  const tds_id *vs = m->fv[f];
  if (q >= 0) {
    for (int k = 0; k < 3; k++) {
      double gc[3] = {sign * gv[k][0], sign * gv[k][1], sign * gv[k][2]};
      if (emap) tds_fixq_add_at(fq, emap[6 * f + 3 * j + k], q, gc);
      else tds_fixq_add(fq, vs[k], q, gc);
    }
  }
  if (press) { /* the general loop's pressure sink: another call, the same value */
    double w = -sign * m->bpressure[bd];
    *vtotal += w * V;
    if (out->grad)
      for (int k = 0; k < 3; k++) v3_axpy(out->grad[vs[k]], w, gv[k]);
  }
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
    const double *x[3] = {y[0], y[1], y[2]};
    double g[3][3];
    double A = geom_area(y[0], y[1], y[2], grad ? g : NULL);
    double ten = m->ften[f];
    tsum += A;
    ttotal += ten * A;
    if (grad)
      for (int k = 0; k < 3; k++) v3_axpy(grad[vs[k]], ten, g[k]);
    if (fl & TDS_NONCONTENT) continue;
    tds_id b0 = m->fb[f][0], b1 = m->fb[f][1];
    if (b0 != TDS_NONE) side(s, out, emap, f, 0, b0, 1.0, T[cd[2]][2], x, &vtotal);
    if (b1 != TDS_NONE) side(s, out, emap, f, 1, b1, -1.0, T[cd[3]][2], x, &vtotal);
  }
  out->energy += ttotal + vtotal;
  out->area += tsum;
  return 1;
}
