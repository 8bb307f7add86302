/*
** export_string.c: export.h's tds_export for string-model surfaces (export.c
** hands them here): the edges as line segments, in OBJ ("v" lines, then
** 1-based "l tail head" lines) or legacy VTK (an unstructured grid of
** VTK_LINE cells, type 3; ASCII, or BINARY big-endian). The points are
** the live vertices of the live edges renumbered in id order, then, in a
** torus, one more point per edge that wraps: its head unwrapped from its
** tail, so no segment runs across the cell. Edges follow id order.
** Other formats hold triangles, and the options that select facets,
** bodies or fields have nothing to act on; asking for them is an error.
** Written to a temporary and renamed when complete, as every export.
*/
#include "export_int.h"

#include <math.h>
#include <string.h>

#include "gather.h"
#include "string_model.h"
#include "wfile.h"

/* What of o the string model cannot honour, or NULL. */
static const char *unsupported(const tds_export_opts *o) {
  if (o->format != TDS_FMT_OBJ && o->format != TDS_FMT_VTK)
    return "the string model exports its edges as lines to obj or vtk only";
  if (o->facets) return "option 'facets': the string model exports every edge";
  if (o->per_body) return "option 'per_body' needs facets, not the string model's edges";
  if (o->vfields || o->ffields) return "fields are not exported in the string model";
  return NULL;
}

static void put_point(FILE *f, const double p[3], int fmt, int bin) {
  if (fmt == TDS_FMT_OBJ) fputc('v', f);
  for (int c = 0; c < 3; c++) {
    if (bin) {
      xput_f64(f, p[c], 0);
      continue;
    }
    if (c || fmt == TDS_FMT_OBJ) fputc(' ', f);
    xput_num(f, p[c]);
  }
  if (!bin) fputc('\n', f);
}

int tds_export_strings(tds_ctx *ctx, tds_surf *s, const char *path,
                       const tds_export_opts *o) {
  const char *why = unsupported(o);
  if (why) return tds_seterr(ctx, TDS_ERANGE, "export: %s", why);
  if (o->encoding == TDS_ENC_BASE64 || (o->encoding == TDS_ENC_BINARY && o->format != TDS_FMT_VTK))
    return tds_seterr(ctx, TDS_ERANGE, "export: %s has no %s encoding in the string model",
                      tds_export_formats[o->format],
                      o->encoding == TDS_ENC_BINARY ? "binary" : "base64");
  const tds_mesh *m = &s->m;
  /* num[v]: the point index of a vertex of a live edge, -1 otherwise */
  int32_t *num = tds_malloc(&ctx->alloc, (size_t)(m->nv > 0 ? m->nv : 1) * sizeof *num);
  if (!num) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (tds_id v = 0; v < m->nv; v++) num[v] = -1;
  int32_t np = 0, ne = 0, nwrap = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    ne++;
    num[m->ev[e][0]] = num[m->ev[e][1]] = 0;
    if (tds_oe_wrap(m, TDS_OREF(e, 0))) nwrap++;
  }
  for (tds_id v = 0; v < m->nv; v++) {
    if (num[v] < 0) continue;
    num[v] = np++;
    if (!isfinite(m->x[v][0]) || !isfinite(m->x[v][1]) || !isfinite(m->x[v][2])) {
      tds_free(&ctx->alloc, num);
      return tds_seterr(ctx, TDS_ENUM, "export: vertex %d has a non-finite coordinate", v + 1);
    }
  }
  if (ne == 0) {
    tds_free(&ctx->alloc, num);
    return tds_seterr(ctx, TDS_ERANGE, "export: no edges to export");
  }
  tds_wfile w;
  int rc = tds_wfile_open(ctx, &w, path);
  if (rc != TDS_OK) {
    tds_free(&ctx->alloc, num);
    return rc;
  }
  FILE *f = w.f;
  int bin = o->encoding == TDS_ENC_BINARY, fmt = o->format;
  int32_t npts = np + nwrap;
  if (fmt == TDS_FMT_OBJ)
    fprintf(f, "# tds %s: string model, %d vertices, %d edges\n", TDS_VERSION, npts, ne);
  else
    fprintf(f, "# vtk DataFile Version 4.2\ntds %s: string model, %d vertices, %d edges\n%s\n"
               "DATASET UNSTRUCTURED_GRID\nPOINTS %d double\n",
            TDS_VERSION, npts, ne, bin ? "BINARY" : "ASCII", npts);
  for (tds_id v = 0; v < m->nv; v++)
    if (num[v] >= 0) put_point(f, m->x[v], fmt, bin);
  for (tds_id e = 0; nwrap && e < m->ne; e++) { /* unwrapped heads */
    if ((m->eflags[e] & TDS_DEAD) || !tds_oe_wrap(m, TDS_OREF(e, 0))) continue;
    tds_corners C;
    tds_gather_edge(m, TDS_OREF(e, 0), &C);
    put_point(f, C.x[1], fmt, bin);
  }
  if (bin) fputc('\n', f);
  if (fmt == TDS_FMT_VTK) fprintf(f, "CELLS %d %d\n", ne, 3 * ne);
  for (tds_id e = 0, k = np; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    int32_t a = num[m->ev[e][0]];
    int32_t b = tds_oe_wrap(m, TDS_OREF(e, 0)) ? k++ : num[m->ev[e][1]];
    if (fmt == TDS_FMT_OBJ) {
      fprintf(f, "l %d %d\n", a + 1, b + 1);
    } else if (bin) {
      xput_i32(f, 2, 0);
      xput_i32(f, a, 0);
      xput_i32(f, b, 0);
    } else {
      fprintf(f, "2 %d %d\n", a, b);
    }
  }
  if (fmt == TDS_FMT_VTK) {
    if (bin) fputc('\n', f);
    fprintf(f, "CELL_TYPES %d\n", ne);
    for (int32_t i = 0; i < ne; i++) {
      if (bin) xput_i32(f, 3, 0);
      else fputs("3\n", f);
    }
    if (bin) fputc('\n', f);
  }
  tds_free(&ctx->alloc, num);
  int crc = tds_wfile_close(ctx, &w);
  if (rc == TDS_OK) rc = crc;
  if (rc == TDS_OK) rc = tds_wfile_commit(ctx, &w);
  if (rc == TDS_OK && o->written) o->written(o->ud, w.path);
  tds_wfile_abort(&w);
  return rc;
}
