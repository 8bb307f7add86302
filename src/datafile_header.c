/*
** datafile_header.c: the keywords of a datafile's top section (PARAMETER,
** CONSTRAINT, BOUNDARY, QUANTITY, GRAVITY_CONSTANT, display hints, ...)
** and the table of Evolver keywords tds refuses as "not supported yet"
** (contracts in datafile_int.h).
*/
#include "datafile_int.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "model.h"
#include "symgroup.h"
#include "torus.h"

/* ---- not supported yet ---- */

/* Evolver keywords whose features the core does not have yet. */
static const char *const unsupported[] = {
    "quadratic", "lagrange", "lagrange_order", "simplex_representation",
    "conformal_metric",
    "method_instance", "optimizing_parameter", "optimising_parameter", "wulff",
    "phasefile", "diffusion", "pressure", "squared_curvature",
    "square_curvature", "mean_curvature_integral", "gauss_curvature",
    "squared_gaussian_curvature", "square_gaussian_curvature", "sqgauss",
    "insulating_knot_energy", "conducting_knot_energy", "mobility",
    "mobility_tensor", "integral_order", "integral_order_1d",
    "integral_order_2d", "runge_kutta", "homothety", "approximate_curvature",
    "effective_area", "jiggle",
    "temperature", "length_method_name", "area_method_name",
    "volume_method_name", "fixed_area",
    "area_fixed", "load_library", "interp_bdry_param",
    "function", "procedure",
    "gradient_mode", "parameter_file", "ideal_gas", "knot_energy",
    "conserved", "on_assign_call", "nonwall", "content_rank",
    "phase", "actual_volume", "form_integrand", "k_form_order",
    "parameter_1", "element_modulus", "clip_coeff", NULL};

int df_unsupported(const char *w) {
  for (int i = 0; unsupported[i]; i++)
    if (!strcmp(w, unsupported[i])) return 1;
  return 0;
}

int df_not_supported(df *d, const char *at, const char *w) {
  char u[64];
  return df_err(d, at, TDS_ESYNTAX, "%s is not supported yet", df_upper(w, u, sizeof u));
}

/* ---- handlers: the keyword table is at the end ---- */

typedef struct hdr_kw hdr_kw;
/* Read what follows keyword k (the cursor is just after it). */
typedef int (*hdr_fn)(df *d, const hdr_kw *k);
struct hdr_kw {
  const char *name;   /* lowercase */
  hdr_fn fn;
  /* for h_value and h_scale only: */
  ptrdiff_t off;      /* offset of the double in tds_surf set, or NOWHERE */
  int check;          /* ANY, POSITIVE or NONNEG */
};
#define NOWHERE (-1)
#define AT(field) offsetof(tds_surf, field)
enum { ANY, POSITIVE, NONNEG };

/* The name after keyword KW (upper case) into name[cap]; *at = where it
** starts. */
static int take_name(df *d, const char *kw, char *name, size_t cap, const char **at) {
  int have, rc = df_more(d, &have);
  if (rc) return rc;
  const char *a = *at = d->p;
  char b[64];
  size_t n = df_word_len(a);
  if (!n)
    return df_err(d, a, TDS_ESYNTAX, "%s: expected a name, found %s", kw,
                  df_describe(a, b, sizeof b));
  if (n >= cap) return df_err(d, a, TDS_ESYNTAX, "%s: name too long", kw);
  memcpy(name, a, n);
  name[n] = 0;
  d->p += n;
  return TDS_OK;
}

/* n values in a row, display only (matrices, slice coefficients). */
static int skip_values(df *d, int n, const char *what) {
  int rc = TDS_OK;
  d->split = 1;
  for (int i = 0; i < n && !rc; i++) {
    double v;
    rc = df_header_value(d, &v, what);
  }
  d->split = 0;
  return rc;
}

/* ---- parameters ---- */

static int h_parameter(df *d, const hdr_kw *k) {
  (void)k;
  const char *a;
  char name[256];
  int rc = take_name(d, "PARAMETER", name, sizeof name, &a);
  if (rc) return rc;
  if (df_expr_word(name, strlen(name)))
    return df_err(d, a, TDS_ESYNTAX, "PARAMETER: '%s' is a reserved name", name);
  static const char *const coord[] = {"x", "y", "z", "w", "x1", "x2", "x3",
                                      "x4", "p1", "p2", NULL};
  for (int i = 0; coord[i]; i++)
    if (!strcasecmp(name, coord[i]))
      return df_err(d, a, TDS_ESYNTAX, "PARAMETER: '%s' is a reserved name", name);
  df_ws(d);
  if (*d->p == '=') d->p++;
  char what[300];
  snprintf(what, sizeof what, "PARAMETER %s", name);
  double v;
  if ((rc = df_header_value(d, &v, what))) return rc;
  if (df_peek(d, "on_assign_call")) return df_not_supported(d, d->p, "on_assign_call");
  if (df_peek(d, "pdelta") || df_peek(d, "pscale"))
    return df_not_supported(d, d->p, "optimizing_parameter");
  if (tds_surf_param_set(d->s, name, v) < 0)
    return df_err(d, NULL, TDS_ENOMEM, "out of memory");
  return TDS_OK;
}

