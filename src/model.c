/* model.c: constraints, boundaries and named quantities of a surface. */
#include "model.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "xattr.h"

/* Parameters first, then the attributes of the scope's element kind
** (xattr.h). */
static int lookup(void *ud, const char *name, size_t len) {
  tds_model_scope *sc = ud;
  sc->why[0] = 0;
  int slot = tds_surf_param_find(sc->s, name, len);
  if (slot >= 0) return slot;
  int j = tds_xattr_slot(sc->s, sc->kind, name, len, sc->why, sizeof sc->why);
  if (j == -3) sc->nomem = 1;
  return j >= 0 ? TDS_EXPR_ATTR(j) : -1;
}

static const char *why(void *ud) {
  tds_model_scope *sc = ud;
  return sc->why[0] ? sc->why : NULL;
}

void tds_model_env(tds_model_scope *sc, tds_surf *s, int flags, tds_expr_env *env) {
  int on = flags & TDS_MODEL_ON_MASK;
  sc->s = s;
  sc->kind = on == TDS_MODEL_ON_VERTEX ? TDS_VERTEX
             : on == TDS_MODEL_ON_EDGE ? TDS_EDGE
             : on == TDS_MODEL_ON_FACET ? TDS_FACET : -1;
  sc->why[0] = 0;
  sc->nomem = 0;
  env->flags = flags & ~TDS_MODEL_ON_MASK;
  env->lookup = lookup;
  env->ud = sc;
  env->why = why;
}

int tds_model_parse(tds_ctx *ctx, tds_surf *s, const char *text, size_t *consumed,
                    int flags, tds_expr **out) {
  tds_model_scope sc;
  tds_expr_env env;
  tds_model_env(&sc, s, flags, &env);
  int rc = tds_expr_parse(ctx, text, consumed, &env, out);
  if (rc != TDS_OK && sc.nomem) rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  return rc;
}

int tds_model_compile(tds_ctx *ctx, tds_surf *s, const char *text, int flags,
                      tds_expr **out) {
  return tds_model_parse(ctx, s, text, NULL, flags, out);
}

static void free3(tds_expr *e[3]) {
  for (int i = 0; e && i < 3; i++) {
    tds_expr_free(e[i]);
    e[i] = NULL;
  }
}

/* Move three integrands into dst; a constant 0 becomes NULL, so the
** integrals skip it (dumps write NULL as 0). */
static void take3(tds_expr *dst[3], tds_expr *src[3]) {
  for (int i = 0; i < 3; i++) {
    dst[i] = src ? src[i] : NULL;
    if (dst[i] && tds_expr_is_const(dst[i]) &&
        tds_expr_eval(dst[i], NULL, (double[TDS_NVARS]){0}) == 0) {
      tds_expr_free(dst[i]);
      dst[i] = NULL;
    }
  }
}

/* Degree of a vector integrand (max over components), -1 if any is not a
** polynomial. */
static int degree3(tds_expr *const e[3]) {
  int d = 0;
  for (int i = 0; i < 3; i++) {
    if (!e[i]) continue;
    int k = tds_expr_degree(e[i]);
    if (k < 0) return -1;
    if (k > d) d = k;
  }
  return d;
}

/* Gauss points on an edge: the midpoint is exact for linear integrands;
** otherwise Evolver's 2-point rule (exact for cubics). */
static int edge_points(tds_expr *const e[3]) {
  int d = degree3(e);
  return d >= 0 && d <= 1 ? 1 : 2;
}

/* Points of the triangle rule: exact for the integrand's degree, or the
** degree-6 rule Evolver uses for anything else. */
static int facet_points(tds_expr *const e[3]) {
  int d = degree3(e);
  return d < 0 || d > 2 ? 12 : d == 2 ? 3 : 1;
}

/* Replace a constraint's or boundary's integrands (taking ownership) and
** choose their quadrature. */
static void set_integrands(tds_expr *e[3], tds_expr *c[3], int npts[2],
                          tds_expr *energy[3], tds_expr *content[3]) {
  free3(e);
  free3(c);
  take3(e, energy);
  take3(c, content);
  npts[0] = edge_points(e);
  npts[1] = edge_points(c);
}

