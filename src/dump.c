/*
** dump.c: writing a surface as a Surface Evolver datafile (contract in
** datafile.h).
**
** Numbers are written with 17 significant digits, so a dump read back
** (by tds or by Evolver) has bit-identical coordinates and parameters.
** Element ids are kept; dead slots are left out (Evolver accepts gaps).
** Formulas are written from their source text, cleaned so that the text
** means the same in a datafile: comments removed, newlines made spaces,
** and a space put after a sign that the datafile's signed-number rule
** would otherwise read as the start of a new number ("z -1" -> "z - 1";
** inside one expression that sign was an operator anyway).
*/
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "attr.h"
#include "datafile.h"
#include "model.h"
#include "string_model.h"
#include "symgroup.h"
#include "wfile.h"
#include "wrap.h"

typedef struct out {
  FILE *f;
  const tds_alloc *alloc; /* for scratch values (the ctx's hook) */
  int bad;        /* a value was not finite */
  char what[96];  /* first non-finite item */
} out;

static void num(out *o, double v, const char *what, int id) {
  if (!isfinite(v) && !o->bad) {
    o->bad = 1;
    snprintf(o->what, sizeof o->what, "%s %d", what, id);
  }
  fprintf(o->f, " %.17g", v);
}

/* VIEW_TRANSFORM_GENERATORS, or else the datafile's VIEW_TRANSFORMS after
** the identity, as Evolver's dump writes them (it leaves out transforms
** made by transform_expr from generators). */
static void matrices(out *o, const char *kw, int n, const double (*m)[16],
                     const uint8_t *swap) {
  fprintf(o->f, "%s %d\n", kw, n);
  for (int t = 0; t < n; t++) {
    if (swap && swap[t]) fputs("swap_colors\n", o->f);
    for (int i = 0; i < 4; i++) {
      for (int j = 0; j < 4; j++) num(o, m[t][4 * i + j], kw, t + 1);
      fputc('\n', o->f);
    }
  }
}

static void view_matrices(out *o, const tds_surf *s) {
  if (s->nvgen) {
    matrices(o, "VIEW_TRANSFORM_GENERATORS", s->nvgen, (const double (*)[16])s->vgen,
             s->vgen_swap);
    return;
  }
  static const double id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (s->view_transforms > 1 && !memcmp(s->view[0], id, sizeof id))
    matrices(o, "VIEW_TRANSFORMS", s->view_transforms - 1, (const double (*)[16])(s->view + 1),
             s->view_swap ? s->view_swap + 1 : NULL);
}

/* Write expression text cleaned for the datafile (see the top). */
static void text(out *o, const tds_expr *e) {
  if (!e) {
    fputs("0", o->f);
    return;
  }
  const char *s = tds_expr_text(e);
  size_t n = strlen(s);
  int prev_space = 1;
  for (size_t i = 0; i < n; i++) {
    char c = s[i];
    if (c == '/' && i + 1 < n && s[i + 1] == '/') {
      while (i < n && s[i] != '\n') i++;
      c = ' ';
    } else if (c == '/' && i + 1 < n && s[i + 1] == '*') {
      i += 2;
      while (i + 1 < n && !(s[i] == '*' && s[i + 1] == '/')) i++;
      i++;
      c = ' ';
    } else if (c == '\\' && i + 1 < n && (s[i + 1] == '\n' || s[i + 1] == '\r')) {
      i++;
      c = ' ';
    }
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    fputc(c, o->f);
    if ((c == '+' || c == '-') && prev_space && i + 1 < n &&
        ((s[i + 1] >= '0' && s[i + 1] <= '9') || s[i + 1] == '.'))
      fputc(' ', o->f);
    prev_space = c == ' ';
  }
}

/* ncomp: 3, or 1 for the string model's scalar content */
static void components(out *o, const char *title, char letter, tds_expr *const e[3],
                       int ncomp) {
  if (!e[0] && !e[1] && !e[2]) return;
  fprintf(o->f, "%s\n", title);
  for (int k = 0; k < ncomp; k++) {
    fprintf(o->f, "%c%d: ", letter, k + 1);
    text(o, e[k]);
    fputc('\n', o->f);
  }
}

