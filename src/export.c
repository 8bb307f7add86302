/*
** export.c: options, the triangle mesh of each file, fields, and writing
** every file atomically (contract in export.h; writers in export_*.c).
*/
#include "torus.h"
#include "export.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "wfile.h"
#include "export_int.h"
#include "gather.h"
#include "geom.h"
#include "metrics.h"
#include "vec3.h"

const char *const tds_export_formats[TDS_FMT_COUNT] = {"obj", "off", "ply", "stl",
                                                       "vtu", "vtk", "msh"};
const char *const tds_export_vfields[TDS_VF_COUNT] = {
    "position", "normal", "mean_curvature", "gauss_curvature", "displacement", "id"};
const char *const tds_export_ffields[TDS_FF_COUNT] = {
    "min_angle", "area", "tension", "color", "frontbody", "backbody", "id"};

/* The 16 colours whose names Evolver's manual gives (BLACK, BLUE, GREEN,
** CYAN, RED, MAGENTA, BROWN, LIGHTGRAY, DARKGRAY, LIGHTBLUE, LIGHTGREEN,
** LIGHTCYAN, LIGHTRED, LIGHTMAGENTA, YELLOW, WHITE) are the PC text-mode
** palette; these are its usual RGB values. */
static const unsigned char palette[16][3] = {
    {0, 0, 0},       {0, 0, 170},     {0, 170, 0},    {0, 170, 170},
    {170, 0, 0},     {170, 0, 170},   {170, 85, 0},   {170, 170, 170},
    {85, 85, 85},    {85, 85, 255},   {85, 255, 85},  {85, 255, 255},
    {255, 85, 85},   {255, 85, 255},  {255, 255, 85}, {255, 255, 255}};

void tds_export_rgba(int color, unsigned char rgba[4]) {
  if (color == -1) { /* CLEAR: transparent */
    rgba[0] = rgba[1] = rgba[2] = 255;
    rgba[3] = 0;
    return;
  }
  int c = ((color % 16) + 16) % 16;
  for (int k = 0; k < 3; k++) rgba[k] = palette[c][k];
  rgba[3] = 255;
}

int tds_export_format_of(const char *path) {
  const char *slash = strrchr(path, '/');
  const char *dot = strrchr(slash ? slash : path, '.');
  if (!dot) return -1;
  for (int i = 0; i < TDS_FMT_COUNT; i++) {
    const char *e = tds_export_formats[i];
    size_t n = strlen(e);
    if (strlen(dot + 1) != n) continue;
    size_t k = 0;
    while (k < n && (dot[1 + k] | 0x20) == e[k]) k++;
    if (k == n) return i;
  }
  return -1;
}

static int has_binary(int fmt) {
  return fmt == TDS_FMT_PLY || fmt == TDS_FMT_STL || fmt == TDS_FMT_VTU ||
         fmt == TDS_FMT_VTK || fmt == TDS_FMT_MSH;
}
static int has_fields(int fmt) {
  return fmt == TDS_FMT_PLY || fmt == TDS_FMT_VTU || fmt == TDS_FMT_VTK;
}

static int check_opts(tds_ctx *ctx, const tds_surf *s, const tds_export_opts *o) {
  const char *fmt = o->format >= 0 && o->format < TDS_FMT_COUNT
                        ? tds_export_formats[o->format] : NULL;
  if (!fmt) return tds_seterr(ctx, TDS_ERANGE, "export: unknown format");
  if (o->encoding == TDS_ENC_BASE64 && o->format != TDS_FMT_VTU)
    return tds_seterr(ctx, TDS_ERANGE,
                      "export: encoding 'base64' is only for vtu, not %s", fmt);
  if (o->encoding == TDS_ENC_BINARY && !has_binary(o->format))
    return tds_seterr(ctx, TDS_ERANGE, "export: %s has no binary encoding", fmt);
  if (o->appended && o->format != TDS_FMT_VTU)
    return tds_seterr(ctx, TDS_ERANGE, "export: option 'appended' is only for vtu, not %s", fmt);
  if (o->format == TDS_FMT_VTU && o->appended && o->encoding == TDS_ENC_ASCII)
    return tds_seterr(ctx, TDS_ERANGE,
                      "export: option 'appended': ascii data is written inline");
  if (o->format == TDS_FMT_VTU && !o->appended && o->encoding == TDS_ENC_BINARY)
    return tds_seterr(ctx, TDS_ERANGE,
                      "export: option 'appended': raw binary data must be appended (use "
                      "encoding = \"base64\" for inline data)");
  if (o->format == TDS_FMT_MSH && o->msh_version != 22 && o->msh_version != 41)
    return tds_seterr(ctx, TDS_ERANGE, "export: msh version must be 2.2 or 4.1");
  if ((o->vfields || o->ffields) && !has_fields(o->format)) {
    int vf = o->vfields != 0;
    unsigned mask = vf ? o->vfields : o->ffields;
    int bit = 0;
    while (!(mask & (1u << bit))) bit++;
    return tds_seterr(ctx, TDS_ERANGE,
                      "export: %s cannot carry the %s field '%s' (use ply, vtu or vtk)",
                      fmt, vf ? "vertex" : "facet",
                      vf ? tds_export_vfields[bit] : tds_export_ffields[bit]);
  }
  if ((o->vfields & (1u << TDS_VF_DISPLACEMENT)) && !o->mark)
    return tds_seterr(ctx, TDS_ERANGE,
                      "export: field 'displacement' needs mark() to record positions first");
  if (o->per_body && tds_mesh_count(&s->m, TDS_BODY) == 0)
    return tds_seterr(ctx, TDS_ERANGE, "export: per_body, but the surface has no bodies");
  return TDS_OK;
}

