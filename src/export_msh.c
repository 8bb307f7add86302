/*
** export_msh.c: Gmsh MSH writers, versions 2.2 and 4.1, ASCII or binary.
**
** Nodes are tagged 1..nv and triangles (element type 2) 1..nt. Version
** 2.2 gives each triangle two tags (physical 1, elementary 1); version
** 4.1 declares one surface entity (tag 1, the mesh's bounding box, no
** physical tags) holding every node and triangle in one block. Binary
** files are written in the machine's byte order, which the leading
** integer 1 of the format section declares; size_t is 8 bytes.
*/
#include <math.h>

#include "export_int.h"

static int host_le(void) {
  uint16_t one = 1;
  return *(unsigned char *)&one == 1;
}

static void msh22(FILE *f, const xmesh *x, int bin) {
  int le = host_le();
  fprintf(f, "$MeshFormat\n2.2 %d 8\n", bin);
  if (bin) {
    xput_i32(f, 1, le);
    fputc('\n', f);
  }
  fprintf(f, "$EndMeshFormat\n$Nodes\n%d\n", x->nv);
  for (int32_t i = 0; i < x->nv; i++) {
    if (bin) {
      xput_i32(f, i + 1, le);
      for (int c = 0; c < 3; c++) xput_f64(f, x->x[i][c], le);
    } else {
      fprintf(f, "%d", i + 1);
      for (int c = 0; c < 3; c++) {
        fputc(' ', f);
        xput_num(f, x->x[i][c]);
      }
      fputc('\n', f);
    }
  }
  if (bin) fputc('\n', f);
  fprintf(f, "$EndNodes\n$Elements\n%d\n", x->nt);
  if (bin) {
    xput_i32(f, 2, le);      /* triangles */
    xput_i32(f, x->nt, le);  /* all in one header block */
    xput_i32(f, 2, le);      /* tags per element */
  }
  for (int32_t t = 0; t < x->nt; t++) {
    if (bin) {
      xput_i32(f, t + 1, le);
      xput_i32(f, 1, le);
      xput_i32(f, 1, le);
      for (int k = 0; k < 3; k++) xput_i32(f, x->tri[t][k] + 1, le);
    } else {
      fprintf(f, "%d 2 2 1 1 %d %d %d\n", t + 1, x->tri[t][0] + 1, x->tri[t][1] + 1,
              x->tri[t][2] + 1);
    }
  }
  if (bin) fputc('\n', f);
  fputs("$EndElements\n", f);
}

/* size_t values: 8-byte unsigned in binary, decimal in ASCII. */
static void sz(FILE *f, uint64_t v, int bin, const char *sep) {
  if (bin) xput_u64(f, v, host_le());
  else fprintf(f, "%llu%s", (unsigned long long)v, sep);
}
static void in(FILE *f, int32_t v, int bin, const char *sep) {
  if (bin) xput_i32(f, v, host_le());
  else fprintf(f, "%d%s", v, sep);
}

static void msh41(FILE *f, const xmesh *x, int bin) {
  int le = host_le();
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int32_t i = 0; i < x->nv; i++)
    for (int c = 0; c < 3; c++) {
      if (x->x[i][c] < lo[c]) lo[c] = x->x[i][c];
      if (x->x[i][c] > hi[c]) hi[c] = x->x[i][c];
    }
  fprintf(f, "$MeshFormat\n4.1 %d 8\n", bin);
  if (bin) {
    xput_i32(f, 1, le);
    fputc('\n', f);
  }
  fputs("$EndMeshFormat\n$Entities\n", f);
  sz(f, 0, bin, " ");
  sz(f, 0, bin, " ");
  sz(f, 1, bin, " ");
  sz(f, 0, bin, "\n");
  in(f, 1, bin, " ");
  for (int c = 0; c < 6; c++) {
    double v = c < 3 ? lo[c] : hi[c - 3];
    if (bin) xput_f64(f, v, le);
    else {
      xput_num(f, v);
      fputc(' ', f);
    }
  }
  sz(f, 0, bin, " ");
  sz(f, 0, bin, "\n");
  if (bin) fputc('\n', f);
  fputs("$EndEntities\n$Nodes\n", f);
  sz(f, 1, bin, " ");
  sz(f, (uint64_t)x->nv, bin, " ");
  sz(f, 1, bin, " ");
  sz(f, (uint64_t)x->nv, bin, "\n");
  in(f, 2, bin, " ");
  in(f, 1, bin, " ");
  in(f, 0, bin, " ");
  sz(f, (uint64_t)x->nv, bin, "\n");
  for (int32_t i = 0; i < x->nv; i++) sz(f, (uint64_t)i + 1, bin, "\n");
  for (int32_t i = 0; i < x->nv; i++)
    for (int c = 0; c < 3; c++) {
      if (bin) xput_f64(f, x->x[i][c], le);
      else {
        xput_num(f, x->x[i][c]);
        fputc(c < 2 ? ' ' : '\n', f);
      }
    }
  if (bin) fputc('\n', f);
  fputs("$EndNodes\n$Elements\n", f);
  sz(f, 1, bin, " ");
  sz(f, (uint64_t)x->nt, bin, " ");
  sz(f, 1, bin, " ");
  sz(f, (uint64_t)x->nt, bin, "\n");
  in(f, 2, bin, " ");
  in(f, 1, bin, " ");
  in(f, 2, bin, " ");
  sz(f, (uint64_t)x->nt, bin, "\n");
  for (int32_t t = 0; t < x->nt; t++) {
    sz(f, (uint64_t)t + 1, bin, " ");
    for (int k = 0; k < 3; k++) sz(f, (uint64_t)x->tri[t][k] + 1, bin, k < 2 ? " " : "\n");
  }
  if (bin) fputc('\n', f);
  fputs("$EndElements\n", f);
}

int tds_write_msh(tds_ctx *ctx, FILE *f, const xmesh *x, int enc, int version) {
  (void)ctx;
  if (version == 22) msh22(f, x, enc == TDS_ENC_BINARY);
  else msh41(f, x, enc == TDS_ENC_BINARY);
  return TDS_OK;
}
