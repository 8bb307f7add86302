/* pg_newton.c: a Newton-type preconditioner of the pg fixed-point map
** (pg_int.h, doc/method.md "Newton preconditioning").
**
** F(X) = G(X) - X is the plain move from the state X (positions of the
** movable vertices, parameters of boundary vertices). A vertex's move
** depends on its own position and its star's other vertices (the normal,
** the star model, the Voronoi centroid), and, globally, on the bodies'
** multipliers, the restoring coefficients and (sessile drops) the
** rigid-motion gauge. Frozen at the base point, those leave a sparse
** Jacobian J_loc with a 3x3 block (i, j) for every pair of neighbours;
** it is measured by finite differences on a distance-2 colouring of the
** movable vertices (vertices of one colour share no neighbour, so one
** evaluation per colour and coordinate gives their columns: about 20
** colours, 60 evaluations). The restoring motion's dependence on the
** volumes is known in closed form (-g Gr^-1 g^T, g the volume gradients
** in the motion spaces, Gr their Gram matrix) and is added as a border:
**
**   [ J_loc  -g  ] [ dX ]   [ -F ]
**   [ g^T    -Gr ] [ s  ] = [  0 ]     (J_loc - g Gr^-1 g^T) dX = -F
**
** factored once (LU, la.h) and used for many steps: the driver mixes the
** preconditioned map X -> X + dX(X) with Anderson's history, which takes
** care of what the preconditioner leaves out (the multipliers' and the
** gauge's dependence on X: a correction of low rank). */
#include <math.h>
#include <string.h>

#include "fixq.h"
#include "la.h"
#include "pg_int.h"
#include "sparse.h"
#include "vec3.h"

void pg_newton_free(pg_newton *nt) {
  tds_la_free(nt->lu);
  tds_free(&nt->al, nt->inv);
  tds_free(&nt->al, nt->nbp);
  tds_free(&nt->al, nt->nbi);
  tds_free(&nt->al, nt->nbn);
  tds_free(&nt->al, nt->color);
  tds_free(&nt->al, nt->X0);
  tds_free(&nt->al, nt->F0);
  tds_free(&nt->al, nt->Xp);
  tds_free(&nt->al, nt->Fp);
  tds_free(&nt->al, nt->b);
  tds_free(&nt->al, nt->xs);
  tds_free(&nt->al, nt->ps);
  tds_free(&nt->al, nt->mark);
  tds_free(&nt->al, nt->R0);
  tds_free(&nt->al, nt->Rp);
  tds_free(&nt->al, nt->dR);
  tds_free(&nt->al, nt->S0);
  tds_free(&nt->al, nt->Sp);
  tds_free(&nt->al, nt->dS);
  memset(nt, 0, sizeof *nt);
}

void pg_newton_drop(pg_newton *nt) {
  tds_la_free(nt->lu);
  nt->lu = NULL;
}

