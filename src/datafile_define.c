/* datafile_define.c: DEFINE kind ATTRIBUTE name type [dim]... in the top
** section of a datafile (contract in datafile_int.h): a user attribute,
** a column of the registry (attr.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "attr.h"
#include "datafile_int.h"

/* The next word (across line ends) into w, lowercase; 0 if none. */
static int word(df *d, char *w, size_t cap) {
  int have;
  if (df_more(d, &have) || !have) return 0;
  return df_take_word(d, w, cap) > 0;
}

int df_define(df *d, const char *at) {
  char kw[64], name[64], ty[64], b[64];
  if (!word(d, kw, sizeof kw))
    return df_err(d, d->p, TDS_ESYNTAX, "DEFINE: expected an element kind, found %s",
                  df_describe(d->p, b, sizeof b));
  int kind = tds_kind_find(kw);
  if (kind < 0 || !df_accept(d, "attribute")) {
    df_ws(d);
    if (kind >= 0 || !strcmp(kw, "facetedge"))
      return df_err(d, d->p, TDS_ESYNTAX, "DEFINE %s: expected ATTRIBUTE, found %s", kw,
                    df_describe(d->p, b, sizeof b));
    /* variables and arrays of the top section */
    return df_err(d, at, TDS_ESYNTAX, "DEFINE of anything but an element attribute is not "
                  "supported yet");
  }
  if (!word(d, name, sizeof name))
    return df_err(d, d->p, TDS_ESYNTAX, "DEFINE %s ATTRIBUTE: expected a name, found %s", kw,
                  df_describe(d->p, b, sizeof b));
  char what[160];
  snprintf(what, sizeof what, "%s attribute %s", kw, name);
  if (!word(d, ty, sizeof ty) ||
      (strcmp(ty, "real") && strcmp(ty, "integer") && strcmp(ty, "ulong")))
    return df_err(d, d->p, TDS_ESYNTAX, "%s: expected a type REAL or INTEGER, found %s", what,
                  df_describe(d->p, b, sizeof b));
  int ndim = 0;
  int32_t dim[TDS_ATTR_MAXDIM];
  df_ws(d);
  while (*d->p == '[') {
    const char *open = d->p++;
    double v;
    int rc = df_read_value(d, &v, what);
    if (rc) return rc;
    df_ws(d);
    if (*d->p != ']')
      return df_err(d, d->p, TDS_ESYNTAX, "%s: expected ']', found %s", what,
                    df_describe(d->p, b, sizeof b));
    d->p++;
    if (ndim == TDS_ATTR_MAXDIM || v < 1 || v > TDS_ATTR_MAXSIZE || v != floor(v))
      return df_err(d, open, TDS_ERANGE, "%s: dimension %g must be a whole number from 1 to %d"
                    " (at most %d dimensions)", what, v, TDS_ATTR_MAXSIZE, TDS_ATTR_MAXDIM);
    dim[ndim++] = (int32_t)v;
    df_ws(d);
  }
  if (df_peek(d, "function"))
    return df_err(d, d->p, TDS_ESYNTAX, "%s: FUNCTION attributes are not supported yet", what);
  int type = strcmp(ty, "real") ? TDS_AT_INT : TDS_AT_REAL;
  int rc = tds_attr_define(d->ctx, &d->s->m, kind, name, type, ndim, dim);
  return rc ? df_core(d, df_line_of(d, at), rc, NULL) : TDS_OK;
}
