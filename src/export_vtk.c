/*
** export_vtk.c: VTK writers: XML UnstructuredGrid (.vtu) and the legacy
** format (.vtk, version 4.2).
**
** VTU: every array is ASCII, base64 (inline or appended) or raw appended
** binary (little-endian, each block preceded by its byte count as UInt64,
** header_type="UInt64"); in base64 the count and the data are encoded
** together, each array on its own, and appended offsets count base64
** characters. Triangles are cell type 5 with Int32
** connectivity and offsets. Legacy VTK: POINTS, CELLS and CELL_TYPES, the
** fields as FIELD arrays under POINT_DATA and CELL_DATA; BINARY data is
** big-endian as that format requires. VTK reads no NaN in ASCII legacy
** files, so an undefined field value there is an error.
*/
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "export_int.h"

typedef struct arr {
  const char *name;  /* NULL for Points */
  int type;          /* XF_* */
  int ncomp;
  int32_t n;         /* tuples */
  const double *v;
} arr;

static const char *vtu_type(int type) {
  return type == XF_DOUBLE ? "Float64" : type == XF_INT ? "Int32" : "UInt8";
}
static int type_size(int type) { return type == XF_DOUBLE ? 8 : type == XF_INT ? 4 : 1; }

/* The array's binary block: UInt64 byte count, then little-endian data. */
static unsigned char *block(const tds_alloc *al, const arr *a, size_t *len) {
  size_t nval = (size_t)a->n * (size_t)a->ncomp, nb = nval * (size_t)type_size(a->type);
  unsigned char *b = tds_malloc(al, 8 + nb + 1);
  if (!b) return NULL;
  uint64_t count = nb;
  for (int i = 0; i < 8; i++) b[i] = (unsigned char)(count >> (8 * i));
  unsigned char *p = b + 8;
  for (size_t i = 0; i < nval; i++) {
    if (a->type == XF_DOUBLE) {
      uint64_t u;
      memcpy(&u, &a->v[i], 8);
      for (int k = 0; k < 8; k++) *p++ = (unsigned char)(u >> (8 * k));
    } else if (a->type == XF_INT) {
      uint32_t u = (uint32_t)(int32_t)a->v[i];
      for (int k = 0; k < 4; k++) *p++ = (unsigned char)(u >> (8 * k));
    } else {
      *p++ = (unsigned char)a->v[i];
    }
  }
  *len = 8 + nb;
  return b;
}