static void cons(out *o, const tds_surf *s, tds_cmask mask, int rev) {
  if (!mask) return;
  fputs(" constraints", o->f);
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (mask & ((tds_cmask)1 << c)) {
      if (s->con[c].name[0]) fprintf(o->f, " %s%s", rev ? "-" : "", s->con[c].name);
      else fprintf(o->f, " %s%d", rev ? "-" : "", s->con[c].number);
    }
}

/* Nested braces of user array values v (dims dim[d..ndim)), from *k. */
static void array(out *o, const tds_attr *a, const double *v, int *k, int d, tds_id id) {
  int n = a->ndim ? (int)a->dim[d] : a->size;
  fputs(" {", o->f);
  for (int i = 0; i < n; i++) {
    if (i) fputc(',', o->f);
    if (a->ndim && d + 1 < a->ndim) array(o, a, v, k, d + 1, id);
    else num(o, v[(*k)++], tds_kind_name[a->kind], id + 1);
  }
  fputs(" }", o->f);
}

/* The attribute words of element id: every TDS_AT_FE attribute of the
** registry that dump writes for it (attr.h), in registry order. */
static void attrs(out *o, tds_surf *s, int kind, tds_id id) {
  int na = tds_attr_count(&s->m, kind);
  double *v = NULL;
  for (int i = 0; i < na; i++) {
    tds_attr a;
    tds_attr_at(&s->m, kind, i, &a);
    if (!(a.io & TDS_AT_FE) || !tds_attr_dumped(s, &a, id)) continue;
    if (a.type == TDS_AT_CONS) {
      tds_cmask mask = kind == TDS_VERTEX ? s->m.vcon[id]
                       : kind == TDS_EDGE ? s->m.econ[id] : s->m.fcon[id];
      cons(o, s, mask, kind == TDS_EDGE && (s->m.eflags[id] & TDS_CONREV));
      continue;
    }
    double one[1];
    v = a.size > 1 ? tds_malloc(o->alloc, sizeof *v * (size_t)a.size) : one;
    int n = 0;
    tds_ctx quiet;
    tds_ctx_init(&quiet);
    quiet.alloc = *o->alloc;
    if (!v || tds_attr_read(&quiet, s, &a, id, v, &n) != TDS_OK || n == 0) {
      if (v != one) tds_free(o->alloc, v);
      if (!v && !o->bad) {
        o->bad = 1;
        snprintf(o->what, sizeof o->what, "memory for %s %d", tds_kind_name[kind], id + 1);
      }
      continue;
    }
    fprintf(o->f, " %s", tds_attr_word(&a));
    if (a.type == TDS_AT_REAL && a.size == 1) {
      num(o, v[0], tds_kind_name[kind], id + 1);
    } else if (a.size > 1) {
      int k = 0;
      array(o, &a, v, &k, 0, id);
    } else if (a.type != TDS_AT_FLAG) {
      fprintf(o->f, " %.17g", v[0]);
    }
    if (v != one) tds_free(o->alloc, v);
  }
  int32_t file = tds_mesh_file_ids(&s->m, kind)[id];
  if (file >= 1 && file != id + 1) fprintf(o->f, " original %d", (int)file);
}

/* DEFINE lines of the user attributes. */
static void defines(out *o, const tds_surf *s) {
  for (int k = 0; k < TDS_NKINDS; k++)
    for (int c = 0; c < s->m.nucol[k]; c++) {
      const tds_ucol *u = &s->m.ucol[k][c];
      fprintf(o->f, "define %s attribute %s %s", tds_kind_name[k], u->name,
              u->type == TDS_AT_INT ? "integer" : "real");
      for (int d = 0; d < u->ndim; d++) fprintf(o->f, "[%d]", (int)u->dim[d]);
      fputc('\n', o->f);
    }
}

