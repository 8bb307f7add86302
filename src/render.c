/* render.c: pictures of a surface with cairo (see render.h). */
#include "torus.h"
#include "render.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export.h"
#include "gather.h"
#include "metrics.h"
#include "render_int.h"
#include "vec3.h"

/* Supersampling factor of the facet buffer: 2, or 1 for pictures of more
** than 4 megapixels (their buffer would pass 64 MB). */
#define SS (o->width * o->height <= (1 << 22) ? 2 : 1)

void tds_render_defaults(tds_render_opts *o) {
  memset(o, 0, sizeof *o);
  o->width = 800;
  o->height = 600;
  o->color = TDS_RCOL_NONE;
  o->azimuth = -60;
  o->elevation = 30;
  o->legend = 1;
  o->lighting = 1;
}

void tds_render_ramp(double t, double rgb[3]) {
  /* Moreland's cool-warm endpoints through a light grey middle. */
  static const double c[3][3] = {
      {0.230, 0.299, 0.754}, {0.865, 0.865, 0.865}, {0.706, 0.016, 0.150}};
  if (!(t >= 0)) t = 0; /* also NaN */
  if (t > 1) t = 1;
  int i = t < 0.5 ? 0 : 1;
  double u = t < 0.5 ? 2 * t : 2 * t - 1;
  for (int k = 0; k < 3; k++) rgb[k] = c[i][k] + u * (c[i + 1][k] - c[i][k]);
}

void tds_render_body_color(tds_id b, double rgb[3]) {
  /* Well separated hues (golden-ratio steps), fixed saturation/value. */
  double h = fmod(0.08 + 0.618033988749895 * (double)b, 1.0) * 6;
  int i = (int)h;
  double f = h - i, v = 0.9, s = 0.6;
  double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
  for (int k = 0; k < 3; k++) rgb[k] = r[i % 6][k];
}

void tds_render_evolver_color(int c, double rgb[3]) {
  unsigned char rgba[4];
  tds_export_rgba(c < 0 || c > 15 ? 15 : c, rgba); /* the one palette */
  for (int k = 0; k < 3; k++) rgb[k] = rgba[k] / 255.0;
}

static const double neutral[3] = {0.80, 0.82, 0.88};
static const double novalue[3] = {0.55, 0.55, 0.55};

/* tds_render_field; with mode MEAN_CURVATURE and hout non-NULL, *hout
** receives the per-vertex values (from ctx->alloc) (NaN where not measured). */
static int field_values(tds_ctx *ctx, tds_surf *s, int mode, double *val, double **hout,
                        tds_surf *orig, const tds_torus_drawn *dv) {
  tds_mesh *m = &s->m;
  if (mode == TDS_RCOL_MEAN_CURVATURE) {
    if (tds_mesh_adjacency(m) != TDS_OK)
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    double *h = tds_calloc(&ctx->alloc, (size_t)(m->nv > 0 ? m->nv : 1), sizeof *h);
    if (!h) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    for (tds_id v = 0; v < m->nv; v++)
      h[v] = (m->vflags[v] & TDS_DEAD) ? (double)NAN
             : dv                      ? tds_torus_drawn_curvature(dv, orig, v)
                                       : tds_vertex_mean_curvature(s, v);
    for (tds_id f = 0; f < m->nf; f++) {
      double sum = 0;
      int n = 0;
      for (int k = 0; k < 3 && !(m->fflags[f] & TDS_DEAD); k++) {
        double x = h[m->fv[f][k]];
        if (!isnan(x)) {
          sum += x;
          n++;
        }
      }
      val[f] = n ? sum / n : (double)NAN;
    }
    if (hout) *hout = h;
    else tds_free(&ctx->alloc, h);
    return TDS_OK;
  }
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) val[f] = NAN;
    else if (mode == TDS_RCOL_MIN_ANGLE) val[f] = tds_facet_min_angle(m, f);
    else val[f] = m->ften[f];
  }
  return TDS_OK;
}

int tds_render_field(tds_ctx *ctx, tds_surf *s, int mode, double *val) {
  return field_values(ctx, s, mode, val, NULL, NULL, NULL);
}

