/*
** datafile_append.c: the reader's append mode, Evolver's `addload`: a
** datafile's declarations and elements are added to a surface that is
** already there, all or nothing (contract in datafile.h).
**
** Before reading, df_app_begin copies what the file may change: the mesh
** (a snapshot, snap.h), the parameter values, the constraint table, the
** boundaries and quantities (their structs; the expressions they point to
** stay owned by the copy once the file redeclares them, see
** df_app_detach) and the scalar settings of the top section. The new
** elements are numbered after the existing slots. df_app_end then either
** frees the replaced declarations (success) or frees what the file added
** and puts everything back (failure), so a bad file leaves the surface
** bit for bit as it was.
*/
#include "datafile_int.h"

#include <string.h>

#include "model.h"
#include "snap.h"

struct df_app {
  tds_snap snap;
  int npar0;
  double *parval0;
  tds_constraint con0[TDS_MAX_CON];
  uint64_t con_rep;        /* slots redeclared by the file */
  int nbdry0, nquant0;
  tds_boundary *bdry0;
  tds_quantity *quant0;
  uint8_t *bdry_rep, *quant_rep;
  double (*view)[16], (*vgen)[16]; /* copies of the view transforms */
  uint8_t *view_swap, *vgen_swap;
  int nview, nvgen;
  double gravity, gap, tol, scale, scale_limit;
  int gravity_on, symmetric, fixed_scale;
  uint64_t param_gen;
};

static void *dup_n(const tds_alloc *a, const void *p, size_t n) {
  void *q = tds_malloc(a, n ? n : 1);
  if (q && n) memcpy(q, p, n);
  return q;
}

static void free_app(const tds_alloc *al, struct df_app *a) {
  tds_snap_free(&a->snap);
  tds_free(al, a->parval0);
  tds_free(al, a->bdry0);
  tds_free(al, a->quant0);
  tds_free(al, a->bdry_rep);
  tds_free(al, a->quant_rep);
  tds_free(al, a->view);
  tds_free(al, a->vgen);
  tds_free(al, a->view_swap);
  tds_free(al, a->vgen_swap);
  tds_free(al, a);
}

int df_app_begin(df *d) {
  tds_surf *s = d->s;
  const tds_alloc *al = &s->m.alloc;
  struct df_app *a = tds_calloc(al, 1, sizeof *a);
  if (!a) return tds_seterr(d->ctx, TDS_ENOMEM, "out of memory");
  int rc = tds_snap_take(d->ctx, s, &a->snap);
  if (rc) {
    tds_free(al, a);
    return rc;
  }
  a->npar0 = s->npar;
  a->parval0 = dup_n(al, s->parval, (size_t)s->npar * sizeof *s->parval);
  memcpy(a->con0, s->con, sizeof s->con);
  a->nbdry0 = s->nbdry;
  a->bdry0 = dup_n(al, s->bdry, (size_t)s->nbdry * sizeof *s->bdry);
  a->bdry_rep = tds_calloc(al, (size_t)s->nbdry + 1, 1);
  a->nquant0 = s->nquant;
  a->quant0 = dup_n(al, s->quant, (size_t)s->nquant * sizeof *s->quant);
  a->quant_rep = tds_calloc(al, (size_t)s->nquant + 1, 1);
  a->nview = s->view_transforms;
  a->view = dup_n(al, s->view, (size_t)(s->view ? s->view_transforms : 0) * sizeof *s->view);
  a->view_swap = dup_n(al, s->view_swap, (size_t)(s->view_swap ? s->view_transforms : 0));
  a->nvgen = s->nvgen;
  a->vgen = dup_n(al, s->vgen, (size_t)(s->vgen ? s->nvgen : 0) * sizeof *s->vgen);
  a->vgen_swap = dup_n(al, s->vgen_swap, (size_t)(s->vgen_swap ? s->nvgen : 0));
  if (!a->parval0 || !a->bdry0 || !a->bdry_rep || !a->quant0 || !a->quant_rep || !a->view ||
      !a->vgen || !a->view_swap || !a->vgen_swap) {
    free_app(al, a);
    return tds_seterr(d->ctx, TDS_ENOMEM, "out of memory");
  }
  a->gravity = s->gravity;
  a->gravity_on = s->gravity_on;
  a->gap = s->gap_constant;
  a->tol = s->constraint_tol;
  a->scale = s->scale;
  a->scale_limit = s->scale_limit;
  a->fixed_scale = s->fixed_scale;
  a->symmetric = s->symmetric_content;
  a->param_gen = s->param_gen;
  d->app = a;
  /* new elements after every existing slot (Evolver renumbers them) */
  d->nread[TDS_VERTEX] = s->m.nv;
  d->nread[TDS_EDGE] = s->m.ne;
  d->ne0 = s->m.ne;
  d->nread[TDS_FACET] = s->m.nf;
  d->nread[TDS_BODY] = s->m.nb;
  d->maxface = s->m.nf;
  return TDS_OK;
}

