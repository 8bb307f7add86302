/*
** datafile_torus.c: the torus model's datafile words (torus.h): TORUS,
** TORUS_FILLED, PERIODS (three rows of three expressions, each row on its
** own line; parameters allowed, re-evaluated by recalc), the display modes
** CLIPPED, CONNECTED and RAW_CELLS, DISPLAY_PERIODS and DISPLAY_ORIGIN
** (display only), and the wrap signs of an edge line (* + -, one per
** period). Contracts in datafile_int.h.
*/
#include "datafile_int.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "expr.h"
#include "gather.h"
#include "symgroup.h"
#include "symmetry.h"
#include "torus.h"

static void unit_periods(tds_mesh *m) {
  memset(m->period, 0, sizeof m->period);
  for (int i = 0; i < 3; i++) m->period[i][i] = 1;
}

int df_torus(df *d, int filled) {
  if (d->app)
    return df_err(d, NULL, TDS_ESYNTAX, "%s in a file added by addload is not supported yet",
                  filled ? "TORUS_FILLED" : "TORUS");
  if (d->s->m.torus)
    return df_err(d, NULL, TDS_ESYNTAX, "%s: %s is already declared (line %d)",
                  filled ? "TORUS_FILLED" : "TORUS",
                  d->s->m.sym ? "SYMMETRY_GROUP" : "the torus model", d->torus_line);
  if (tds_mesh_set_torus(&d->s->m, filled ? 2 : 1)) return df_core(d, df_line_of(d, NULL), TDS_ENOMEM, NULL);
  if (!d->periods_line) unit_periods(&d->s->m); /* Evolver's default */
  d->torus_line = df_line_of(d, NULL);
  return TDS_OK;
}

int df_symmetry_group(df *d) {
  char name[64];
  int have, rc = df_more(d, &have);
  if (rc) return rc;
  const char *at = d->p;
  const char *q = have && *at == '"' ? strchr(at + 1, '"') : NULL;
  if (!q || q - at - 1 >= (long)sizeof name) {
    char b[64];
    return df_err(d, at, TDS_ESYNTAX,
                  "SYMMETRY_GROUP: expected a group name in double quotes, found %s",
                  df_describe(at, b, sizeof b));
  }
  memcpy(name, at + 1, (size_t)(q - at - 1));
  name[q - at - 1] = 0;
  if (d->app)
    return df_err(d, at, TDS_ESYNTAX, "SYMMETRY_GROUP in a file added by addload is not supported yet");
  if (d->s->m.torus)
    return df_err(d, at, TDS_ESYNTAX, "SYMMETRY_GROUP: %s is already declared (line %d)",
                  d->s->m.sym ? "SYMMETRY_GROUP" : "the torus model", d->torus_line);
  int id = tds_sym_lookup(name);
  if (id == 0)
    return df_err(d, at, TDS_ESYNTAX,
                  "SYMMETRY_GROUP: unknown group \"%s\" (Evolver's built-in groups: torus, "
                  "rotate, flip_rotate, cubocta, cubelat, xyz, genus2, dodecahedron, "
                  "central_symmetry, screw_symmetry, quarter_turn)", name);
  if (id < 0)
    return df_err(d, at, TDS_ESYNTAX,
                  "SYMMETRY_GROUP \"%s\" is not supported yet (Evolver's manual does not "
                  "define its elements and its codes could not be pinned down: doc/torus.md)",
                  name);
  if (d->string_model && id != TDS_SYM_GENUS2) /* genus2: datafile_string.c */
    return df_err(d, at, TDS_ESYNTAX, "SYMMETRY_GROUP in the string model is not supported yet");
  if (tds_mesh_set_torus(&d->s->m, 1)) return df_core(d, df_line_of(d, at), TDS_ENOMEM, NULL);
  d->s->m.sym = id;
  for (int k = 0; k < 2; k++) d->s->m.symp[k] = tds_sym_param_default(id, k);
  if (!d->periods_line) unit_periods(&d->s->m); /* Evolver's default */
  d->torus_line = df_line_of(d, at);
  d->p = q + 1;
  return TDS_OK;
}