static void base64(FILE *f, const unsigned char *b, size_t n) {
  static const char tab[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (size_t i = 0; i < n; i += 3) {
    uint32_t w = (uint32_t)b[i] << 16;
    if (i + 1 < n) w |= (uint32_t)b[i + 1] << 8;
    if (i + 2 < n) w |= b[i + 2];
    fputc(tab[(w >> 18) & 63], f);
    fputc(tab[(w >> 12) & 63], f);
    fputc(i + 1 < n ? tab[(w >> 6) & 63] : '=', f);
    fputc(i + 2 < n ? tab[w & 63] : '=', f);
  }
}

static void ascii_values(FILE *f, const arr *a) {
  size_t nval = (size_t)a->n * (size_t)a->ncomp;
  for (size_t i = 0; i < nval; i++) {
    fputc(i % 9 ? ' ' : '\n', f);
    if (a->type == XF_DOUBLE) xput_num(f, a->v[i]);
    else fprintf(f, "%d", (int)a->v[i]);
  }
  fputc('\n', f);
}

/* Write one DataArray; *offset advances for appended data. */
static int vtu_array(tds_ctx *ctx, FILE *f, const arr *a, int enc, int appended,
                     uint64_t *offset) {
  fprintf(f, "<DataArray type=\"%s\"", vtu_type(a->type));
  if (a->name) fprintf(f, " Name=\"%s\"", a->name);
  fprintf(f, " NumberOfComponents=\"%d\"", a->ncomp);
  if (enc == TDS_ENC_ASCII) {
    fputs(" format=\"ascii\">", f);
    ascii_values(f, a);
  } else if (appended) {
    fprintf(f, " format=\"appended\" offset=\"%llu\"/>\n", (unsigned long long)*offset);
    uint64_t len = 8 + (uint64_t)a->n * (uint64_t)a->ncomp * (uint64_t)type_size(a->type);
    *offset += enc == TDS_ENC_BASE64 ? 4 * ((len + 2) / 3) : len;
    return TDS_OK;
  } else {
    fputs(" format=\"binary\">\n", f);
    size_t len;
    unsigned char *b = block(&ctx->alloc, a, &len);
    if (!b) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    base64(f, b, len);
    tds_free(&ctx->alloc, b);
    fputc('\n', f);
  }
  fputs("</DataArray>\n", f);
  return TDS_OK;
}

/* The arrays of a mesh in file order: point fields, cell fields, points,
** connectivity, offsets, types. Returns the count; *buf owns the cell
** arrays. */
static int arrays(const xmesh *x, arr *out, double **buf) {
  int n = 0;
  for (int j = 0; j < x->nvf; j++)
    out[n++] = (arr){x->vf[j].name, x->vf[j].type, x->vf[j].ncomp, x->nv, x->vf[j].v};
  for (int j = 0; j < x->nff; j++)
    out[n++] = (arr){x->ff[j].name, x->ff[j].type, x->ff[j].ncomp, x->nt, x->ff[j].v};
  out[n++] = (arr){NULL, XF_DOUBLE, 3, x->nv, &x->x[0][0]};
  size_t nt = (size_t)x->nt;
  double *b = tds_malloc(&x->alloc, (5 * nt + 1) * sizeof *b);
  *buf = b;
  if (!b) return -1;
  for (size_t t = 0; t < nt; t++) {
    for (int k = 0; k < 3; k++) b[3 * t + k] = x->tri[t][k];
    b[3 * nt + t] = 3.0 * (double)(t + 1);
    b[4 * nt + t] = 5; /* VTK_TRIANGLE */
  }
  out[n++] = (arr){"connectivity", XF_INT, 1, (int32_t)(3 * nt), b};
  out[n++] = (arr){"offsets", XF_INT, 1, x->nt, b + 3 * nt};
  out[n++] = (arr){"types", XF_UCHAR, 1, x->nt, b + 4 * nt};
  return n;
}

int tds_write_vtu(tds_ctx *ctx, FILE *f, const xmesh *x, int enc, int appended) {
  arr a[2 * XF_MAX + 4];
  double *buf;
  int na = arrays(x, a, &buf);
  if (na < 0) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  fprintf(f, "<?xml version=\"1.0\"?>\n<!-- %s -->\n", x->title);
  fputs("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\">\n<UnstructuredGrid>\n", f);
  fprintf(f, "<Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n", x->nv, x->nt);
  uint64_t off = 0;
  int rc = TDS_OK, i = 0;
  fputs("<PointData>\n", f);
  for (; i < x->nvf && rc == TDS_OK; i++) rc = vtu_array(ctx, f, &a[i], enc, appended, &off);
  fputs("</PointData>\n<CellData>\n", f);
  for (; i < x->nvf + x->nff && rc == TDS_OK; i++) rc = vtu_array(ctx, f, &a[i], enc, appended, &off);
  fputs("</CellData>\n<Points>\n", f);
  if (rc == TDS_OK) rc = vtu_array(ctx, f, &a[i++], enc, appended, &off);
  fputs("</Points>\n<Cells>\n", f);
  for (; i < na && rc == TDS_OK; i++) rc = vtu_array(ctx, f, &a[i], enc, appended, &off);
  fputs("</Cells>\n</Piece>\n</UnstructuredGrid>\n", f);
  if (appended && rc == TDS_OK) {
    int b64 = enc == TDS_ENC_BASE64;
    fprintf(f, "<AppendedData encoding=\"%s\">\n_", b64 ? "base64" : "raw");
    for (int j = 0; j < na && rc == TDS_OK; j++) {
      size_t len;
      unsigned char *b = block(&ctx->alloc, &a[j], &len);
      if (!b) rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      else if (b64) base64(f, b, len);
      else fwrite(b, 1, len, f);
      tds_free(&ctx->alloc, b);
    }
    fputs("\n</AppendedData>\n", f);
  }
  fputs("</VTKFile>\n", f);
  tds_free(&x->alloc, buf);
  return rc;
}

static void legacy_values(FILE *f, const arr *a, int enc) {
  if (enc == TDS_ENC_ASCII) {
    ascii_values(f, a);
    return;
  }
  size_t nval = (size_t)a->n * (size_t)a->ncomp;
  for (size_t i = 0; i < nval; i++) {
    if (a->type == XF_DOUBLE) xput_f64(f, a->v[i], 0);
    else if (a->type == XF_INT) xput_i32(f, (int32_t)a->v[i], 0);
    else fputc((int)a->v[i] & 255, f);
  }
  fputc('\n', f);
}

static void legacy_fields(FILE *f, const xfield *fl, int nfl, int32_t n, int enc) {
  fprintf(f, "FIELD FieldData %d\n", nfl);
  for (int j = 0; j < nfl; j++) {
    const char *t = fl[j].type == XF_DOUBLE ? "double" : fl[j].type == XF_INT ? "int"
                                                                              : "unsigned_char";
    fprintf(f, "%s %d %d %s\n", fl[j].name, fl[j].ncomp, n, t);
    arr a = {fl[j].name, fl[j].type, fl[j].ncomp, n, fl[j].v};
    legacy_values(f, &a, enc);
  }
}

/* VTK's legacy reader parses ASCII numbers with C++ streams, which take
** no text for NaN: an undefined value cannot be written there. */
static int ascii_nan(tds_ctx *ctx, const xfield *fl, int nfl, int32_t n, const char *what) {
  for (int j = 0; j < nfl; j++)
    for (int32_t i = 0; i < n; i++)
      for (int c = 0; c < fl[j].ncomp; c++)
        if (isnan(fl[j].v[(size_t)i * fl[j].ncomp + c]))
          return tds_seterr(ctx, TDS_ERANGE,
                            "export: field '%s' is undefined (NaN) at exported %s %d, which "
                            "ASCII legacy vtk cannot hold; use encoding = \"binary\" or vtu",
                            fl[j].name, what, i + 1);
  return TDS_OK;
}

int tds_write_vtk(tds_ctx *ctx, FILE *f, const xmesh *x, int enc) {
  int bin = enc != TDS_ENC_ASCII;
  if (!bin) {
    int rc = ascii_nan(ctx, x->vf, x->nvf, x->nv, "vertex");
    if (rc == TDS_OK) rc = ascii_nan(ctx, x->ff, x->nff, x->nt, "facet");
    if (rc != TDS_OK) return rc;
  }
  fprintf(f, "# vtk DataFile Version 4.2\n%s\n%s\nDATASET UNSTRUCTURED_GRID\n", x->title,
          bin ? "BINARY" : "ASCII");
  fprintf(f, "POINTS %d double\n", x->nv);
  arr p = {NULL, XF_DOUBLE, 3, x->nv, &x->x[0][0]};
  legacy_values(f, &p, enc);
  fprintf(f, "CELLS %d %d\n", x->nt, 4 * x->nt);
  for (int32_t t = 0; t < x->nt; t++) {
    if (bin) {
      xput_i32(f, 3, 0);
      for (int k = 0; k < 3; k++) xput_i32(f, x->tri[t][k], 0);
    } else {
      fprintf(f, "3 %d %d %d\n", x->tri[t][0], x->tri[t][1], x->tri[t][2]);
    }
  }
  if (bin) fputc('\n', f);
  fprintf(f, "CELL_TYPES %d\n", x->nt);
  for (int32_t t = 0; t < x->nt; t++) {
    if (bin) xput_i32(f, 5, 0);
    else fputs("5\n", f);
  }
  if (bin) fputc('\n', f);
  if (x->nvf) {
    fprintf(f, "POINT_DATA %d\n", x->nv);
    legacy_fields(f, x->vf, x->nvf, x->nv, enc);
  }
  if (x->nff) {
    fprintf(f, "CELL_DATA %d\n", x->nt);
    legacy_fields(f, x->ff, x->nff, x->nt, enc);
  }
  return TDS_OK;
}