static int is_field(int mode) {
  return mode == TDS_RCOL_MEAN_CURVATURE || mode == TDS_RCOL_MIN_ANGLE ||
         mode == TDS_RCOL_TENSION;
}

typedef struct {
  float x[3], y[3];
  float depth;
  float rgb[3];     /* flat colour, shaded */
  float vrgb[3][3]; /* smooth: the corners' colours, shaded */
} rfacet;

static int by_depth(const void *a, const void *b) {
  float da = ((const rfacet *)a)->depth, db = ((const rfacet *)b)->depth;
  return (da > db) - (da < db);
}

/* The camera frame and the fit of the bounding sphere into the picture. */
static int frame(tds_ctx *ctx, const tds_mesh *m, const tds_render_opts *o,
                 int plotw, tds_render_info *in) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  int any = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    tds_corners C;
    tds_gather_facet(m, f, &C);
    for (int k = 0; k < 3; k++) {
      const double *p = C.x[k];
      if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
        return tds_seterr(ctx, TDS_ENUM, "snapshot: vertex %d has a non-finite "
                          "coordinate", m->fv[f][k] + 1);
      for (int c = 0; c < 3; c++) {
        if (p[c] < lo[c]) lo[c] = p[c];
        if (p[c] > hi[c]) hi[c] = p[c];
      }
    }
    any = 1;
  }
  if (!any) return tds_seterr(ctx, TDS_ERANGE, "snapshot: the surface has no facets");
  double R = 0;
  for (int c = 0; c < 3; c++) in->center[c] = 0.5 * (lo[c] + hi[c]);
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    tds_corners C;
    tds_gather_facet(m, f, &C);
    for (int k = 0; k < 3; k++) {
      double d[3];
      v3_sub(d, C.x[k], in->center);
      double r = v3_norm(d);
      if (r > R) R = r;
    }
  }
  if (!(R < 1e150)) /* also inf: the picture's arithmetic would overflow */
    return tds_seterr(ctx, TDS_ERANGE, "snapshot: the surface is too large to draw");
  if (!(R > 0)) R = 1;
  in->radius = R;
  tds_render_camera(o, o->azimuth * TDS_PI / 180, o->elevation * TDS_PI / 180, 1, plotw, in);
  return TDS_OK;
}

void tds_render_camera(const tds_render_opts *o, double a, double e, int persp, int plotw,
                       tds_render_info *in) {
  double d[3] = {cos(e) * cos(a), cos(e) * sin(a), sin(e)};
  double r[3] = {-sin(a), cos(a), 0};
  v3_copy(in->toward, d);
  v3_copy(in->right, r);
  v3_cross(in->up, d, r);
  double fit = 0.46 * (plotw < o->height ? plotw : o->height);
  double apparent = in->radius; /* radius of the bounding sphere's image */
  if (persp && o->distance > 0) apparent = in->radius / sqrt(1 - 1 / (o->distance * o->distance));
  in->scale = fit / apparent;
  in->cx = 0.5 * plotw;
  in->cy = 0.5 * o->height;
}

void tds_render_project(const tds_render_info *in, const tds_render_opts *o, const double p[3],
                        double *x, double *y, double *z) {
  double q[3];
  v3_sub(q, p, in->center);
  double u = v3_dot(q, in->right), w = v3_dot(q, in->up), dz = v3_dot(q, in->toward);
  double k = in->scale;
  if (o->distance > 0) {
    double D = o->distance * in->radius;
    k *= D / (D - dz);
  }
  *x = in->cx + k * u;
  *y = in->cy - k * w;
  *z = dz;
}

static void facet_color(const tds_mesh *m, tds_id f, int mode, double v,
                        double lo, double hi, double rgb[3]) {
  switch (mode) {
  case TDS_RCOL_BODY: {
    tds_id b = m->fb[f][0] != TDS_NONE ? m->fb[f][0] : m->fb[f][1];
    if (b == TDS_NONE) v3_copy(rgb, neutral);
    else tds_render_body_color(b, rgb);
    break;
  }
  case TDS_RCOL_COLOR:
    /* a facet given no colour has Evolver's default, 15 (white) */
    tds_render_evolver_color(m->fcolor[f], rgb);
    break;
  case TDS_RCOL_NONE:
    v3_copy(rgb, neutral);
    break;
  default:
    if (isnan(v)) v3_copy(rgb, novalue);
    else tds_render_ramp(hi > lo ? (v - lo) / (hi - lo) : 0.5, rgb);
  }
}