static void xmesh_free(xmesh *x) {
  tds_free(&x->alloc, x->x);
  tds_free(&x->alloc, x->tri);
  for (int i = 0; i < x->nvf; i++) tds_free(&x->alloc, x->vf[i].v);
  for (int i = 0; i < x->nff; i++) tds_free(&x->alloc, x->ff[i].v);
  memset(x, 0, sizeof *x);
}

void xtri_normal(const xmesh *x, int32_t t, double n[3]) {
  const double *a = x->x[x->tri[t][0]], *b = x->x[x->tri[t][1]], *c = x->x[x->tri[t][2]];
  double u[3], v[3];
  v3_sub(u, b, a);
  v3_sub(v, c, a);
  v3_cross(n, u, v);
  double l = v3_norm(n);
  if (l > 0) v3_scale(n, 1 / l);
  else n[0] = n[1] = n[2] = 0;
}

/* Build the triangles of one file: facets with sel[f] set, reversed where
** rev[f]; body >= 0 restricts to that body's shell. src[t] receives the
** facet of triangle t; vid[i] the vertex of compact vertex i. */
typedef struct build {
  xmesh x;
  tds_id *src;       /* per triangle: facet, or TDS_NONE (cap) */
  uint8_t *rev;      /* per triangle: written reversed */
  tds_id *vid;       /* per compact vertex: surface vertex */
  int32_t ncap;
  tds_id body;       /* the body of a per-body file, or TDS_NONE */
} build;

static void build_free(build *b) {
  tds_alloc a = b->x.alloc;
  xmesh_free(&b->x);
  tds_free(&a, b->src);
  tds_free(&a, b->rev);
  tds_free(&a, b->vid);
}

static int in_shell(const tds_mesh *m, tds_id f, tds_id body, int *rev) {
  *rev = 0;
  if (body == TDS_NONE) return 1;
  if (m->fb[f][0] == body) return 1;
  if (m->fb[f][1] == body) {
    *rev = 1;
    return 1;
  }
  return 0;
}