int tds_model_constraint(tds_ctx *ctx, tds_surf *s, int number, int flags,
                         tds_expr *formula, tds_expr *energy[3],
                         tds_expr *content[3]) {
  int slot = tds_surf_con_slot(s, number);
  if (slot < 0)
    for (int i = 0; i < TDS_MAX_CON && slot < 0; i++)
      if (s->con[i].number == 0) slot = i;
  if (number < 1 || slot < 0 || !formula) {
    tds_expr_free(formula);
    free3(energy);
    free3(content);
    if (!formula) return tds_seterr(ctx, TDS_ESYNTAX, "constraint %d has no formula", number);
    return tds_seterr(ctx, TDS_ERANGE,
                      number < 1 ? "constraint number %d must be positive"
                                 : "constraint %d: at most 64 constraints are supported",
                      number);
  }
  if (s->str && content && content[0] && tds_expr_uses_attrs(content[0])) {
    tds_expr_free(formula);
    free3(energy);
    free3(content);
    return tds_seterr(ctx, TDS_ESYNTAX,
                      "constraint %d: element attributes in the string model's content are "
                      "not supported yet", number);
  }
  if ((flags & TDS_CON_CONVEX) && tds_expr_uses_attrs(formula)) {
    tds_expr_free(formula);
    free3(energy);
    free3(content);
    return tds_seterr(ctx, TDS_ESYNTAX,
                      "constraint %d: CONVEX with vertex attributes in the formula is not "
                      "supported yet", number);
  }
  tds_constraint *c = &s->con[slot];
  tds_expr_free(c->formula);
  c->number = number;
  c->flags = flags;
  c->formula = formula;
  set_integrands(c->energy, c->content, c->npts, energy, content);
  return TDS_OK;
}

int tds_model_boundary_slot(const tds_surf *s, int number) {
  for (int i = 0; i < s->nbdry; i++)
    if (s->bdry[i].number == number) return i;
  return -1;
}

int tds_model_boundary(tds_ctx *ctx, tds_surf *s, int number, int nparams,
                       int flags, tds_expr *x[3], tds_expr *energy[3],
                       tds_expr *content[3]) {
  int bad = number < 1 || nparams < 1 || nparams > 2, attrs = 0;
  for (int i = 0; i < 3; i++) bad |= !x[i];
  for (int i = 0; i < 3 && !bad; i++) attrs |= tds_expr_uses_attrs(x[i]);
  if (attrs) {
    free3(x);
    free3(energy);
    free3(content);
    return tds_seterr(ctx, TDS_ESYNTAX,
                      "boundary %d: vertex attributes in the parametrisation are not "
                      "supported yet", number);
  }
  int slot = tds_model_boundary_slot(s, number);
  tds_boundary *nb = NULL;
  if (!bad && slot < 0) nb = tds_realloc(&s->m.alloc, s->bdry, (size_t)(s->nbdry + 1) * sizeof *nb);
  if (bad || (slot < 0 && !nb)) {
    free3(x);
    free3(energy);
    free3(content);
    if (!bad) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    return tds_seterr(ctx, TDS_ERANGE,
                      "boundary %d: needs a positive number, 1 or 2 parameters "
                      "and x, y and z formulas", number);
  }
  if (slot < 0) {
    s->bdry = nb;
    slot = s->nbdry++;
    memset(&s->bdry[slot], 0, sizeof s->bdry[slot]);
  }
  tds_boundary *b = &s->bdry[slot];
  free3(b->x);
  b->number = number;
  b->nparams = nparams;
  b->flags = flags;
  for (int i = 0; i < 3; i++) b->x[i] = x[i]; /* positions stay, even 0 */
  set_integrands(b->energy, b->content, b->npts, energy, content);
  return TDS_OK;
}

int tds_model_quantity_find(const tds_surf *s, const char *name) {
  for (int i = 0; i < s->nquant; i++)
    if (!strcasecmp(s->quant[i].name, name)) return i;
  return -1;
}