/* ---- constraints and boundaries ---- */

/* Optional ENERGY and CONTENT integrands of a constraint or boundary. */
static int integrals(df *d, tds_expr *en[3], tds_expr *ct[3], int flags,
                     const char *what) {
  for (;;) {
    int have, rc = df_more(d, &have);
    if (rc || !have) return rc;
    const char *a = d->p;
    char w2[300];
    if (df_accept(d, "energy")) {
      if (en[0] || en[1] || en[2])
        return df_err(d, a, TDS_ESYNTAX, "%s: ENERGY given twice", what);
      snprintf(w2, sizeof w2, "%s ENERGY", what);
      if ((rc = df_components(d, 'e', flags, en, w2))) return rc;
    } else if (df_accept(d, "content")) {
      if (ct[0] || ct[1] || ct[2])
        return df_err(d, a, TDS_ESYNTAX, "%s: CONTENT given twice", what);
      snprintf(w2, sizeof w2, "%s CONTENT", what);
      if ((rc = df_components(d, 'c', flags, ct, w2))) return rc;
    } else {
      return TDS_OK;
    }
  }
}

/* The number after keyword kw (constraint, boundary): in 1..1e9 and not
** declared before (slot_of finds declared ones); what = "kw N". */
static int decl_number(df *d, const char *kw, int (*slot_of)(const tds_surf *, int),
                       int app_kind, int64_t *n, char *what, size_t cap) {
  char u[64];
  int rc = df_header_int(d, 0, df_upper(kw, u, sizeof u), n);
  if (rc) return rc;
  if (*n < 1 || *n > 1000000000)
    return df_err(d, NULL, TDS_ESYNTAX, "%s: number %lld out of range", u, (long long)*n);
  snprintf(what, cap, "%s %lld", kw, (long long)*n);
  int slot = slot_of(d->s, (int)*n);
  if (slot >= 0 && !df_app_detach(d, app_kind, slot)) /* addload replaces */
    return df_err(d, NULL, TDS_ESYNTAX, "%s is declared twice", what);
  return TDS_OK;
}

static int h_constraint(df *d, const hdr_kw *k) {
  int64_t n;
  char what[64], w[64], name[32] = "";
  int have, rc = df_more(d, &have);
  if (rc) return rc;
  size_t nl = have ? df_word_len(d->p) : 0;
  if (nl) { /* a named constraint: the smallest free number */
    const char *a = d->p;
    if (nl >= sizeof name)
      return df_err(d, a, TDS_ESYNTAX, "CONSTRAINT: name longer than %d characters",
                    (int)sizeof name - 1);
    if (df_expr_word(a, nl))
      return df_err(d, a, TDS_ESYNTAX, "CONSTRAINT: '%.*s' is a function or constant name",
                    (int)nl, a);
    for (size_t i = 0; i < nl; i++) name[i] = (char)(a[i] >= 'A' && a[i] <= 'Z' ? a[i] + 32 : a[i]);
    d->p += nl;
    snprintf(what, sizeof what, "constraint %s", name);
    int old = tds_surf_con_named(d->s, name, nl);
    if (old >= 0 && !df_app_detach(d, DF_APP_CON, old))
      return df_err(d, a, TDS_ESYNTAX, "%s is declared twice", what);
    n = old >= 0 ? d->s->con[old].number : tds_surf_con_free_number(d->s);
  } else if ((rc = decl_number(d, k->name, tds_surf_con_slot, DF_APP_CON, &n, what, sizeof what))) {
    return rc;
  }
  int flags = 0;
  for (;;) {
    if ((rc = df_more(d, &have))) return rc;
    if (!have)
      return df_err(d, NULL, TDS_ESYNTAX, "%s: expected FORMULA, found end of file", what);
    const char *a = d->p;
    df_take_word(d, w, sizeof w);
    if (!strcmp(w, "global")) flags |= TDS_CON_GLOBAL;
    else if (!strcmp(w, "convex")) flags |= TDS_CON_CONVEX;
    else if (!strcmp(w, "nonnegative")) flags |= TDS_CON_NONNEG;
    else if (!strcmp(w, "nonpositive")) flags |= TDS_CON_NONPOS;
    else if (!strcmp(w, "formula") || !strcmp(w, "function") || !strcmp(w, "equation"))
      break;
    else if (df_unsupported(w)) {
      char u[64];
      return df_err(d, a, TDS_ESYNTAX, "%s: %s is not supported yet", what,
                    df_upper(w, u, sizeof u));
    } else {
      char b[64];
      d->p = a;
      return df_err(d, a, TDS_ESYNTAX, "%s: expected FORMULA, found %s", what,
                    df_describe(a, b, sizeof b));
    }
  }
  if ((flags & TDS_CON_NONNEG) && (flags & TDS_CON_NONPOS))
    return df_err(d, NULL, TDS_ESYNTAX, "%s: both NONNEGATIVE and NONPOSITIVE", what);
  tds_expr *f = NULL, *en[3] = {0}, *ct[3] = {0};
  char w2[80];
  snprintf(w2, sizeof w2, "%s FORMULA", what);
  if ((rc = df_header_expr(d, TDS_EXPR_FORMULA | TDS_MODEL_ON_VERTEX, &f, w2)) ||
      (rc = integrals(d, en, ct, TDS_MODEL_ON_EDGE, what))) {
    tds_expr_free(f);
    df_free3(en);
    df_free3(ct);
    return rc;
  }
  int line = df_line_of(d, NULL);
  rc = tds_model_constraint(d->ctx, d->s, (int)n, flags, f, en, ct);
  if (rc) return df_core(d, line, rc, NULL);
  memcpy(d->s->con[tds_surf_con_slot(d->s, (int)n)].name, name, sizeof name);
  return TDS_OK;
}