static int make_mesh(tds_ctx *ctx, const tds_surf *s, const tds_export_opts *o,
                     tds_id body, build *b) {
  const tds_mesh *m = &s->m;
  memset(b, 0, sizeof *b);
  b->x.alloc = ctx->alloc;
  b->body = body;
  int32_t nt = 0, nv = 0;
  int32_t *map = tds_calloc(&ctx->alloc, (size_t)(m->nv > 0 ? m->nv : 1), sizeof *map);
  if (!map) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (tds_id f = 0; f < m->nf; f++) {
    int rev;
    if (!tds_alive(m->fflags, f)) continue;
    if (o->facets ? !o->facets[f] : (m->fflags[f] & TDS_NODISPLAY) != 0) continue;
    if (!in_shell(m, f, body, &rev)) continue;
    nt++;
    for (int k = 0; k < 3; k++) map[m->fv[f][k]] = 1;
  }
  for (tds_id v = 0; v < m->nv; v++) map[v] = map[v] ? nv++ : -1;
  /* room for caps (tds_export_caps) */
  int32_t room = 6 * nt + 1;
  b->x.x = tds_calloc(&ctx->alloc, (size_t)(nv > 0 ? nv : 1), sizeof *b->x.x);
  b->vid = tds_calloc(&ctx->alloc, (size_t)(nv > 0 ? nv : 1), sizeof *b->vid);
  b->x.tri = tds_calloc(&ctx->alloc, (size_t)room, sizeof *b->x.tri);
  b->src = tds_calloc(&ctx->alloc, (size_t)room, sizeof *b->src);
  b->rev = tds_calloc(&ctx->alloc, (size_t)room, 1);
  if (!b->x.x || !b->vid || !b->x.tri || !b->src || !b->rev) {
    tds_free(&ctx->alloc, map);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  for (tds_id v = 0; v < m->nv; v++) {
    if (map[v] < 0) continue;
    for (int k = 0; k < 3; k++) {
      if (!isfinite(m->x[v][k])) {
        tds_free(&ctx->alloc, map);
        return tds_seterr(ctx, TDS_ENUM, "export: vertex %d has a coordinate that is not finite",
                          v + 1);
      }
      b->x.x[map[v]][k] = m->x[v][k];
    }
    b->vid[map[v]] = v;
  }
  b->x.nv = nv;
  int32_t t = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    int rev;
    if (!tds_alive(m->fflags, f)) continue;
    if (o->facets ? !o->facets[f] : (m->fflags[f] & TDS_NODISPLAY) != 0) continue;
    if (!in_shell(m, f, body, &rev)) continue;
    for (int k = 0; k < 3; k++) b->x.tri[t][k] = map[m->fv[f][rev ? 2 - k : k]];
    b->src[t] = f;
    b->rev[t] = (uint8_t)rev;
    t++;
  }
  b->x.nt = t;
  tds_free(&ctx->alloc, map);
  if (body != TDS_NONE && o->caps) {
    int rc = tds_export_caps(ctx, &b->x, &b->ncap);
    if (rc != TDS_OK) return rc;
    for (int32_t i = t; i < b->x.nt; i++) {
      b->src[i] = TDS_NONE;
      b->rev[i] = 0;
    }
  }
  return TDS_OK;
}

static double *add_field(xmesh *x, int vertex, const char *name, int type, int ncomp) {
  int32_t n = vertex ? x->nv : x->nt;
  xfield *fl = vertex ? &x->vf[x->nvf] : &x->ff[x->nff];
  fl->v = tds_calloc(&x->alloc, (size_t)(n > 0 ? n : 1) * (size_t)ncomp, sizeof(double));
  if (!fl->v) return NULL;
  fl->name = name;
  fl->type = type;
  fl->ncomp = ncomp;
  if (vertex) x->nvf++;
  else x->nff++;
  return fl->v;
}

static double tri_area(const xmesh *x, int32_t t) {
  return geom_area(x->x[x->tri[t][0]], x->x[x->tri[t][1]], x->x[x->tri[t][2]], NULL);
}

static double facet_area(const tds_mesh *m, tds_id f) {
  tds_corners C;
  tds_gather_facet(m, f, &C);
  return geom_area(C.x[0], C.x[1], C.x[2], NULL);
}

static double tri_min_angle(const xmesh *x, int32_t t) {
  const double *a = x->x[x->tri[t][0]], *b = x->x[x->tri[t][1]], *c = x->x[x->tri[t][2]];
  double A = geom_angle(a, b, c), B = geom_angle(b, c, a), C = TDS_PI - A - B;
  double mn = A < B ? A : B;
  if (C < mn) mn = C;
  if (!(mn > 0)) mn = 0;
  return mn * 180 / TDS_PI;
}

