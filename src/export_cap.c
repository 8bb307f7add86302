/*
** export_cap.c: closing a body's open shell for per-body export
** (contract in export_int.h).
**
** The boundary half-edges the caps need are the reverse of the shell's
** unmatched half-edges. They are chained into loops (at a vertex where
** several leave, any unused one is taken), and each loop is ear-clipped
** in the plane normal to its Newell normal, so cap triangles run the same
** way round as the loop and every shell edge ends up with one half-edge
** each way. An ear is a convex corner whose triangle holds no other loop
** vertex; of the ears, the one whose triangle has the largest smallest
** angle is clipped first, which avoids the slivers of clipping in order.
** A loop that is not simple in that plane (none is an ear) is finished by
** clipping its most convex corners: still closed, but the cap may then
** overlap itself.
*/
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "export_int.h"
#include "vec3.h"

typedef struct hedge {
  int32_t lo, hi; /* lo < hi */
  int32_t dir;    /* +1: lo -> hi, -1: hi -> lo */
} hedge;

static int cmp_hedge(const void *a, const void *b) {
  const hedge *p = a, *q = b;
  if (p->lo != q->lo) return p->lo < q->lo ? -1 : 1;
  if (p->hi != q->hi) return p->hi < q->hi ? -1 : 1;
  return 0;
}

static double cross2(const double a[2], const double b[2], const double c[2]) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int inside(const double p[2], const double a[2], const double b[2], const double c[2]) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

/* Smallest angle of the plane triangle abc (radians). */
static double min_angle(const double a[2], const double b[2], const double c[2]) {
  const double *v[3] = {a, b, c};
  double mn = TDS_PI;
  for (int k = 0; k < 3; k++) {
    const double *o = v[k], *q = v[(k + 1) % 3], *r = v[(k + 2) % 3];
    double ux = q[0] - o[0], uy = q[1] - o[1], wx = r[0] - o[0], wy = r[1] - o[1];
    double t = atan2(fabs(ux * wy - uy * wx), ux * wx + uy * wy);
    if (t < mn) mn = t;
  }
  return mn;
}

