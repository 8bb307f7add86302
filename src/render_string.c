/* render_string.c: pictures of string-model surfaces (render.h's
** tds_render_png hands them here): the edges drawn as lines, over the
** cells filled with their body's or their own colour. In 2-D space the
** picture is always the plane seen from +z (x to the right, y up); in 3-D
** space the options' view, orthographic or perspective as for facets.
** Each edge is drawn from its tail to its head unwrapped (tds_gather_edge),
** and each cell as the polygon of its loop's edge vectors from its first
** corner, so a torus string surface never shows a wall across the cell.
** Cells are painted back to front (the depth of their corners' mean),
** then every edge; without cells to fill the edges stand alone. */
#include "render.h"

#include <cairo.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gather.h"
#include "render_int.h"
#include "string_model.h"
#include "vec3.h"

typedef struct {
  tds_id f;
  double depth;
} rcell;

static int by_depth(const void *a, const void *b) {
  double da = ((const rcell *)a)->depth, db = ((const rcell *)b)->depth;
  return (da > db) - (da < db);
}

/* The camera and the fit of the edges' bounding sphere into plotw x h. */
static int frame(tds_ctx *ctx, const tds_surf *s, const tds_render_opts *o, int plotw,
                 tds_render_info *in) {
  const tds_mesh *m = &s->m;
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  int any = 0;
  for (int pass = 0; pass < 2; pass++) {
    double R = 0;
    for (tds_id e = 0; e < m->ne; e++) {
      if (m->eflags[e] & TDS_DEAD) continue;
      tds_corners C;
      tds_gather_edge(m, TDS_OREF(e, 0), &C);
      for (int k = 0; k < 2; k++) {
        const double *p = C.x[k];
        if (pass == 0) {
          if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            return tds_seterr(ctx, TDS_ENUM, "snapshot: vertex %d has a non-finite coordinate",
                              m->ev[e][k] + 1);
          for (int c = 0; c < 3; c++) {
            if (p[c] < lo[c]) lo[c] = p[c];
            if (p[c] > hi[c]) hi[c] = p[c];
          }
          any = 1;
        } else {
          double d[3];
          v3_sub(d, p, in->center);
          if (v3_norm(d) > R) R = v3_norm(d);
        }
      }
    }
    if (pass == 0) {
      if (!any) return tds_seterr(ctx, TDS_ERANGE, "snapshot: the surface has no edges");
      for (int c = 0; c < 3; c++) in->center[c] = 0.5 * (lo[c] + hi[c]);
    } else {
      if (!(R < 1e150))
        return tds_seterr(ctx, TDS_ERANGE, "snapshot: the surface is too large to draw");
      in->radius = R > 0 ? R : 1;
    }
  }
  double a = o->azimuth * TDS_PI / 180, e = o->elevation * TDS_PI / 180;
  int plane = s->str->space_dim == 2;
  if (plane) { /* the plane from +z: x right, y up */
    a = -TDS_PI / 2;
    e = TDS_PI / 2;
  }
  tds_render_camera(o, a, e, !plane, plotw, in);
  return TDS_OK;
}

/* The fill colour of cell f, 0 when it has none (no body; CLEAR). */
static int cell_color(const tds_strings *st, tds_id f, int mode, double rgb[3]) {
  if (mode == TDS_RCOL_BODY) {
    tds_id b = st->fb[f][0] != TDS_NONE ? st->fb[f][0] : st->fb[f][1];
    if (b == TDS_NONE) return 0;
    tds_render_body_color(b, rgb);
    return 1;
  }
  if (mode == TDS_RCOL_COLOR && st->color[f] >= 0) {
    tds_render_evolver_color(st->color[f], rgb);
    return 1;
  }
  return 0;
}

static void edge_color(const tds_mesh *m, tds_id e, int mode, double lo, double hi,
                       double rgb[3]) {
  if (mode == TDS_RCOL_TENSION) {
    tds_render_ramp(hi > lo ? (m->eten[e] - lo) / (hi - lo) : 0.5, rgb);
  } else if (mode == TDS_RCOL_COLOR && m->ecolor[e] >= 0 && m->ecolor[e] != 15) {
    tds_render_evolver_color(m->ecolor[e], rgb); /* 15 (white, the default): black */
  } else {
    rgb[0] = rgb[1] = rgb[2] = 0.1;
  }
}

