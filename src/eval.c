/* eval.c: energy, gradient and constrained-quantity assembly. */
#include "eval.h"

#include <math.h>
#include <string.h>

#include "eval_int.h"
#include "geom.h"

/* Facet pass: area energy, body volumes and gravity. */
static void facet_pass(tds_surf *s, tds_eval_out *out) {
  tds_mesh *m = &s->m;
  double (*grad)[3] = out->grad;
  tds_fixq *fq = out->fq;
  const int grav = s->gravity_on && s->gravity != 0;
  const int sym = s->symmetric_content;
  double energy = 0, area = 0;

  for (tds_id b = 0; b < m->nb; b++)
    m->bvol[b] = (m->bflags[b] & TDS_DEAD) ? 0 : m->bvolconst[b];

  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    const tds_id *fv = m->fv[f];
    const double *a = m->x[fv[0]], *b = m->x[fv[1]], *c = m->x[fv[2]];
    double g[3][3];
    double A = geom_area(a, b, c, grad ? g : NULL);
    double ten = m->ften[f];
    area += A;
    energy += ten * A;
    if (grad && ten != 0)
      for (int k = 0; k < 3; k++) v3_axpy(grad[fv[k]], ten, g[k]);

    tds_id fb0 = m->fb[f][0], fb1 = m->fb[f][1];
    if ((fb0 == TDS_NONE && fb1 == TDS_NONE) || (m->fflags[f] & TDS_NONCONTENT))
      continue;
    int need_vg = fq != NULL || grad != NULL;
    double V = sym ? geom_volume_sym(a, b, c, need_vg ? g : NULL)
                   : geom_volume_z(a, b, c, need_vg ? g : NULL);
    double gw[3][3], W = 0;
    int wdone = 0;
    for (int j = 0; j < 2; j++) {
      tds_id bd = m->fb[f][j];
      if (bd == TDS_NONE) continue;
      double sign = j ? -1.0 : 1.0;
      m->bvol[bd] += sign * V;
      if (fq && fq->bq[bd] >= 0) {
        int32_t q = fq->bq[bd];
        for (int k = 0; k < 3; k++) {
          double gk[3] = {sign * g[k][0], sign * g[k][1], sign * g[k][2]};
          tds_fixq_add(fq, fv[k], q, gk);
        }
      }
      if (m->bflags[bd] & TDS_PRESSURE) { /* energy -p V */
        double p = m->bpressure[bd];
        energy -= sign * p * V;
        if (grad)
          for (int k = 0; k < 3; k++) v3_axpy(grad[fv[k]], -sign * p, g[k]);
      }
      if (grav && m->bdensity[bd] != 0) {
        if (!wdone) {
          W = geom_zmoment(a, b, c, grad ? gw : NULL);
          wdone = 1;
        }
        double w = sign * s->gravity * m->bdensity[bd];
        energy += w * W;
        if (grad)
          for (int k = 0; k < 3; k++) v3_axpy(grad[fv[k]], w, gw[k]);
      }
    }
  }
  out->energy += energy;
  out->area += area;
}

/* Edges with a tension (soapfilm: only where set). */
static void edge_pass(tds_surf *s, tds_eval_out *out) {
  tds_mesh *m = &s->m;
  for (tds_id e = 0; e < m->ne; e++) {
    if ((m->eflags[e] & TDS_DEAD) || m->eten[e] == 0) continue;
    const double *a = m->x[m->ev[e][0]], *b = m->x[m->ev[e][1]];
    double d[3];
    v3_sub(d, b, a);
    double len = v3_norm(d);
    out->energy += m->eten[e] * len;
    if (out->grad && len > 0) {
      double t = m->eten[e] / len;
      v3_axpy(out->grad[m->ev[e][1]], t, d);
      v3_axpy(out->grad[m->ev[e][0]], -t, d);
    }
  }
}

int tds_eval(tds_ctx *ctx, tds_surf *s, tds_eval_out *out) {
  tds_mesh *m = &s->m;
  out->energy = 0;
  out->area = 0;
  if (out->grad) memset(out->grad, 0, (size_t)m->nv * sizeof *out->grad);
  if (out->fq) tds_fixq_clear(out->fq);
  facet_pass(s, out);
  edge_pass(s, out);
  tds_eval_edges(s, out);
  tds_eval_quantities(s, out);
  if (out->fq)
    for (int32_t q = 0; q < out->fq->nq; q++) {
      tds_id b = out->fq->qbody[q];
      if (b != TDS_NONE) out->fq->value[q] = m->bvol[b];
    }
  if (!isfinite(out->energy))
    return tds_seterr(ctx, TDS_ENUM, "energy is not finite (%s)",
                     isnan(out->energy) ? "NaN" : out->energy > 0 ? "inf" : "-inf");
  return TDS_OK;
}

int tds_surf_update(tds_ctx *ctx, tds_surf *s) {
  tds_eval_out out = {0};
  int rc = tds_eval(ctx, s, &out);
  s->energy = out.energy;
  s->area = out.area;
  return rc;
}