int pg_newton_init(pg_newton *nt, const tds_alloc *al, const pgw *w) {
  memset(nt, 0, sizeof *nt);
  nt->al = *al;
  size_t nv = (size_t)(w->nv > 0 ? w->nv : 1), nm = (size_t)(w->nmov > 0 ? w->nmov : 1);
  size_t nq = (size_t)w->fq.nq, nu = nq <= PG_NT_NQ ? nq : 0;
  size_t N = 3 * nm + 2 * nq + 7;
  nt->inv = tds_calloc(al, nv, sizeof *nt->inv);
  nt->nbp = tds_calloc(al, nm + 1, sizeof *nt->nbp);
  nt->color = tds_calloc(al, nm, sizeof *nt->color);
  nt->X0 = tds_calloc(al, N, sizeof *nt->X0);
  nt->F0 = tds_calloc(al, N, sizeof *nt->F0);
  nt->Xp = tds_calloc(al, N, sizeof *nt->Xp);
  nt->Fp = tds_calloc(al, N, sizeof *nt->Fp);
  nt->b = tds_calloc(al, N, sizeof *nt->b);
  nt->xs = tds_calloc(al, nv, sizeof *nt->xs);
  nt->ps = tds_calloc(al, nv, sizeof *nt->ps);
  nt->mark = tds_calloc(al, nm + 1, sizeof *nt->mark);
  nt->R0 = tds_calloc(al, nm * nu + 1, sizeof *nt->R0);
  nt->Rp = tds_calloc(al, nm * nu + 1, sizeof *nt->Rp);
  nt->dR = tds_calloc(al, nm * nu + 1, sizeof *nt->dR);
  nt->S0 = tds_calloc(al, nm * nu * nu + 1, sizeof *nt->S0);
  nt->Sp = tds_calloc(al, nm * nu * nu + 1, sizeof *nt->Sp);
  nt->dS = tds_calloc(al, nm * nu * nu + 1, sizeof *nt->dS);
  if (!nt->inv || !nt->nbp || !nt->color || !nt->X0 || !nt->F0 || !nt->Xp ||
      !nt->Fp || !nt->b || !nt->xs || !nt->ps || !nt->mark || !nt->R0 || !nt->Rp ||
      !nt->dR || !nt->S0 || !nt->Sp || !nt->dS) {
    pg_newton_free(nt);
    return TDS_ENOMEM;
  }
  return TDS_OK;
}

/* Closed neighbourhoods of the movable vertices (CSR over movable
** indices, the vertex itself first): the vertices of its facets, from the
** facets themselves (the vertex-edge lists may lag behind flips). */
static int neighbours(const tds_surf *s, const pgw *w, pg_newton *nt) {
  const tds_mesh *m = &s->m;
  int32_t nm = w->nmov;
  for (tds_id v = 0; v < m->nv; v++) nt->inv[v] = -1;
  for (int32_t j = 0; j < nm; j++) nt->inv[w->mov[j]] = j;
  int32_t *cnt = nt->nbp; /* upper bounds first: 1 + 2 per facet */
  for (int32_t j = 0; j <= nm; j++) cnt[j] = 0;
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    for (int k = 0; k < 3; k++) {
      int32_t j = nt->inv[m->fv[f][k]];
      if (j >= 0) cnt[j + 1] += 2;
    }
  }
  for (int32_t j = 0; j < nm; j++) cnt[j + 1] += cnt[j] + 1;
  tds_free(&nt->al, nt->nbi);
  nt->nbi = tds_calloc(&nt->al, (size_t)cnt[nm] + 1, sizeof *nt->nbi);
  tds_free(&nt->al, nt->nbn);
  nt->nbn = tds_calloc(&nt->al, (size_t)nm + 1, sizeof *nt->nbn);
  if (!nt->nbi || !nt->nbn) return TDS_ENOMEM;
  for (int32_t j = 0; j < nm; j++) {
    nt->nbi[cnt[j]] = j;
    nt->nbn[j] = 1;
  }
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    for (int k = 0; k < 3; k++) {
      int32_t j = nt->inv[m->fv[f][k]];
      if (j < 0) continue;
      for (int l = 1; l < 3; l++) {
        int32_t u = nt->inv[m->fv[f][(k + l) % 3]];
        if (u < 0) continue;
        int dup = 0;
        for (int32_t q = cnt[j]; q < cnt[j] + nt->nbn[j]; q++) dup |= nt->nbi[q] == u;
        if (!dup) nt->nbi[cnt[j] + nt->nbn[j]++] = u;
      }
    }
  }
  /* compact */
  int32_t p = 0;
  for (int32_t j = 0; j < nm; j++) {
    int32_t b0 = cnt[j], n = nt->nbn[j];
    cnt[j] = p;
    for (int32_t q = 0; q < n; q++) nt->nbi[p + q] = nt->nbi[b0 + q];
    p += n;
  }
  cnt[nm] = p;
  return TDS_OK;
}

