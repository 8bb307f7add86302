/* torus_view.c: the torus surface as drawn, for exports, pictures and the
** live view (tds_torus_view, torus.h). */
#include "torus.h"

#include <math.h>
#include <string.h>

#include "metrics.h"

int tds_torus_view(tds_ctx *ctx, tds_surf *s, tds_torus_drawn *view) {
  memset(view, 0, sizeof *view);
  if (tds_mesh_adjacency(&s->m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  view->s = *s;
  /* derived arrays of s are not shared: the view builds its own */
  tds_surf *v = &view->s;
  v->tlift = NULL;
  v->tlift_cap = 0;
  v->tlift_gen = 0;
  v->tplan = NULL;
  v->orig_start = v->orig_facets = NULL;
  v->orig_gen = 0;
  v->cg_dir = v->cg_prev = NULL;
  v->cg_nv = 0;
  tds_mesh_init(&v->m);
  v->m.alloc = s->m.alloc;
  if (tds_mesh_copy(&v->m, &s->m) != TDS_OK) return tds_seterr(ctx, TDS_ENOMEM, "out of memory");
  int32_t *src[2] = {NULL, NULL};
  int rc = tds_torus_detorus(ctx, &v->m, src);
  if (rc != TDS_OK) {
    tds_mesh_free(&v->m);
    return rc;
  }
  view->vsrc = src[0];
  view->fsrc = src[1];
  if (s->str) { /* the cells are not cut: edges only */
    view->str = *s->str;
    view->str.nf = 0;
    v->str = &view->str;
  }
  return TDS_OK;
}

void tds_torus_view_free(tds_torus_drawn *view) {
  tds_surf *v = &view->s;
  tds_alloc a = v->m.alloc;
  tds_free(&a, view->vsrc);
  tds_free(&a, view->fsrc);
  tds_mesh_free(&v->m);
  tds_free(&a, v->tlift);
  tds_free(&a, v->tplan);
  tds_free(&a, v->orig_start);
  tds_free(&a, v->orig_facets);
  tds_free(&a, v->cg_dir);
  tds_free(&a, v->cg_prev);
}

double tds_torus_drawn_curvature(const tds_torus_drawn *view, tds_surf *orig, tds_id v) {
  return view->vsrc[v] >= 0 ? tds_vertex_mean_curvature(orig, view->vsrc[v]) : (double)NAN;
}