/* The gravity constant; G = 0 when gravity is off but bodies have a
** density (the body lines carry it, and Evolver turns gravity on then). */
static void gravity(out *o, const tds_surf *s) {
  const tds_mesh *m = &s->m;
  int density = 0;
  for (tds_id b = 0; b < m->nb; b++)
    if (tds_alive(m->bflags, b) && m->bdensity[b] != 0) density = 1;
  if (!s->gravity_on && density) {
    fputs("// gravity was off: G = 0 keeps the bodies' densities without energy\n"
          "GRAVITY_CONSTANT 0\n", o->f);
  } else {
    fputs("GRAVITY_CONSTANT", o->f);
    num(o, s->gravity, "gravity_constant", 0);
    fputc('\n', o->f);
  }
}

static void header(out *o, const tds_surf *s) {
  FILE *f = o->f;
  for (int i = 0; i < s->npar; i++) {
    fprintf(f, "PARAMETER %s =", s->parname[i]);
    num(o, s->parval[i], "parameter", i + 1);
    fputc('\n', f);
  }
  if (s->str)
    fprintf(f, "STRING\nSPACE_DIMENSION %d\n\n", s->str->space_dim);
  if (s->klein) fputs("KLEIN_METRIC\n\n", f);
  if (s->str && s->metric_on) { /* METRIC: N rows of N components */
    int n = s->str->space_dim;
    fputs("METRIC\n", f);
    for (int i = 0; i < n; i++) {
      for (int j = 0; j < n; j++) {
        fputs(j ? "  " : "", f);
        text(o, s->metric[3 * i + j]);
      }
      fputc('\n', f);
    }
    fputc('\n', f);
  }
  if (s->npar) fputc('\n', f);
  if (s->m.torus) {
    /* the period formulas as given (parameters stay live), one row a line */
    if (s->m.sym) /* the group's name; its wraps are `wrap` words (attr_rows.c) */
      fprintf(f, "SYMMETRY_GROUP \"%s\"\n", tds_sym_name(s->m.sym));
    if (s->m.sym > TDS_SYM_TORUS) /* no periods; parameters are written above */
      ;
    else if (s->m.sym)
      fputs("PERIODS\n", f);
    else
      fputs(s->m.torus == 2 ? "TORUS_FILLED\nPERIODS\n" : "TORUS\nPERIODS\n", f);
    int pd = s->str && s->str->space_dim == 2 ? 2 : 3; /* the plane: two of two */
    for (int i = 0; i < pd && s->m.sym <= TDS_SYM_TORUS; i++) {
      for (int j = 0; j < pd; j++) {
        if (s->period_expr[i][j]) {
          fputs(j ? " (" : "(", f);
          text(o, s->period_expr[i][j]);
          fputc(')', f);
        } else {
          num(o, s->m.period[i][j], "period", i + 1);
        }
      }
      fputc('\n', f);
    }
    fputc('\n', f);
  }
  defines(o, s);
  gravity(o, s);
  if (s->gap_constant != 1) {
    fputs("GAP_CONSTANT", f);
    num(o, s->gap_constant, "gap_constant", 0);
    fputc('\n', f);
  }
  if (s->constraint_tol != 1e-12) {
    fputs("CONSTRAINT_TOLERANCE", f);
    num(o, s->constraint_tol, "constraint_tolerance", 0);
    fputc('\n', f);
  }
  if (s->scale_limit != 1) {
    fputs("SCALE_LIMIT", f);
    num(o, s->scale_limit, "scale_limit", 0);
    fputc('\n', f);
  }
  if (s->fixed_scale) {
    fputs("SCALE", f);
    num(o, s->scale, "scale", 0);
    fputs(" FIXED\n", f);
  }
  if (s->symmetric_content) fputs("SYMMETRIC_CONTENT\n", f);
  /* g's toggles that a datafile can give (Evolver's dump writes them) */
  if (s->autochop) {
    fputs("AUTOCHOP", f);
    num(o, s->autochop_length, "autochop", 0);
    fputc('\n', f);
  }
  if (s->autopop) fputs("AUTOPOP\n", f);
  if (s->area_normalization) fputs("AREA_NORMALIZATION\n", f);
  if (s->m.has_origin) {
    fputs("DISPLAY_ORIGIN", f);
    for (int i = 0; i < 3; i++) num(o, s->m.origin[i], "display_origin", i + 1);
    fputc('\n', f);
  }
  view_matrices(o, s);
  fputc('\n', f);

  /* constraints in order of their numbers */
  int last = 0;
  for (;;) {
    int best = -1;
    for (int c = 0; c < TDS_MAX_CON; c++)
      if (s->con[c].number > last && (best < 0 || s->con[c].number < s->con[best].number))
        best = c;
    if (best < 0) break;
    const tds_constraint *c = &s->con[best];
    last = c->number;
    /* a named one is written by name, in its number's place: reading it
    ** back gives it the same number (the smallest free one) */
    if (c->name[0]) fprintf(f, "CONSTRAINT %s", c->name);
    else fprintf(f, "CONSTRAINT %d", c->number);
    fprintf(f, "%s%s%s%s\nFORMULA: ",
            (c->flags & TDS_CON_GLOBAL) ? " GLOBAL" : "",
            (c->flags & TDS_CON_CONVEX) ? " CONVEX" : "",
            (c->flags & TDS_CON_NONNEG) ? " NONNEGATIVE" : "",
            (c->flags & TDS_CON_NONPOS) ? " NONPOSITIVE" : "");
    text(o, c->formula);
    fputc('\n', f);
    components(o, "ENERGY", 'E', c->energy, s->str ? 1 : 3);
    components(o, "CONTENT", 'C', c->content, s->str ? 1 : 3);
    fputc('\n', f);
  }
  for (int i = 0; i < s->nbdry; i++) {
    const tds_boundary *b = &s->bdry[i];
    if (!b->number) continue;
    fprintf(f, "BOUNDARY %d PARAMETERS %d%s\n", b->number, b->nparams,
            (b->flags & TDS_CON_CONVEX) ? " CONVEX" : "");
    for (int k = 0; k < 3; k++) {
      fprintf(f, "X%d: ", k + 1);
      text(o, b->x[k]);
      fputc('\n', f);
    }
    components(o, "ENERGY", 'E', b->energy, s->str ? 1 : 3);
    components(o, "CONTENT", 'C', b->content, s->str ? 1 : 3);
    fputc('\n', f);
  }
  if (s->special_normal[0]) {
    fputs("HESSIAN_SPECIAL_NORMAL_VECTOR\n", f);
    for (int k = 0; k < 3 && s->special_normal[k]; k++) { /* C3 absent in 2-D */
      fprintf(f, "C%d: ", k + 1);
      text(o, s->special_normal[k]);
      fputc('\n', f);
    }
    fputc('\n', f);
  }
  for (int i = 0; i < s->nquant; i++) {
    const tds_quantity *q = &s->quant[i];
    fprintf(f, "QUANTITY %s ", q->name);
    if (q->kind == TDS_Q_FIXED) {
      fputs("FIXED =", f);
      num(o, q->target, "quantity target", i + 1);
      fputs(" LAGRANGE_MULTIPLIER", f);
      num(o, q->pressure, "quantity pressure", i + 1);
    } else {
      fputs(q->kind == TDS_Q_ENERGY ? "ENERGY" : "INFO_ONLY", f);
    }
    if (q->modulus != 1) {
      fputs(" MODULUS", f);
      num(o, q->modulus, "quantity modulus", i + 1);
    }
    if (q->volconst != 0) {
      fputs(" VOLCONST", f);
      num(o, q->volconst, "quantity volconst", i + 1);
    }
    fputc('\n', f);
    for (int j = 0; j < q->ninst; j++) {
      const tds_method_inst *mi = &q->inst[j];
      int mth = mi->method >= 0 && mi->method < TDS_M_COUNT ? mi->method : 0;
      fprintf(f, "METHOD %s", tds_methods[mth].name);
      if (mi->modulus != 1) {
        fputs(" MODULUS", f);
        num(o, mi->modulus, "method modulus", i + 1);
      }
      fputs(" GLOBAL\n", f);
      if (tds_methods[mth].flags & TDS_MF_VECTOR) {
        fputs("VECTOR_INTEGRAND:\n", f);
        for (int k = 0; k < 3; k++) {
          fprintf(f, "Q%d: ", k + 1);
          text(o, mi->integrand[k]);
          fputc('\n', f);
        }
      } else if (mi->integrand[0]) {
        fputs("SCALAR_INTEGRAND: ", f);
        text(o, mi->integrand[0]);
        fputc('\n', f);
      }
    }
    fputc('\n', f);
  }
}