int df_periods(df *d) {
  tds_surf *s = d->s;
  if (d->periods_line)
    return df_err(d, NULL, TDS_ESYNTAX, "PERIODS given twice (first at line %d)",
                  d->periods_line);
  d->periods_line = df_line_of(d, NULL);
  /* in SPACE_DIMENSION 2 (the string model's plane) two rows of two; the
  ** third period is then the unit z vector, so the cell "volume" is the
  ** parallelogram's area and z never wraps */
  int dim = d->space_dim == 2 ? 2 : 3;
  d->periods_dim = dim;
  double p[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}};
  tds_expr *e[3][3] = {{NULL}};
  int rc = TDS_OK;
  d->split = 1;
  for (int i = 0; i < dim && !rc; i++) {
    int line = 0;
    for (int j = 0; j < dim && !rc; j++) {
      char what[64];
      snprintf(what, sizeof what, "PERIODS row %d", i + 1);
      rc = df_header_expr(d, TDS_EXPR_NOCOORD, &e[i][j], what);
      if (rc) break;
      int l = df_line_of(d, d->p);
      if (j == 0) line = l;
      else if (l != line) {
        rc = df_err_line(d, line, TDS_ESYNTAX,
                    "PERIODS row %d has %d values; a period vector needs %d on one line",
                    i + 1, j, dim);
        break;
      }
      double vars[TDS_NVARS] = {0};
      vars[TDS_G] = s->gravity;
      p[i][j] = tds_expr_eval(e[i][j], s->parval, vars);
      if (!isfinite(p[i][j]))
        rc = df_err(d, NULL, TDS_ESYNTAX, "%s: value of '%s' is not finite", what,
                    tds_expr_text(e[i][j]));
    }
    if (!rc && !df_at_eol(d) && df_looks_value(d))
      rc = df_err(d, d->p, TDS_ESYNTAX,
                  "PERIODS row %d has more than %d values (%s)", i + 1, dim,
                  dim == 3 ? "the torus model is 3-dimensional" : "SPACE_DIMENSION 2");
  }
  d->split = 0;
  if (!rc) {
    tds_mesh tmp;
    memcpy(tmp.period, p, sizeof p);
    if (!(tds_torus_cell_volume(&tmp) > 0))
      rc = df_err(d, NULL, TDS_ESYNTAX, "PERIODS: the period vectors span no volume");
  }
  if (rc) {
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) tds_expr_free(e[i][j]);
    return rc;
  }
  memcpy(s->m.period, p, sizeof p);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      if (e[i][j] && tds_expr_uses_params(e[i][j])) {
        s->period_expr[i][j] = e[i][j];
      } else {
        tds_expr_free(e[i][j]);
      }
    }
  return TDS_OK;
}

int df_torus_start(df *d, const char *at) {
  if (d->periods_line && !d->s->m.torus)
    return df_err_line(d, d->periods_line, TDS_ESYNTAX,
                       "PERIODS without TORUS or TORUS_FILLED");
  if (d->periods_line && tds_mesh_rotates(&d->s->m))
    return df_err_line(d, d->periods_line, TDS_ESYNTAX,
                       "PERIODS with SYMMETRY_GROUP \"%s\" (only the torus group has periods)",
                       tds_sym_name(d->s->m.sym));
  /* the group's parameters (rotation_order, ...) as the top section left them */
  if (d->s->m.sym && tds_sym_read_params(d->ctx, d->s) != TDS_OK)
    return df_core(d, d->torus_line, TDS_ERANGE, NULL);
  int dim = d->space_dim == 2 ? 2 : 3;
  if (d->periods_line && d->periods_dim != dim)
    return df_err_line(d, d->periods_line, TDS_ESYNTAX,
                       "PERIODS has %d vectors of %d but the space has dimension %d "
                       "(give SPACE_DIMENSION before PERIODS)", d->periods_dim,
                       d->periods_dim, dim);
  if (d->s->m.torus && dim == 2) { /* the unit square, not the unit cube */
    d->s->m.period[2][0] = d->s->m.period[2][1] = 0;
    d->s->m.period[2][2] = 1;
  }
  (void)at;
  return TDS_OK;
}