/* Lambert shade of a facet or vertex with normal N (either side). */
static double lambert(const tds_render_info *in, const double L[3], const double N[3]) {
  double nl = v3_norm(N);
  if (!(nl > 0)) return 0.4;
  double c = (v3_dot(N, in->right) * L[0] + v3_dot(N, in->up) * L[1] +
              v3_dot(N, in->toward) * L[2]) / nl;
  return 0.4 + 0.6 * fabs(c);
}

static void corner_patch(cairo_pattern_t *pat, const rfacet *r) {
  cairo_mesh_pattern_begin_patch(pat);
  cairo_mesh_pattern_move_to(pat, r->x[0], r->y[0]);
  cairo_mesh_pattern_line_to(pat, r->x[1], r->y[1]);
  cairo_mesh_pattern_line_to(pat, r->x[2], r->y[2]);
  for (int j = 0; j < 3; j++)
    cairo_mesh_pattern_set_corner_color_rgb(pat, (unsigned)j, r->vrgb[j][0],
                                            r->vrgb[j][1], r->vrgb[j][2]);
  cairo_mesh_pattern_end_patch(pat);
}

/* Paint the sorted facets back to front: flat fills, or (smooth) one
** mesh pattern whose patches cairo paints in order; with edges every
** facet is filled and outlined in turn, so hidden edges stay hidden. */
static void paint_facets(cairo_t *cr, const rfacet *rf, int32_t n, int smooth,
                         int edges) {
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  cairo_set_line_width(cr, 0.9);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  if (smooth && !edges) {
    cairo_pattern_t *pat = cairo_pattern_create_mesh();
    for (int32_t i = 0; i < n; i++) corner_patch(pat, &rf[i]);
    cairo_set_source(cr, pat);
    cairo_paint(cr);
    cairo_pattern_destroy(pat);
    return;
  }
  for (int32_t i = 0; i < n; i++) {
    const rfacet *r = &rf[i];
    cairo_move_to(cr, r->x[0], r->y[0]);
    cairo_line_to(cr, r->x[1], r->y[1]);
    cairo_line_to(cr, r->x[2], r->y[2]);
    cairo_close_path(cr);
    cairo_pattern_t *pat = NULL;
    if (smooth) {
      pat = cairo_pattern_create_mesh();
      corner_patch(pat, r);
      cairo_set_source(cr, pat);
    } else {
      cairo_set_source_rgb(cr, r->rgb[0], r->rgb[1], r->rgb[2]);
    }
    if (edges) {
      cairo_fill_preserve(cr);
      cairo_set_source_rgb(cr, 0.35 * (double)r->rgb[0], 0.35 * (double)r->rgb[1], 0.35 * (double)r->rgb[2]);
      cairo_stroke(cr);
    } else {
      cairo_fill(cr);
    }
    if (pat) cairo_pattern_destroy(pat);
  }
}

