/* surf.c: surface lifetime, parameters and constraint lookup. */
#include "surf.h"

#include <ctype.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <strings.h>

#include "expr.h"
#include "string_model.h"
#include "xattr.h"

void tds_surf_init(tds_surf *s) {
  memset(s, 0, sizeof *s);
  tds_mesh_init(&s->m);
  s->gravity = 1;            /* Evolver's default G; off until a density */
  s->gap_constant = 1;
  s->constraint_tol = 1e-12;
  s->scale = 0.1;
  s->scale_limit = 1;
  s->rng = 1; /* a fixed seed: runs repeat */
}

static void free_exprs(tds_expr **e, int n) {
  for (int i = 0; i < n; i++) tds_expr_free(e[i]);
}

void tds_surf_free(tds_surf *s) {
  tds_alloc a = s->m.alloc;
  tds_mesh_free(&s->m);
  for (int i = 0; i < s->npar; i++) tds_free(&a, s->parname[i]);
  tds_free(&a, s->parname);
  tds_free(&a, s->parval ? s->parval - s->xcap : NULL);
  tds_xattr_free(s);
  for (int i = 0; i < TDS_MAX_CON; i++) {
    tds_constraint *c = &s->con[i];
    tds_expr_free(c->formula);
    free_exprs(c->energy, 3);
    free_exprs(c->content, 3);
  }
  for (int i = 0; i < s->nbdry; i++) {
    free_exprs(s->bdry[i].x, 3);
    free_exprs(s->bdry[i].energy, 3);
    free_exprs(s->bdry[i].content, 3);
  }
  tds_free(&a, s->bdry);
  free_exprs(s->special_normal, 3);
  for (int i = 0; i < s->nquant; i++) {
    tds_free(&a, s->quant[i].name);
    for (int j = 0; j < s->quant[i].ninst; j++)
      free_exprs(s->quant[i].inst[j].integrand, 3);
    tds_free(&a, s->quant[i].inst);
  }
  tds_free(&a, s->quant);
  free_exprs(s->metric, 9);
  for (int i = 0; i < 3; i++) free_exprs(s->period_expr[i], 3);
  tds_free(&a, s->tlift);
  tds_free(&a, s->tplan);
  tds_free(&a, s->read_text);
  tds_free(&a, s->orig_start);
  tds_free(&a, s->orig_facets);
  tds_free(&a, s->cg_dir);
  tds_free(&a, s->cg_prev);
  tds_free(&a, s->view);
  tds_free(&a, s->vgen);
  tds_free(&a, s->view_swap);
  tds_free(&a, s->vgen_swap);
  tds_strings_free(s);
  tds_surf_init(s);
  s->m.alloc = a;
}

int tds_surf_set_view(tds_ctx *ctx, tds_surf *s, int gen, int n, const double (*m)[16],
                      const uint8_t *swap) {
  if (n < 0 || n > TDS_MAX_VIEW)
    return tds_seterr(ctx, TDS_ERANGE, "%d view transforms: at most %d", n, TDS_MAX_VIEW);
  for (int i = 0; i < n; i++)
    for (int k = 0; k < 16; k++)
      if (!isfinite(m[i][k]))
        return tds_seterr(ctx, TDS_ERANGE, "view transform %d: entry [%d][%d] is not finite",
                          i + 1, k / 4 + 1, k % 4 + 1);
  double (*c)[16] = NULL;
  uint8_t *sw = NULL;
  if (n) {
    c = tds_malloc(&s->m.alloc, (size_t)n * sizeof *c);
    sw = tds_calloc(&s->m.alloc, (size_t)n, 1);
    if (!c || !sw) {
      tds_free(&s->m.alloc, c);
      tds_free(&s->m.alloc, sw);
      return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
    }
    memcpy(c, m, (size_t)n * sizeof *c);
    for (int i = 0; swap && i < n; i++) sw[i] = swap[i] != 0;
  }
  double (**pm)[16] = gen ? &s->vgen : &s->view;
  uint8_t **ps = gen ? &s->vgen_swap : &s->view_swap;
  tds_free(&s->m.alloc, *pm);
  tds_free(&s->m.alloc, *ps);
  *pm = c;
  *ps = sw;
  if (gen) s->nvgen = n;
  else s->view_transforms = n;
  return TDS_OK;
}

int tds_surf_param_find(const tds_surf *s, const char *name, size_t len) {
  for (int i = 0; i < s->npar; i++)
    if (strlen(s->parname[i]) == len && strncasecmp(s->parname[i], name, len) == 0)
      return i;
  return -1;
}

int tds_surf_param_room(tds_surf *s, int xcap, int cap) {
  if (xcap <= s->xcap && cap <= s->cappar) return TDS_OK;
  if (xcap < s->xcap) xcap = s->xcap;
  if (cap < s->cappar) cap = s->cappar;
  double *old = s->parval ? s->parval - s->xcap : NULL;
  double *b = tds_calloc(&s->m.alloc, (size_t)xcap + (size_t)cap + 1, sizeof *b);
  if (!b) return TDS_ENOMEM;
  if (old) memcpy(b + xcap - s->xcap, old, sizeof *b * ((size_t)s->xcap + (size_t)s->npar));
  tds_free(&s->m.alloc, old);
  s->parval = b + xcap;
  s->xcap = xcap;
  s->cappar = cap;
  return TDS_OK;
}

int tds_surf_param_set(tds_surf *s, const char *name, double value) {
  int i = tds_surf_param_find(s, name, strlen(name));
  if (i >= 0) {
    if (s->parval[i] != value) s->param_gen++;
    s->parval[i] = value;
    return i;
  }
  if (s->npar == s->cappar) {
    int cap = s->cappar ? 2 * s->cappar : 16;
    char **n = tds_reallocarray(&s->m.alloc, s->parname, (size_t)cap, sizeof *n);
    if (!n) return -1;
    s->parname = n;
    if (tds_surf_param_room(s, s->xcap, cap) != TDS_OK) return -1;
  }
  char *copy = tds_strdup(&s->m.alloc, name);
  if (!copy) return -1;
  for (char *p = copy; *p; p++) *p = (char)tolower((unsigned char)*p);
  s->parname[s->npar] = copy;
  s->parval[s->npar] = value;
  return s->npar++;
}

int tds_surf_con_slot(const tds_surf *s, int number) {
  for (int i = 0; i < TDS_MAX_CON; i++)
    if (s->con[i].number == number && number != 0) return i;
  return -1;
}

int tds_surf_con_named(const tds_surf *s, const char *name, size_t len) {
  if (len == 0 || len >= sizeof s->con[0].name) return -1;
  for (int i = 0; i < TDS_MAX_CON; i++) {
    const char *n = s->con[i].name;
    if (!s->con[i].number || strlen(n) != len) continue;
    size_t k = 0;
    while (k < len && n[k] == (char)tolower((unsigned char)name[k])) k++;
    if (k == len) return i;
  }
  return -1;
}

int tds_surf_con_free_number(const tds_surf *s) {
  int n = 1;
  while (tds_surf_con_slot(s, n) >= 0) n++;
  return n;
}

tds_cmask tds_surf_global_cons(const tds_surf *s) {
  tds_cmask mask = 0;
  for (int i = 0; i < TDS_MAX_CON; i++)
    if (s->con[i].number && (s->con[i].flags & TDS_CON_GLOBAL))
      mask |= (tds_cmask)1 << i;
  return mask;
}
