/* xattr.c: element attributes in expressions (contracts in xattr.h). */
#include "xattr.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "attr.h"

/* Whether a built-in row can stand in an expression: a scalar that is a
** constant of the element (not its length, area or valence). */
static int row_ok(const tds_attr *a) {
  if (a->size != 1) return 0;
  if (!strcmp(a->name, "original")) return 1;
  if (a->type == TDS_AT_FLAG || a->type == TDS_AT_COLOR) return 1;
  return (a->type == TDS_AT_REAL || a->type == TDS_AT_INT) && (a->io & TDS_AT_FE);
}

static int name_is(const char *w, const char *name, size_t len) {
  return w && strlen(w) == len && !strncasecmp(w, name, len);
}

/* Attribute name[0..len) of kind k into *col / *row: 1 usable, 2 found
** but not usable (an array, or a row that is not a constant), 0 none. */
static int find(const tds_surf *s, int k, const char *name, size_t len, int *col,
                const tds_attr **row) {
  *col = -1;
  *row = NULL;
  for (int i = 0; i < tds_attr_nrows[k]; i++) {
    const tds_attr *a = &tds_attr_rows[k][i];
    if (!name_is(a->name, name, len) && !name_is(a->alias, name, len)) continue;
    *row = a;
    return row_ok(a) ? 1 : 2;
  }
  for (int c = 0; c < s->m.nucol[k]; c++)
    if (name_is(s->m.ucol[k][c].name, name, len)) {
      *col = c;
      return s->m.ucol[k][c].size == 1 ? 1 : 2;
    }
  return 0;
}

int tds_xattr_slot(tds_surf *s, int kind, const char *name, size_t len, char *why,
                   size_t cap) {
  int col;
  const tds_attr *row;
  int r = kind >= 0 && kind < TDS_BODY ? find(s, kind, name, len, &col, &row) : 0;
  if (r == 1) {
    for (int j = 0; j < s->nxa; j++)
      if (s->xa[j].kind == kind && s->xa[j].col == col && s->xa[j].row == row) return j;
    if (s->nxa == s->xcap) {
      int n = s->xcap ? 2 * s->xcap : 8;
      tds_xattr *xa = tds_reallocarray(&s->m.alloc, s->xa, (size_t)n, sizeof *xa);
      if (!xa) goto nomem;
      s->xa = xa;
      if (tds_surf_param_room(s, n, s->cappar) != TDS_OK) goto nomem;
    }
    s->xa[s->nxa] = (tds_xattr){kind, col, row};
    s->nxa_kind[kind]++;
    return s->nxa++;
  }
  if (r == 2) {
    snprintf(why, cap, "%s attribute %.*s is %s here", tds_kind_name[kind], (int)len, name,
             col >= 0 ? "an array, not usable" : "not a constant of the element, not usable");
    return -2;
  }
  for (int k = 0; k < TDS_BODY; k++)
    if (k != kind && find(s, k, name, len, &col, &row) && (col >= 0 || row_ok(row))) {
      static const char *const plural[] = {"vertices", "edges", "facets"};
      if (kind < 0)
        snprintf(why, cap, "%.*s is %s %s attribute, not usable here", (int)len, name,
                 k == TDS_EDGE ? "an" : "a", tds_kind_name[k]);
      else
        snprintf(why, cap, "%.*s is %s %s attribute, but this expression is evaluated on %s",
                 (int)len, name, k == TDS_EDGE ? "an" : "a", tds_kind_name[k], plural[kind]);
      return -2;
    }
  return -1;
nomem:
  snprintf(why, cap, "out of memory");
  return -3;
}

void tds_xattr_fill_slow(const tds_surf *s, int kind, tds_id el) {
  /* the getters take a mutable surface; the rows used here only read */
  tds_surf *ms = (tds_surf *)(uintptr_t)s;
  for (int j = 0; j < s->nxa; j++) {
    const tds_xattr *x = &s->xa[j];
    if (x->kind != kind) continue;
    double v = 0;
    if (x->row) {
      double buf[1];
      int n = 0;
      if (x->row->get(NULL, ms, x->row, el, buf, &n) == TDS_OK && n == 1) v = buf[0];
    } else if (x->col < s->m.nucol[kind]) { /* a restored mesh may have fewer */
      const tds_ucol *c = &s->m.ucol[kind][x->col];
      v = c->v[(size_t)el * (size_t)c->size];
    }
    s->parval[-1 - j] = v;
  }
}

void tds_xattr_free(tds_surf *s) {
  tds_free(&s->m.alloc, s->xa);
  s->xa = NULL;
  s->nxa = 0;
  memset(s->nxa_kind, 0, sizeof s->nxa_kind);
}