int tds_model_quantity(tds_ctx *ctx, tds_surf *s, const char *name, int kind,
                       double modulus, double target, int *idx, tds_quantity *saved) {
  int i = tds_model_quantity_find(s, name);
  if (saved) memset(saved, 0, sizeof *saved);
  if (i < 0) {
    tds_quantity *nq = tds_realloc(&s->m.alloc, s->quant, (size_t)(s->nquant + 1) * sizeof *nq);
    if (!nq) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    s->quant = nq;
    i = s->nquant;
    memset(&s->quant[i], 0, sizeof s->quant[i]);
    s->quant[i].name = tds_strdup(&s->m.alloc, name);
    if (!s->quant[i].name) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    s->nquant++;
  } else {
    tds_quantity *q = &s->quant[i];
    if (saved) { /* the caller keeps the old methods until it commits */
      *saved = *q;
      saved->name = tds_strdup(&s->m.alloc, q->name);
      if (!saved->name) {
        memset(saved, 0, sizeof *saved);
        return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
      }
      q->inst = NULL; /* the old methods' array is saved's now */
    } else {
      for (int j = 0; j < q->ninst; j++) free3(q->inst[j].integrand);
    }
    q->ninst = 0;
  }
  tds_quantity *q = &s->quant[i];
  q->kind = kind;
  q->modulus = modulus;
  q->target = target;
  q->value = q->pressure = 0;
  *idx = i;
  return TDS_OK;
}

void tds_model_quantity_forget(tds_surf *s, tds_quantity *saved) {
  for (int j = 0; j < saved->ninst; j++) free3(saved->inst[j].integrand);
  tds_free(&s->m.alloc, saved->inst);
  tds_free(&s->m.alloc, saved->name);
  memset(saved, 0, sizeof *saved);
}

void tds_model_quantity_undo(tds_surf *s, int idx, tds_quantity *saved) {
  tds_quantity *q = &s->quant[idx];
  for (int j = 0; j < q->ninst; j++) free3(q->inst[j].integrand);
  tds_free(&s->m.alloc, q->inst);
  q->inst = NULL;
  q->ninst = 0;
  if (saved->name) { /* redeclared: the old definition comes back */
    tds_free(&s->m.alloc, saved->name);
    saved->name = q->name;
    *q = *saved;
  } else { /* new: it was appended last */
    tds_free(&s->m.alloc, q->name);
    s->nquant--;
  }
  memset(saved, 0, sizeof *saved);
}

int tds_model_method(tds_ctx *ctx, tds_surf *s, int idx, int method,
                     double modulus, tds_expr *integrand[3]) {
  tds_quantity *q = &s->quant[idx];
  int user = method >= 0 && method < TDS_M_NROWS && (tds_methods[method].flags & TDS_MF_USER);
  int flags = user ? tds_methods[method].flags : 0;
  int need = (flags & TDS_MF_VECTOR) ? 3 : (flags & TDS_MF_SCALAR) ? 1 : 0;
  int have = 0;
  for (int i = 0; integrand && i < 3; i++) have += integrand[i] != NULL;
  /* A scalar integrand sits alone in slot 0; anything in slots 1-2 means a
  ** vector integrand was given to a scalar method (evaluating it would use
  ** a missing slot 0). A vector method needs at least one component. */
  int scalar_given = have == 1 && integrand[0];
  const char *why = NULL;
  if (!user) why = "is not a method";
  else if (need == 1 && !have) why = "needs a scalar_integrand";
  else if (need == 1 && !scalar_given) why = "needs a scalar_integrand, not a vector_integrand";
  else if (need == 3 && !have) why = "needs a vector_integrand";
  else if (need == 0 && have) why = "takes no integrand";
  tds_method_inst *ni = why ? NULL : tds_realloc(&s->m.alloc, q->inst, (size_t)(q->ninst + 1) * sizeof *ni);
  if (!ni) {
    free3(integrand);
    if (!why) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    return tds_seterr(ctx, TDS_ESYNTAX, "quantity %s: method %s %s", q->name,
                      user ? tds_methods[method].name : "?", why);
  }
  q->inst = ni;
  tds_method_inst *mi = &q->inst[q->ninst++];
  mi->method = method;
  mi->modulus = modulus;
  if (need == 1) { /* a scalar integrand is kept even when constant 0 */
    mi->integrand[0] = integrand[0];
    mi->integrand[1] = mi->integrand[2] = NULL;
    integrand[0] = NULL;
  } else {
    take3(mi->integrand, integrand);
  }
  mi->npts = tds_methods[method].kind == TDS_EL_EDGE ? edge_points(mi->integrand)
                                                    : facet_points(mi->integrand);
  return TDS_OK;
}
