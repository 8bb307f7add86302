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
** overlap itself. A loop inside another loop of the opposite orientation
** in the same plane (to 1e-8 of the outer loop's size) is a hole: it is
** joined to the outer loop by a bridge edge from its rightmost vertex to
** the nearest outer vertex further right that the bridge reaches without
** crossing an edge, and the joined polygon is clipped as one (a ring-
** shaped cap). One level only: a loop inside a hole gets its own cap.
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
static int clip(tds_ctx *ctx, xmesh *x, const int32_t *lp, int32_t n) {
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
  double (*p)[2] = tds_malloc(&ctx->alloc, (size_t)n * sizeof *p);
  if (!p) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (int32_t i = 0; i < n; i++) {
    p[i][0] = v3_dot(x->x[lp[i]], u);
    p[i][1] = v3_dot(x->x[lp[i]], v);
  }
  /* idx: remaining corners (positions into lp and p) */
  int32_t *idx = tds_malloc(&ctx->alloc, (size_t)n * sizeof *idx);
  if (!idx) {
    tds_free(&ctx->alloc, p);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  for (int32_t i = 0; i < n; i++) idx[i] = i;
  /* refl: corners that are not strictly convex; only they can lie in an
  ** ear's triangle, so only they are tested */
  int32_t *refl = tds_malloc(&ctx->alloc, (size_t)n * sizeof *refl);
  if (!refl) {
    tds_free(&ctx->alloc, idx);
    tds_free(&ctx->alloc, p);
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
  tds_free(&ctx->alloc, refl);
  x->tri[x->nt][0] = lp[idx[0]];
  x->tri[x->nt][1] = lp[idx[1]];
  x->tri[x->nt][2] = lp[idx[2]];
  x->nt++;
  tds_free(&ctx->alloc, idx);
  tds_free(&ctx->alloc, p);
  return TDS_OK;
}

/* Newell normal of loop lp[0..n-1] (length: twice its area). */
static void newell(const xmesh *x, const int32_t *lp, int32_t n, double N[3]) {
  N[0] = N[1] = N[2] = 0;
  for (int32_t i = 0; i < n; i++) {
    const double *a = x->x[lp[i]], *b = x->x[lp[(i + 1) % n]];
    N[0] += (a[1] - b[1]) * (a[2] + b[2]);
    N[1] += (a[2] - b[2]) * (a[0] + b[0]);
    N[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
}

typedef struct plane {
  double u[3], v[3];
} plane;

static void plane_of(const double N[3], plane *pl) {
  double n[3] = {N[0], N[1], N[2]}, l = v3_norm(n);
  if (l > 0) v3_scale(n, 1 / l);
  else n[2] = 1;
  double u[3] = {1, 0, 0};
  if (n[0] * n[0] > 0.5) u[0] = 0, u[1] = 1;
  double d = v3_dot(u, n);
  for (int c = 0; c < 3; c++) u[c] -= d * n[c];
  v3_scale(u, 1 / v3_norm(u));
  for (int c = 0; c < 3; c++) pl->u[c] = u[c];
  v3_cross(pl->v, n, pl->u);
}

static void proj(const xmesh *x, const plane *pl, int32_t v, double p[2]) {
  p[0] = v3_dot(x->x[v], pl->u);
  p[1] = v3_dot(x->x[v], pl->v);
}

/* Nonzero when point q is inside the polygon lp[0..n-1] (even-odd). */
static int in_poly(const xmesh *x, const plane *pl, const int32_t *lp, int32_t n,
                   const double q[2]) {
  int in = 0;
  for (int32_t i = 0, j = n - 1; i < n; j = i++) {
    double a[2], b[2];
    proj(x, pl, lp[i], a);
    proj(x, pl, lp[j], b);
    if ((a[1] > q[1]) != (b[1] > q[1]) &&
        q[0] < (b[0] - a[0]) * (q[1] - a[1]) / (b[1] - a[1]) + a[0])
      in = !in;
  }
  return in;
}

/* Nonzero when open segments pq and ab cross properly. */
static int crosses(const double p[2], const double q[2], const double a[2], const double b[2]) {
  double d1 = cross2(p, q, a), d2 = cross2(p, q, b), d3 = cross2(a, b, p), d4 = cross2(a, b, q);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/* Does segment (vertex h, vertex o) cross an edge of the polygon or of a
** hole (edges at h or o excepted)? */
static int blocked(const xmesh *x, const plane *pl, int32_t h, int32_t o, const int32_t *poly,
                   int32_t np, const int32_t *loop, const int32_t *lstart, const int32_t *holes,
                   int32_t nholes) {
  double p[2], q[2], a[2], b[2];
  proj(x, pl, h, p);
  proj(x, pl, o, q);
  for (int32_t i = 0; i < np; i++) {
    int32_t s = poly[i], t = poly[(i + 1) % np];
    if (s == h || s == o || t == h || t == o) continue;
    proj(x, pl, s, a);
    proj(x, pl, t, b);
    if (crosses(p, q, a, b)) return 1;
  }
  for (int32_t k = 0; k < nholes; k++) {
    const int32_t *lp = loop + lstart[holes[k]];
    int32_t n = lstart[holes[k] + 1] - lstart[holes[k]];
    for (int32_t i = 0; i < n; i++) {
      int32_t s = lp[i], t = lp[(i + 1) % n];
      if (s == h || s == o || t == h || t == o) continue;
      proj(x, pl, s, a);
      proj(x, pl, t, b);
      if (crosses(p, q, a, b)) return 1;
    }
  }
  return 0;
}

/* Clip every loop; a loop lying inside another of the opposite
** orientation in the same plane (the rim of a hole in a ring-shaped cap)
** is joined to it by a bridge edge first, so the two become one cap with
** a hole. A hole that cannot be bridged is capped on its own. */
static int cap_loops(tds_ctx *ctx, xmesh *x, const int32_t *loop, const int32_t *lstart,
                     int32_t nl) {
  double (*N)[3] = tds_malloc(&ctx->alloc, (size_t)nl * sizeof *N);
  int32_t *hole_of = tds_malloc(&ctx->alloc, (size_t)nl * sizeof *hole_of);
  int32_t *poly = tds_malloc(&ctx->alloc, (size_t)(lstart[nl] + 2 * nl + 1) * sizeof *poly);
  int32_t *holes = tds_malloc(&ctx->alloc, (size_t)nl * sizeof *holes);
  int32_t *tmp = tds_malloc(&ctx->alloc, (size_t)(lstart[nl] + 2 * nl + 1) * sizeof *tmp);
  int rc = TDS_OK;
  if (!N || !hole_of || !poly || !holes || !tmp) {
    rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    goto done;
  }
  for (int32_t i = 0; i < nl; i++) newell(x, loop + lstart[i], lstart[i + 1] - lstart[i], N[i]);
  for (int32_t h = 0; h < nl; h++) {
    hole_of[h] = -1;
    double lh = v3_norm(N[h]), best = INFINITY;
    for (int32_t o = 0; o < nl; o++) {
      double lo = v3_norm(N[o]);
      if (o == h || !(lo > lh) || !(v3_dot(N[o], N[h]) < -0.999 * lo * lh)) continue;
      double n[3] = {N[o][0] / lo, N[o][1] / lo, N[o][2] / lo};
      double tol = 1e-8 * sqrt(lo), d0 = v3_dot(x->x[loop[lstart[o]]], n);
      int flat = 1;
      for (int32_t i = lstart[h]; i < lstart[h + 1] && flat; i++)
        flat = fabs(v3_dot(x->x[loop[i]], n) - d0) <= tol;
      if (!flat || !(lo < best)) continue;
      plane pl;
      plane_of(N[o], &pl);
      double q[2];
      proj(x, &pl, loop[lstart[h]], q);
      if (!in_poly(x, &pl, loop + lstart[o], lstart[o + 1] - lstart[o], q)) continue;
      best = lo;
      hole_of[h] = o;
    }
  }
  for (int32_t h = 0; h < nl; h++) /* only one level: a hole's islands cap alone */
    if (hole_of[h] >= 0 && hole_of[hole_of[h]] >= 0) hole_of[h] = -1;
  for (int32_t o = 0; o < nl && rc == TDS_OK; o++) {
    if (hole_of[o] >= 0) continue;
    int32_t np = lstart[o + 1] - lstart[o], nh = 0;
    memcpy(poly, loop + lstart[o], (size_t)np * sizeof *poly);
    for (int32_t h = 0; h < nl; h++)
      if (hole_of[h] == o) holes[nh++] = h;
    plane pl;
    plane_of(N[o], &pl);
    /* bridge holes in order of their rightmost point, rightmost first */
    while (nh > 0) {
      int32_t bi = 0, bk = 0;
      double bu = -INFINITY;
      for (int32_t k = 0; k < nh; k++)
        for (int32_t i = lstart[holes[k]]; i < lstart[holes[k] + 1]; i++) {
          double p[2];
          proj(x, &pl, loop[i], p);
          if (p[0] > bu) bu = p[0], bi = i, bk = k;
        }
      int32_t hv = loop[bi], hk = holes[bk];
      holes[bk] = holes[--nh];
      /* the nearest polygon vertex to the right that the bridge reaches */
      int32_t jbest = -1;
      double dbest = INFINITY, ph[2];
      proj(x, &pl, hv, ph);
      for (int32_t j = 0; j < np; j++) {
        double pj[2];
        proj(x, &pl, poly[j], pj);
        double d = (pj[0] - ph[0]) * (pj[0] - ph[0]) + (pj[1] - ph[1]) * (pj[1] - ph[1]);
        if (!(pj[0] > ph[0]) || !(d < dbest)) continue;
        int32_t *hl = holes; /* the other holes still unbridged, and this one */
        holes[nh] = hk;
        if (blocked(x, &pl, hv, poly[j], poly, np, loop, lstart, hl, nh + 1)) continue;
        dbest = d;
        jbest = j;
      }
      if (jbest < 0) { /* no bridge: cap the hole by itself */
        rc = clip(ctx, x, loop + lstart[hk], lstart[hk + 1] - lstart[hk]);
        if (rc != TDS_OK) goto done;
        continue;
      }
      /* poly[0..j], hole from hv round to hv, poly[j], poly[j+1..] */
      int32_t m = lstart[hk + 1] - lstart[hk], off = bi - lstart[hk], n2 = 0;
      for (int32_t j = 0; j <= jbest; j++) tmp[n2++] = poly[j];
      for (int32_t i = 0; i <= m; i++) tmp[n2++] = loop[lstart[hk] + (off + i) % m];
      for (int32_t j = jbest; j < np; j++) tmp[n2++] = poly[j];
      memcpy(poly, tmp, (size_t)n2 * sizeof *poly);
      np = n2;
    }
    rc = clip(ctx, x, poly, np);
  }
done:
  tds_free(&ctx->alloc, N);
  tds_free(&ctx->alloc, hole_of);
  tds_free(&ctx->alloc, poly);
  tds_free(&ctx->alloc, holes);
  tds_free(&ctx->alloc, tmp);
  return rc;
}

int tds_export_caps(tds_ctx *ctx, xmesh *x, int32_t *ncap) {
  int32_t nt0 = x->nt, nh = 3 * nt0;
  *ncap = 0;
  hedge *h = tds_malloc(&ctx->alloc, (size_t)(nh > 0 ? nh : 1) * sizeof *h);
  int32_t (*need)[2] = tds_malloc(&ctx->alloc, (size_t)(nh > 0 ? nh : 1) * sizeof *need);
  int32_t *start = tds_calloc(&ctx->alloc, (size_t)x->nv + 1, sizeof *start);
  int32_t *out = tds_malloc(&ctx->alloc, (size_t)(nh > 0 ? nh : 1) * sizeof *out);
  int32_t *loop = tds_malloc(&ctx->alloc, (size_t)(nh > 0 ? nh : 1) * sizeof *loop);
  uint8_t *used = tds_calloc(&ctx->alloc, (size_t)(nh > 0 ? nh : 1), 1);
  int32_t *lstart = tds_malloc(&ctx->alloc, (size_t)(nh + 2) * sizeof *lstart);
  int rc = TDS_OK;
  if (!h || !need || !start || !out || !loop || !used || !lstart) {
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
    int32_t *fill = tds_calloc(&ctx->alloc, (size_t)x->nv + 1, sizeof *fill);
    if (!fill) {
      rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      goto done;
    }
    for (int32_t i = 0; i < nneed; i++) out[start[need[i][0]] + fill[need[i][0]]++] = i;
    tds_free(&ctx->alloc, fill);
  }
  int32_t nl = 0, nloop = 0;
  for (int32_t e0 = 0; e0 < nneed && rc == TDS_OK; e0++) {
    if (used[e0]) continue;
    int32_t n = 0, e = e0, v0 = need[e0][0];
    for (;;) {
      used[e] = 1;
      loop[nloop + n++] = need[e][0];
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
    if (rc == TDS_OK && n >= 3) {
      lstart[nl++] = nloop;
      nloop += n;
      lstart[nl] = nloop;
    }
  }
  if (rc == TDS_OK && nl > 0) rc = cap_loops(ctx, x, loop, lstart, nl);
  *ncap = x->nt - nt0;
done:
  tds_free(&ctx->alloc, h);
  tds_free(&ctx->alloc, need);
  tds_free(&ctx->alloc, start);
  tds_free(&ctx->alloc, out);
  tds_free(&ctx->alloc, loop);
  tds_free(&ctx->alloc, used);
  tds_free(&ctx->alloc, lstart);
  return rc;
}
