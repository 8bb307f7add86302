/* render_plot.c: line plots, histograms and the colour bar (render.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "render.h"
#include "render_int.h"

int tds_write_png(tds_ctx *ctx, cairo_surface_t *img, const char *path) {
  cairo_surface_flush(img);
  cairo_status_t st = cairo_surface_write_to_png(img, path);
  if (st != CAIRO_STATUS_SUCCESS)
    return tds_seterr(ctx, TDS_EIO, "cannot write '%s': %s", path,
                      st == CAIRO_STATUS_WRITE_ERROR ? "write error"
                                                     : cairo_status_to_string(st));
  return TDS_OK;
}

static void font(cairo_t *cr, double size) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

/* Text with its anchor: ax, ay in {0, 0.5, 1} of its extents. */
static void text_at(cairo_t *cr, double x, double y, double ax, double ay,
                    const char *s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s, &e);
  cairo_move_to(cr, x - e.x_bearing - ax * e.width, y - e.y_bearing - ay * e.height);
  cairo_show_text(cr, s);
}

/* Tick spacing of a linear axis: 1, 2 or 5 times a power of ten. */
static double nice_step(double range, int want) {
  double raw = range / want, p = pow(10, floor(log10(raw)));
  double f = raw / p;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
}

static void fmt_num(char *buf, size_t n, double v, double step) {
  if (fabs(v) < 1e-12 * step) v = 0;
  snprintf(buf, n, "%.4g", v);
}

void tds_draw_colorbar(cairo_t *cr, double x, double y, double w, double h,
                       double lo, double hi, const char *title) {
  int steps = (int)h;
  for (int i = 0; i < steps; i++) {
    double rgb[3];
    tds_render_ramp((i + 0.5) / steps, rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_rectangle(cr, x, y + h - (i + 1) * h / steps, w, h / steps + 0.5);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, x + 0.5, y + 0.5, w - 1, h - 1);
  cairo_stroke(cr);
  font(cr, 12);
  text_at(cr, x + w / 2, y - 8, 0.5, 1, title);
  if (!(hi > lo)) return;
  double step = nice_step(hi - lo, 5);
  for (double t = ceil(lo / step) * step; t <= hi + 1e-9 * step; t += step) {
    double yy = y + h - (t - lo) / (hi - lo) * h;
    char buf[32];
    fmt_num(buf, sizeof buf, t, step);
    cairo_move_to(cr, x + w, yy);
    cairo_line_to(cr, x + w + 4, yy);
    cairo_stroke(cr);
    text_at(cr, x + w + 7, yy, 0, 0.5, buf);
  }
}

void tds_draw_swatches(cairo_t *cr, double x, double y, const int32_t *ids,
                       int n) {
  font(cr, 12);
  cairo_set_line_width(cr, 1);
  for (int i = 0; i < n && i < 16; i++) {
    double rgb[3], yy = y + 20 * i;
    char buf[32];
    if (i == 15 && n > 16) {
      cairo_set_source_rgb(cr, 0, 0, 0);
      text_at(cr, x + 20, yy + 7, 0, 0.5, "...");
      break;
    }
    tds_render_body_color(ids[i], rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_rectangle(cr, x, yy, 14, 14);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, x + 0.5, yy + 0.5, 13, 13);
    cairo_stroke(cr);
    snprintf(buf, sizeof buf, "body %d", (int)ids[i] + 1);
    text_at(cr, x + 20, yy + 7, 0, 0.5, buf);
  }
}

/* Axis range of a series (log10 of the positive values when log). */
static int series_range(const double *y, int32_t n, int lg, double *lo, double *hi) {
  *lo = INFINITY;
  *hi = -INFINITY;
  for (int32_t i = 0; i < n; i++) {
    double v = y[i];
    if (!isfinite(v) || (lg && !(v > 0))) continue;
    if (lg) v = log10(v);
    if (v < *lo) *lo = v;
    if (v > *hi) *hi = v;
  }
  if (!(*lo <= *hi)) return 0;
  if (lg) {
    *lo = floor(*lo);
    *hi = ceil(*hi);
    if (*hi == *lo) *hi += 1;
  } else if (*hi - *lo <= 1e-12 * (fabs(*lo) + fabs(*hi))) {
    double pad = *lo != 0 ? 1e-6 * fabs(*lo) : 1;
    *lo -= pad;
    *hi += pad;
  } else {
    double pad = 0.05 * (*hi - *lo);
    *lo -= pad;
    *hi += pad;
  }
  return 1;
}

/* Frame, grid and labels of a panel; x ticks labelled when xlabels. */
static void axes(cairo_t *cr, double X0, double Y0, double X1, double Y1,
                 double xlo, double xhi, double lo, double hi, int lg,
                 const char *title, const char *xtitle) {
  char buf[32];
  cairo_set_line_width(cr, 1);
  font(cr, 12);
  double step = nice_step(xhi - xlo, 6);
  if (step < 1) step = 1;
  for (double t = ceil(xlo / step) * step; t <= xhi; t += step) {
    double xx = X0 + (t - xlo) / (xhi - xlo) * (X1 - X0);
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, floor(xx) + 0.5, Y0);
    cairo_line_to(cr, floor(xx) + 0.5, Y1);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    fmt_num(buf, sizeof buf, t, step);
    if (xtitle) text_at(cr, xx, Y1 + 6, 0.5, 0, buf);
  }
  double ystep = lg ? (hi - lo > 8 ? ceil((hi - lo) / 8) : 1) : nice_step(hi - lo, 5);
  for (double t = ceil(lo / ystep) * ystep; t <= hi + 1e-9 * ystep; t += ystep) {
    double yy = Y1 - (t - lo) / (hi - lo) * (Y1 - Y0);
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, X0, floor(yy) + 0.5);
    cairo_line_to(cr, X1, floor(yy) + 0.5);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    if (lg) snprintf(buf, sizeof buf, "1e%d", (int)lround(t));
    else fmt_num(buf, sizeof buf, t, ystep);
    text_at(cr, X0 - 6, yy, 1, 0.5, buf);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, floor(X0) + 0.5, floor(Y0) + 0.5, floor(X1 - X0), floor(Y1 - Y0));
  cairo_stroke(cr);
  font(cr, 13);
  text_at(cr, (X0 + X1) / 2, Y0 - 6, 0.5, 1, title);
  if (xtitle) text_at(cr, (X0 + X1) / 2, Y1 + 24, 0.5, 0, xtitle);
}