/* Cells (when the colouring fills them) back to front, then the edges. */
static int paint(tds_ctx *ctx, const tds_surf *s, const tds_render_opts *o,
                 const tds_render_info *in, cairo_t *cr, int32_t *drawn) {
  const tds_mesh *m = &s->m;
  const tds_strings *st = s->str;
  int fill = o->color == TDS_RCOL_BODY || o->color == TDS_RCOL_COLOR;
  rcell *rc = NULL;
  int32_t n = 0;
  if (fill && st->nf > 0) {
    rc = tds_calloc(&ctx->alloc, (size_t)st->nf, sizeof *rc);
    if (!rc) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  for (tds_id f = 0; rc && f < st->nf; f++) {
    if ((st->flags[f] & (TDS_DEAD | TDS_NODISPLAY)) || st->start[f] == st->start[f + 1])
      continue;
    double rgb[3], p[3], sum = 0;
    if (!cell_color(st, f, o->color, rgb)) continue;
    tds_corners C;
    tds_gather_edge(m, st->oe[st->start[f]], &C);
    v3_copy(p, C.x[0]);
    for (int32_t k = st->start[f]; k < st->start[f + 1]; k++) {
      double d[3], x, y, z;
      tds_render_project(in, o, p, &x, &y, &z);
      sum += z;
      tds_edge_vec(m, st->oe[k], d);
      v3_add(p, p, d);
    }
    rc[n++] = (rcell){f, sum / (st->start[f + 1] - st->start[f])};
  }
  if (n > 1) qsort(rc, (size_t)n, sizeof *rc, by_depth);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (int32_t i = 0; i < n; i++) {
    tds_id f = rc[i].f;
    double rgb[3], p[3], x, y, z;
    cell_color(st, f, o->color, rgb);
    tds_corners C;
    tds_gather_edge(m, st->oe[st->start[f]], &C);
    v3_copy(p, C.x[0]);
    tds_render_project(in, o, p, &x, &y, &z);
    cairo_move_to(cr, x, y);
    for (int32_t k = st->start[f]; k < st->start[f + 1]; k++) {
      double d[3];
      tds_edge_vec(m, st->oe[k], d);
      v3_add(p, p, d);
      tds_render_project(in, o, p, &x, &y, &z);
      cairo_line_to(cr, x, y);
    }
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_fill(cr);
  }
  tds_free(&ctx->alloc, rc);
  /* about 1/300 of the picture, at least a pixel */
  double lw = (o->width < o->height ? o->width : o->height) / 300.0;
  cairo_set_line_width(cr, lw > 1 ? lw : 1);
  *drawn = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    tds_corners C;
    tds_gather_edge(m, TDS_OREF(e, 0), &C);
    double x0, y0, x1, y1, z, rgb[3];
    tds_render_project(in, o, C.x[0], &x0, &y0, &z);
    tds_render_project(in, o, C.x[1], &x1, &y1, &z);
    edge_color(m, e, o->color, in->lo, in->hi, rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_move_to(cr, x0, y0);
    cairo_line_to(cr, x1, y1);
    cairo_stroke(cr);
    (*drawn)++;
  }
  return TDS_OK;
}

int tds_render_strings(tds_ctx *ctx, tds_surf *s, const tds_render_opts *o, const char *path,
                       tds_render_info *info) {
  tds_mesh *m = &s->m;
  tds_render_info in;
  memset(&in, 0, sizeof in);
  if (o->width < 16 || o->height < 16 || o->width > 8192 || o->height > 8192)
    return tds_seterr(ctx, TDS_ERANGE, "snapshot: size must be 16..8192 pixels each way");
  if (o->distance != 0 && !(o->distance > 1))
    return tds_seterr(ctx, TDS_ERANGE, "snapshot: view distance must exceed 1 (bounding radii)");
  if (o->color == TDS_RCOL_MEAN_CURVATURE || o->color == TDS_RCOL_MIN_ANGLE)
    return tds_seterr(ctx, TDS_ERANGE, "snapshot: color = \"%s\" needs facets; the string "
                      "model's pictures colour by \"body\", \"color\" or \"tension\"",
                      o->color == TDS_RCOL_MIN_ANGLE ? "min_angle" : "mean_curvature");
  int32_t nbody = o->color == TDS_RCOL_BODY ? tds_mesh_count(m, TDS_BODY) : 0;
  int field = o->color == TDS_RCOL_TENSION;
  int legend = (field || nbody > 0) && o->legend && o->width >= 200;
  int plotw = o->width - (legend ? 110 : 0);
  int rc = frame(ctx, s, o, plotw, &in);
  if (rc != TDS_OK) return rc;
  if (field) {
    in.lo = HUGE_VAL;
    in.hi = -HUGE_VAL;
    for (tds_id e = 0; e < m->ne; e++)
      if (!(m->eflags[e] & TDS_DEAD)) {
        if (m->eten[e] < in.lo) in.lo = m->eten[e];
        if (m->eten[e] > in.hi) in.hi = m->eten[e];
      }
    if (o->has_range) {
      in.lo = o->range[0];
      in.hi = o->range[1];
    } else if (in.hi - in.lo <= 1e-9 * (fabs(in.lo) + fabs(in.hi))) { /* one tension */
      double pad = in.lo != 0 ? 0.01 * fabs(in.lo) : 0.5;
      in.lo -= pad;
      in.hi += pad;
    }
  }
  cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, o->width, o->height);
  if (cairo_surface_status(img)) {
    cairo_surface_destroy(img);
    return tds_seterr(ctx, TDS_ENOMEM, "snapshot: out of memory for the image");
  }
  cairo_t *cr = cairo_create(img);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_rectangle(cr, 0, 0, plotw, o->height);
  cairo_clip(cr);
  rc = paint(ctx, s, o, &in, cr, &in.drawn);
  cairo_reset_clip(cr);
  if (rc == TDS_OK && legend && nbody > 0) {
    int32_t ids[16], k = 0;
    for (tds_id b = 0; b < m->nb && k < 16; b++)
      if (!(m->bflags[b] & TDS_DEAD)) ids[k++] = b;
    tds_draw_swatches(cr, plotw + 10, 0.15 * o->height, ids, nbody > 16 ? 17 : k);
  } else if (rc == TDS_OK && legend) {
    tds_draw_colorbar(cr, plotw + 20, 0.15 * o->height, 22, 0.7 * o->height, in.lo, in.hi,
                      "tension");
  }
  cairo_destroy(cr);
  if (rc == TDS_OK) rc = tds_write_png(ctx, img, path);
  cairo_surface_destroy(img);
  if (rc != TDS_OK) return rc;
  if (o->color == TDS_RCOL_BODY) in.nbody_colors = nbody;
  if (info) *info = in;
  return TDS_OK;
}
