/* eval_quant.c: named quantities (the methods the Evolver examples use).
**
** A quantity's value is modulus * sum over its method instances of
** (instance modulus * method value) + volconst. Methods apply to every
** live facet or edge (Evolver's GLOBAL); vector facet integrals use the
** facet's right-hand-rule normal. Energy quantities add to the energy,
** FIXED ones are held at their target by the fixq machinery, INFO_ONLY
** ones are only reported.
*/
#include <math.h>
#include <string.h>

#include "eval_int.h"
#include "geom.h"
#include "vec3.h"

/* Where a method instance's gradient goes: scale * dvalue into the energy
** gradient (energy quantities) or into quantity q of the fixq. */
typedef struct sink {
  tds_eval_out *out;
  double scale;
  int32_t q; /* fixq index, or -1 for the energy gradient */
} sink;

static void put(const sink *k, tds_id v, const double g[3]) {
  double w[3] = {k->scale * g[0], k->scale * g[1], k->scale * g[2]};
  if (k->q >= 0)
    tds_fixq_add(k->out->fq, v, k->q, w);
  else if (k->out->grad)
    v3_add(k->out->grad[v], k->out->grad[v], w);
}

/* int over facet of F . n dA = sum_q w_q F(p_q) . N / 2. */
static double facet_vint(const tds_surf *s, tds_expr *const F[3], int npts,
                         const double *x[3], double g[3][3]) {
  const tds_rule *R = tds_facet_rule(npts);
  double N[3], ab[3], ac[3];
  v3_sub(ab, x[1], x[0]);
  v3_sub(ac, x[2], x[0]);
  v3_cross(N, ab, ac);
  double sum = 0, favg[3] = {0, 0, 0};
  if (g) memset(g, 0, sizeof(double[3][3]));
  for (int i = 0; i < R->n; i++) {
    double p[3] = {0, 0, 0}, vars[TDS_NVARS], f[3] = {0, 0, 0}, jtn[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) v3_axpy(p, R->b[i][k], x[k]);
    tds_eval_vars(s, p, vars);
    for (int j = 0; j < 3; j++) {
      if (!F[j]) continue;
      double gr[TDS_NDIFF];
      f[j] = g ? tds_expr_eval_grad(F[j], s->parval, vars, gr)
               : tds_expr_eval(F[j], s->parval, vars);
      if (g)
        for (int k = 0; k < 3; k++) jtn[k] += gr[k] * N[j];
    }
    double w = R->w[i];
    sum += w * v3_dot(f, N) / 2;
    if (g) {
      v3_axpy(favg, w / 2, f);
      for (int k = 0; k < 3; k++) v3_axpy(g[k], w * R->b[i][k] / 2, jtn);
    }
  }
  if (g) { /* d(F . N)/da = (b - c) x F, cyclic */
    for (int k = 0; k < 3; k++) {
      double d[3], c[3];
      v3_sub(d, x[(k + 1) % 3], x[(k + 2) % 3]);
      v3_cross(c, d, favg);
      v3_add(g[k], g[k], c);
    }
  }
  return sum;
}

/* int over facet of f dA. */
static double facet_sint(const tds_surf *s, const tds_expr *f, int npts,
                         const double *x[3], double g[3][3]) {
  const tds_rule *R = tds_facet_rule(npts);
  double ga[3][3];
  double A = geom_area(x[0], x[1], x[2], g ? ga : NULL);
  double avg = 0, grad_avg[3][3];
  if (g) memset(grad_avg, 0, sizeof grad_avg);
  for (int i = 0; i < R->n; i++) {
    double p[3] = {0, 0, 0}, vars[TDS_NVARS], gr[TDS_NDIFF];
    for (int k = 0; k < 3; k++) v3_axpy(p, R->b[i][k], x[k]);
    tds_eval_vars(s, p, vars);
    double w = R->w[i];
    avg += w * (g ? tds_expr_eval_grad(f, s->parval, vars, gr)
                  : tds_expr_eval(f, s->parval, vars));
    if (g)
      for (int k = 0; k < 3; k++) v3_axpy(grad_avg[k], w * R->b[i][k], gr);
  }
  if (g)
    for (int k = 0; k < 3; k++)
      for (int j = 0; j < 3; j++) g[k][j] = A * grad_avg[k][j] + avg * ga[k][j];
  return A * avg;
}

/* int over edge of f ds. */
static double edge_sint(const tds_surf *s, const tds_expr *f, int npts,
                        const double *a, const double *b, double ga[3],
                        double gb[3]) {
  const tds_rule *R = tds_edge_rule(npts);
  double d[3];
  v3_sub(d, b, a);
  double len = v3_norm(d), avg = 0, gavg_a[3] = {0, 0, 0}, gavg_b[3] = {0, 0, 0};
  for (int i = 0; i < R->n; i++) {
    double t = R->t[i], w = R->w[i], p[3], vars[TDS_NVARS], gr[TDS_NDIFF];
    for (int k = 0; k < 3; k++) p[k] = a[k] + t * d[k];
    tds_eval_vars(s, p, vars);
    avg += w * (ga ? tds_expr_eval_grad(f, s->parval, vars, gr)
                   : tds_expr_eval(f, s->parval, vars));
    if (ga) {
      v3_axpy(gavg_a, w * (1 - t), gr);
      v3_axpy(gavg_b, w * t, gr);
    }
  }
  if (ga && len > 0)
    for (int k = 0; k < 3; k++) {
      ga[k] = len * gavg_a[k] - avg * d[k] / len;
      gb[k] = len * gavg_b[k] + avg * d[k] / len;
    }
  return len * avg;
}