static int h_boundary(df *d, const hdr_kw *k) {
  int64_t n, np;
  char what[64];
  int rc = decl_number(d, k->name, tds_model_boundary_slot, DF_APP_BDRY, &n, what, sizeof what);
  if (rc) return rc;
  int have;
  if ((rc = df_more(d, &have))) return rc;
  if (!have || (!df_accept(d, "parameters") && !df_accept(d, "parameter"))) {
    char b[64];
    return df_err(d, d->p, TDS_ESYNTAX, "%s: expected PARAMETERS, found %s", what,
                  df_describe(d->p, b, sizeof b));
  }
  if ((rc = df_header_int(d, 0, what, &np))) return rc;
  if (np < 1 || np > 2)
    return df_err(d, NULL, TDS_ESYNTAX, "%s: %lld parameters (1 or 2 are supported)",
                  what, (long long)np);
  int flags = 0;
  if ((rc = df_more(d, &have))) return rc;
  if (have && df_accept(d, "convex")) flags |= TDS_CON_CONVEX;
  tds_expr *x[3] = {0}, *en[3] = {0}, *ct[3] = {0};
  rc = df_components(d, 'x', TDS_EXPR_PARAMS | TDS_MODEL_ON_VERTEX, x, what);
  if (!rc && (!x[0] || !x[1] || !x[2]))
    rc = df_err(d, d->p, TDS_ESYNTAX, "%s: needs X1, X2 and X3", what);
  if (!rc) rc = integrals(d, en, ct, TDS_MODEL_ON_EDGE, what);
  if (rc) {
    df_free3(x);
    df_free3(en);
    df_free3(ct);
    return rc;
  }
  int line = df_line_of(d, NULL);
  rc = tds_model_boundary(d->ctx, d->s, (int)n, (int)np, flags, x, en, ct);
  return rc ? df_core(d, line, rc, NULL) : TDS_OK;
}

/* HESSIAN_SPECIAL_NORMAL_VECTOR with C1: C2: C3: (functions of the
** coordinates and parameters); C1: C2: only in 2-D space (SPACE_DIMENSION
** 2 before it), as Evolver. */
static int h_special_normal(df *d, const hdr_kw *k) {
  (void)k;
  const char *what = "HESSIAN_SPECIAL_NORMAL_VECTOR";
  tds_expr *c[3] = {0};
  int rc = df_components(d, 'c', 0, c, what);
  if (!rc && d->space_dim == 2 && (!c[0] || !c[1] || c[2]))
    rc = df_err(d, d->p, TDS_ESYNTAX, "%s: needs C1 and C2 (and no C3) in 2-D space", what);
  else if (!rc && d->space_dim != 2 && (!c[0] || !c[1] || !c[2]))
    rc = df_err(d, d->p, TDS_ESYNTAX, "%s: needs C1, C2 and C3", what);
  if (rc) {
    df_free3(c);
    return rc;
  }
  for (int i = 0; i < 3; i++) {
    tds_expr_free(d->s->special_normal[i]);
    d->s->special_normal[i] = c[i];
  }
  return TDS_OK;
}