/* The string model's cells as faces: their edge lists. */
static void string_faces(out *o, const tds_surf *s) {
  const tds_strings *st = s->str;
  for (tds_id t = 0; t < st->nf; t++) {
    if (st->flags[t] & TDS_DEAD) continue;
    fprintf(o->f, "%d", t + 1);
    int col = 0;
    for (int32_t i = st->start[t]; i < st->start[t + 1]; i++) {
      if (++col == 20) {
        fputs(" \\\n ", o->f);
        col = 0;
      }
      fprintf(o->f, " %s%d", TDS_OREV(st->oe[i]) ? "-" : "", TDS_OID(st->oe[i]) + 1);
    }
    if (st->flags[t] & TDS_FIXED) fputs(" fixed", o->f);
    if (st->flags[t] & TDS_NODISPLAY) fputs(" nodisplay", o->f);
    if (st->flags[t] & TDS_NONCONTENT) fputs(" noncontent", o->f);
    if (st->color[t]) fprintf(o->f, " color %d", st->color[t]);
    fputc('\n', o->f);
  }
}

/* The cells of body b (string model), signed. */
static void string_body(out *o, const tds_surf *s, tds_id b) {
  const tds_strings *st = s->str;
  int col = 0;
  for (tds_id t = 0; t < st->nf; t++) {
    if (st->flags[t] & TDS_DEAD) continue;
    for (int j = 0; j < 2; j++)
      if (st->fb[t][j] == b) {
        if (col++ == 16) {
          fputs(" \\\n ", o->f);
          col = 0;
        }
        fprintf(o->f, " %s%d", j ? "-" : "", t + 1);
      }
  }
}

