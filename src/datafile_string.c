/* datafile_string.c: the string model in datafiles (STRING, SURFACE_DIMENSION
** 1, SPACE_DIMENSION 2): faces are cells bounded by edge lists, bodies own
** cells (contracts in datafile_int.h). */
#include "datafile_int.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "attr.h"
#include "string_model.h"
#include "symgroup.h"

static int by_id(const void *a, const void *b) {
  const df_face *x = a, *y = b;
  return (x->id > y->id) - (x->id < y->id);
}

int df_klein_check(df *d) {
  int sym = d->s->m.sym;
  /* the Klein ball is mapped to itself by genus2 and the groups that fix
  ** the origin; lattice translations move it */
  if (d->klein_line && d->s->m.torus && sym != TDS_SYM_GENUS2 && sym != TDS_SYM_ROTATE &&
      sym != TDS_SYM_FLIP_ROTATE && sym != TDS_SYM_CUBOCTA && sym != TDS_SYM_XYZ &&
      sym != TDS_SYM_CENTRAL)
    return df_err_line(d, d->klein_line, TDS_ESYNTAX,
                       "KLEIN_METRIC with %s is not supported (its translations do not map "
                       "the unit ball, the Klein model, to itself)",
                       sym ? "this SYMMETRY_GROUP" : "the torus model");
  if (d->klein_line && d->s->metric_on)
    return df_err_line(d, d->klein_line, TDS_ESYNTAX, "KLEIN_METRIC and METRIC both given");
  if (sym && sym != TDS_SYM_GENUS2 && d->string_model)
    return df_err_line(d, d->torus_line, TDS_ESYNTAX,
                       "SYMMETRY_GROUP in the string model is not supported yet");
  return TDS_OK;
}

int df_string_faces(df *d) {
  if (d->s->m.sym == TDS_SYM_GENUS2 && d->nfaces)
    return df_err_line(d, d->faces[0].line, TDS_ESYNTAX,
                       "faces under SYMMETRY_GROUP \"genus2\" are not supported yet (edges "
                       "with tension are)");
  qsort(d->faces, (size_t)d->nfaces, sizeof *d->faces, by_id);
  for (int32_t i = 0; i < d->nfaces; i++) {
    df_face *r = &d->faces[i];
    if (r->at.con)
      return df_err_line(d, r->line, TDS_ESYNTAX,
                         "face %d: constraints on faces of the string model are not "
                         "supported yet", r->id + 1);
    /* valued attributes (registry rows, datafile_elements.c): a colour */
    int16_t color = r->at.color;
    for (int32_t j = r->pv0; j < r->pv1;) {
      tds_attr a;
      tds_attr_at(&d->s->m, TDS_FACET, (int)d->pv[j], &a);
      int n = (int)d->pv[j + 1];
      if (!strcmp(a.name, "color") && n == 1)
        color = (int16_t)d->pv[j + 2];
      else
        return df_err_line(d, r->line, TDS_ESYNTAX,
                           "face %d: %s on faces of the string model is not supported yet",
                           r->id + 1, a.name);
      j += 2 + n;
    }
    int rc = tds_strings_add(d->ctx, d->s, r->id, r->n, d->oe + r->off,
                             r->at.flags & (TDS_FIXED | TDS_NONCONTENT | TDS_NODISPLAY), color);
    if (rc) return df_core(d, r->line, rc, NULL);
  }
  d->nfaces = 0;
  d->npv = 0;
  return TDS_OK;
}

int df_string_body(df *d, tds_id id, int n, const int32_t *faces) {
  tds_surf *s = d->s;
  tds_strings *st = s->str;
  int line = df_line_of(d, NULL);
  for (int i = 0; i < n; i++) {
    tds_id f = (faces[i] < 0 ? -faces[i] : faces[i]) - 1;
    if (st->fb[f][faces[i] < 0] != TDS_NONE)
      return df_err_line(d, line, TDS_ETOPO, "body %d: face %d is already in body %d",
                         id + 1, f + 1, st->fb[f][faces[i] < 0] + 1);
  }
  uint64_t gen = s->m.topo_gen;
  int rc = tds_mesh_claim(&s->m, TDS_BODY, id);
  if (rc == TDS_ERANGE)
    return df_err_line(d, line, rc, "body %d is declared twice", id + 1);
  if (rc != TDS_OK) return df_err_line(d, line, rc, "out of memory");
  s->m.topo_gen = gen;
  for (int i = 0; i < n; i++) {
    tds_id f = (faces[i] < 0 ? -faces[i] : faces[i]) - 1;
    st->fb[f][faces[i] < 0] = id;
  }
  st->gen++;
  return TDS_OK;
}

