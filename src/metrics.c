/* metrics.c: mesh quality and discrete mean curvature (see metrics.h). */
#include "metrics.h"

#include <math.h>
#include <stdlib.h>

#include "gather.h"
#include "geom.h"
#include "pg.h"
#include "vec3.h"


double tds_facet_min_angle(const tds_mesh *m, tds_id f) {
  tds_corners F;
  tds_gather_facet(m, f, &F);
  const double *a = F.x[0], *b = F.x[1], *c = F.x[2];
  double A = geom_angle(a, b, c), B = geom_angle(b, c, a), C = TDS_PI - A - B;
  double mn = A < B ? A : B;
  if (C < mn) mn = C;
  if (!(mn > 0)) mn = 0;
  return mn * 180 / TDS_PI;
}

void tds_quality(const tds_surf *s, tds_quality_out *q) {
  const tds_mesh *m = &s->m;
  double sum = 0, sum2 = 0, mn = INFINITY;
  int32_t n = 0, above[4] = {0, 0, 0, 0};
  static const double lim[4] = {30, 40, 50, 55};
  for (int i = 0; i < 12; i++) q->hist[i] = 0;
  q->worst = TDS_NONE;
  for (tds_id f = 0; f < m->nf; f++) {
    if (!tds_facet_measured(m, f)) continue;
    double a = tds_facet_min_angle(m, f);
    n++;
    sum += a;
    sum2 += a * a;
    if (a < mn) {
      mn = a;
      q->worst = f;
    }
    for (int i = 0; i < 4; i++) above[i] += a > lim[i];
    int bin = (int)(a / 5);
    if (bin > 11) bin = 11;
    if (bin < 0) bin = 0;
    q->hist[bin]++;
  }
  q->n = n;
  q->min = n ? mn : (double)NAN;
  q->mean = n ? sum / n : (double)NAN;
  double var = n ? sum2 / n - q->mean * q->mean : (double)NAN;
  q->std = n ? sqrt(var > 0 ? var : 0) : (double)NAN;
  for (int i = 0; i < 4; i++) q->above[i] = n ? 100.0 * above[i] / n : (double)NAN;
}

int tds_vertex_measured(const tds_surf *s, tds_id v) {
  const tds_mesh *m = &s->m;
  if (m->vflags[v] & (TDS_DEAD | TDS_FIXED)) return 0;
  if (m->vf_start[v + 1] == m->vf_start[v]) return 0;
  for (int32_t i = m->ve_start[v]; i < m->ve_start[v + 1]; i++)
    if (tds_edge_valence(m, TDS_OID(m->ve[i])) != 2) return 0;
  return 1;
}

int tds_vertex_star_sums(const tds_surf *s, tds_id v, double K[3], double S[3],
                         double *amixp, double *anglep) {
  const tds_mesh *m = &s->m;
  double amix = 0, angle = 0;
  for (int c = 0; c < 3; c++) S[c] = 0;
  if (K) for (int c = 0; c < 3; c++) K[c] = 0;
  for (int32_t i = m->vf_start[v]; i < m->vf_start[v + 1]; i++) {
    tds_id f = m->vf[i];
    int k = tds_facet_corner(m, f, v);
    tds_corners C;
    tds_gather_facet(m, f, &C);
    const double *xi = C.x[k], *xj = C.x[(k + 1) % 3], *xk = C.x[(k + 2) % 3];
    double eij[3], eik[3], ejk[3], N[3];
    v3_sub(eij, xj, xi);
    v3_sub(eik, xk, xi);
    v3_sub(ejk, xk, xj);
    v3_cross(N, eij, eik);
    double nl = v3_norm(N);
    if (!(nl > 0)) return 0;
    v3_add(S, S, N);
    double di = v3_dot(eij, eik);          /* at i */
    double dj = -v3_dot(eij, ejk);         /* at j: (xi - xj) . (xk - xj) */
    double dk = v3_dot(eik, ejk);          /* at k: (xi - xk) . (xj - xk) */
    double cotj = dj / nl, cotk = dk / nl;
    /* edge ij is opposite k, edge ik opposite j */
    if (K) for (int c = 0; c < 3; c++) K[c] += -cotk * eij[c] - cotj * eik[c];
    if (anglep) angle += atan2(nl, di);
    double A = 0.5 * nl;
    if (di < 0) amix += A / 2;
    else if (dj < 0 || dk < 0) amix += A / 4;
    else amix += (v3_dot(eij, eij) * cotk + v3_dot(eik, eik) * cotj) / 8;
  }
  *amixp = amix;
  if (anglep) *anglep = angle;
  return amix > 0;
}

