/*
** export.h: writing the surface as a triangle mesh for other tools
** (doc/output.md, "Export").
**
** Formats: OBJ, OFF (ASCII), PLY, STL, VTK legacy (ASCII or binary), VTU
** (ASCII, base64 inline or appended, raw appended binary), Gmsh MSH 2.2 and 4.1
** (ASCII or binary). Vertices are the live vertices of the chosen facets,
** renumbered in id order; triangles follow facet id order. Coordinates
** are written as doubles (17 significant digits in ASCII) except in STL,
** whose binary form holds floats.
**
** Fields: per vertex and per facet, written by the formats that carry
** fields (PLY, VTU, VTK); asking another format for a field is an error.
** Values that are undefined (curvature at a vertex that is not measured,
** displacement of a vertex created after the mark) are NaN.
**
** Per body: one file per live body ("<stem>_body<id><ext>") holding the
** body's facets oriented outward (a facet on the body's back side is
** reversed). With caps, every boundary loop of that shell is closed by
** ear-clipping it in the plane of its Newell normal (export_cap.c), so a
** shell that was open where the body meets a constraint becomes closed.
**
** All files are written to temporaries and renamed only when every one is
** complete: a failure leaves no partial file and no new file at all.
*/
#ifndef TDS_EXPORT_H
#define TDS_EXPORT_H

#include "surf.h"

enum { TDS_FMT_OBJ = 0, TDS_FMT_OFF, TDS_FMT_PLY, TDS_FMT_STL, TDS_FMT_VTU,
       TDS_FMT_VTK, TDS_FMT_MSH, TDS_FMT_COUNT };
enum { TDS_ENC_ASCII = 0, TDS_ENC_BINARY, TDS_ENC_BASE64 };

/* Per-vertex fields (bit numbers of tds_export_opts.vfields). */
enum { TDS_VF_POSITION = 0, TDS_VF_NORMAL, TDS_VF_MEAN_CURVATURE,
       TDS_VF_GAUSS_CURVATURE, TDS_VF_DISPLACEMENT, TDS_VF_ID, TDS_VF_COUNT };
/* Per-facet fields (bit numbers of tds_export_opts.ffields). */
enum { TDS_FF_MIN_ANGLE = 0, TDS_FF_AREA, TDS_FF_TENSION, TDS_FF_COLOR,
       TDS_FF_FRONTBODY, TDS_FF_BACKBODY, TDS_FF_ID, TDS_FF_COUNT };

extern const char *const tds_export_formats[TDS_FMT_COUNT];   /* "obj", ... */
extern const char *const tds_export_vfields[TDS_VF_COUNT];    /* "position", ... */
extern const char *const tds_export_ffields[TDS_FF_COUNT];    /* "min_angle", ... */

/* Evolver's colour table (-1 CLEAR .. 15 WHITE) as RGBA; values outside
** the table wrap modulo 16 as Evolver's drivers do. */
void tds_export_rgba(int color, unsigned char rgba[4]);

typedef struct tds_export_opts {
  int format;                /* TDS_FMT_* */
  int encoding;              /* TDS_ENC_*; BASE64 only for VTU */
  int msh_version;           /* 22 or 41 */
  int appended;              /* VTU: arrays in the AppendedData section (raw
                                for BINARY, which needs it; base64 for
                                BASE64); otherwise 0 */
  const uint8_t *facets;     /* m.nf entries, nonzero = export; NULL = all
                                facets not flagged nodisplay */
  unsigned vfields, ffields; /* bit masks of TDS_VF_*, TDS_FF_* */
  int per_body;              /* one file per body */
  int caps;                  /* with per_body: close open shells */
  const double (*mark)[3];   /* positions recorded by mark(), or NULL */
  int32_t nmark;             /* vertex slots the mark covers */
  /* Called with each file name once all are written (may be NULL). */
  void (*written)(void *ud, const char *path);
  void *ud;
} tds_export_opts;

/* Format from a file name's extension (case-insensitive), or -1. */
int tds_export_format_of(const char *path);

/* Write the export. TDS_OK, or TDS_ERANGE (an option does not fit the
** format or the surface, e.g. a field in OBJ, displacement without a mark,
** per_body without bodies, a cap that cannot be triangulated), TDS_ENUM
** (a coordinate is not finite), TDS_EIO, TDS_ENOMEM; the message names
** the option or file. The surface is not changed. */
int tds_export(tds_ctx *ctx, tds_surf *s, const char *path, const tds_export_opts *o);

#endif