static int has3(tds_expr *const e[3]) { return e[0] || e[1] || e[2]; }

int df_string_model(df *d) {
  tds_surf *s = d->s;
  for (int c = 0; c < TDS_MAX_CON; c++) {
    const tds_constraint *k = &s->con[c];
    if (!k->number) continue;
    if (has3(k->energy))
      return df_err(d, NULL, TDS_ESYNTAX,
                    "constraint %d: ENERGY integrands in the string model are not "
                    "supported yet", k->number);
    if (k->content[1] || k->content[2])
      return df_err(d, NULL, TDS_ESYNTAX,
                    "constraint %d: the string model's CONTENT has one component (c1)",
                    k->number);
    if (k->flags & TDS_CON_CONVEX)
      return df_err(d, NULL, TDS_ESYNTAX,
                    "constraint %d: CONVEX in the string model is not supported yet",
                    k->number);
    if (k->content[0] && tds_expr_uses_attrs(k->content[0]))
      return df_err(d, NULL, TDS_ESYNTAX,
                    "constraint %d: element attributes in the string model's CONTENT are "
                    "not supported yet", k->number);
  }
  for (int b = 0; b < s->nbdry; b++)
    if (has3(s->bdry[b].energy) || has3(s->bdry[b].content))
      return df_err(d, NULL, TDS_ESYNTAX,
                    "boundary %d: integrands in the string model are not supported yet",
                    s->bdry[b].number);
  for (int q = 0; q < s->nquant; q++)
    for (int j = 0; j < s->quant[q].ninst; j++)
      if (tds_methods[s->quant[q].inst[j].method].kind == TDS_EL_FACET &&
          tds_methods[s->quant[q].inst[j].method].iter == TDS_IT_ELEMENT)
        return df_err(d, NULL, TDS_ESYNTAX,
                      "quantity %s: method %s on facets in the string model is not "
                      "supported yet", s->quant[q].name,
                      tds_methods[s->quant[q].inst[j].method].name);
  return TDS_OK;
}

int df_string_finish(df *d) {
  if (d->s->klein) /* the Klein model is the open unit ball */
    for (tds_id v = 0; v < d->s->m.nv; v++) {
      const double *x = d->s->m.x[v];
      if (!(d->s->m.vflags[v] & TDS_DEAD) && !(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] < 1))
        return df_err_line(d, 0, TDS_ERANGE,
                           "vertex %d: (%g, %g) is not inside the unit disk, the Klein model "
                           "of KLEIN_METRIC", v + 1, x[0], x[1]);
    }
  int rc = tds_strings_check(d->ctx, d->s);
  return rc ? df_core(d, 0, rc, NULL) : TDS_OK;
}

/* METRIC g11 g12 ... (N x N expressions, N the space dimension, any line
** layout): the Riemannian metric of the string model. */
int df_metric(df *d, const char *at) {
  if (!d->string_model)
    return df_err(d, at, TDS_ESYNTAX,
                  "METRIC on a soapfilm surface is not supported yet (the string model "
                  "has it: give STRING and SPACE_DIMENSION before METRIC)");
  if (d->s->metric_on) return df_err(d, at, TDS_ESYNTAX, "METRIC given twice");
  int n = d->space_dim ? d->space_dim : 3;
  tds_expr *e[9] = {NULL};
  for (int k = 0; k < n * n; k++) {
    char what[48];
    snprintf(what, sizeof what, "METRIC component %d,%d", k / n + 1, k % n + 1);
    int rc = df_header_expr(d, 0, &e[3 * (k / n) + k % n], what);
    if (rc) {
      for (int j = 0; j < 9; j++) tds_expr_free(e[j]);
      return rc;
    }
  }
  memcpy(d->s->metric, e, sizeof e);
  d->s->metric_on = 1;
  return TDS_OK;
}