static void elements(out *o, tds_surf *s) {
  FILE *f = o->f;
  const tds_mesh *m = &s->m;
  fputs("vertices\n", f);
  for (tds_id v = 0; v < m->nv; v++) {
    if (!tds_alive(m->vflags, v)) continue;
    fprintf(f, "%d", v + 1);
    int32_t bd = m->vbdry[v];
    if (bd != TDS_NONE && bd >= 0 && bd < s->nbdry) {
      for (int k = 0; k < s->bdry[bd].nparams; k++) num(o, m->vp[v][k], "vertex", v + 1);
    } else {
      int dim = s->str ? s->str->space_dim : 3;
      for (int k = 0; k < dim; k++) num(o, m->x[v][k], "vertex", v + 1);
    }
    attrs(o, s, TDS_VERTEX, v);
    fputc('\n', f);
  }
  fputs("\nedges\n", f);
  for (tds_id e = 0; e < m->ne; e++) {
    if (!tds_alive(m->eflags, e)) continue;
    fprintf(f, "%d %d %d", e + 1, m->ev[e][0] + 1, m->ev[e][1] + 1);
    if (m->torus && !m->sym) { /* Evolver's signs; larger counts by the wrap word */
      int k[3];
      tds_wrap_unpack(m->ewrap[e], k);
      int pd = s->str && s->str->space_dim == 2 ? 2 : 3;
      if (k[0] * k[0] <= 1 && k[1] * k[1] <= 1 && k[2] * k[2] <= 1)
        for (int i = 0; i < pd; i++) fputs(k[i] > 0 ? " +" : k[i] < 0 ? " -" : " *", f);
    }
    attrs(o, s, TDS_EDGE, e);
    fputc('\n', f);
  }
  fputs("\nfaces\n", f);
  for (tds_id t = 0; t < m->nf; t++) {
    if (!tds_alive(m->fflags, t)) continue;
    fprintf(f, "%d", t + 1);
    for (int k = 0; k < 3; k++) {
      int32_t r = m->fe[t][k];
      fprintf(f, " %s%d", TDS_OREV(r) ? "-" : "", TDS_OID(r) + 1);
    }
    attrs(o, s, TDS_FACET, t);
    fputc('\n', f);
  }
  if (s->str) string_faces(o, s);
  int any = 0;
  for (tds_id b = 0; b < m->nb; b++) any |= tds_alive(m->bflags, b);
  if (!any) return;
  fputs("\nbodies\n", f);
  for (tds_id b = 0; b < m->nb; b++) {
    if (!tds_alive(m->bflags, b)) continue;
    fprintf(f, "%d", b + 1);
    int col = 0;
    if (s->str) string_body(o, s, b);
    for (tds_id t = 0; t < m->nf; t++) {
      if (!tds_alive(m->fflags, t)) continue;
      for (int j = 0; j < 2; j++)
        if (m->fb[t][j] == b) {
          if (col == 16) {
            fputs(" \\\n ", f);
            col = 0;
          }
          fprintf(f, " %s%d", j ? "-" : "", t + 1);
          col++;
        }
    }
    attrs(o, s, TDS_BODY, b);
    fputc('\n', f);
  }
}

