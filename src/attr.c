/* attr.c: the registry's lookup, checks and user attributes (contracts in
** attr.h); the built-in rows are in attr_rows.c. */
#include "attr.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const tds_kind_name[TDS_NKINDS] = {"vertex", "edge", "facet", "body"};

int tds_kind_find(const char *name) {
  for (int k = 0; k < TDS_NKINDS; k++)
    if (!strcmp(name, tds_kind_name[k])) return k;
  if (!strcmp(name, "face")) return TDS_FACET;
  return -1;
}

const char *tds_attr_type_name(int type) {
  static const char *const names[] = {"boolean", "real", "integer", "colour",
                                      "vertex", "body", "constraint list",
                                      "boundary number"};
  return type >= 0 && type <= TDS_AT_BDRY ? names[type] : "?";
}

int tds_attr_count(const tds_mesh *m, int kind) {
  return tds_attr_nrows[kind] + m->nucol[kind];
}

static int user_get(tds_ctx *ctx, tds_surf *s, const tds_attr *a, tds_id id, double *v,
                    int *n) {
  (void)ctx;
  const tds_ucol *c = &s->m.ucol[a->kind][a->col];
  memcpy(v, c->v + (size_t)id * (size_t)c->size, sizeof *v * (size_t)c->size);
  *n = c->size;
  return TDS_OK;
}

static int user_set(tds_ctx *ctx, tds_surf *s, const tds_attr *a, tds_id id,
                    const double *v, int n) {
  (void)ctx;
  tds_ucol *c = &s->m.ucol[a->kind][a->col];
  double *dst = c->v + (size_t)id * (size_t)c->size;
  if (n == 0) memset(dst, 0, sizeof *dst * (size_t)c->size); /* unset: back to 0 */
  else memcpy(dst, v, sizeof *v * (size_t)c->size);
  return TDS_OK;
}

static int user_dumped(const tds_surf *s, tds_id id) {
  (void)s;
  (void)id;
  return 1; /* as Evolver, every element carries its value */
}

void tds_attr_at(const tds_mesh *m, int kind, int i, tds_attr *a) {
  if (i < tds_attr_nrows[kind]) {
    *a = tds_attr_rows[kind][i];
    return;
  }
  const tds_ucol *c = &m->ucol[kind][i - tds_attr_nrows[kind]];
  memset(a, 0, sizeof *a);
  a->name = c->name;
  a->kind = kind;
  a->type = c->type;
  a->size = c->size;
  a->io = TDS_AT_FE | TDS_AT_DECL | TDS_AT_USER;
  a->get = user_get;
  a->set = user_set;
  a->dumped = user_dumped;
  a->col = i - tds_attr_nrows[kind];
  a->ndim = c->ndim;
  a->dim = c->dim;
}

/* Whether w is one of the blank-separated words of list (NULL: none). */
static int in_list(const char *list, const char *w) {
  size_t n = strlen(w);
  while (list && *list) {
    const char *e = strchr(list, ' ');
    size_t k = e ? (size_t)(e - list) : strlen(list);
    if (k == n && !strncmp(list, w, n)) return 1;
    list = e ? e + 1 : NULL;
  }
  return 0;
}

int tds_attr_find(const tds_mesh *m, int kind, const char *name, tds_attr *a) {
  for (int i = 0; i < tds_attr_nrows[kind]; i++) { /* no copies while searching */
    const tds_attr *r = &tds_attr_rows[kind][i];
    if (!strcmp(r->name, name) || in_list(r->alias, name)) {
      *a = *r;
      return 1;
    }
  }
  for (int c = 0; c < m->nucol[kind]; c++)
    if (!strcmp(m->ucol[kind][c].name, name)) {
      tds_attr_at(m, kind, tds_attr_nrows[kind] + c, a);
      return 1;
    }
  return 0;
}

int tds_attr_find_fe(const tds_mesh *m, int kind, const char *word, tds_attr *a) {
  int n = tds_attr_count(m, kind);
  for (int i = 0; i < n; i++) {
    tds_attr_at(m, kind, i, a);
    if (!(a->io & TDS_AT_FE)) continue;
    if (!strcmp(tds_attr_word(a), word) || in_list(a->fe_alias, word)) return 1;
  }
  return 0;
}