static int fields(tds_ctx *ctx, const tds_surf *s, const tds_export_opts *o, build *b,
                  const tds_surf *orig, const tds_torus_drawn *dv) {
  const tds_mesh *m = &s->m;
  xmesh *x = &b->x;
  for (int fi = 0; fi < TDS_VF_COUNT; fi++) {
    if (!(o->vfields & (1u << fi))) continue;
    int vec = fi == TDS_VF_POSITION || fi == TDS_VF_NORMAL || fi == TDS_VF_DISPLACEMENT;
    double *v = add_field(x, 1, tds_export_vfields[fi], fi == TDS_VF_ID ? XF_INT : XF_DOUBLE,
                          vec ? 3 : 1);
    if (!v) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    if (fi == TDS_VF_NORMAL) { /* area-weighted mean of the written triangles' normals */
      for (int32_t t = 0; t < x->nt; t++) {
        double n[3];
        xtri_normal(x, t, n);
        double a = tri_area(x, t);
        for (int k = 0; k < 3; k++)
          for (int c = 0; c < 3; c++) v[3 * x->tri[t][k] + c] += a * n[c];
      }
      for (int32_t i = 0; i < x->nv; i++) {
        double l = v3_norm(v + 3 * i);
        if (l > 0) v3_scale(v + 3 * i, 1 / l);
      }
      continue;
    }
    for (int32_t i = 0; i < x->nv; i++) {
      tds_id sv = b->vid[i];
      const tds_surf *fs = s; /* the surface and vertex the values are of */
      if (dv && sv != TDS_NONE) {
        fs = orig;
        sv = dv->vsrc[sv] >= 0 ? dv->vsrc[sv] : TDS_NONE;
      }
      int none = sv == TDS_NONE;
      switch (fi) {
      case TDS_VF_POSITION:
        for (int c = 0; c < 3; c++) v[3 * i + c] = x->x[i][c];
        break;
      case TDS_VF_MEAN_CURVATURE: v[i] = none ? (double)NAN : tds_vertex_mean_curvature(fs, sv); break;
      case TDS_VF_GAUSS_CURVATURE: v[i] = none ? (double)NAN : tds_vertex_gauss_curvature(fs, sv); break;
      case TDS_VF_DISPLACEMENT:
        for (int c = 0; c < 3; c++)
          v[3 * i + c] = !none && sv < o->nmark ? fs->m.x[sv][c] - o->mark[sv][c] : (double)NAN;
        break;
      default: v[i] = sv + 1; break;
      }
    }
  }
  for (int fi = 0; fi < TDS_FF_COUNT; fi++) {
    if (!(o->ffields & (1u << fi))) continue;
    double *v = add_field(x, 0, tds_export_ffields[fi],
                          fi == TDS_FF_AREA || fi == TDS_FF_MIN_ANGLE || fi == TDS_FF_TENSION
                              ? XF_DOUBLE : XF_INT, 1);
    if (!v) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    double *rgba = NULL;
    if (fi == TDS_FF_COLOR && !(rgba = add_field(x, 0, "rgba", XF_UCHAR, 4)))
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    for (int32_t t = 0; t < x->nt; t++) {
      tds_id f = b->src[t];
      tds_id fb = f == TDS_NONE ? TDS_NONE : m->fb[f][b->rev[t]];
      tds_id bb = f == TDS_NONE ? TDS_NONE : m->fb[f][!b->rev[t]];
      switch (fi) {
      case TDS_FF_MIN_ANGLE:
        v[t] = f == TDS_NONE ? tri_min_angle(x, t) : tds_facet_min_angle(m, f);
        break;
      case TDS_FF_AREA:
        v[t] = f == TDS_NONE ? tri_area(x, t) : facet_area(m, f);
        break;
      case TDS_FF_TENSION: v[t] = f == TDS_NONE ? 0 : m->ften[f]; break;
      case TDS_FF_COLOR: {
        int c = f == TDS_NONE ? 0 : m->fcolor[f];
        unsigned char q[4];
        tds_export_rgba(c, q);
        v[t] = c;
        for (int k = 0; k < 4; k++) rgba[4 * t + k] = q[k];
        break;
      }
      case TDS_FF_FRONTBODY: v[t] = f == TDS_NONE ? b->body + 1 : fb + 1; break;
      case TDS_FF_BACKBODY: v[t] = f == TDS_NONE ? 0 : bb + 1; break;
      default: v[t] = f == TDS_NONE ? 0 : (dv ? dv->fsrc[f] : f) + 1; break;
      }
    }
  }
  return TDS_OK;
}

static int write_one(tds_ctx *ctx, FILE *f, const tds_export_opts *o, const xmesh *x) {
  switch (o->format) {
  case TDS_FMT_OBJ: return tds_write_obj(ctx, f, x);
  case TDS_FMT_OFF: return tds_write_off(ctx, f, x);
  case TDS_FMT_STL: return tds_write_stl(ctx, f, x, o->encoding);
  case TDS_FMT_PLY: return tds_write_ply(ctx, f, x, o->encoding);
  case TDS_FMT_VTU: return tds_write_vtu(ctx, f, x, o->encoding, o->appended);
  case TDS_FMT_VTK: return tds_write_vtk(ctx, f, x, o->encoding);
  default: return tds_write_msh(ctx, f, x, o->encoding, o->msh_version);
  }
}

/* "<stem>_body<id><ext>" for path "<stem><ext>". Caller frees. */
static char *body_path(const tds_alloc *a, const char *path, tds_id body) {
  const char *slash = strrchr(path, '/');
  const char *dot = strrchr(slash ? slash : path, '.');
  size_t stem = dot ? (size_t)(dot - path) : strlen(path);
  size_t n = strlen(path) + 32;
  char *p = tds_malloc(a, n);
  if (p) snprintf(p, n, "%.*s_body%d%s", (int)stem, path, body + 1, dot ? dot : "");
  return p;
}

