/*
** render.h: off-screen pictures of a surface, plots and histograms, drawn
** with cairo into PNG files (the `snapshot`, `plot` and `quality{png=}`
** commands; doc/output.md).
**
** Surface pictures use the painter's algorithm: facets are projected,
** sorted by the depth of their centroids and filled back to front, flat
** shaded (Lambert, two-sided, a fixed light over the viewer's left
** shoulder), or with `smooth` Gouraud-like from colours and light at the
** corners (cairo mesh patterns, painted in depth order). Facets are filled without anti-aliasing into a buffer of twice
** the size (pictures up to 4 megapixels), which is then reduced by cairo's
** filter: anti-aliased edges without the hairline seams that anti-aliased
** neighbouring triangles leave. Text and the colour bar are drawn on the
** final image.
*/
#ifndef TDS_RENDER_H
#define TDS_RENDER_H

#include "surf.h"

enum {                        /* what colours the facets */
  TDS_RCOL_NONE = 0,          /* one neutral colour */
  TDS_RCOL_MEAN_CURVATURE,    /* k1 + k2 at the vertices, averaged per facet */
  TDS_RCOL_MIN_ANGLE,         /* smallest angle of the facet, degrees */
  TDS_RCOL_BODY,              /* front body (else back body), one hue each */
  TDS_RCOL_TENSION,           /* facet tension */
  TDS_RCOL_COLOR              /* the facet's Evolver colour (0..15; -1 clear) */
};

typedef struct tds_render_opts {
  int width, height;          /* pixels, 16..8192 each */
  int color;                  /* TDS_RCOL_* */
  double azimuth, elevation;  /* viewing direction, degrees: the camera
                                 looks from (cos e cos a, cos e sin a, sin e) */
  double distance;            /* 0: orthographic; > 1: perspective from
                                 this many bounding radii off the centre */
  int edges;                  /* outline every facet */
  int legend;                 /* colour bar (scalar fields only) */
  int lighting;               /* 0: flat colours without shading */
  int smooth;                 /* Gouraud-like: colours and light at the
                                 vertices, blended across facets (slower) */
  int has_range;              /* use range[] instead of the data's extent */
  double range[2];
} tds_render_opts;

typedef struct tds_render_info {
  /* The projection: a point p goes to pixel (cx + scale * (p - c).right,
  ** cy - scale * (p - c).up) when orthographic (pixel centres at +0.5). */
  double center[3], right[3], up[3], toward[3];
  double cx, cy, scale, radius;
  double lo, hi;              /* the colour range used (scalar fields) */
  int32_t drawn;              /* facets drawn */
  int32_t nbody_colors;       /* bodies with a colour (TDS_RCOL_BODY) */
} tds_render_info;

/* Defaults: 800 x 600, no colouring, the iso view, orthographic, no
** edges, legend on, lighting on. */
void tds_render_defaults(tds_render_opts *o);

/* Colour of a scalar at t in [0, 1] (the diverging map of the pictures:
** blue, light grey at 0.5, red) and of body b (0-based), Evolver colour c
** (0..15). rgb in [0, 1]. */
void tds_render_ramp(double t, double rgb[3]);
void tds_render_body_color(tds_id b, double rgb[3]);
void tds_render_evolver_color(int c, double rgb[3]);

/* Per-facet value of a field colouring (TDS_RCOL_MEAN_CURVATURE: the mean
** of the facet's measured vertices; MIN_ANGLE; TENSION) into val[0..nf),
** NaN where there is none (dead facets, no measured vertex). For other
** viewers (export, live view) to colour alike. TDS_OK or TDS_ENOMEM. */
int tds_render_field(tds_ctx *ctx, tds_surf *s, int mode, double *val);

/* Render the surface to a PNG file. info (may be NULL) receives the
** projection and colour range. TDS_OK, TDS_ENOMEM, TDS_ERANGE (bad
** options, nothing to draw), TDS_ENUM (a non-finite coordinate), TDS_EIO
** (the file cannot be written). Nothing is written on failure. */
int tds_render_png(tds_ctx *ctx, tds_surf *s, const tds_render_opts *o,
                   const char *path, tds_render_info *info);

/* A plot of up to two series against a common x, each in its own panel
** stacked vertically. A series with log set is drawn on a log10 axis (its
** non-positive values are skipped). */
typedef struct tds_plot_series {
  const double *y;            /* n values (NaN: no point) */
  const char *title;
  int log;
} tds_plot_series;

typedef struct tds_plot_info {
  double x0, y0, x1, y1;      /* first panel's data rectangle in pixels */
  double lo[2], hi[2];        /* axis ranges of the panels (log10 if log) */
} tds_plot_info;

int tds_plot_png(tds_ctx *ctx, const char *path, int width, int height,
                 const double *x, int32_t n, const tds_plot_series *ser,
                 int nser, const char *xtitle, tds_plot_info *info);

/* Bar chart of counts (nbins bars over [lo, hi]). info->y0, y1 receive
** the pixel rows of count 0 and count info->hi; x0, x1 the bars' span. */
int tds_histogram_png(tds_ctx *ctx, const char *path, int width, int height,
                      const int32_t *counts, int nbins, double lo, double hi,
                      const char *title, const char *xtitle,
                      tds_plot_info *info);

#endif