/* ---- named quantities ---- */

typedef struct meth {
  int method;
  int global;
  double modulus;
  tds_expr *in[3];
  int scalar;         /* the integrand was a SCALAR_INTEGRAND */
  int line;
} meth;

static int h_quantity(df *d, const hdr_kw *k) {
  (void)k;
  const char *a;
  char name[128], w[64], b[64];
  int have, rc = take_name(d, "QUANTITY", name, sizeof name, &a);
  if (rc) return rc;
  int qline = df_line_of(d, a);
  char what[160];
  snprintf(what, sizeof what, "quantity %s", name);
  int sameline = !df_at_eol(d);
  if ((rc = df_more(d, &have))) return rc;
  static const char *const kinds[] = {"energy", "fixed", "info_only", "conserved", NULL};
  size_t wl = have ? df_word_len(d->p) : 0;
  int kind = -1;
  for (int i = 0; kinds[i] && wl; i++)
    if (df_word_eq(d->p, wl, kinds[i])) kind = i;
  if (kind < 0) {
    if (!sameline) return TDS_OK; /* "quantity name;" forward declaration */
    return df_err(d, d->p, TDS_ESYNTAX,
                  "%s: expected ENERGY, FIXED = value or INFO_ONLY, found %s", what,
                  df_describe(d->p, b, sizeof b));
  }
  int oldq = tds_model_quantity_find(d->s, name);
  if (oldq >= 0 && !df_app_detach(d, DF_APP_QUANT, oldq))
    return df_err_line(d, qline, TDS_ESYNTAX, "%s is declared twice", what);
  if (kind == 3) return df_not_supported(d, d->p, "conserved");
  d->p += wl;
  double target = 0, modulus = 1, lagrange = 0, volconst = 0;
  int qkind = kind == 0 ? TDS_Q_ENERGY : kind == 1 ? TDS_Q_FIXED : TDS_Q_INFO;
  if (kind == 1) {
    df_ws(d);
    if (*d->p == '=') d->p++;
    if ((rc = df_header_value(d, &target, what))) return rc;
  }
  meth *ms = NULL; /* the methods, any number */
  int nm = 0;
  for (;;) {
    if ((rc = df_more(d, &have))) goto fail;
    if (!have) break;
    const char *at = d->p;
    df_take_word(d, w, sizeof w);
    if (!strcmp(w, "lagrange_multiplier")) {
      rc = df_header_value(d, &lagrange, what);
    } else if (!strcmp(w, "tolerance")) {
      double tol;
      rc = df_header_value(d, &tol, what);
    } else if (!strcmp(w, "volconst")) {
      rc = df_header_value(d, &volconst, what);
    } else if (!strcmp(w, "modulus")) {
      rc = df_header_value(d, nm ? &ms[nm - 1].modulus : &modulus, what);
    } else if (!strcmp(w, "method") || !strcmp(w, "global_method")) {
      meth *nms = tds_realloc(&d->ctx->alloc, ms, (size_t)(nm + 1) * sizeof *ms);
      if (!nms) {
        rc = df_err(d, at, TDS_ENOMEM, "out of memory");
        goto fail;
      }
      ms = nms;
      memset(&ms[nm], 0, sizeof ms[nm]);
      int gm = w[0] == 'g';
      if ((rc = df_more(d, &have))) goto fail;
      const char *ma = d->p;
      char mname[64];
      if (!have || !df_take_word(d, mname, sizeof mname)) {
        rc = df_err(d, ma, TDS_ESYNTAX, "%s: expected a method name, found %s", what,
                    df_describe(ma, b, sizeof b));
        goto fail;
      }
      int mi = tds_method_by_name(mname);
      if (mi < 0) {
        char u[64];
        rc = df_err(d, ma, TDS_ESYNTAX, "method %s is not supported yet",
                    df_upper(mname, u, sizeof u));
        goto fail;
      }
      meth *m = &ms[nm++];
      m->method = mi;
      m->global = gm;
      m->modulus = 1;
      m->line = df_line_of(d, ma);
      if (!gm && df_accept(d, "global")) m->global = 1;
    } else if (!strcmp(w, "global")) {
      if (!nm) {
        rc = df_err(d, at, TDS_ESYNTAX, "%s: GLOBAL before any METHOD", what);
        goto fail;
      }
      ms[nm - 1].global = 1;
    } else if (!strcmp(w, "scalar_integrand") || !strcmp(w, "vector_integrand")) {
      if (!nm) {
        rc = df_err(d, at, TDS_ESYNTAX, "%s: %s before any METHOD", what, w);
        goto fail;
      }
      meth *m = &ms[nm - 1];
      if (m->in[0] || m->in[1] || m->in[2]) {
        rc = df_err(d, at, TDS_ESYNTAX, "%s: method has two integrands", what);
        goto fail;
      }
      m->scalar = w[0] == 's';
      int on = tds_methods[m->method].kind == TDS_EL_FACET  ? TDS_MODEL_ON_FACET
               : tds_methods[m->method].kind == TDS_EL_EDGE ? TDS_MODEL_ON_EDGE
                                                             : 0;
      if (w[0] == 's')
        rc = df_header_expr(d, on, &m->in[0], what);
      else
        rc = df_components(d, 'q', on, m->in, what);
    } else if (df_unsupported(w)) {
      rc = df_not_supported(d, at, w);
    } else {
      d->p = at;
      break;
    }
    if (rc) goto fail;
  }
  if (!nm) {
    rc = df_err(d, d->p, TDS_ESYNTAX, "%s: no METHOD given", what);
    goto fail;
  }
  for (int i = 0; i < nm; i++)
    if (!ms[i].global) {
      char u[64];
      rc = df_err_line(d, ms[i].line, TDS_ESYNTAX,
                       "%s: method %s without GLOBAL (applied to listed elements) is "
                       "not supported yet", what,
                       df_upper(tds_methods[ms[i].method].name, u, sizeof u));
      goto fail;
    }
  int idx;
  rc = tds_model_quantity(d->ctx, d->s, name, qkind, modulus, target, &idx, NULL);
  if (rc) {
    rc = df_core(d, qline, rc, NULL);
    goto fail;
  }
  d->s->quant[idx].pressure = lagrange;
  d->s->quant[idx].volconst = volconst;
  for (int i = 0; i < nm; i++)
    if (ms[i].scalar && (ms[i].method == TDS_M_FACET_VECTOR_INTEGRAL ||
                         ms[i].method == TDS_M_EDGE_VECTOR_INTEGRAL)) {
      rc = df_err_line(d, ms[i].line, TDS_ESYNTAX,
                       "quantity %s: method %s needs a vector_integrand, not a "
                       "scalar_integrand", name, tds_methods[ms[i].method].name);
      goto fail;
    }
  for (int i = 0; i < nm; i++) {
    rc = tds_model_method(d->ctx, d->s, idx, ms[i].method, ms[i].modulus, ms[i].in);
    memset(ms[i].in, 0, sizeof ms[i].in); /* taken, also on failure */
    if (rc) {
      rc = df_core(d, ms[i].line, rc, NULL);
      goto fail;
    }
  }
  tds_free(&d->ctx->alloc, ms);
  return TDS_OK;
fail:
  for (int i = 0; i < nm; i++) df_free3(ms[i].in);
  tds_free(&d->ctx->alloc, ms);
  return rc;
}

