/*
** export_int.h: the triangle mesh that export's format writers receive.
**
** export.c builds one xmesh per file from the surface (selection, body
** shell, caps, fields); the writers (export_simple.c: OBJ, OFF, STL;
** export_ply.c; export_vtk.c: VTU, VTK; export_msh.c) only encode it.
** Writers return TDS_OK or an error set in ctx; they write through
** stdio and leave error checks on the stream to the caller.
*/
#ifndef TDS_EXPORT_INT_H
#define TDS_EXPORT_INT_H

#include <stdio.h>

#include "export.h"

enum { XF_DOUBLE = 0, XF_INT, XF_UCHAR };

typedef struct xfield {
  const char *name;
  int type;          /* XF_*: written as Float64, Int32 or UInt8 */
  int ncomp;         /* components per element: 1, 3 or 4 */
  double *v;         /* n * ncomp values (integers stored exactly) */
} xfield;

#define XF_MAX 16

typedef struct xmesh {
  int32_t nv, nt;
  double (*x)[3];    /* positions */
  int32_t (*tri)[3]; /* vertex indices 0..nv-1, counter-clockwise seen
                        from the side the facet's normal points to */
  int nvf, nff;
  xfield vf[XF_MAX], ff[XF_MAX];
  const char *title; /* one line describing the surface */
  tds_alloc alloc;   /* of the arrays and fields (the ctx's) */
} xmesh;

/* Writers. enc is TDS_ENC_* (already checked against the format). */
int tds_write_obj(tds_ctx *ctx, FILE *f, const xmesh *x);
int tds_write_off(tds_ctx *ctx, FILE *f, const xmesh *x);
int tds_write_stl(tds_ctx *ctx, FILE *f, const xmesh *x, int enc);
int tds_write_ply(tds_ctx *ctx, FILE *f, const xmesh *x, int enc);
int tds_write_vtu(tds_ctx *ctx, FILE *f, const xmesh *x, int enc, int appended);
int tds_write_vtk(tds_ctx *ctx, FILE *f, const xmesh *x, int enc);
int tds_write_msh(tds_ctx *ctx, FILE *f, const xmesh *x, int enc, int version);

/* export.h's tds_export for a string-model surface (export_string.c):
** its edges as lines (OBJ, legacy VTK). Same status codes. */
int tds_export_strings(tds_ctx *ctx, tds_surf *s, const char *path, const tds_export_opts *o);

/* Byte writers with an explicit byte order (le: little-endian). */
void xput_i32(FILE *f, int32_t v, int le);
void xput_u32(FILE *f, uint32_t v, int le);
void xput_u64(FILE *f, uint64_t v, int le);
void xput_f64(FILE *f, double v, int le);
void xput_f32(FILE *f, float v, int le);

/* A number in ASCII: 17 significant digits (round trips a double), NaN
** as "nan". Integer-typed fields are printed without a fraction. */
void xput_num(FILE *f, double v);

/* Unit normal of triangle t (zero when degenerate). */
void xtri_normal(const xmesh *x, int32_t t, double n[3]);

/* Close every boundary loop of the triangle set in x by appending cap
** triangles (export_cap.c); x->tri must have room for 6 * nt + 1
** triangles (caps add at most 5/3 of the boundary's at most 3 * nt
** sides: a loop of n sides adds n - 2, a bridged hole 2 more). An edge
** is on the boundary by the excess of its uses in one direction over the
** other, so caps also close a set whose orientation is inconsistent.
** TDS_OK, TDS_ENOMEM, or TDS_ERANGE when the boundary edges do not chain
** into loops (the message names a vertex). *ncap: triangles added. */
int tds_export_caps(tds_ctx *ctx, xmesh *x, int32_t *ncap);

#endif