int tds_attr_check(tds_ctx *ctx, const tds_attr *a, const char *what, const double *v,
                   int n) {
  if (a->type != TDS_AT_CONS && n != 0 && n != a->size)
    return tds_seterr(ctx, TDS_ERANGE, "%s: %s takes %d value%s, got %d", what, a->name,
                      a->size, a->size == 1 ? "" : "s", n);
  for (int i = 0; i < n; i++) {
    double x = v[i];
    if (!isfinite(x))
      return tds_seterr(ctx, TDS_ERANGE, "%s: %s must be finite, not %s", what, a->name,
                        isnan(x) ? "NaN" : x < 0 ? "-inf" : "inf");
    if (a->type != TDS_AT_REAL && x != floor(x))
      return tds_seterr(ctx, TDS_ERANGE, "%s: %s must be a whole number, not %.17g", what,
                        a->name, x);
    if (a->type == TDS_AT_COLOR && (x < -32768 || x > 32767))
      return tds_seterr(ctx, TDS_ERANGE, "%s: %s %.17g is out of range (-32768 to 32767)",
                        what, a->name, x);
    if (a->type == TDS_AT_INT && fabs(x) > 9007199254740992.0)
      return tds_seterr(ctx, TDS_ERANGE, "%s: %s %.17g is too large for an integer",
                        what, a->name, x);
  }
  return TDS_OK;
}

int tds_attr_read(tds_ctx *ctx, tds_surf *s, const tds_attr *a, tds_id id, double *v,
                  int *n) {
  *n = 0;
  return a->get(ctx, s, a, id, v, n);
}

int tds_attr_write(tds_ctx *ctx, tds_surf *s, const tds_attr *a, tds_id id,
                   const double *v, int n) {
  char what[64];
  snprintf(what, sizeof what, "%s %d", tds_kind_name[a->kind], (int)id + 1);
  if (!a->set)
    return tds_seterr(ctx, TDS_ERANGE, "%s: %s cannot be set", what, a->name);
  int rc = tds_attr_check(ctx, a, what, v, n);
  return rc ? rc : a->set(ctx, s, a, id, v, n);
}

int tds_attr_dumped(tds_surf *s, const tds_attr *a, tds_id id) {
  if (a->dumped) return a->dumped(s, id);
  double v[TDS_MAX_CON];
  int n = 0;
  tds_ctx quiet;
  tds_ctx_init(&quiet);
  if (a->get(&quiet, s, a, id, v, &n) != TDS_OK || n == 0) return 0;
  if (a->type == TDS_AT_CONS) return 1;
  for (int i = 0; i < n; i++)
    if (v[i] != a->dflt) return 1;
  return 0;
}

/* The position of the attribute `name` of `kind` in the registry, or -1. */
static int row_of(const tds_mesh *m, int kind, const char *name) {
  tds_attr a;
  if (!tds_attr_find(m, kind, name, &a)) return -1;
  for (int i = 0; i < tds_attr_count(m, kind); i++) {
    tds_attr b;
    tds_attr_at(m, kind, i, &b);
    if (!strcmp(a.name, b.name)) return i;
  }
  return -1;
}

int tds_attr_exclusive(tds_ctx *ctx, const tds_mesh *m, int kind, const char *what, int fe,
                       const char *const *names, int n) {
  for (int i = 0; i < n; i++) {
    tds_attr a;
    if (!tds_attr_find(m, kind, names[i], &a) || !a.excl) continue;
    for (int j = 0; j < n; j++) {
      int ri = row_of(m, kind, names[i]), rj = row_of(m, kind, names[j]);
      if (j == i || !in_list(a.excl, names[j]) || rj < 0) continue;
      tds_attr first, second; /* in registry order, so the message is stable */
      tds_attr_at(m, kind, ri < rj ? ri : rj, &first);
      tds_attr_at(m, kind, ri < rj ? rj : ri, &second);
      char w1[TDS_ATTR_NAMELEN], w2[TDS_ATTR_NAMELEN];
      snprintf(w1, sizeof w1, "%s", fe ? tds_attr_word(&first) : first.name);
      snprintf(w2, sizeof w2, "%s", fe ? tds_attr_word(&second) : second.name);
      for (char *c = w1; fe && *c; c++) *c = (char)toupper((unsigned char)*c);
      for (char *c = w2; fe && *c; c++) *c = (char)toupper((unsigned char)*c);
      return tds_seterr(ctx, TDS_ESYNTAX, "%s: give either %s or %s, not both", what, w1, w2);
    }
  }
  return TDS_OK;
}

/* ---- user attributes ---- */

static int valid_name(const char *name) {
  if (!name[0] || strlen(name) >= TDS_ATTR_NAMELEN) return 0;
  if (!((name[0] >= 'a' && name[0] <= 'z') || (name[0] >= 'A' && name[0] <= 'Z') ||
        name[0] == '_'))
    return 0;
  for (const char *p = name; *p; p++)
    if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
          *p == '_'))
      return 0;
  return 1;
}

