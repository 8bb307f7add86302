/* motion.c: vertex motion spaces, level-set projection, boundary placement. */
#include "motion.h"

#include <math.h>
#include <string.h>

#include "expr.h"
#include "fixq.h"
#include "vec3.h"
#include "xattr.h"

#define MAX_ACTIVE 3        /* independent level sets a vertex can be on */
#define MAX_NEWTON 25

void tds_motion_vars(const tds_surf *s, const double x[3], const double p[2],
                     double vars[TDS_NVARS]) {
  vars[TDS_X] = x[0];
  vars[TDS_Y] = x[1];
  vars[TDS_Z] = x[2];
  vars[TDS_P1] = p ? p[0] : 0;
  vars[TDS_P2] = p ? p[1] : 0;
  vars[TDS_G] = s->gravity_on ? s->gravity : 0;
}

/* Gradients (and values) of the level sets that bind vertex v at x:
** equality constraints always, one-sided ones only when violated. */
static int active_sets(const tds_surf *s, tds_id v, const double x[3],
                       double n[MAX_ACTIVE][3], double val[MAX_ACTIVE],
                       int violated_only) {
  tds_cmask mask = s->m.vcon[v];
  int k = 0;
  double vars[TDS_NVARS], g[TDS_NDIFF];
  tds_motion_vars(s, x, NULL, vars);
  tds_xattr_fill(s, TDS_VERTEX, v); /* the formulas' vertex attributes */
  for (int c = 0; mask && c < TDS_MAX_CON; c++) {
    if (!(mask & ((tds_cmask)1 << c))) continue;
    mask &= ~((tds_cmask)1 << c);
    const tds_constraint *con = &s->con[c];
    if (!con->formula) continue;
    double f = tds_expr_eval_grad(con->formula, s->parval, vars, g);
    int onesided = con->flags & (TDS_CON_NONNEG | TDS_CON_NONPOS);
    if (onesided) {
      int bad = (con->flags & TDS_CON_NONNEG) ? f < 0 : f > 0;
      if (!bad || !violated_only) continue;
    }
    if (k == MAX_ACTIVE) break;
    val[k] = f;
    n[k][0] = g[0];
    n[k][1] = g[1];
    n[k][2] = g[2];
    k++;
  }
  return k;
}

/* w -= N mu with (N^T N) mu = N^T w + rhs_shift (rhs NULL: plain projection). */
static int remove_normal(int k, double n[MAX_ACTIVE][3], const double *rhs,
                         double w[3]) {
  double A[MAX_ACTIVE * MAX_ACTIVE], b[MAX_ACTIVE];
  for (int i = 0; i < k; i++) {
    for (int j = 0; j < k; j++) A[i * k + j] = v3_dot(n[i], n[j]);
    b[i] = rhs ? rhs[i] : v3_dot(n[i], w);
  }
  if (tds_dense_solve(k, A, b) != 0) return -1;
  for (int i = 0; i < k; i++) v3_axpy(w, -b[i], n[i]);
  return 0;
}

void tds_motion_project(const tds_surf *s, tds_id v, double w[3]) {
  const tds_mesh *m = &s->m;
  if (m->vflags[v] & (TDS_FIXED | TDS_DEAD)) {
    v3_zero(w);
    return;
  }
  int32_t bd = m->vbdry[v];
  if (bd != TDS_NONE) {
    /* Parameter-space covector: J^T w, J = dX/dp. */
    const tds_boundary *B = &s->bdry[bd];
    double vars[TDS_NVARS], g[TDS_NDIFF], out[3] = {0, 0, 0};
    tds_motion_vars(s, m->x[v], m->vp[v], vars);
    for (int i = 0; i < 3; i++) {
      tds_expr_eval_grad(B->x[i], s->parval, vars, g);
      for (int j = 0; j < B->nparams; j++) out[j] += g[TDS_P1 + j] * w[i];
    }
    v3_copy(w, out);
    return;
  }
  if (!m->vcon[v]) return;
  double n[MAX_ACTIVE][3], val[MAX_ACTIVE];
  int k = active_sets(s, v, m->x[v], n, val, 0);
  if (k > 0 && remove_normal(k, n, NULL, w) != 0) v3_zero(w);
}