/* ---- settings and display hints ---- */

/* One value, checked as k->check says ("KW must be positive") and stored
** at k->off (NOWHERE: read and ignored, as dump hints and warnings). */
static int h_value(df *d, const hdr_kw *k) {
  char u[64];
  double v;
  df_upper(k->name, u, sizeof u);
  int rc = df_header_value(d, &v, u);
  if (rc) return rc;
  if (k->check == POSITIVE && v <= 0)
    return df_err(d, NULL, TDS_ESYNTAX, "%s must be positive", u);
  if (k->check == POSITIVE && !isnormal(v)) /* a subnormal limit never ends a search */
    return df_err(d, NULL, TDS_ESYNTAX, "%s is too small (subnormal)", u);
  if (k->check == NONNEG && v < 0)
    return df_err(d, NULL, TDS_ESYNTAX, "%s must not be negative", u);
  if (k->off != NOWHERE) *(double *)((char *)d->s + k->off) = v;
  return TDS_OK;
}

/* SCALE value [FIXED] */
static int h_scale(df *d, const hdr_kw *k) {
  int rc = h_value(d, k);
  if (!rc && df_accept(d, "fixed")) d->s->fixed_scale = 1;
  return rc;
}

static int h_symmetric(df *d, const hdr_kw *k) {
  (void)k;
  d->s->symmetric_content = 1;
  return TDS_OK;
}

static int string_after_sym(df *d);