int df_app_detach(df *d, int kind, int slot) {
  struct df_app *a = d->app;
  if (!a) return 0;
  tds_surf *s = d->s;
  switch (kind) {
  case DF_APP_CON:
    if (!a->con0[slot].number || (a->con_rep >> slot & 1)) return 0;
    a->con_rep |= (uint64_t)1 << slot;
    s->con[slot].formula = NULL; /* a->con0 owns the old expressions */
    memset(s->con[slot].energy, 0, sizeof s->con[slot].energy);
    memset(s->con[slot].content, 0, sizeof s->con[slot].content);
    return 1;
  case DF_APP_BDRY:
    if (slot >= a->nbdry0 || a->bdry_rep[slot]) return 0;
    a->bdry_rep[slot] = 1;
    memset(s->bdry[slot].x, 0, sizeof s->bdry[slot].x);
    memset(s->bdry[slot].energy, 0, sizeof s->bdry[slot].energy);
    memset(s->bdry[slot].content, 0, sizeof s->bdry[slot].content);
    return 1;
  default:
    if (slot >= a->nquant0 || a->quant_rep[slot]) return 0;
    a->quant_rep[slot] = 1;
    s->quant[slot].inst = NULL; /* a->quant0 owns the old methods */
    s->quant[slot].ninst = 0;
    return 1;
  }
}

static void free3(tds_expr *e[3]) {
  for (int i = 0; i < 3; i++) tds_expr_free(e[i]), e[i] = NULL;
}

static void free_con(tds_constraint *c) {
  tds_expr_free(c->formula);
  free3(c->energy);
  free3(c->content);
}

static void free_bdry(tds_boundary *b) {
  free3(b->x);
  free3(b->energy);
  free3(b->content);
}

static void free_methods(const tds_alloc *al, tds_quantity *q) {
  for (int j = 0; j < q->ninst; j++) free3(q->inst[j].integrand);
  tds_free(al, q->inst);
  q->inst = NULL;
  q->ninst = 0;
}

void df_app_end(df *d, int ok) {
  struct df_app *a = d->app;
  if (!a) return;
  tds_surf *s = d->s;
  const tds_alloc *al = &s->m.alloc;
  d->app = NULL;
  if (ok) { /* the replaced declarations go */
    for (int c = 0; c < TDS_MAX_CON; c++)
      if (a->con_rep >> c & 1) free_con(&a->con0[c]);
    for (int i = 0; i < a->nbdry0; i++)
      if (a->bdry_rep[i]) free_bdry(&a->bdry0[i]);
    for (int i = 0; i < a->nquant0; i++)
      if (a->quant_rep[i]) free_methods(al, &a->quant0[i]);
    free_app(al, a);
    return;
  }
  /* what the file added goes, what it replaced comes back */
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (s->con[c].number && (!a->con0[c].number || (a->con_rep >> c & 1)))
      free_con(&s->con[c]);
  memcpy(s->con, a->con0, sizeof s->con);
  for (int i = 0; i < s->nbdry; i++)
    if (i >= a->nbdry0 || a->bdry_rep[i]) free_bdry(&s->bdry[i]);
  if (a->nbdry0) memcpy(s->bdry, a->bdry0, (size_t)a->nbdry0 * sizeof *s->bdry);
  s->nbdry = a->nbdry0;
  for (int i = 0; i < s->nquant; i++) {
    if (i < a->nquant0 && !a->quant_rep[i]) continue;
    free_methods(al, &s->quant[i]);
    if (i >= a->nquant0) tds_free(al, s->quant[i].name);
  }
  if (a->nquant0) memcpy(s->quant, a->quant0, (size_t)a->nquant0 * sizeof *s->quant);
  s->nquant = a->nquant0;
  for (int i = a->npar0; i < s->npar; i++) tds_free(al, s->parname[i]);
  s->npar = a->npar0;
  if (a->npar0) memcpy(s->parval, a->parval0, (size_t)a->npar0 * sizeof *s->parval);
  s->param_gen = a->param_gen; /* the values are the old ones again */
  s->gravity = a->gravity;
  s->gravity_on = a->gravity_on;
  s->gap_constant = a->gap;
  s->constraint_tol = a->tol;
  s->scale_limit = a->scale_limit;
  s->fixed_scale = a->fixed_scale;
  s->symmetric_content = a->symmetric;
  tds_free(al, s->view); /* the copies come back */
  tds_free(al, s->vgen);
  tds_free(al, s->view_swap);
  tds_free(al, s->vgen_swap);
  s->view_transforms = a->nview;
  s->view = a->nview ? a->view : NULL;
  s->view_swap = a->nview ? a->view_swap : NULL;
  if (a->nview) a->view = NULL, a->view_swap = NULL;
  s->nvgen = a->nvgen;
  s->vgen = a->nvgen ? a->vgen : NULL;
  s->vgen_swap = a->nvgen ? a->vgen_swap : NULL;
  if (a->nvgen) a->vgen = NULL, a->vgen_swap = NULL;
  tds_snap_restore(s, &a->snap); /* mesh, scale, quantity values, ... */
  s->scale = a->scale;
  free_app(al, a);
}

int tds_datafile_replace_load(tds_ctx *ctx, tds_surf *s, const char *path) {
  TDS_REQUIRE(ctx, s && path);
  if (s->str || s->m.torus)
    return tds_seterr(ctx, TDS_ESYNTAX, "%s: replace_load in the %s model is not supported yet",
                      path, s->str ? "string" : "torus");
  tds_snap sn;
  int rc = tds_snap_take(ctx, s, &sn);
  if (rc) return rc;
  /* Evolver dissolves every element, then addloads: ids start at 1 again */
  tds_mesh *m = &s->m;
  m->nv = m->ne = m->nf = m->nb = 0;
  m->topo_gen++;
  m->coord_gen++;
  m->adj_gen = 0;
  rc = tds_datafile_addload(ctx, s, path);
  if (rc == TDS_OK) tds_snap_free(&sn);
  else tds_snap_restore(s, &sn);
  return rc;
}