/* The export of s; for a torus surface s is its drawn mesh (dv), and the
** vertex fields and ids are those of the vertices and facets it is drawn
** from in orig. */
static int export_drawn(tds_ctx *ctx, tds_surf *s, const char *path, const tds_export_opts *o,
                        const tds_surf *orig, const tds_torus_drawn *dv) {
  int rc = check_opts(ctx, s, o);
  if (rc != TDS_OK) return rc;
  tds_mesh *m = &s->m;
  if (tds_mesh_adjacency(m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  int32_t nfiles = o->per_body ? m->nb : 1;
  tds_wfile *af = tds_calloc(&ctx->alloc, (size_t)(nfiles > 0 ? nfiles : 1), sizeof *af);
  if (!af) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  int32_t opened = 0;
  for (int32_t i = 0; i < nfiles && rc == TDS_OK; i++) {
    tds_id body = o->per_body ? i : TDS_NONE;
    if (body != TDS_NONE && !tds_alive(m->bflags, body)) continue;
    char *p = body != TDS_NONE ? body_path(&ctx->alloc, path, body) : NULL;
    if (body != TDS_NONE && !p) {
      rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      break;
    }
    build b;
    rc = make_mesh(ctx, s, o, body, &b);
    if (rc == TDS_OK && b.x.nt == 0)
      rc = body != TDS_NONE
               ? tds_seterr(ctx, TDS_ERANGE, "export: body %d has no facets to export", body + 1)
               : tds_seterr(ctx, TDS_ERANGE, "export: no facets to export");
    if (rc == TDS_OK) rc = fields(ctx, s, o, &b, orig, dv);
    char title[160];
    if (body != TDS_NONE)
      snprintf(title, sizeof title, "tds %s: body %d, %d vertices, %d facets (%d cap)",
               TDS_VERSION, body + 1, b.x.nv, b.x.nt, b.ncap);
    else
      snprintf(title, sizeof title, "tds %s: %d vertices, %d facets", TDS_VERSION, b.x.nv,
               b.x.nt);
    b.x.title = title;
    if (rc == TDS_OK) rc = tds_wfile_open(ctx, &af[opened], p ? p : path);
    if (rc == TDS_OK) {
      opened++;
      rc = write_one(ctx, af[opened - 1].f, o, &b.x);
      int crc = tds_wfile_close(ctx, &af[opened - 1]);
      if (rc == TDS_OK) rc = crc;
    }
    build_free(&b);
    tds_free(&ctx->alloc, p);
  }
  for (int32_t i = 0; i < opened && rc == TDS_OK; i++) rc = tds_wfile_commit(ctx, &af[i]);
  if (rc == TDS_OK && o->written)
    for (int32_t i = 0; i < opened; i++) o->written(o->ud, af[i].path);
  for (int32_t i = 0; i < opened; i++) tds_wfile_abort(&af[i]);
  tds_free(&ctx->alloc, af);
  return rc;
}

int tds_export(tds_ctx *ctx, tds_surf *s, const char *path, const tds_export_opts *o) {
  int strings_clipped = s->str && s->m.torus && s->m.draw == TDS_DRAW_CLIPPED;
  if (s->str && !strings_clipped) return tds_export_strings(ctx, s, path, o); /* edges */
  if (!s->m.torus) return export_drawn(ctx, s, path, o, NULL, NULL);
  tds_torus_drawn view; /* as drawn: no edge across the cell */
  int rc = tds_torus_view(ctx, s, &view);
  if (rc != TDS_OK) return rc;
  if (strings_clipped) {
    rc = tds_export_strings(ctx, &view.s, path, o);
    tds_torus_view_free(&view);
    return rc;
  }
  tds_export_opts o2 = *o;
  uint8_t *sel = NULL;
  if (o->facets) { /* the selection, carried to the facets drawn from it */
    sel = tds_calloc(&ctx->alloc, (size_t)view.s.m.nf + 1, 1);
    if (!sel) rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    for (tds_id f = 0; sel && f < view.s.m.nf; f++)
      sel[f] = view.fsrc[f] >= 0 && o->facets[view.fsrc[f]];
    o2.facets = sel;
  }
  if (rc == TDS_OK) rc = export_drawn(ctx, &view.s, path, &o2, s, &view);
  tds_free(&ctx->alloc, sel);
  tds_torus_view_free(&view);
  return rc;
}
