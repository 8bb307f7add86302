/*
** export_simple.c: OBJ, OFF and STL writers, and the byte and number
** helpers every writer shares (export_int.h).
**
** OBJ: "v x y z" lines and 1-based "f a b c" lines. OFF: the counts line,
** coordinates, "3 a b c" 0-based. STL: one facet per triangle with its
** unit normal; binary STL is the 80-byte header, a little-endian count
** and 50-byte records of float32 (about 7 significant digits, the
** format's limit), ASCII STL keeps 17 digits.
*/
#include <math.h>
#include <string.h>

#include "export_int.h"

static void put_bytes(FILE *f, const unsigned char *b, int n, int le) {
  unsigned char r[8];
  int big_host = 0;
  {
    uint16_t one = 1;
    big_host = *(unsigned char *)&one == 0;
  }
  int swap = le == big_host;
  for (int i = 0; i < n; i++) r[i] = swap ? b[n - 1 - i] : b[i];
  fwrite(r, 1, (size_t)n, f);
}
void xput_i32(FILE *f, int32_t v, int le) { put_bytes(f, (unsigned char *)&v, 4, le); }
void xput_u32(FILE *f, uint32_t v, int le) { put_bytes(f, (unsigned char *)&v, 4, le); }
void xput_u64(FILE *f, uint64_t v, int le) { put_bytes(f, (unsigned char *)&v, 8, le); }
void xput_f64(FILE *f, double v, int le) { put_bytes(f, (unsigned char *)&v, 8, le); }
void xput_f32(FILE *f, float v, int le) { put_bytes(f, (unsigned char *)&v, 4, le); }

void xput_num(FILE *f, double v) {
  if (isnan(v)) fputs("nan", f);
  else if (isinf(v)) fputs(v > 0 ? "inf" : "-inf", f);
  else fprintf(f, "%.17g", v);
}

int tds_write_obj(tds_ctx *ctx, FILE *f, const xmesh *x) {
  (void)ctx;
  fprintf(f, "# %s\n", x->title);
  for (int32_t i = 0; i < x->nv; i++) {
    fputs("v", f);
    for (int c = 0; c < 3; c++) {
      fputc(' ', f);
      xput_num(f, x->x[i][c]);
    }
    fputc('\n', f);
  }
  for (int32_t t = 0; t < x->nt; t++)
    fprintf(f, "f %d %d %d\n", x->tri[t][0] + 1, x->tri[t][1] + 1, x->tri[t][2] + 1);
  return TDS_OK;
}

int tds_write_off(tds_ctx *ctx, FILE *f, const xmesh *x) {
  (void)ctx;
  fprintf(f, "OFF\n# %s\n%d %d 0\n", x->title, x->nv, x->nt);
  for (int32_t i = 0; i < x->nv; i++) {
    for (int c = 0; c < 3; c++) {
      if (c) fputc(' ', f);
      xput_num(f, x->x[i][c]);
    }
    fputc('\n', f);
  }
  for (int32_t t = 0; t < x->nt; t++)
    fprintf(f, "3 %d %d %d\n", x->tri[t][0], x->tri[t][1], x->tri[t][2]);
  return TDS_OK;
}

int tds_write_stl(tds_ctx *ctx, FILE *f, const xmesh *x, int enc) {
  (void)ctx;
  if (enc == TDS_ENC_ASCII) {
    fputs("solid tds\n", f);
    for (int32_t t = 0; t < x->nt; t++) {
      double n[3];
      xtri_normal(x, t, n);
      fprintf(f, "facet normal %.17g %.17g %.17g\n outer loop\n", n[0], n[1], n[2]);
      for (int k = 0; k < 3; k++) {
        const double *p = x->x[x->tri[t][k]];
        fprintf(f, "  vertex %.17g %.17g %.17g\n", p[0], p[1], p[2]);
      }
      fputs(" endloop\nendfacet\n", f);
    }
    fputs("endsolid tds\n", f);
    return TDS_OK;
  }
  /* The header must not begin with "solid" (readers take that as ASCII). */
  char head[80];
  memset(head, ' ', sizeof head);
  size_t n = strlen(x->title);
  memcpy(head, x->title, n < 80 ? n : 80);
  fwrite(head, 1, 80, f);
  xput_u32(f, (uint32_t)x->nt, 1);
  for (int32_t t = 0; t < x->nt; t++) {
    double nn[3];
    xtri_normal(x, t, nn);
    for (int c = 0; c < 3; c++) xput_f32(f, (float)nn[c], 1);
    for (int k = 0; k < 3; k++)
      for (int c = 0; c < 3; c++) xput_f32(f, (float)x->x[x->tri[t][k]][c], 1);
    fputc(0, f);
    fputc(0, f);
  }
  return TDS_OK;
}