int df_edge_wrap(df *d, const char *what, int32_t *wrap) {
  *wrap = 0;
  df_ws(d);
  if (*d->p != '*' && !((*d->p == '+' || *d->p == '-') &&
                        (d->p[1] == ' ' || d->p[1] == '\t' || d->p[1] == 0)))
    return TDS_OK;
  if (!d->s->m.torus)
    return df_err(d, d->p, TDS_ESYNTAX,
                  "%s: wrap signs (* + -) need TORUS or TORUS_FILLED in the top section",
                  what);
  if (tds_mesh_rotates(&d->s->m))
    return df_err(d, d->p, TDS_ESYNTAX,
                  "%s: wrap signs (* + -) are the torus's; SYMMETRY_GROUP \"%s\" takes "
                  "wrap N (the group element's code)", what, tds_sym_name(d->s->m.sym));
  int k[3] = {0, 0, 0}, dim = d->space_dim == 2 ? 2 : 3;
  for (int i = 0; i < dim; i++) {
    df_ws(d);
    char c = *d->p;
    int end = d->p[0] && (d->p[1] == ' ' || d->p[1] == '\t' || d->p[1] == 0);
    if ((c != '*' && c != '+' && c != '-') || !end) {
      char b[64];
      return df_err(d, d->p, TDS_ESYNTAX,
                    "%s: expected %d wrap signs (* + -), one per period; found %s as sign %d",
                    what, dim, df_describe(d->p, b, sizeof b), i + 1);
    }
    k[i] = c == '+' ? 1 : c == '-' ? -1 : 0;
    d->p++;
  }
  df_ws(d);
  if (*d->p == '*' || ((*d->p == '+' || *d->p == '-') &&
                       (d->p[1] == ' ' || d->p[1] == '\t' || d->p[1] == 0)))
    return df_err(d, d->p, TDS_ESYNTAX,
                  "%s: more than %d wrap signs (the torus has %d periods)", what, dim, dim);
  *wrap = tds_wrap_pack(k);
  return TDS_OK;
}

int df_torus_finish(df *d) {
  tds_surf *s = d->s;
  if (tds_torus_check(d->ctx, &s->m) != TDS_OK) {
    char msg[sizeof d->ctx->errmsg];
    memcpy(msg, d->ctx->errmsg, sizeof msg);
    msg[sizeof msg - 1] = 0;
    return tds_seterr(d->ctx, TDS_ETOPO, "%s: %.900s", d->name, msg);
  }
  s->m.topo_gen++;
  if (s->m.sym) return TDS_OK; /* Euclidean volumes: no lifts, no settling */
  int bad = tds_torus_lifts(d->ctx, s);
  if (bad < 0) return -bad;
  if (bad > 0)
    tds_warnf(d->ctx,
              "%s: %d bodies wrap round the torus (their facets do not close up in "
              "space): their volumes are not exact\n", d->name, bad);
  if (s->m.nb > 0) {
    int rc = tds_surf_update(d->ctx, s);
    if (rc) { /* the whole file's (huge coordinates: an infinite energy) */
      char msg[sizeof d->ctx->errmsg];
      memcpy(msg, d->ctx->errmsg, sizeof msg);
      msg[sizeof msg - 1] = 0;
      return tds_seterr(d->ctx, rc, "%s: %.900s", d->name, msg);
    }
    tds_torus_settle(s);
  }
  return TDS_OK;
}
