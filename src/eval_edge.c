/* eval_edge.c: constraint and boundary edge integrals, content, gap energy.
**
** For an edge on a constraint (or boundary) with an energy integrand F,
** the energy is the line integral of F along the edge in its own
** direction, negated for TDS_CONREV edges. A content integrand adds its
** line integral to the bodies of the facets on the edge: + for a facet that
** uses the edge forwards and lies on the positive side of its front body
** (Evolver's rule), with signs flipped for reversed use or back bodies.
** Boundary content runs the other way (Evolver's convention, checked
** against evolver-nox-d on column.fe and a test body: a boundary's content
** integrand is added where a constraint's would be subtracted).
** FIXED edges carry no constraint integrals (Evolver's rule); boundary
** integrals apply to every edge on the boundary.
*/
#include <math.h>

#include "eval_int.h"
#include "vec3.h"

void tds_eval_vars(const tds_surf *s, const double x[3], double vars[TDS_NVARS]) {
  vars[TDS_X] = x[0];
  vars[TDS_Y] = x[1];
  vars[TDS_Z] = x[2];
  vars[TDS_P1] = vars[TDS_P2] = 0;
  vars[TDS_G] = s->gravity_on ? s->gravity : 0;
}

double tds_edge_vint(const tds_surf *s, tds_expr *const F[3], int npts,
                     const double a[3], const double b[3], double ga[3],
                     double gb[3]) {
  const tds_rule *R = tds_edge_rule(npts);
  double d[3], sum = 0;
  v3_sub(d, b, a);
  for (int i = 0; i < R->n; i++) {
    double t = R->t[i], w = R->w[i], p[3], vars[TDS_NVARS];
    for (int k = 0; k < 3; k++) p[k] = a[k] + t * d[k];
    tds_eval_vars(s, p, vars);
    double f[3] = {0, 0, 0}, jtd[3] = {0, 0, 0};
    for (int j = 0; j < 3; j++) {
      if (!F[j]) continue;
      if (ga) {
        double g[TDS_NDIFF];
        f[j] = tds_expr_eval_grad(F[j], s->parval, vars, g);
        for (int k = 0; k < 3; k++) jtd[k] += g[k] * d[j];
      } else {
        f[j] = tds_expr_eval(F[j], s->parval, vars);
      }
    }
    sum += w * v3_dot(f, d);
    if (ga)
      for (int k = 0; k < 3; k++) {
        ga[k] += w * ((1 - t) * jtd[k] - f[k]);
        gb[k] += w * (t * jtd[k] + f[k]);
      }
  }
  return sum;
}

static int has_any(tds_expr *const e[3]) { return e[0] || e[1] || e[2]; }

/* Add sign * (value, gradient) of an edge content integral to the bodies
** of the facets around edge e. */
static void add_content(tds_surf *s, tds_eval_out *out, tds_id e, double c,
                        const double ga[3], const double gb[3]) {
  tds_mesh *m = &s->m;
  int32_t h = m->eside[e];
  if (h == TDS_NONE) return;
  int32_t sd = h;
  do {
    tds_id f = sd / 3;
    double o = TDS_OREV(m->fe[f][sd % 3]) ? -1 : 1;
    for (int j = 0; j < 2; j++) {
      tds_id b = m->fb[f][j];
      if (b == TDS_NONE) continue;
      double sg = j ? -o : o;
      m->bvol[b] += sg * c;
      if (out->fq && out->fq->bq[b] >= 0) {
        int32_t q = out->fq->bq[b];
        double a3[3] = {sg * ga[0], sg * ga[1], sg * ga[2]};
        double b3[3] = {sg * gb[0], sg * gb[1], sg * gb[2]};
        tds_fixq_add(out->fq, m->ev[e][0], q, a3);
        tds_fixq_add(out->fq, m->ev[e][1], q, b3);
      }
    }
    sd = m->side_next[sd];
  } while (sd != h);
}