static int canvas(tds_ctx *ctx, const char *what, int w, int h,
                  cairo_surface_t **img, cairo_t **cr) {
  if (w < 100 || h < 80 || w > 8192 || h > 8192)
    return tds_seterr(ctx, TDS_ERANGE, "%s: size must be 100..8192 by 80..8192 pixels",
                      what);
  *img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  if (cairo_surface_status(*img)) {
    cairo_surface_destroy(*img);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory for the image");
  }
  *cr = cairo_create(*img);
  cairo_set_source_rgb(*cr, 1, 1, 1);
  cairo_paint(*cr);
  return TDS_OK;
}

int tds_plot_png(tds_ctx *ctx, const char *path, int width, int height,
                 const double *x, int32_t n, const tds_plot_series *ser,
                 int nser, const char *xtitle, tds_plot_info *info) {
  if (n < 1) return tds_seterr(ctx, TDS_ERANGE, "plot: no iterations recorded yet");
  cairo_t *cr;
  cairo_surface_t *img;
  int rc0 = canvas(ctx, "plot", width, height, &img, &cr);
  if (rc0 != TDS_OK) return rc0;
  double xlo = x[0], xhi = x[n - 1];
  if (!(xhi > xlo)) {
    xlo -= 1;
    xhi += 1;
  }
  double X0 = 80, X1 = width - 20, top = 30, bottom = height - 50;
  double ph = (bottom - top - 30 * (nser - 1)) / nser;
  tds_plot_info pi;
  memset(&pi, 0, sizeof pi);
  static const double col[2][3] = {{0.1, 0.3, 0.75}, {0.8, 0.2, 0.1}};
  for (int s = 0; s < nser; s++) {
    double Y0 = top + s * (ph + 30), Y1 = Y0 + ph, lo, hi;
    int lg = ser[s].log;
    if (!series_range(ser[s].y, n, lg, &lo, &hi)) {
      lo = 0;
      hi = 1;
    }
    axes(cr, X0, Y0, X1, Y1, xlo, xhi, lo, hi, lg, ser[s].title,
         s == nser - 1 ? xtitle : NULL);
    if (s == 0) {
      pi.x0 = X0;
      pi.x1 = X1;
      pi.y0 = Y0;
      pi.y1 = Y1;
    }
    pi.lo[s] = lo;
    pi.hi[s] = hi;
    cairo_save(cr);
    cairo_rectangle(cr, X0, Y0, X1 - X0, Y1 - Y0);
    cairo_clip(cr);
    cairo_set_source_rgb(cr, col[s][0], col[s][1], col[s][2]);
    cairo_set_line_width(cr, 1.5);
    int pen = 0;
    for (int32_t i = 0; i < n; i++) {
      double v = ser[s].y[i];
      if (!isfinite(v) || (lg && !(v > 0))) {
        pen = 0;
        continue;
      }
      if (lg) v = log10(v);
      double xx = X0 + (x[i] - xlo) / (xhi - xlo) * (X1 - X0);
      double yy = Y1 - (v - lo) / (hi - lo) * (Y1 - Y0);
      if (pen) cairo_line_to(cr, xx, yy);
      else cairo_move_to(cr, xx, yy);
      if (!pen && (i + 1 == n || !isfinite(ser[s].y[i + 1]))) {
        cairo_rectangle(cr, xx - 1.5, yy - 1.5, 3, 3); /* a lone point */
        cairo_move_to(cr, xx, yy);
      }
      pen = 1;
    }
    cairo_stroke(cr);
    cairo_restore(cr);
  }
  cairo_destroy(cr);
  int rc = tds_write_png(ctx, img, path);
  cairo_surface_destroy(img);
  if (rc == TDS_OK && info) *info = pi;
  return rc;
}