/* SPACE_DIMENSION 2 or 3; SURFACE_DIMENSION 1 (the string model, as
** STRING) or 2: anything else is refused. The string model is set up when
** the VERTICES section starts (the keywords may come in any order). */
static int h_dimension(df *d, const hdr_kw *k) {
  int64_t n;
  char u[64];
  df_upper(k->name, u, sizeof u);
  int rc = df_header_int(d, 0, u, &n);
  if (rc) return rc;
  int space = k->name[1] == 'p';
  if (space ? n != 2 && n != 3 : n != 1 && n != 2)
    return df_err(d, NULL, TDS_ESYNTAX, "%s %lld is not supported yet", u, (long long)n);
  if (d->app && (space ? n != 3 : n != 2))
    return df_err(d, NULL, TDS_ESYNTAX, "addload of a string-model datafile is not supported yet");
  if (!space && n == 1 && (rc = string_after_sym(d)) != TDS_OK) return rc;
  if (space) d->space_dim = (int)n;
  else d->string_model = n == 1;
  return TDS_OK;
}

static int h_metric(df *d, const hdr_kw *k) {
  (void)k;
  return df_metric(d, d->p);
}

/* KLEIN_METRIC: hyperbolic lengths in the Klein model (string model:
** checked when the vertices begin, df_klein_check). */
static int h_klein(df *d, const hdr_kw *k) {
  (void)k;
  if (d->klein_line) return df_err(d, NULL, TDS_ESYNTAX, "KLEIN_METRIC given twice");
  d->klein_line = df_line_of(d, NULL);
  d->s->klein = 1;
  return TDS_OK;
}

/* The string model after SYMMETRY_GROUP: refused as in the other order
** (df_klein_check), but for genus2, which the string model has. */
static int string_after_sym(df *d) {
  if (!d->s->m.sym || d->s->m.sym == TDS_SYM_GENUS2) return TDS_OK;
  return df_err(d, NULL, TDS_ESYNTAX,
                "SYMMETRY_GROUP (line %d) in the string model is not supported yet", d->torus_line);
}

static int h_string(df *d, const hdr_kw *k) {
  (void)k;
  if (d->app) return df_err(d, NULL, TDS_ESYNTAX, "addload of a string-model datafile is not supported yet");
  int rc = string_after_sym(d);
  if (rc) return rc;
  d->string_model = 1;
  return TDS_OK;
}

/* VIEW_MATRIX: 16 numbers (9 after SPACE_DIMENSION 2, as Evolver dumps
** a 2-D string model), display only. */
static int h_view_matrix(df *d, const hdr_kw *k) {
  (void)k;
  return skip_values(d, d->space_dim == 2 ? 9 : 16, "VIEW_MATRIX");
}

/* slice_coeff = { a, b, c, d } (written by Evolver's dump; three values
** after SPACE_DIMENSION 2), display only. */
static int h_slice(df *d, const hdr_kw *k) {
  (void)k;
  int have, rc = df_more(d, &have);
  if (rc) return rc;
  if (have && *d->p == '=') d->p++;
  if ((rc = df_more(d, &have))) return rc;
  int brace = have && *d->p == '{';
  if (brace) d->p++;
  if ((rc = skip_values(d, d->space_dim == 2 ? 3 : 4, "SLICE_COEFF"))) return rc;
  if (brace) {
    if ((rc = df_more(d, &have))) return rc;
    if (!have || *d->p != '}') {
      char b[64];
      return df_err(d, d->p, TDS_ESYNTAX, "SLICE_COEFF: expected '}', found %s",
                    df_describe(d->p, b, sizeof b));
    }
    d->p++;
  }
  return TDS_OK;
}

/* VIEW_TRANSFORMS n or VIEW_TRANSFORM_GENERATORS n, then n matrices (4x4,
** row-major) each optionally preceded by COLOR c or SWAP_COLORS (display
** only, skipped). The view transforms are kept after the identity, as
** Evolver lists them; generators are for transform_expr. */
static int read_matrices(df *d, int gen) {
  const char *what = gen ? "VIEW_TRANSFORM_GENERATORS" : "VIEW_TRANSFORMS";
  int64_t n;
  int rc = df_header_int(d, 0, what, &n);
  if (rc) return rc;
  if (n > TDS_MAX_VIEW - 1)
    return df_err(d, NULL, TDS_ESYNTAX, "%s: too many (%lld)", what, (long long)n);
  int line = df_line_of(d, NULL);
  int first = gen ? 0 : 1, total = (int)n + first;
  double (*m)[16] = tds_calloc(&d->ctx->alloc, (size_t)total + 1, sizeof *m);
  uint8_t *sw = tds_calloc(&d->ctx->alloc, (size_t)total + 1, 1);
  if (!m || !sw) {
    tds_free(&d->ctx->alloc, m);
    tds_free(&d->ctx->alloc, sw);
    return df_err(d, NULL, TDS_ENOMEM, "out of memory");
  }
  if (!gen)
    for (int k = 0; k < 4; k++) m[0][5 * k] = 1;
  for (int64_t t = 0; t < n && !rc; t++) {
    int have;
    for (;;) {
      if ((rc = df_more(d, &have))) break;
      if (have && df_accept(d, "swap_colors")) {
        sw[first + t] = 1;
        continue;
      }
      if (have && df_accept(d, "color")) {
        int16_t c;
        if ((rc = df_more(d, &have)) || (rc = df_read_color(d, &c, what))) break;
        continue;
      }
      break;
    }
    d->split = 1;
    for (int k = 0; k < 16 && !rc; k++) rc = df_header_value(d, &m[first + t][k], what);
    d->split = 0;
  }
  if (!rc) {
    rc = tds_surf_set_view(d->ctx, d->s, gen, n || gen ? total : 0, (const double (*)[16])m, sw);
    if (rc) rc = df_core(d, line, rc, what);
  }
  tds_free(&d->ctx->alloc, m);
  tds_free(&d->ctx->alloc, sw);
  return rc;
}