/* Greedy distance-2 colouring: j and k differ when some vertex has both
** in its closed neighbourhood. */
static void colour(const pgw *w, pg_newton *nt) {
  int32_t nm = w->nmov, nc = 0;
  int32_t *mark = nt->mark; /* per colour: the vertex that last used it */
  for (int32_t c = 0; c <= nm; c++) mark[c] = -1;
  for (int32_t j = 0; j < nm; j++) nt->color[j] = -1;
  for (int32_t j = 0; j < nm; j++) {
    for (int32_t a = nt->nbp[j]; a < nt->nbp[j + 1]; a++) {
      int32_t i = nt->nbi[a];
      for (int32_t b = nt->nbp[i]; b < nt->nbp[i + 1]; b++) {
        int32_t c = nt->color[nt->nbi[b]];
        if (c >= 0) mark[c] = j;
      }
    }
    int32_t c = 0;
    while (c < nc && mark[c] == j) c++;
    nt->color[j] = c;
    if (c == nc) nc++;
  }
  nt->ncolor = nc;
}

/* Per movable vertex j, its contributions to the multipliers' least
** squares (pg_step.c): R[j nq + q] to the right-hand side, S[(j nq + q)
** nq + q2] to the Gram matrix, at the last pass and step. */
static void mult_parts(const pgw *w, double *R, double *S) {
  const tds_fixq *fq = &w->fq;
  int32_t nq = fq->nq;
  memset(R, 0, (size_t)w->nmov * (size_t)nq * sizeof *R);
  memset(S, 0, (size_t)w->nmov * (size_t)nq * (size_t)nq * sizeof *S);
  for (int32_t j = 0; j < w->nmov; j++) {
    tds_id v = w->mov[j];
    const double *d = w->d[v];
    double gd = v3_dot(w->acc[v].ga, d) + v3_dot(w->grad[v], d);
    for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++) {
      R[j * nq + fq->eq[e]] += w->an[e] * gd;
      for (int32_t e2 = fq->start[v]; e2 < fq->start[v + 1]; e2++)
        S[((size_t)j * nq + fq->eq[e]) * nq + fq->eq[e2]] += w->an[e] * w->an[e2];
    }
  }
}

/* The plain map at state X with the global coefficients frozen: F = G(X)
** - X into F. Leaves the surface moved (the caller restores it). */
static int frozen_map(tds_ctx *ctx, tds_surf *s, pgw *w, double sfac, const double *X,
                      double *F) {
  pg_stepinfo si;
  double energy;
  if (pg_set_state(s, w, X)) return TDS_ENUM;
  int rc = pg_pass(ctx, s, w, &energy);
  if (rc == TDS_OK) rc = pg_step(ctx, s, w, sfac, &si);
  if (rc != TDS_OK) return rc;
  if (pg_apply(s, w)) return TDS_ENUM;
  pg_get_state(s, w, F);
  for (int32_t i = 0; i < 3 * w->nmov; i++) F[i] -= X[i];
  return TDS_OK;
}

/* Nonzero when some facet at a movable vertex has an angle below ~10
** degrees (cos above 0.985): the Jacobian of a mesh that is that far
** from a CVT is ill-conditioned, and Newton steps there found degenerate
** fixed points (a collapsing catenoid converged to a facet of zero
** angle). */
int pg_newton_sliver(const tds_surf *s, const pgw *w) {
  const tds_mesh *m = &s->m;
  for (tds_id f = 0; f < m->nf; f++) {
    if (m->fflags[f] & TDS_DEAD) continue;
    const tds_id *fv = m->fv[f];
    if (!(w->kind[fv[0]] | w->kind[fv[1]] | w->kind[fv[2]])) continue;
    for (int k = 0; k < 3; k++) {
      double a[3], b[3];
      v3_sub(a, m->x[fv[(k + 1) % 3]], m->x[fv[k]]);
      v3_sub(b, m->x[fv[(k + 2) % 3]], m->x[fv[k]]);
      double ab = v3_dot(a, b), aa = v3_dot(a, a), bb = v3_dot(b, b);
      if (ab > 0 && !(ab * ab < 0.99726 * aa * bb)) return 1; /* cos^2 3 degrees */
    }
  }
  return 0;
}

