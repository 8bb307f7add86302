/* render_int.h: drawing helpers shared by render.c and render_plot.c. */
#ifndef TDS_RENDER_INT_H
#define TDS_RENDER_INT_H

#include <cairo.h>

#include "tds.h"

/* Vertical colour bar of the ramp at (x, y) of size w x h, lo at the
** bottom, with tick labels to its right and a title above. */
void tds_draw_colorbar(cairo_t *cr, double x, double y, double w, double h,
                       double lo, double hi, const char *title);

/* A key of body colours: a swatch and "body id" per line for the n
** bodies (0-based ids) from (x, y) down; past 15 lines, "..." when n > 16. */
void tds_draw_swatches(cairo_t *cr, double x, double y, const int32_t *ids, int n);

/* Write the image as PNG: TDS_OK or TDS_EIO naming the file. */
int tds_write_png(tds_ctx *ctx, cairo_surface_t *img, const char *path);

/* render.h's tds_render_png for a string-model surface (s->str):
** render_string.c. Same options, results and status codes. */
struct tds_surf;
struct tds_render_opts;
struct tds_render_info;
int tds_render_strings(tds_ctx *ctx, struct tds_surf *s, const struct tds_render_opts *o,
                       const char *path, struct tds_render_info *info);

/* The camera of render.h's info: looking from azimuth a, elevation e
** (radians) at in->center, fitting the bounding sphere (in->radius; seen
** in perspective when persp and o->distance > 0) into plotw x o->height
** pixels (render.c). */
void tds_render_camera(const struct tds_render_opts *o, double a, double e, int persp, int plotw,
                       struct tds_render_info *in);

/* Pixel position of p and its view depth (larger: nearer). */
void tds_render_project(const struct tds_render_info *in, const struct tds_render_opts *o,
                        const double p[3], double *x, double *y, double *z);

#endif