/* Energy and content integrals of one set of integrands on edge e;
** csign (+1 constraint, -1 boundary) orients the content. */
static void integrals(tds_surf *s, tds_eval_out *out, tds_id e, double sign,
                      double csign, tds_expr *const energy[3],
                      tds_expr *const content[3], const int npts[2]) {
  tds_mesh *m = &s->m;
  const double *a = m->x[m->ev[e][0]], *b = m->x[m->ev[e][1]];
  if (has_any(energy)) {
    double ga[3] = {0, 0, 0}, gb[3] = {0, 0, 0};
    double E = tds_edge_vint(s, energy, npts[0], a, b, out->grad ? ga : NULL, gb);
    out->energy += sign * E;
    if (out->grad) {
      v3_axpy(out->grad[m->ev[e][0]], sign, ga);
      v3_axpy(out->grad[m->ev[e][1]], sign, gb);
    }
  }
  if (has_any(content)) {
    int need = out->fq != NULL;
    double ga[3] = {0, 0, 0}, gb[3] = {0, 0, 0};
    double C = tds_edge_vint(s, content, npts[1], a, b, need ? ga : NULL, gb);
    v3_scale(ga, sign * csign);
    v3_scale(gb, sign * csign);
    add_content(s, out, e, sign * csign * C, ga, gb);
  }
}

/* Gap energy of an edge on a convex constraint: k |S| |S.n| / 6, with S
** the edge vector and n the unit normal of the constraint at the tail:
** |S.n| is the height of the head above the tail's tangent plane, and
** |S||S.n|/6 the area between a chord and a circular wall to leading order
** (2/3 chord x sagitta). This is what evolver-nox-d computes (measured on
** skew edges); its manual's |S x Q| formula agrees only to leading order. */
static void gap(tds_surf *s, tds_eval_out *out, tds_id e, const tds_expr *f) {
  tds_mesh *m = &s->m;
  tds_id t = m->ev[e][0], h = m->ev[e][1];
  double S[3], vars[TDS_NVARS], g[TDS_NDIFF], H[TDS_NDIFF][TDS_NDIFF];
  v3_sub(S, m->x[h], m->x[t]);
  tds_eval_vars(s, m->x[t], vars);
  tds_expr_eval_hess(f, s->parval, vars, g, H);
  double ulen = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  double len = v3_norm(S);
  if (!(ulen > 0) || !(len > 0)) return;
  double n[3] = {g[0] / ulen, g[1] / ulen, g[2] / ulen};
  double a = v3_dot(S, n), k = s->gap_constant / 6;
  out->energy += k * len * fabs(a);
  if (!out->grad) return;
  double sa = a > 0 ? 1 : a < 0 ? -1 : 0;
  double dS[3], dn[3];
  for (int i = 0; i < 3; i++) {
    dS[i] = k * (fabs(a) * S[i] / len + len * sa * n[i]);
    dn[i] = k * len * sa * S[i]; /* dE/dn with |n| held */
  }
  /* dn/dx_t = (I - n n^T) H / |u|: chain rule through the tail's normal. */
  double pn = v3_dot(dn, n), tang[3];
  for (int i = 0; i < 3; i++) tang[i] = (dn[i] - pn * n[i]) / ulen;
  for (int i = 0; i < 3; i++) {
    double hn = 0;
    for (int j = 0; j < 3; j++) hn += H[j][i] * tang[j];
    out->grad[t][i] += -dS[i] + hn;
    out->grad[h][i] += dS[i];
  }
}

void tds_eval_edges(tds_surf *s, tds_eval_out *out) {
  tds_mesh *m = &s->m;
  int anycon = 0;
  for (int c = 0; c < TDS_MAX_CON; c++) anycon |= s->con[c].number != 0;
  if (!anycon && s->nbdry == 0) return;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    double sign = (m->eflags[e] & TDS_CONREV) ? -1 : 1;
    if (m->ebdry[e] != TDS_NONE) {
      const tds_boundary *B = &s->bdry[m->ebdry[e]];
      integrals(s, out, e, sign, -1, B->energy, B->content, B->npts);
    }
    tds_cmask mask = m->econ[e];
    if (!mask || (m->eflags[e] & TDS_FIXED)) continue;
    for (int c = 0; mask && c < TDS_MAX_CON; c++) {
      if (!(mask & ((tds_cmask)1 << c))) continue;
      mask &= ~((tds_cmask)1 << c);
      const tds_constraint *con = &s->con[c];
      integrals(s, out, e, sign, 1, con->energy, con->content, con->npts);
      if ((con->flags & TDS_CON_CONVEX) && con->formula && s->gap_constant != 0)
        gap(s, out, e, con->formula);
    }
  }
}