int tds_histogram_png(tds_ctx *ctx, const char *path, int width, int height,
                      const int32_t *counts, int nbins, double lo, double hi,
                      const char *title, const char *xtitle,
                      tds_plot_info *info) {
  cairo_t *cr;
  cairo_surface_t *img;
  int rc0 = canvas(ctx, "quality", width, height, &img, &cr);
  if (rc0 != TDS_OK) return rc0;
  int32_t most = 1;
  for (int i = 0; i < nbins; i++)
    if (counts[i] > most) most = counts[i];
  double ymax = most * 1.05;
  double X0 = 80, X1 = width - 20, Y0 = 30, Y1 = height - 50;
  double step = nice_step(ymax, 5);
  double top = ceil(ymax / step) * step;
  /* the x axis is labelled by the bin edges below */
  axes(cr, X0, Y0, X1, Y1, lo, hi, 0, top, 0, title, NULL);
  double bw = (X1 - X0) / nbins;
  cairo_set_source_rgb(cr, 0.25, 0.45, 0.75);
  for (int i = 0; i < nbins; i++) {
    double h = counts[i] / top * (Y1 - Y0);
    cairo_rectangle(cr, X0 + i * bw + 1, Y1 - h, bw - 2, h);
  }
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  font(cr, 12);
  char buf[32];
  for (int i = 0; i <= nbins; i++) {
    fmt_num(buf, sizeof buf, lo + i * (hi - lo) / nbins, (hi - lo) / nbins);
    text_at(cr, X0 + i * bw, Y1 + 6, 0.5, 0, buf);
  }
  font(cr, 13);
  text_at(cr, (X0 + X1) / 2, Y1 + 24, 0.5, 0, xtitle);
  cairo_destroy(cr);
  int rc = tds_write_png(ctx, img, path);
  cairo_surface_destroy(img);
  if (rc == TDS_OK && info) {
    info->x0 = X0;
    info->x1 = X1;
    info->y0 = Y1; /* count 0 */
    info->y1 = Y0; /* count `top` */
    info->lo[0] = 0;
    info->hi[0] = top;
  }
  return rc;
}