/* Newton projection of x onto the vertex's binding level sets. */
static int project_levels(const tds_surf *s, tds_id v, double x[3]) {
  for (int it = 0; it < MAX_NEWTON; it++) {
    double n[MAX_ACTIVE][3], val[MAX_ACTIVE];
    int k = active_sets(s, v, x, n, val, 1);
    double worst = 0;
    for (int i = 0; i < k; i++)
      if (fabs(val[i]) > worst) worst = fabs(val[i]);
    if (worst <= s->constraint_tol) return TDS_OK;
    double d[3] = {0, 0, 0};
    if (remove_normal(k, n, val, d) != 0) return TDS_ENUM;
    /* d = -N mu with (N^T N) mu = val: the Newton step for N^T dx = -val. */
    v3_add(x, x, d);
    if (!isfinite(x[0] + x[1] + x[2])) return TDS_ENUM;
  }
  return TDS_ENUM;
}

static int place_on_boundary(tds_surf *s, tds_id v) {
  tds_mesh *m = &s->m;
  const tds_boundary *B = &s->bdry[m->vbdry[v]];
  double vars[TDS_NVARS];
  tds_motion_vars(s, m->x[v], m->vp[v], vars);
  for (int i = 0; i < 3; i++)
    m->x[v][i] = tds_expr_eval(B->x[i], s->parval, vars);
  return isfinite(m->x[v][0] + m->x[v][1] + m->x[v][2]) ? TDS_OK : TDS_ENUM;
}

int tds_motion_enforce(tds_surf *s, tds_id v) {
  tds_mesh *m = &s->m;
  if (m->vbdry[v] != TDS_NONE) return place_on_boundary(s, v);
  if (m->vcon[v]) return project_levels(s, v, m->x[v]);
  return TDS_OK;
}

int tds_motion_apply(tds_surf *s, tds_id v, const double x0[3],
                     const double p0[2], const double d[3]) {
  tds_mesh *m = &s->m;
  if (m->vbdry[v] != TDS_NONE) {
    int np = s->bdry[m->vbdry[v]].nparams;
    for (int j = 0; j < 2; j++)
      m->vp[v][j] = p0[j] + (d && j < np ? d[j] : 0);
    return place_on_boundary(s, v);
  }
  v3_copy(m->x[v], x0);
  if (d) v3_add(m->x[v], m->x[v], d);
  return m->vcon[v] ? project_levels(s, v, m->x[v]) : TDS_OK;
}

void tds_boundary_param_toward(const tds_surf *s, int32_t bd, const double target[3],
                               const double pstart[2], double p[2]) {
  const tds_boundary *B = &s->bdry[bd];
  int np = B->nparams;
  p[0] = pstart[0];
  p[1] = pstart[1];
  for (int it = 0; it < 5; it++) {
    double vars[TDS_NVARS], g[TDS_NDIFF], J[3][2], r[3];
    tds_motion_vars(s, target, p, vars);
    for (int i = 0; i < 3; i++) {
      r[i] = target[i] - tds_expr_eval_grad(B->x[i], s->parval, vars, g);
      J[i][0] = g[TDS_P1];
      J[i][1] = g[TDS_P2];
    }
    double A[4], b[2];
    for (int j = 0; j < np; j++) {
      b[j] = 0;
      for (int i = 0; i < 3; i++) b[j] += J[i][j] * r[i];
      for (int k = 0; k < np; k++) {
        A[j * np + k] = 0;
        for (int i = 0; i < 3; i++) A[j * np + k] += J[i][j] * J[i][k];
      }
    }
    if (tds_dense_solve(np, A, b) != 0) return;
    for (int j = 0; j < np; j++) p[j] += b[j];
  }
}