double tds_vertex_mean_curvature(const tds_surf *s, tds_id v) {
  if (!tds_vertex_measured(s, v)) return NAN;
  double K[3], S[3], amix, angle;
  if (!tds_vertex_star_sums(s, v, K, S, &amix, &angle)) return NAN;
  double sl = v3_norm(S);
  if (!(sl > 0)) return NAN;
  return v3_dot(K, S) / (sl * 2 * amix);
}

double tds_vertex_meyer_curvature(const tds_surf *s, tds_id v) {
  if (!tds_vertex_measured(s, v)) return NAN;
  double K[3], S[3], amix, angle;
  if (!tds_vertex_star_sums(s, v, K, S, &amix, &angle)) return NAN;
  double k = v3_norm(K) / (2 * amix);
  return v3_dot(K, S) < 0 ? -k : k;
}

double tds_vertex_gauss_curvature(const tds_surf *s, tds_id v) {
  if (!tds_vertex_measured(s, v)) return NAN;
  double K[3], S[3], amix, angle;
  if (!tds_vertex_star_sums(s, v, K, S, &amix, &angle)) return NAN;
  return (2 * TDS_PI - angle) / amix;
}

/* Target at vertex v from its first star facet's bodies. */
static double target_at(const tds_surf *s, tds_id v, int mode, const double *mult) {
  const tds_mesh *m = &s->m;
  tds_id f = m->vf[m->vf_start[v]];
  double t = 0;
  int grav = mode == TDS_CURV_PRESSURE && s->gravity_on;
  for (int j = 0; j < 2; j++) {
    tds_id b = m->fb[f][j];
    if (b == TDS_NONE) continue;
    double p = (m->bflags[b] & TDS_TARGET) ? mult[b]
               : (m->bflags[b] & TDS_PRESSURE) ? m->bpressure[b] : 0;
    if (grav) p -= s->gravity * m->bdensity[b] * m->x[v][2];
    t += j ? -p : p;
  }
  return t;
}

int tds_curvature(tds_ctx *ctx, tds_surf *s, int mode, double value,
                  double *h, double *hn, double *target, tds_curv_out *out) {
  tds_mesh *m = &s->m;
  if (tds_mesh_adjacency(m) != TDS_OK)
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  double *mult = NULL;
  if (mode != TDS_CURV_VALUE && m->nb > 0) {
    mult = tds_calloc(&ctx->alloc, (size_t)m->nb, sizeof *mult);
    if (!mult) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    int rc = tds_pg_multipliers(ctx, s, mult);
    if (rc != TDS_OK) {
      tds_free(&ctx->alloc, mult);
      return rc;
    }
  }
  /* [0]: Meyer's signed |K|, [1]: K . n */
  double sum[2] = {0, 0}, sum2[2] = {0, 0}, mx[2] = {-1, -1}, hs[2] = {0, 0};
  tds_id worst[2] = {TDS_NONE, TDS_NONE};
  int32_t n = 0;
  for (tds_id v = 0; v < m->nv; v++) {
    double hv[2] = {NAN, NAN}, tv = NAN;
    if (!(m->vflags[v] & TDS_DEAD) && tds_vertex_measured(s, v)) {
      double K[3], S[3], amix, angle;
      if (tds_vertex_star_sums(s, v, K, S, &amix, &angle)) {
        double sl = v3_norm(S), kn = v3_dot(K, S);
        if (sl > 0) {
          double k = v3_norm(K) / (2 * amix);
          hv[0] = kn < 0 ? -k : k;
          hv[1] = kn / (sl * 2 * amix);
        }
      }
    }
    if (!isnan(hv[0])) {
      tv = mode == TDS_CURV_VALUE ? value : mult ? target_at(s, v, mode, mult) : 0;
      n++;
      for (int j = 0; j < 2; j++) {
        double e = fabs(hv[j] - tv);
        sum[j] += e;
        sum2[j] += e * e;
        hs[j] += hv[j];
        if (e > mx[j]) {
          mx[j] = e;
          worst[j] = v;
        }
      }
    }
    if (h) h[v] = hv[0];
    if (hn) hn[v] = hv[1];
    if (target) target[v] = tv;
  }
  tds_free(&ctx->alloc, mult);
  out->n = n;
  for (int j = 0; j < 2; j++) {
    tds_curv_stats *o = j ? &out->normal : &out->meyer;
    o->max = n ? mx[j] : (double)NAN;
    o->mean = n ? sum[j] / n : (double)NAN;
    o->rms = n ? sqrt(sum2[j] / n) : (double)NAN;
    o->hmean = n ? hs[j] / n : (double)NAN;
    o->worst = worst[j];
  }
  return TDS_OK;
}