/* Write the file: the model header (model) or the caller's header text,
** the elements, the read section. */
static int write(tds_ctx *ctx, tds_surf *s, const char *path, int model, const char *hdr,
                 const char *read) {
  tds_wfile w;
  int rc = tds_wfile_open(ctx, &w, path);
  if (rc != TDS_OK) return rc;
  out o = {0};
  o.f = w.f;
  o.alloc = &ctx->alloc;
  const tds_mesh *m = &s->m;
  if (model) {
    tds_ctx quiet = *ctx;
    double energy = NAN;
    if (tds_surf_update(&quiet, s) == TDS_OK) energy = s->energy;
    fprintf(o.f, "// %s: Surface Evolver datafile written by tds %s\n", path, TDS_VERSION);
    fprintf(o.f, "// vertices %d, edges %d, facets %d, bodies %d",
            tds_mesh_count(m, TDS_VERTEX), tds_mesh_count(m, TDS_EDGE),
            tds_surf_count(s, TDS_FACET), tds_mesh_count(m, TDS_BODY));
    if (isfinite(energy)) fprintf(o.f, "; total energy %.17g", energy);
    fputs("\n\n", o.f);
    header(&o, s);
  } else {
    fprintf(o.f, "// %s: written by tds write_fe\n", path);
    if (hdr) fprintf(o.f, "%s\n", hdr);
    if (s->gravity_on || m->nb) gravity(&o, s);
    defines(&o, s);
    fputc('\n', o.f);
  }
  elements(&o, s);
  /* the display mode is a command, as Evolver writes it (its datafile
  ** header does not take one) */
  static const char *const draw[] = {NULL, "connected\n", "clipped\n"};
  const char *mode = model && m->torus ? draw[m->draw] : NULL;
  if (read || mode) {
    fputs("\nread\n", o.f);
    if (mode) fputs(mode, o.f);
    if (!read) read = "";
    fputs(read, o.f);
    size_t k = strlen(read);
    if (k && read[k - 1] != '\n') fputc('\n', o.f);
  }
  if (o.bad)
    rc = tds_seterr(ctx, TDS_ENUM, "cannot dump to '%s': %s is not finite", path, o.what);
  else
    rc = tds_wfile_commit(ctx, &w);
  tds_wfile_abort(&w);
  return rc;
}

int tds_datafile_dump(tds_ctx *ctx, tds_surf *s, const char *path) {
  return write(ctx, s, path, 1, NULL, s->read_text);
}

int tds_datafile_dump_read(tds_ctx *ctx, tds_surf *s, const char *path, const char *read) {
  return write(ctx, s, path, 1, NULL, read);
}

int tds_datafile_write_fe(tds_ctx *ctx, tds_surf *s, const char *path, const char *header,
                          const char *read) {
  return write(ctx, s, path, 0, header, read);
}