int pg_newton_build(tds_ctx *ctx, tds_surf *s, pgw *w, pg_newton *nt, const double *X,
                    double sfac, double h) {
  tds_mesh *m = &s->m;
  pg_newton_drop(nt);
  if (pg_newton_sliver(s, w)) return TDS_OK; /* not now */
  int32_t nm = w->nmov, N = 3 * nm, nq = w->fq.nq;
  int32_t nu = nq <= PG_NT_NQ ? nq : 0; /* multipliers in the border */
  int32_t nr = w->nrig; /* rigid motions the constraints allow: their
                           directions are exact null vectors of J (the
                           map moves with the surface), fixed by a border */
  int32_t nb = N + nq + nu + nr;
  int rc = neighbours(s, w, nt);
  if (rc != TDS_OK) return tds_seterr(ctx, rc, "out of memory");
  colour(w, nt);
  memcpy(nt->xs, m->x, (size_t)m->nv * sizeof *nt->xs);
  memcpy(nt->ps, m->vp, (size_t)m->nv * sizeof *nt->ps);
  memcpy(nt->X0, X, (size_t)N * sizeof *X);
  tds_sptrip t = {.nrow = nb, .ncol = nb, .alloc = ctx->alloc};
  tds_spmat A = {0};
  /* The base point: multipliers and restoring coefficients from here,
  ** then frozen for the differences. */
  w->frozen = 0;
  rc = frozen_map(ctx, s, w, sfac, X, nt->F0);
  if (rc != TDS_OK) goto out;
  double mult[PG_NT_NQ];
  for (int32_t q = 0; q < nu; q++) mult[q] = w->mult[q];
  if (nu) mult_parts(w, nt->R0, nt->S0);
  /* The border: g (volume gradients in the motion spaces, as the step
  ** left them in fq->g) and their Gram matrix. */
  const tds_fixq *fq = &w->fq;
  for (int32_t j = 0; j < nm && nq; j++) {
    tds_id v = w->mov[j];
    if (w->kind[v] != VK_FREE && w->kind[v] != VK_LEVEL) continue;
    for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++) {
      int32_t q = fq->eq[e];
      for (int c = 0; c < 3; c++) {
        double g = fq->g[e][c];
        if (g == 0) continue;
        if (tds_sptrip_add(&t, 3 * j + c, N + q, -g) || tds_sptrip_add(&t, N + q, 3 * j + c, g))
          goto nomem;
      }
    }
  }
  for (int32_t q = 0; q < nq; q++)
    for (int32_t q2 = 0; q2 < nq; q2++) {
      double gr = 0;
      for (int32_t j = 0; j < nm; j++) {
        tds_id v = w->mov[j];
        if (w->kind[v] != VK_FREE && w->kind[v] != VK_LEVEL) continue;
        double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
        for (int32_t e = fq->start[v]; e < fq->start[v + 1]; e++) {
          if (fq->eq[e] == q) v3_add(a, a, fq->g[e]);
          if (fq->eq[e] == q2) v3_add(b, b, fq->g[e]);
        }
        gr += v3_dot(a, b);
      }
      if (q == q2 && !(gr > 0)) gr = 1;
      if (tds_sptrip_add(&t, N + q, N + q2, -gr)) goto nomem;
    }
  /* The multipliers' inverse Gram matrix (their least squares). */
  double Ginv[PG_NT_NQ * PG_NT_NQ];
  for (int32_t q = 0; q < nu; q++) {
    double Gm[PG_NT_NQ * PG_NT_NQ], col[PG_NT_NQ];
    memset(Gm, 0, sizeof Gm);
    for (int32_t j = 0; j < nm; j++)
      for (int32_t k = 0; k < nu * nu; k++) Gm[k] += nt->S0[(size_t)j * nu * nu + k];
    for (int32_t k = 0; k < nu; k++) {
      if (!(Gm[k * nu + k] > 0)) Gm[k * nu + k] = 1;
      col[k] = k == q ? 1 : 0;
    }
    if (tds_dense_solve(nu, Gm, col) != 0) {
      rc = tds_seterr(ctx, TDS_ENUM, "pg newton: dependent constraints");
      goto out;
    }
    for (int32_t k = 0; k < nu; k++) Ginv[k * nu + q] = col[k];
  }
  w->frozen = 1;
  /* dF/dmu_q: the frozen map with one multiplier moved. */
  for (int32_t q = 0; q < nu; q++) {
    double dm = 1e-7 * (fabs(mult[q]) > 1 ? fabs(mult[q]) : 1);
    w->mult[q] = mult[q] + dm;
    rc = frozen_map(ctx, s, w, sfac, X, nt->Fp);
    w->mult[q] = mult[q];
    if (rc != TDS_OK) goto out;
    for (int32_t i = 0; i < N; i++) {
      double u = (nt->Fp[i] - nt->F0[i]) / dm;
      if (u != 0 && tds_sptrip_add(&t, i, N + nq + q, u)) goto nomem;
    }
    if (tds_sptrip_add(&t, N + nq + q, N + nq + q, -1)) goto nomem;
  }
  for (int32_t c = 0; c < nt->ncolor; c++)
    for (int d = 0; d < 3; d++) {
      memcpy(nt->Xp, X, (size_t)N * sizeof *X);
      for (int32_t j = 0; j < nm; j++)
        if (nt->color[j] == c) nt->Xp[3 * j + d] += h;
      rc = frozen_map(ctx, s, w, sfac, nt->Xp, nt->Fp);
      if (rc != TDS_OK) goto out;
      if (nu) {
        mult_parts(w, nt->Rp, nt->Sp);
        memset(nt->dR, 0, (size_t)nm * nu * sizeof *nt->dR);
        memset(nt->dS, 0, (size_t)nm * nu * nu * sizeof *nt->dS);
      }
      for (int32_t i = 0; i < nm; i++)
        for (int32_t a = nt->nbp[i]; a < nt->nbp[i + 1]; a++) {
          int32_t k = nt->nbi[a];
          if (nt->color[k] != c) continue;
          for (int e = 0; e < 3; e++) {
            double jv = (nt->Fp[3 * i + e] - nt->F0[3 * i + e]) / h;
            if (jv != 0 && tds_sptrip_add(&t, 3 * i + e, 3 * k + d, jv)) goto nomem;
          }
          for (int32_t q = 0; q < nu; q++) {
            nt->dR[(size_t)k * nu + q] += (nt->Rp[(size_t)i * nu + q] - nt->R0[(size_t)i * nu + q]) / h;
            for (int32_t q2 = 0; q2 < nu; q2++) {
              size_t o = ((size_t)i * nu + q) * nu + q2;
              nt->dS[((size_t)k * nu + q) * nu + q2] += (nt->Sp[o] - nt->S0[o]) / h;
            }
          }
        }
      /* d mult = Ginv (d rhs - d Gram mult), per column 3k + d */
      for (int32_t k = 0; k < nm && nu; k++) {
        if (nt->color[k] != c) continue;
        double tmp[PG_NT_NQ];
        for (int32_t q = 0; q < nu; q++) {
          tmp[q] = nt->dR[(size_t)k * nu + q];
          for (int32_t q2 = 0; q2 < nu; q2++)
            tmp[q] -= nt->dS[((size_t)k * nu + q) * nu + q2] * mult[q2];
        }
        for (int32_t q = 0; q < nu; q++) {
          double gm = 0;
          for (int32_t q2 = 0; q2 < nu; q2++) gm += Ginv[q * nu + q2] * tmp[q2];
          if (gm != 0 && tds_sptrip_add(&t, N + nq + q, 3 * k + d, gm)) goto nomem;
        }
      }
    }
  for (int32_t j = 0; j < nm && nr; j++) {
    /* The gauge keeps contact-line vertices in place along the line: the
    ** map never moves them that way, so J has a zero row there; the
    ** Newton step keeps them too (-t t^T, t along the line). */
    tds_id v = w->mov[j];
    if (w->bnb[v][0] < 0) continue;
    double tl[3];
    v3_sub(tl, m->x[w->bnb[v][1]], m->x[w->bnb[v][0]]);
    double tn = v3_norm(tl);
    if (!(tn > 0)) continue;
    v3_scale(tl, 1 / tn);
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++)
        if (tl[a] * tl[b] != 0 && tds_sptrip_add(&t, 3 * j + a, 3 * j + b, -tl[a] * tl[b]))
          goto nomem;
  }
  if (nr) { /* [J R; R^T 0]: the step has no rigid component */
    double xc[3] = {0, 0, 0};
    for (int32_t j = 0; j < nm; j++) v3_add(xc, xc, m->x[w->mov[j]]);
    v3_scale(xc, 1.0 / nm);
    for (int32_t k = 0; k < nr; k++) {
      int rk = w->rig[k];
      for (int32_t j = 0; j < nm; j++) {
        double e[3] = {0, 0, 0}, md[3], rel[3];
        e[rk % 3] = 1;
        if (rk < 3) {
          v3_copy(md, e);
        } else {
          v3_sub(rel, m->x[w->mov[j]], xc);
          v3_cross(md, e, rel);
        }
        for (int c = 0; c < 3; c++)
          if (md[c] != 0 && (tds_sptrip_add(&t, 3 * j + c, N + nq + nu + k, md[c]) ||
                             tds_sptrip_add(&t, N + nq + nu + k, 3 * j + c, md[c])))
            goto nomem;
      }
    }
  }
  for (int32_t i = 0; i < nb; i++) /* the pattern's diagonal */
    if (tds_sptrip_add(&t, i, i, 0)) goto nomem;
  if (tds_spmat_from_trip(&t, 0, &A)) goto nomem;
  rc = tds_la_factor_lu(ctx, &A, &nt->lu);
  if (rc == TDS_OK && tds_la_inertia(nt->lu).zero) {
    pg_newton_drop(nt);
    rc = tds_seterr(ctx, TDS_ENUM, "pg newton: singular Jacobian");
  }
  nt->builds++;
  goto out;
nomem:
  rc = tds_seterr(ctx, TDS_ENOMEM, "out of memory");
out:
  w->frozen = 0;
  for (int32_t q = 0; q < nu; q++) w->mult[q] = mult[q];
  tds_sptrip_free(&t);
  tds_spmat_free(&A);
  memcpy(m->x, nt->xs, (size_t)m->nv * sizeof *nt->xs);
  memcpy(m->vp, nt->ps, (size_t)m->nv * sizeof *nt->ps);
  m->coord_gen++;
  return rc;
}

int pg_newton_apply(tds_ctx *ctx, pg_newton *nt, const pgw *w, const double *X, double *G) {
  int32_t N = 3 * w->nmov, nq = w->fq.nq;
  int32_t nu = nq <= PG_NT_NQ ? nq : 0;
  for (int32_t i = 0; i < N; i++) nt->b[i] = X[i] - G[i];
  for (int32_t q = 0; q < nq + nu + w->nrig; q++) nt->b[N + q] = 0;
  int rc = tds_la_solve(ctx, nt->lu, nt->b, 0);
  if (rc != TDS_OK) return rc;
  for (int32_t i = 0; i < N; i++) G[i] = X[i] + nt->b[i];
  return TDS_OK;
}
