/*
** export_ply.c: the PLY writer (ASCII or binary_little_endian).
**
** Vertex element: x y z as double, then the vertex fields; face element:
** "list uchar int vertex_indices", then the facet fields. A vector field
** NAME becomes properties NAME_x NAME_y NAME_z, except the normal, which
** is nx ny nz as viewers expect; the colour's rgba becomes red green blue
** alpha (uchar), which viewers such as MeshLab show.
*/
#include <string.h>

#include "export_int.h"

static const char *type_name(int type) {
  return type == XF_DOUBLE ? "double" : type == XF_INT ? "int" : "uchar";
}

static void declare(FILE *f, const xfield *fl) {
  static const char *xyz[3] = {"x", "y", "z"}, *rgba[4] = {"red", "green", "blue", "alpha"};
  const char *t = type_name(fl->type);
  if (fl->ncomp == 1) {
    fprintf(f, "property %s %s\n", t, fl->name);
  } else if (fl->ncomp == 4) {
    for (int c = 0; c < 4; c++) fprintf(f, "property %s %s\n", t, rgba[c]);
  } else if (!strcmp(fl->name, "normal")) {
    for (int c = 0; c < 3; c++) fprintf(f, "property %s n%s\n", t, xyz[c]);
  } else {
    for (int c = 0; c < 3; c++) fprintf(f, "property %s %s_%s\n", t, fl->name, xyz[c]);
  }
}

static void value(FILE *f, int type, double v, int enc) {
  if (enc == TDS_ENC_ASCII) {
    fputc(' ', f);
    if (type == XF_DOUBLE) xput_num(f, v);
    else fprintf(f, "%d", (int)v);
  } else if (type == XF_DOUBLE) {
    xput_f64(f, v, 1);
  } else if (type == XF_INT) {
    xput_i32(f, (int32_t)v, 1);
  } else {
    fputc((int)v & 255, f);
  }
}

static void values(FILE *f, const xfield *fl, int nfl, int32_t i, int enc) {
  for (int j = 0; j < nfl; j++)
    for (int c = 0; c < fl[j].ncomp; c++)
      value(f, fl[j].type, fl[j].v[(size_t)i * fl[j].ncomp + c], enc);
}

int tds_write_ply(tds_ctx *ctx, FILE *f, const xmesh *x, int enc) {
  (void)ctx;
  fprintf(f, "ply\nformat %s 1.0\ncomment %s\nelement vertex %d\n",
          enc == TDS_ENC_ASCII ? "ascii" : "binary_little_endian", x->title, x->nv);
  fputs("property double x\nproperty double y\nproperty double z\n", f);
  for (int j = 0; j < x->nvf; j++) declare(f, &x->vf[j]);
  fprintf(f, "element face %d\nproperty list uchar int vertex_indices\n", x->nt);
  for (int j = 0; j < x->nff; j++) declare(f, &x->ff[j]);
  fputs("end_header\n", f);
  for (int32_t i = 0; i < x->nv; i++) {
    for (int c = 0; c < 3; c++) {
      if (enc == TDS_ENC_ASCII) {
        if (c) fputc(' ', f);
        xput_num(f, x->x[i][c]);
      } else {
        xput_f64(f, x->x[i][c], 1);
      }
    }
    values(f, x->vf, x->nvf, i, enc);
    if (enc == TDS_ENC_ASCII) fputc('\n', f);
  }
  for (int32_t t = 0; t < x->nt; t++) {
    if (enc == TDS_ENC_ASCII) {
      fprintf(f, "3 %d %d %d", x->tri[t][0], x->tri[t][1], x->tri[t][2]);
    } else {
      fputc(3, f);
      for (int k = 0; k < 3; k++) xput_i32(f, x->tri[t][k], 1);
    }
    values(f, x->ff, x->nff, t, enc);
    if (enc == TDS_ENC_ASCII) fputc('\n', f);
  }
  return TDS_OK;
}