/* Value of one method instance over the whole surface; gradient to k. */
static double method_value(tds_surf *s, const tds_method_inst *mi, const sink *k) {
  tds_mesh *m = &s->m;
  int want = k->q >= 0 || k->out->grad;
  double total = 0;
  int facet_method = mi->method == TDS_M_FACET_AREA ||
                     mi->method == TDS_M_FACET_VECTOR_INTEGRAL ||
                     mi->method == TDS_M_FACET_SCALAR_INTEGRAL ||
                     mi->method == TDS_M_GRAVITY || mi->method == TDS_M_FULL_GRAVITY;
  if (facet_method) {
    for (tds_id f = 0; f < m->nf; f++) {
      if (m->fflags[f] & TDS_DEAD) continue;
      const double *x[3] = {m->x[m->fv[f][0]], m->x[m->fv[f][1]], m->x[m->fv[f][2]]};
      double g[3][3], val;
      switch (mi->method) {
      case TDS_M_FACET_AREA: val = geom_area(x[0], x[1], x[2], want ? g : NULL); break;
      case TDS_M_FACET_VECTOR_INTEGRAL: val = facet_vint(s, mi->integrand, mi->npts, x, want ? g : NULL); break;
      case TDS_M_FACET_SCALAR_INTEGRAL: val = facet_sint(s, mi->integrand[0], mi->npts, x, want ? g : NULL); break;
      default: { /* gravity: density-weighted z moment of the facet's bodies */
        double rho = 0;
        if (m->fb[f][0] != TDS_NONE) rho += m->bdensity[m->fb[f][0]];
        if (m->fb[f][1] != TDS_NONE) rho -= m->bdensity[m->fb[f][1]];
        if (mi->method == TDS_M_FULL_GRAVITY) rho *= s->gravity_on ? s->gravity : 0;
        if (rho == 0) continue;
        val = rho * geom_zmoment(x[0], x[1], x[2], want ? g : NULL);
        if (want)
          for (int i = 0; i < 3; i++) v3_scale(g[i], rho);
      }
      }
      total += val;
      if (want)
        for (int i = 0; i < 3; i++) put(k, m->fv[f][i], g[i]);
    }
    return total;
  }
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    const double *a = m->x[m->ev[e][0]], *b = m->x[m->ev[e][1]];
    double ga[3] = {0, 0, 0}, gb[3] = {0, 0, 0}, val;
    if (mi->method == TDS_M_EDGE_LENGTH) {
      double d[3];
      v3_sub(d, b, a);
      val = v3_norm(d);
      if (want && val > 0)
        for (int i = 0; i < 3; i++) {
          gb[i] = d[i] / val;
          ga[i] = -gb[i];
        }
    } else if (mi->method == TDS_M_EDGE_VECTOR_INTEGRAL) {
      val = tds_edge_vint(s, mi->integrand, mi->npts, a, b, want ? ga : NULL, gb);
    } else {
      val = edge_sint(s, mi->integrand[0], mi->npts, a, b, want ? ga : NULL, gb);
    }
    total += val;
    if (want) {
      put(k, m->ev[e][0], ga);
      put(k, m->ev[e][1], gb);
    }
  }
  return total;
}

void tds_eval_quantities(tds_surf *s, tds_eval_out *out) {
  int32_t qfixed = 0; /* fixq index of the next FIXED quantity */
  if (out->fq)
    while (qfixed < out->fq->nq && out->fq->qbody[qfixed] != TDS_NONE) qfixed++;
  for (int i = 0; i < s->nquant; i++) {
    tds_quantity *Q = &s->quant[i];
    tds_eval_out none = {0}; /* a sink without gradients */
    sink k = {out, 0, -1};
    if (Q->kind == TDS_Q_FIXED && out->fq) k.q = qfixed++;
    else if (Q->kind != TDS_Q_ENERGY) k.out = &none;
    double v = 0;
    for (int j = 0; j < Q->ninst; j++) {
      const tds_method_inst *mi = &Q->inst[j];
      if (mi->modulus == 0 || Q->modulus == 0) continue;
      k.scale = Q->modulus * mi->modulus;
      v += k.scale * method_value(s, mi, &k);
    }
    Q->value = v + Q->volconst;
    if (Q->kind == TDS_Q_ENERGY) out->energy += Q->value;
    if (k.q >= 0) out->fq->value[k.q] = Q->value;
  }
}