static int h_view_transforms(df *d, const hdr_kw *k) {
  (void)k;
  return read_matrices(d, 0);
}

static int h_view_generators(df *d, const hdr_kw *k) {
  (void)k;
  return read_matrices(d, 1);
}

/* TORUS, TORUS_FILLED, PERIODS (datafile_torus.c) */
static int h_torus(df *d, const hdr_kw *k) {
  if (d->app) return df_err(d, NULL, TDS_ESYNTAX, "addload of a torus datafile is not supported yet");
  return df_torus(d, k->name[5] == '_');
}
static int h_periods(df *d, const hdr_kw *k) {
  (void)k;
  if (d->app) return df_err(d, NULL, TDS_ESYNTAX, "addload of a torus datafile is not supported yet");
  return df_periods(d);
}
static int h_symmetry_group(df *d, const hdr_kw *k) {
  (void)k;
  return df_symmetry_group(d);
}
/* DISPLAY_PERIODS (3 rows of 3) and DISPLAY_ORIGIN (3): display only. */
static int h_display_periods(df *d, const hdr_kw *k) {
  (void)k;
  return skip_values(d, 9, "DISPLAY_PERIODS");
}
/* DISPLAY_ORIGIN x y z: the lower corner of the clip box (torus.h). */
static int h_display_origin(df *d, const hdr_kw *k) {
  (void)k;
  double o[3] = {0, 0, 0};
  int rc = TDS_OK;
  d->split = 1;
  for (int i = 0; i < 3 && !rc; i++) rc = df_header_value(d, &o[i], "DISPLAY_ORIGIN");
  d->split = 0;
  if (rc) return rc;
  memcpy(d->s->m.origin, o, sizeof o);
  d->s->m.has_origin = 1;
  return TDS_OK;
}
/* CLIPPED, CONNECTED, RAW_CELLS: how a torus surface is drawn, exported
** and detorused (torus.h, doc/torus.md). */
static int h_display_mode(df *d, const hdr_kw *k) {
  d->s->m.draw = k->name[0] == 'r' ? TDS_DRAW_RAW : k->name[1] == 'l' ? TDS_DRAW_CLIPPED
                                                                       : TDS_DRAW_CONNECTED;
  return TDS_OK;
}

/* AUTOPOP, AUTOCHOP length, AREA_NORMALIZATION: the toggles of g
** (autopop.h, iterate.c), on from the start as in Evolver. */
static int h_toggle(df *d, const hdr_kw *k) {
  tds_surf *s = d->s;
  if (!strcmp(k->name, "autopop")) {
    s->autopop = 1;
  } else if (!strcmp(k->name, "autochop")) {
    double v;
    int rc = df_header_value(d, &v, "AUTOCHOP");
    if (rc) return rc;
    if (!(v > 0)) return df_err(d, NULL, TDS_ESYNTAX, "AUTOCHOP length must be positive");
    s->autochop = 1;
    s->autochop_length = v;
  } else {
    s->area_normalization = 1;
  }
  return TDS_OK;
}

/* A keyword asking for what tds does anyway. */
static int h_nothing(df *d, const hdr_kw *k) {
  (void)d;
  (void)k;
  return TDS_OK;
}

/* DEFINE kind ATTRIBUTE ... (datafile_define.c) */
static int h_define(df *d, const hdr_kw *k) {
  (void)k;
  return df_define(d, d->p);
}