/* The picture of s; for a torus surface s is its drawn mesh (dv), whose
** vertices have the curvature of those they are drawn from in orig. */
static int render_drawn(tds_ctx *ctx, tds_surf *s, const tds_render_opts *o, const char *path,
                        tds_render_info *info, tds_surf *orig, const tds_torus_drawn *dv) {
  tds_mesh *m = &s->m;
  tds_render_info in;
  memset(&in, 0, sizeof in);
  if (o->width < 16 || o->height < 16 || o->width > 8192 || o->height > 8192)
    return tds_seterr(ctx, TDS_ERANGE, "snapshot: size must be 16..8192 pixels each way");
  if (o->distance != 0 && !(o->distance > 1))
    return tds_seterr(ctx, TDS_ERANGE,
                      "snapshot: view distance must exceed 1 (bounding radii)");
  int field = is_field(o->color);
  int32_t nbody = o->color == TDS_RCOL_BODY ? tds_mesh_count(m, TDS_BODY) : 0;
  int legend = (field || nbody > 0) && o->legend && o->width >= 200;
  int legw = legend ? 110 : 0;
  int plotw = o->width - legw;
  int rc = frame(ctx, m, o, plotw, &in);
  if (rc != TDS_OK) return rc;

  double *val = tds_calloc(&ctx->alloc, (size_t)(m->nf > 0 ? m->nf : 1), sizeof *val);
  rfacet *rf = tds_calloc(&ctx->alloc, (size_t)(m->nf > 0 ? m->nf : 1), sizeof *rf);
  if (!val || !rf) {
    tds_free(&ctx->alloc, val);
    tds_free(&ctx->alloc, rf);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  double *h = NULL, (*vn)[3] = NULL; /* smooth: vertex k1+k2 and normals */
  rc = field ? field_values(ctx, s, o->color, val, o->smooth ? &h : NULL, orig, dv) : TDS_OK;
  if (rc == TDS_OK && o->smooth) {
    vn = tds_calloc(&ctx->alloc, (size_t)(m->nv > 0 ? m->nv : 1), sizeof *vn);
    if (!vn) rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    for (tds_id f = 0; vn && f < m->nf; f++) {
      if (m->fflags[f] & (TDS_DEAD | TDS_NODISPLAY)) continue;
      double a[3], b[3], N[3];
      tds_corners C;
      tds_gather_facet(m, f, &C);
      v3_sub(a, C.x[1], C.x[0]);
      v3_sub(b, C.x[2], C.x[0]);
      v3_cross(N, a, b);
      for (int k = 0; k < 3; k++) v3_add(vn[m->fv[f][k]], vn[m->fv[f][k]], N);
    }
  }
  double lo = INFINITY, hi = -INFINITY;
  if (rc == TDS_OK && field) {
    for (tds_id f = 0; f < m->nf; f++)
      if (!isnan(val[f])) {
        if (val[f] < lo) lo = val[f];
        if (val[f] > hi) hi = val[f];
      }
    for (tds_id v = 0; h && v < m->nv; v++) /* smooth: the vertices' values */
      if (!isnan(h[v])) {
        if (h[v] < lo) lo = h[v];
        if (h[v] > hi) hi = h[v];
      }
    if (o->has_range) {
      lo = o->range[0];
      hi = o->range[1];
    } else if (!(lo <= hi)) {
      lo = 0;
      hi = 1;
    } else if (hi - lo <= 1e-9 * (fabs(lo) + fabs(hi))) {
      double pad = lo != 0 ? 0.01 * fabs(lo) : 0.5;
      lo -= pad;
      hi += pad;
    }
    in.lo = lo;
    in.hi = hi;
  }
  /* light in view coordinates (right, up, toward) */
  double L[3] = {-0.35, 0.55, 0.76}, ln = v3_norm(L);
  for (int k = 0; k < 3; k++) L[k] /= ln;
  int32_t n = 0;
  for (tds_id f = 0; rc == TDS_OK && f < m->nf; f++) {
    if (m->fflags[f] & (TDS_DEAD | TDS_NODISPLAY)) continue;
    if (o->color == TDS_RCOL_COLOR && m->fcolor[f] < 0) continue; /* CLEAR */
    rfacet *r = &rf[n];
    float z[3];
    tds_corners C;
    tds_gather_facet(m, f, &C);
    for (int k = 0; k < 3; k++) {
      double px, py, pz;
      tds_render_project(&in, o, C.x[k], &px, &py, &pz);
      r->x[k] = (float)px, r->y[k] = (float)py, z[k] = (float)pz;
    }
    r->depth = (z[0] + z[1] + z[2]) / 3;
    double rgb[3], N[3];
    facet_color(m, f, o->color, val[f], lo, hi, rgb);
    double a[3], b[3];
    v3_sub(a, C.x[1], C.x[0]);
    v3_sub(b, C.x[2], C.x[0]);
    v3_cross(N, a, b);
    double shade = o->lighting ? lambert(&in, L, N) : 1;
    for (int k = 0; k < 3; k++) r->rgb[k] = (float)(rgb[k] * shade);
    for (int j = 0; o->smooth && j < 3; j++) { /* Gouraud: corner colours */
      tds_id v = m->fv[f][j];
      double c[3], sv = 1;
      v3_copy(c, rgb);
      if (h && !isnan(h[v])) tds_render_ramp(hi > lo ? (h[v] - lo) / (hi - lo) : 0.5, c);
      if (o->lighting) sv = lambert(&in, L, v3_norm(vn[v]) > 0 ? vn[v] : N);
      for (int k = 0; k < 3; k++) r->vrgb[j][k] = (float)(c[k] * sv);
    }
    n++;
  }
  tds_free(&ctx->alloc, val);
  tds_free(&ctx->alloc, h);
  tds_free(&ctx->alloc, vn);
  if (rc != TDS_OK) {
    tds_free(&ctx->alloc, rf);
    return rc;
  }
  qsort(rf, (size_t)n, sizeof *rf, by_depth);

  cairo_surface_t *big = cairo_image_surface_create(CAIRO_FORMAT_RGB24, SS * plotw,
                                                    SS * o->height);
  cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, o->width, o->height);
  if (cairo_surface_status(big) || cairo_surface_status(img)) {
    cairo_surface_destroy(big);
    cairo_surface_destroy(img);
    tds_free(&ctx->alloc, rf);
    return tds_seterr(ctx, TDS_ENOMEM, "snapshot: out of memory for the image");
  }
  cairo_t *cr = cairo_create(big);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_scale(cr, SS, SS);
  paint_facets(cr, rf, n, o->smooth, o->edges);
  cairo_destroy(cr);
  tds_free(&ctx->alloc, rf);

  cr = cairo_create(img);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_save(cr);
  cairo_scale(cr, 1.0 / SS, 1.0 / SS);
  cairo_set_source_surface(cr, big, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
  cairo_paint(cr);
  cairo_restore(cr);
  if (legend && nbody > 0) {
    int32_t ids[16], k = 0;
    for (tds_id b = 0; b < m->nb && k < 16; b++)
      if (!(m->bflags[b] & TDS_DEAD)) ids[k++] = b;
    tds_draw_swatches(cr, plotw + 10, 0.15 * o->height, ids, nbody > 16 ? 17 : k);
  } else if (legend)
    tds_draw_colorbar(cr, plotw + 20, 0.15 * o->height, 22, 0.7 * o->height, lo, hi,
                      o->color == TDS_RCOL_MEAN_CURVATURE ? "k1+k2"
                      : o->color == TDS_RCOL_MIN_ANGLE  ? "min angle"
                                                        : "tension");
  cairo_destroy(cr);
  cairo_surface_destroy(big);
  rc = tds_write_png(ctx, img, path);
  cairo_surface_destroy(img);
  if (rc != TDS_OK) return rc;
  in.drawn = n;
  if (o->color == TDS_RCOL_BODY) in.nbody_colors = tds_mesh_count(m, TDS_BODY);
  if (info) *info = in;
  return TDS_OK;
}

int tds_render_png(tds_ctx *ctx, tds_surf *s, const tds_render_opts *o,
                   const char *path, tds_render_info *info) {
  int strings_clipped = s->str && s->m.torus && s->m.draw == TDS_DRAW_CLIPPED;
  if (s->str && !strings_clipped) return tds_render_strings(ctx, s, o, path, info); /* edges */
  if (!s->m.torus) return render_drawn(ctx, s, o, path, info, NULL, NULL);
  tds_torus_drawn view; /* as drawn: no edge across the cell */
  int rc = tds_torus_view(ctx, s, &view);
  if (rc != TDS_OK) return rc;
  rc = strings_clipped ? tds_render_strings(ctx, &view.s, o, path, info)
                       : render_drawn(ctx, &view.s, o, path, info, s, &view);
  tds_torus_view_free(&view);
  return rc;
}