/* Give user column col of kind the dimensions dim (same number as now),
** keeping each element's values at the indices both shapes have (Evolver:
** "data will be preserved as best as possible"); new places are 0. */
static int resize(tds_ctx *ctx, tds_mesh *m, int kind, int col, const int32_t *dim,
                  int64_t size) {
  tds_ucol *u = &m->ucol[kind][col];
  int32_t cap = kind == TDS_VERTEX ? m->capv
                : kind == TDS_EDGE ? m->cape
                : kind == TDS_FACET ? m->capf : m->capb;
  double *v = tds_calloc(&m->alloc, (size_t)(cap > 0 ? cap : 1) * (size_t)size, sizeof *v);
  if (!v) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  for (int64_t k = 0; k < size; k++) { /* new flat index k -> old one, if inside */
    int64_t rest = k, old = 0, stride = 1;
    int inside = 1;
    for (int i = u->ndim - 1; i >= 0; i--) {
      int64_t idx = rest % dim[i];
      rest /= dim[i];
      if (idx >= u->dim[i]) inside = 0;
      old += idx * stride;
      stride *= u->dim[i];
    }
    if (!inside) continue;
    for (int32_t e = 0; e < cap; e++) v[(size_t)e * (size_t)size + (size_t)k] = u->v[(size_t)e * (size_t)u->size + (size_t)old];
  }
  tds_free(&m->alloc, u->v);
  u->v = v;
  for (int i = 0; i < u->ndim; i++) u->dim[i] = dim[i];
  u->size = (int32_t)size;
  return TDS_OK;
}

int tds_attr_define(tds_ctx *ctx, tds_mesh *m, int kind, const char *name, int type,
                    int ndim, const int32_t *dim) {
  const char *kn = kind >= 0 && kind < TDS_NKINDS ? tds_kind_name[kind] : NULL;
  if (!kn) return tds_seterr(ctx, TDS_ERANGE, "attribute %s: bad element kind", name);
  if (!valid_name(name))
    return tds_seterr(ctx, TDS_ERANGE,
                      "%s attribute '%s': a name is a letter or _ followed by letters, "
                      "digits or _ (at most %d)", kn, name, TDS_ATTR_NAMELEN - 1);
  if (type != TDS_AT_REAL && type != TDS_AT_INT)
    return tds_seterr(ctx, TDS_ERANGE, "%s attribute %s: the type must be real or integer",
                      kn, name);
  if (ndim < 0 || ndim > TDS_ATTR_MAXDIM)
    return tds_seterr(ctx, TDS_ERANGE, "%s attribute %s: at most %d dimensions", kn, name,
                      TDS_ATTR_MAXDIM);
  int64_t size = 1;
  for (int i = 0; i < ndim; i++) {
    if (dim[i] < 1)
      return tds_seterr(ctx, TDS_ERANGE, "%s attribute %s: dimension %d must be at least 1, "
                        "not %d", kn, name, i + 1, (int)dim[i]);
    size *= dim[i];
    if (size > TDS_ATTR_MAXSIZE)
      return tds_seterr(ctx, TDS_ERANGE, "%s attribute %s: more than %d values per element",
                        kn, name, TDS_ATTR_MAXSIZE);
  }
  tds_attr a;
  if (tds_attr_find(m, kind, name, &a)) {
    if (!(a.io & TDS_AT_USER))
      return tds_seterr(ctx, TDS_ERANGE, "%s attribute %s: %s is a built-in attribute", kn,
                        name, name);
    int same = a.type == type && a.ndim == ndim;
    for (int i = 0; same && i < ndim; i++) same = a.dim[i] == dim[i];
    if (same) return TDS_OK;
    if (a.type == type && a.ndim == ndim) return resize(ctx, m, kind, a.col, dim, size);
    return tds_seterr(ctx, TDS_ERANGE, "%s attribute %s is already defined as %s%s", kn,
                      name, tds_attr_type_name(a.type),
                      a.ndim ? " with another number of dimensions" : "");
  }
  int32_t cap = kind == TDS_VERTEX ? m->capv
                : kind == TDS_EDGE ? m->cape
                : kind == TDS_FACET ? m->capf : m->capb;
  double *v = tds_calloc(&m->alloc, (size_t)(cap > 0 ? cap : 1) * (size_t)size, sizeof *v);
  tds_ucol *cols =
      tds_realloc(&m->alloc, m->ucol[kind], sizeof *cols * (size_t)(m->nucol[kind] + 1));
  if (cols) m->ucol[kind] = cols;
  if (!v || !cols) {
    tds_free(&m->alloc, v);
    return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  }
  tds_ucol *c = &cols[m->nucol[kind]++];
  memset(c, 0, sizeof *c);
  snprintf(c->name, sizeof c->name, "%s", name);
  c->type = type;
  c->ndim = ndim;
  for (int i = 0; i < ndim; i++) c->dim[i] = dim[i];
  c->size = (int32_t)size;
  c->v = v;
  return TDS_OK;
}