/* EVOLVER_VERSION "x" */
static int h_version(df *d, const hdr_kw *k) {
  (void)k;
  int have, rc = df_more(d, &have);
  if (rc) return rc;
  if (!have || *d->p != '"') {
    char b[64];
    return df_err(d, d->p, TDS_ESYNTAX,
                  "EVOLVER_VERSION: expected a quoted version, found %s",
                  df_describe(d->p, b, sizeof b));
  }
  const char *q = strchr(d->p + 1, '"');
  d->p = q ? q + 1 : d->p + strlen(d->p);
  return TDS_OK;
}

/* KEEP_ORIGINALS: element ids as the file gives them (datafile_int.h). */
static int h_keep(df *d, const hdr_kw *k) {
  (void)k;
  d->keep_ids = !d->app; /* addload renumbers, as Evolver */
  return TDS_OK;
}

static const hdr_kw header_kw[] = {
    {"parameter", h_parameter, 0, 0},
    {"define", h_define, 0, 0},
    {"constraint", h_constraint, 0, 0},
    {"boundary", h_boundary, 0, 0},
    {"hessian_special_normal_vector", h_special_normal, 0, 0},
    {"quantity", h_quantity, 0, 0},
    {"gravity_constant", h_value, AT(gravity), ANY},
    {"spring_constant", h_value, AT(gap_constant), ANY},
    {"gap_constant", h_value, AT(gap_constant), ANY},
    {"symmetric_content", h_symmetric, 0, 0},
    {"string", h_string, 0, 0},
    {"metric", h_metric, 0, 0},
    {"klein_metric", h_klein, 0, 0},
    {"torus", h_torus, 0, 0},
    {"torus_filled", h_torus, 0, 0},
    {"periods", h_periods, 0, 0},
    {"torus_periods", h_periods, 0, 0},
    {"symmetry_group", h_symmetry_group, 0, 0},
    {"display_periods", h_display_periods, 0, 0},
    {"display_origin", h_display_origin, 0, 0},
    {"clipped", h_display_mode, 0, 0},
    {"clipped_cells", h_display_mode, 0, 0},
    {"connected", h_display_mode, 0, 0},
    {"connected_cells", h_display_mode, 0, 0},
    {"raw_cells", h_display_mode, 0, 0},
    {"constraint_tolerance", h_value, AT(constraint_tol), POSITIVE},
    {"space_dimension", h_dimension, 0, 0},
    {"surface_dimension", h_dimension, 0, 0},
    {"scale", h_scale, AT(scale), NONNEG},
    {"autopop", h_toggle, 0, 0},
    {"autochop", h_toggle, 0, 0},
    {"area_normalization", h_toggle, 0, 0},
    {"scale_limit", h_value, AT(scale_limit), POSITIVE},
    {"view_matrix", h_view_matrix, 0, 0},
    {"slice_coeff", h_slice, 0, 0},
    {"view_transforms", h_view_transforms, 0, 0},
    {"view_transform_generators", h_view_generators, 0, 0},
    {"evolver_version", h_version, 0, 0},
    {"soapfilm", h_nothing, 0, 0},
    {"linear", h_nothing, 0, 0},
    {"keep_originals", h_keep, 0, 0},
    {"keep_macros", h_nothing, 0, 0},
    {"everything_quantities", h_nothing, 0, 0},
    {"merit_factor", h_nothing, 0, 0},
    {"vertices_predicted", h_value, NOWHERE, ANY},
    {"edges_predicted", h_value, NOWHERE, ANY},
    {"facets_predicted", h_value, NOWHERE, ANY},
    {"facetedges_predicted", h_value, NOWHERE, ANY},
    {"bodies_predicted", h_value, NOWHERE, ANY},
    {"quantities_predicted", h_value, NOWHERE, ANY},
    {"method_instances_predicted", h_value, NOWHERE, ANY},
    {"suppress_warning", h_value, NOWHERE, ANY},
    {"unsuppress_warning", h_value, NOWHERE, ANY},
    {"zoom_vertex", h_value, NOWHERE, ANY},
    {"zoom_radius", h_value, NOWHERE, ANY},
    /* Evolver's elapsed evolution time, written into every dump after g. */
    {"total_time", h_value, NOWHERE, ANY},
    {NULL, NULL, 0, 0}};

static const hdr_kw *find_kw(const char *w) {
  for (int i = 0; header_kw[i].name; i++)
    if (!strcmp(w, header_kw[i].name)) return &header_kw[i];
  return NULL;
}

int df_header_word(const char *w) { return find_kw(w) || df_unsupported(w); }

int df_header_keyword(df *d, const char *w, const char *at) {
  const hdr_kw *k = find_kw(w);
  if (k) return k->fn(d, k);
  if (df_unsupported(w)) return df_not_supported(d, at, w);
  char b[64];
  return df_err(d, at, TDS_ESYNTAX, "unknown keyword %s", df_describe(at, b, sizeof b));
}