/* Ear-clip the loop lp[0..n-1] (vertex indices) into x's triangles. */
static int clip(tds_ctx *ctx, xmesh *x, int32_t *lp, int32_t n) {
  double N[3] = {0, 0, 0};
  for (int32_t i = 0; i < n; i++) {
    const double *a = x->x[lp[i]], *b = x->x[lp[(i + 1) % n]];
    N[0] += (a[1] - b[1]) * (a[2] + b[2]);
    N[1] += (a[2] - b[2]) * (a[0] + b[0]);
    N[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  double l = v3_norm(N);
  if (l > 0) v3_scale(N, 1 / l);
  else N[2] = 1;
  double u[3] = {1, 0, 0}, v[3];
  if (N[0] * N[0] > 0.5) u[0] = 0, u[1] = 1;
  double d = v3_dot(u, N);
  for (int c = 0; c < 3; c++) u[c] -= d * N[c];
  v3_scale(u, 1 / v3_norm(u));
  v3_cross(v, N, u); /* (u, v, N) right-handed: the loop runs counter-clockwise */
  double (*p)[2] = malloc((size_t)n * sizeof *p);
  if (!p) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (int32_t i = 0; i < n; i++) {
    p[i][0] = v3_dot(x->x[lp[i]], u);
    p[i][1] = v3_dot(x->x[lp[i]], v);
  }
  /* idx: remaining corners (positions into lp and p) */
  int32_t *idx = malloc((size_t)n * sizeof *idx);
  if (!idx) {
    free(p);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  for (int32_t i = 0; i < n; i++) idx[i] = i;
  /* refl: corners that are not strictly convex; only they can lie in an
  ** ear's triangle, so only they are tested */
  int32_t *refl = malloc((size_t)n * sizeof *refl);
  if (!refl) {
    free(idx);
    free(p);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  int32_t m = n;
  while (m > 3) {
    int32_t nr = 0, ear = -1, most = 0;
    double bestq = -1, bestc = -1e300;
    for (int32_t i = 0; i < m; i++) {
      double cr = cross2(p[idx[(i + m - 1) % m]], p[idx[i]], p[idx[(i + 1) % m]]);
      if (!(cr > 0)) refl[nr++] = idx[i];
      if (cr > bestc) {
        bestc = cr;
        most = i;
      }
    }
    for (int32_t i = 0; i < m; i++) {
      int32_t a = idx[(i + m - 1) % m], b = idx[i], c = idx[(i + 1) % m];
      if (!(cross2(p[a], p[b], p[c]) > 0)) continue;
      int ok = 1;
      for (int32_t j = 0; j < nr && ok; j++) {
        int32_t q = refl[j];
        if (lp[q] == lp[a] || lp[q] == lp[b] || lp[q] == lp[c]) continue;
        if (inside(p[q], p[a], p[b], p[c])) ok = 0;
      }
      if (!ok) continue;
      double q = min_angle(p[a], p[b], p[c]);
      if (q > bestq) {
        bestq = q;
        ear = i;
      }
    }
    if (ear < 0) ear = most;
    int32_t a = idx[(ear + m - 1) % m], b = idx[ear], c = idx[(ear + 1) % m];
    x->tri[x->nt][0] = lp[a];
    x->tri[x->nt][1] = lp[b];
    x->tri[x->nt][2] = lp[c];
    x->nt++;
    memmove(idx + ear, idx + ear + 1, (size_t)(m - ear - 1) * sizeof *idx);
    m--;
  }
  free(refl);
  x->tri[x->nt][0] = lp[idx[0]];
  x->tri[x->nt][1] = lp[idx[1]];
  x->tri[x->nt][2] = lp[idx[2]];
  x->nt++;
  free(idx);
  free(p);
  return TDS_OK;
}

int tds_export_caps(tds_ctx *ctx, xmesh *x, int32_t *ncap) {
  int32_t nt0 = x->nt, nh = 3 * nt0;
  *ncap = 0;
  hedge *h = malloc((size_t)(nh > 0 ? nh : 1) * sizeof *h);
  int32_t (*need)[2] = malloc((size_t)(nh > 0 ? nh : 1) * sizeof *need);
  int32_t *start = tds_calloc((size_t)x->nv + 1, sizeof *start);
  int32_t *out = malloc((size_t)(nh > 0 ? nh : 1) * sizeof *out);
  int32_t *loop = malloc((size_t)(nh > 0 ? nh : 1) * sizeof *loop);
  uint8_t *used = tds_calloc((size_t)(nh > 0 ? nh : 1), 1);
  int rc = TDS_OK;
  if (!h || !need || !start || !out || !loop || !used) {
    rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    goto done;
  }
  for (int32_t t = 0; t < nt0; t++)
    for (int k = 0; k < 3; k++) {
      int32_t a = x->tri[t][k], b = x->tri[t][(k + 1) % 3];
      h[3 * t + k] = a < b ? (hedge){a, b, 1} : (hedge){b, a, -1};
    }
  qsort(h, (size_t)nh, sizeof *h, cmp_hedge);
  int32_t nneed = 0;
  for (int32_t i = 0; i < nh;) {
    int32_t j = i, net = 0;
    while (j < nh && !cmp_hedge(&h[i], &h[j])) net += h[j++].dir;
    /* the caps supply the opposite of the excess */
    for (; net > 0; net--) need[nneed][0] = h[i].hi, need[nneed++][1] = h[i].lo;
    for (; net < 0; net++) need[nneed][0] = h[i].lo, need[nneed++][1] = h[i].hi;
    i = j;
  }
  /* outgoing cap half-edges per vertex, CSR */
  for (int32_t i = 0; i < nneed; i++) start[need[i][0] + 1]++;
  for (int32_t v = 0; v < x->nv; v++) start[v + 1] += start[v];
  {
    int32_t *fill = tds_calloc((size_t)x->nv + 1, sizeof *fill);
    if (!fill) {
      rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      goto done;
    }
    for (int32_t i = 0; i < nneed; i++) out[start[need[i][0]] + fill[need[i][0]]++] = i;
    free(fill);
  }
  for (int32_t e0 = 0; e0 < nneed && rc == TDS_OK; e0++) {
    if (used[e0]) continue;
    int32_t n = 0, e = e0, v0 = need[e0][0];
    for (;;) {
      used[e] = 1;
      loop[n++] = need[e][0];
      int32_t v = need[e][1];
      if (v == v0) break;
      e = -1;
      for (int32_t i = start[v]; i < start[v + 1]; i++)
        if (!used[out[i]]) {
          e = out[i];
          break;
        }
      if (e < 0) {
        rc = tds_seterr(ctx, TDS_ERANGE,
                        "export: caps: the open boundary does not close into a loop at "
                        "exported vertex %d", v + 1);
        break;
      }
    }
    if (rc == TDS_OK && n >= 3) rc = clip(ctx, x, loop, n);
  }
  *ncap = x->nt - nt0;
done:
  free(h);
  free(need);
  free(start);
  free(out);
  free(loop);
  free(used);
  return rc;
}
