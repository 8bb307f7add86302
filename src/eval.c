/* eval.c: energy, gradient and constrained-quantity assembly.
**
** Every term is a row of the method table (method.h) bound to the
** elements it applies to: a term names its row, its gathered constants
** (integrands, quadrature), and a sink function that says, per element,
** with which weights the row's value goes where: to the term's own total
** (the energy, or a named quantity) or to a body's volume. One loop,
** assemble(), gathers each element's corners, calls the row and scatters
** value and gradient. The terms (Evolver's model):
**   facet tension      facet_area x tension                 -> energy
**   body volume        facet_volume(_symmetric) +-1         -> bodies
**   prescribed pressure  the same volume x -+p              -> energy
**   gravity            full_gravity_method x G density      -> energy
**   edge tension       edge_length x tension                -> energy
**   constraint/boundary energy   edge_vector_integral x +-1 -> energy
**   constraint/boundary content  edge_vector_integral       -> bodies
**   gap energy         edge_gap on convex constraints       -> energy
**   named quantities   any user row x modulus               -> quantity
** With tds_eval_out.hess the same loop also asks each kernel for its
** Hessian and scatters it, weighted like the gradient (hess.c).
** FIXED edges carry no constraint integrals (Evolver's rule); boundary
** integrals apply to every edge on the boundary.
*/
#include "eval.h"

#include <math.h>
#include <string.h>

#include "gather.h"
#include "method.h"
#include "string_model.h"
#include "symmetry.h"
#include "torus.h"
#include "vec3.h"
#include "xattr.h"

/* Where a weighted value goes: body b (its volume and, if constrained,
** its fixq gradient), or with b == TDS_NONE the term's own total. mslot:
** 1 + the slot of the body's entries in fixq.h's emap (for the row's
** element kind), or 0 (the entries are searched). k: the row constant
** for this sink, for a term whose kernel depends on the sink (ksink). */
typedef struct sink {
  tds_id body;
  int32_t mslot;
  double w;
  double k;
} sink;

#define MAX_SINKS 64 /* bodies around one edge, and the own total */

typedef struct term term;
/* Sinks of element el (facet or edge by the row's kind): count, 0 to skip
** the element, or -1 when there are more than MAX_SINKS. */
typedef int (*sink_fn)(const tds_surf *s, const term *t, tds_id el, sink *out);

struct term {
  const tds_method *row;
  sink_fn sinks;
  tds_mlocal L;   /* constants for the row; x is filled per element */
  int slot;       /* constraint or boundary slot, for the sink function */
  double w;       /* weight for the sink function (sign, modulus) */
  int ksink;      /* the kernel runs once per sink, with the sink's k */
  int32_t gq;     /* own total's gradient: -1 the energy gradient,
                     q >= 0 fixq quantity q, -2 none */
  double total;   /* out: sum of w * value to the own total */
  double sum;     /* out: sum of the unweighted values (total area) */
  int xkind;      /* element kind whose attributes the integrands read
                     (xattr.h), filled per element; -1 none */
};

/* Add w * h (the element Hessian) to the upper half of the global one
** (hess.h's index map; rows of vertices that cannot move are left out). */
void tds_eval_scatter_hess(tds_hess_acc *ha, const tds_id *vs, int kind, double w,
                           double (*h)[9]) {
  if (w == 0) return;
  if (ha->add) {
    ha->add(ha, vs, kind, w, h);
    return;
  }
  for (int c = 0; c < kind; c++) {
    int32_t r = ha->vidx[vs[c]];
    if (r < 0) continue;
    for (int d = 0; d < kind; d++) {
      int32_t k = ha->vidx[vs[d]];
      if (k < 0) continue;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          if ((ha->lower ? r + i >= k + j : r + i <= k + j) &&
              tds_sptrip_add(ha->trip, r + i, k + j, w * h[3 * c + i][3 * d + j]))
            ha->status = TDS_ENOMEM;
    }
  }
}

/* Scatter value v, gradient g and (h not NULL) Hessian h of term t on an
** element with corners vs to its sinks. */
static inline __attribute__((always_inline)) void
scatter(tds_surf *s, tds_eval_out *out, term *t, const tds_id *vs, int kind,
        const sink *sk, int ns, double v, double (*g)[3], double (*h)[9]) {
  tds_fixq *fq = out->fq;
  t->sum += v;
  for (int k = 0; k < ns; k++) {
    double w = sk[k].w;
    tds_id b = sk[k].body;
    int32_t q = b == TDS_NONE ? t->gq : fq && fq->bq[b] >= 0 ? fq->bq[b] : -2;
    if (b == TDS_NONE) t->total += w * v;
    else s->m.bvol[b] += w * v;
    if (q == -1)
      for (int c = 0; c < kind; c++) v3_axpy(out->grad[vs[c]], w, g[c]);
    else if (q >= 0) {
      const int32_t *mp =
          sk[k].mslot && fq->emap_kind == kind ? fq->emap + kind * (sk[k].mslot - 1) : NULL;
      for (int c = 0; c < kind; c++) {
        double gc[3] = {w * g[c][0], w * g[c][1], w * g[c][2]};
        if (mp) tds_fixq_add_at(fq, mp[c], q, gc);
        else tds_fixq_add(fq, vs[c], q, gc);
      }
    }
    if (out->hess) {
      tds_hess_acc *ha = out->hess;
      double hw = q == -1 ? ha->ew : q >= 0 && ha->qw ? ha->qw[q] : 0;
      tds_eval_scatter_hess(ha, vs, kind, w * hw, h);
    }
  }
}

/* Whether any sink needs the gradient. */
static inline int want_grad(const tds_eval_out *out, const term *t, const sink *sk, int ns) {
  int want = out->hess != NULL;
  for (int k = 0; k < ns; k++)
    want |= sk[k].body == TDS_NONE ? t->gq != -2 : out->fq && out->fq->bq[sk[k].body] >= 0;
  return want;
}

/* The assembly loop: for every live element of the kind, the sinks of
** term t0 (and t1, when not NULL), one gather, the row kernels, the
** scatter. Written once and instantiated (always_inline) with constant
** kernels and sink functions for the fused facet pass, and with the
** row's own for every other term. t1 shares t0's constants (L): only
** rows without integrands are fused; with t1->ksink its kernel runs per
** sink with L.k the sink's k (the torus's lifted volumes), so t0's row
** must read no k. TDS_OK or TDS_ERANGE (too many bodies on an edge).
** raw: the corners are the vertices' stored positions, wraps ignored
** (SYMMETRIC_CONTENT under the torus group). */
static inline __attribute__((always_inline)) int
assemble_k(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, int kind, term *t0,
           tds_mkernel k0, sink_fn f0, term *t1, tds_mkernel k1, sink_fn f1, int raw) {
  tds_mesh *m = &s->m;
  const tds_id n = kind == TDS_EL_FACET ? m->nf : m->ne;
  const uint32_t *flags = kind == TDS_EL_FACET ? m->fflags : m->eflags;
  tds_mlocal L = t0->L;
  sink sk0[MAX_SINKS], sk1[4]; /* a fused t1 (body volumes) has at most 4 */
  double g[3][3], h[9][9];
  double (*hp)[9] = out->hess ? h : NULL;
  for (tds_id el = 0; el < n; el++) {
    if (flags[el] & TDS_DEAD) continue;
    int n0 = f0(s, t0, el, sk0), n1 = t1 ? f1(s, t1, el, sk1) : 0;
    if (n0 == 0 && n1 == 0) continue;
    if (n0 < 0)
      return tds_seterr(ctx, TDS_ERANGE, "edge %d: more than %d bodies around it",
                        (int)el + 1, MAX_SINKS - 1);
    const tds_id *vs = kind == TDS_EL_FACET ? m->fv[el] : m->ev[el];
    tds_corners C;
    if (raw) /* the stored positions, wraps ignored */
      for (int c = 0; c < kind; c++) C.x[c] = m->x[vs[c]];
    else if (kind == TDS_EL_FACET)
      tds_gather_facet(m, el, &C);
    else
      tds_gather_edge(m, TDS_OREF(el, 0), &C);
    if (t0->xkind >= 0) tds_xattr_fill(s, t0->xkind, el);
    L.x[0] = C.x[0]; /* not a loop: gcc makes it a memcpy call per element */
    L.x[1] = C.x[1];
    if (kind == TDS_EL_FACET) L.x[2] = C.x[2];
    if (n0) {
      int want = want_grad(out, t0, sk0, n0);
      double v = k0(&L, want ? g : NULL, hp);
      if (want && tds_mesh_rotates(m)) tds_sym_pullback(m, kind, el, g, hp);
      scatter(s, out, t0, vs, kind, sk0, n0, v, g, hp);
    }
    if (n1 && t1->ksink) {
      for (int i = 0; i < n1; i++) {
        L.k = sk1[i].k;
        int want = want_grad(out, t1, sk1 + i, 1);
        double v = k1(&L, want ? g : NULL, hp);
        if (want && tds_mesh_rotates(m)) tds_sym_pullback(m, kind, el, g, hp);
        scatter(s, out, t1, vs, kind, sk1 + i, 1, v, g, hp);
      }
    } else if (n1) {
      int want = want_grad(out, t1, sk1, n1);
      double v = k1(&L, want ? g : NULL, hp);
      if (want && tds_mesh_rotates(m)) tds_sym_pullback(m, kind, el, g, hp);
      scatter(s, out, t1, vs, kind, sk1, n1, v, g, hp);
    }
  }
  return TDS_OK;
}

/* One term, any row. */
static int assemble(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, term *t) {
  return assemble_k(ctx, s, out, t->row->kind, t, t->row->eval, t->sinks, NULL, NULL, NULL, 0);
}

/* ---- sink functions ---- */

static inline __attribute__((always_inline)) int
s_tension(const tds_surf *s, const term *t, tds_id f, sink *o) {
  (void)t;
  o[0] = (sink){TDS_NONE, 0, s->m.ften[f], 0};
  return 1;
}

/* Body volumes: + for the front body, - for the back; with a prescribed
** pressure p the energy -p V as well. */
static inline __attribute__((always_inline)) int
s_volume(const tds_surf *s, const term *t, tds_id f, sink *o) {
  const tds_mesh *m = &s->m;
  (void)t;
  if (m->fflags[f] & TDS_NONCONTENT) return 0;
  int n = 0;
  double pw = 0;
  for (int j = 0; j < 2; j++) {
    tds_id b = m->fb[f][j];
    if (b == TDS_NONE) continue;
    double sign = j ? -1.0 : 1.0;
    o[n++] = (sink){b, 2 * f + j + 1, sign, 0};
    if (m->bflags[b] & TDS_PRESSURE) pw -= sign * m->bpressure[b];
  }
  if (pw != 0) o[n++] = (sink){TDS_NONE, 0, pw, 0};
  return n;
}

/* Gravity: G density int z dV per body, as the flux of (0, 0, z^2/2). */
static int s_gravity(const tds_surf *s, const term *t, tds_id f, sink *o) {
  const tds_mesh *m = &s->m;
  (void)t;
  if (m->fflags[f] & TDS_NONCONTENT) return 0;
  double w = 0;
  if (m->fb[f][0] != TDS_NONE) w += m->bdensity[m->fb[f][0]];
  if (m->fb[f][1] != TDS_NONE) w -= m->bdensity[m->fb[f][1]];
  o[0] = (sink){TDS_NONE, 0, s->gravity * w, 0};
  return w != 0;
}

static inline __attribute__((always_inline)) int
s_edge_tension(const tds_surf *s, const term *t, tds_id e, sink *o) {
  (void)t;
  o[0] = (sink){TDS_NONE, 0, s->m.eten[e], 0};
  return s->m.eten[e] != 0;
}

static double conrev(const tds_mesh *m, tds_id e) {
  return (m->eflags[e] & TDS_CONREV) ? -1 : 1;
}

static int on_con(const tds_mesh *m, const term *t, tds_id e) {
  return (m->econ[e] & ((tds_cmask)1 << t->slot)) && !(m->eflags[e] & TDS_FIXED);
}

static int s_con_energy(const tds_surf *s, const term *t, tds_id e, sink *o) {
  if (!on_con(&s->m, t, e)) return 0;
  o[0] = (sink){TDS_NONE, 0, conrev(&s->m, e), 0};
  return 1;
}

static int s_gap(const tds_surf *s, const term *t, tds_id e, sink *o) {
  if (!on_con(&s->m, t, e)) return 0;
  o[0] = (sink){TDS_NONE, 0, 1, 0};
  return 1;
}

/* The bodies of the facets around edge e with their content signs: + for
** a facet that uses the edge forwards and its front body (Evolver's rule),
** flipped for reversed use or back bodies, times w. Merged per body. */
static int edge_bodies(const tds_mesh *m, tds_id e, double w, sink *o) {
  int32_t h = m->eside[e];
  if (h == TDS_NONE) return 0;
  int n = 0;
  int32_t sd = h;
  do {
    tds_id f = sd / 3;
    double or = TDS_OREV(m->fe[f][sd % 3]) ? -1 : 1;
    for (int j = 0; j < 2; j++) {
      tds_id b = m->fb[f][j];
      if (b == TDS_NONE) continue;
      double sg = (j ? -or : or) * w;
      int k = 0;
      while (k < n && o[k].body != b) k++;
      if (k == n) {
        if (n == MAX_SINKS) return -1;
        o[n++] = (sink){b, 0, 0, 0};
      }
      o[k].w += sg;
    }
    sd = m->side_next[sd];
  } while (sd != h);
  return n;
}

/* Constraint content adds to the bodies with edge_bodies' signs; boundary
** content the other way round (Evolver's convention, checked against
** evolver-nox-d on column.fe and a test body). */
static int s_con_content(const tds_surf *s, const term *t, tds_id e, sink *o) {
  if (!on_con(&s->m, t, e)) return 0;
  return edge_bodies(&s->m, e, conrev(&s->m, e), o);
}

static int s_bdry_energy(const tds_surf *s, const term *t, tds_id e, sink *o) {
  if (s->m.ebdry[e] != (tds_id)t->slot) return 0;
  o[0] = (sink){TDS_NONE, 0, conrev(&s->m, e), 0};
  return 1;
}

static int s_bdry_content(const tds_surf *s, const term *t, tds_id e, sink *o) {
  if (s->m.ebdry[e] != (tds_id)t->slot) return 0;
  return edge_bodies(&s->m, e, -conrev(&s->m, e), o);
}

/* A named quantity's method instance: every live element (Evolver's
** GLOBAL), weight modulus x instance modulus. */
static int s_quantity(const tds_surf *s, const term *t, tds_id el, sink *o) {
  (void)s;
  (void)el;
  o[0] = (sink){TDS_NONE, 0, t->w, 0};
  return 1;
}

/* Rows flagged TDS_MF_DENSITY (gravity_method, full_gravity_method): the
** density difference of the facet's bodies (times G with TDS_MF_TIMES_G). */
static int s_quantity_density(const tds_surf *s, const term *t, tds_id f, sink *o) {
  const tds_mesh *m = &s->m;
  double rho = 0;
  if (m->fb[f][0] != TDS_NONE) rho += m->bdensity[m->fb[f][0]];
  if (m->fb[f][1] != TDS_NONE) rho -= m->bdensity[m->fb[f][1]];
  if (t->row->flags & TDS_MF_TIMES_G) rho *= s->gravity_on ? s->gravity : 0;
  o[0] = (sink){TDS_NONE, 0, t->w * rho, 0};
  return rho != 0;
}

/* ---- the terms of a surface ---- */

/* The element kind whose attributes integrands ig of row read, or -1. */
static int ig_xkind(const tds_method *row, tds_expr *const *ig) {
  int n = !ig ? 0 : (row->flags & TDS_MF_VECTOR) ? 3 : (row->flags & TDS_MF_METRIC) ? 9
          : (row->flags & (TDS_MF_SCALAR | TDS_MF_FORMULA)) ? 1 : 0;
  for (int i = 0; i < n; i++)
    if (ig[i] && tds_expr_uses_attrs(ig[i]))
      return row->kind == TDS_EL_FACET ? TDS_FACET : TDS_EDGE;
  return -1;
}

static term make(const tds_surf *s, int row, sink_fn fn, tds_expr *const *ig, int npts) {
  term t = {.row = &tds_methods[row], .sinks = fn, .gq = -1, .w = 1};
  t.xkind = ig_xkind(t.row, ig);
  t.L.ig = ig;
  t.L.npts = npts;
  t.L.param = s->parval;
  t.L.G = s->gravity_on ? s->gravity : 0;
  return t;
}

/* Torus lifts (torus.h), symmetric content: the facet's volume
** translated by its body's lattice translation t exceeds the
** untranslated one by t_d / 3 times the facet_flux row with d; t->slot is
** d. Weighted as s_volume weights the volume, with the energy -p of a
** prescribed pressure. */
static int s_torus_lift(const tds_surf *s, const term *t, tds_id f, sink *o) {
  const tds_mesh *m = &s->m;
  if (m->fflags[f] & TDS_NONCONTENT) return 0;
  int n = 0;
  double pw = 0;
  for (int j = 0; j < 2; j++) {
    tds_id b = m->fb[f][j];
    int32_t w = s->tlift[2 * f + j];
    if (b == TDS_NONE || !w) continue;
    double tv[3];
    tds_wrap_vec(m->period, w, tv);
    double c = tv[t->slot] * t->w * (j ? -1.0 : 1.0);
    if (c == 0) continue;
    o[n++] = (sink){b, 2 * f + j + 1, c, 0};
    if (m->bflags[b] & TDS_PRESSURE) pw -= c * m->bpressure[b];
  }
  if (pw != 0) o[n++] = (sink){TDS_NONE, 0, pw, 0};
  return n;
}

/* Torus lifts (torus.h), z content: s_volume's sinks, each with the z
** of its body's lattice translation of the facet as k for
** tds_mk_volume_zshift (the facet's int z dx dy translated by t is its
** own plus t_z N_z / 2, and only t_z matters). Every side gets its sinks
** whether lifted or not: on a foam 40% of the facets are, in no order a
** branch could predict. */
static inline __attribute__((always_inline)) int
s_volume_lift(const tds_surf *s, const term *t, tds_id f, sink *o) {
  const tds_mesh *m = &s->m;
  (void)t;
  if (m->fflags[f] & TDS_NONCONTENT) return 0;
  int n = 0;
  for (int j = 0; j < 2; j++) {
    tds_id b = m->fb[f][j];
    if (b == TDS_NONE) continue;
    int k[3];
    tds_wrap_unpack(s->tlift[2 * f + j], k);
    double tz = k[0] * m->period[0][2] + k[1] * m->period[1][2] + k[2] * m->period[2][2];
    double sign = j ? -1.0 : 1.0;
    o[n++] = (sink){b, 2 * f + j + 1, sign, tz};
    if (m->bflags[b] & TDS_PRESSURE) o[n++] = (sink){TDS_NONE, 0, -sign * m->bpressure[b], tz};
  }
  return n;
}

/* Run t and add its own total to the energy. */
static int energy_term(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, term t) {
  if (!out->grad) t.gq = -2;
  int rc = assemble(ctx, s, out, &t);
  out->energy += t.total;
  return rc;
}

static int has_any(tds_expr *const e[3]) { return e[0] || e[1] || e[2]; }

/* Facet tension, body volumes, pressures and gravity. Tension and volume
** run fused (one gather per facet), the kernels compiled into the loop:
** the hot path of every iteration. */
static int facet_terms(tds_ctx *ctx, tds_surf *s, tds_eval_out *out) {
  term ten = make(s, TDS_M_FACET_AREA, s_tension, NULL, 0);
  int sym = s->symmetric_content;
  term vol = make(s, sym ? TDS_M_FACET_VOLUME_SYM : TDS_M_FACET_VOLUME, s_volume, NULL, 0);
  if (!out->grad) ten.gq = vol.gq = -2;
  /* SYMMETRY_GROUP: Evolver's Euclidean volumes, each facet's integral
  ** where its corners are gathered (no lifts; model.htm) */
  int lifts = s->m.torus && !s->m.sym && s->m.nb > 0;
  if (lifts) {
    int bad = tds_torus_lifts(ctx, s);
    if (bad < 0) return -bad;
  }
  int rc;
  if (s->klein) {
    /* KLEIN_METRIC: hyperbolic facet areas; volumes stay Euclidean, as in
    ** Evolver (measured: a tetrahedron's body reads its Euclidean volume),
    ** gathered as under the other groups (no torus here: datafile) */
    ten = make(s, TDS_M_KLEIN_AREA, s_tension, NULL, 0);
    if (!out->grad) ten.gq = -2;
    rc = assemble_k(ctx, s, out, TDS_EL_FACET, &ten, tds_mk_klein_area, s_tension,
                    s->m.nb ? &vol : NULL, sym ? tds_mk_volume_sym : tds_mk_volume, s_volume, 0);
  } else if (s->m.nb == 0) {
    rc = assemble_k(ctx, s, out, TDS_EL_FACET, &ten, tds_mk_area, s_tension, NULL, NULL, NULL, 0);
  } else if (sym && s->m.sym == TDS_SYM_TORUS) {
    /* Evolver 2.70's symmetric content under SYMMETRY_GROUP "torus": each
    ** facet's (x,y,z)/3 flux from its vertices' stored positions, the
    ** wraps ignored (measured on symtest.fe and skewed, perturbed copies:
    ** tests/evolver/symmetry.sh); under the other groups the facets are
    ** gathered as for every other term */
    rc = assemble_k(ctx, s, out, TDS_EL_FACET, &ten, tds_mk_area, s_tension, NULL, NULL, NULL, 0);
    if (rc == TDS_OK)
      rc = assemble_k(ctx, s, out, TDS_EL_FACET, &vol, tds_mk_volume_sym, s_volume, NULL, NULL,
                      NULL, 1);
  } else if (sym) {
    rc = assemble_k(ctx, s, out, TDS_EL_FACET, &ten, tds_mk_area, s_tension, &vol,
                    tds_mk_volume_sym, s_volume, 0);
  } else if (lifts && !out->hess && tds_eval_torus_facets(s, out)) {
    rc = TDS_OK; /* the same, specialised (eval_torus.c); ten, vol stay 0 */
  } else if (lifts) { /* each body's volume of the facet lifted (torus.h) */
    vol.ksink = 1;
    rc = assemble_k(ctx, s, out, TDS_EL_FACET, &ten, tds_mk_area, s_tension, &vol,
                    tds_mk_volume_zshift, s_volume_lift, 0);
  } else {
    rc = assemble_k(ctx, s, out, TDS_EL_FACET, &ten, tds_mk_area, s_tension, &vol,
                    tds_mk_volume, s_volume, 0);
  }
  out->energy += ten.total + vol.total;
  out->area += ten.sum;
  /* symmetric content: the lifts' fluxes t . N / 6, a pass per direction */
  for (int d = 0; lifts && sym && d < 3 && rc == TDS_OK; d++) {
    term t = make(s, TDS_M_FACET_FLUX, s_torus_lift, NULL, 0);
    t.slot = d;
    t.L.k = d;
    t.w = 1.0 / 3;
    rc = energy_term(ctx, s, out, t);
  }
  if (rc == TDS_OK && s->gravity_on && s->gravity != 0 && s->m.nb > 0)
    rc = energy_term(ctx, s, out, make(s, TDS_M_FULL_GRAVITY, s_gravity, NULL, 0));
  return rc;
}

/* The energy and content integrands of constraint or boundary `slot`
** (edge_vector_integral rows; NULL components are 0), each with its sink
** function and quadrature (npts[0] energy, npts[1] content). */
static int integrand_terms(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, int slot,
                           tds_expr *const energy[3], tds_expr *const content[3],
                           const int npts[2], sink_fn fe, sink_fn fc) {
  tds_expr *const *ig[2] = {energy, content};
  const sink_fn fn[2] = {fe, fc};
  int rc = TDS_OK;
  for (int k = 0; k < 2 && rc == TDS_OK; k++) {
    if (!has_any(ig[k])) continue;
    term t = make(s, TDS_M_EDGE_VECTOR_INTEGRAL, fn[k], ig[k], npts[k]);
    t.slot = slot;
    rc = energy_term(ctx, s, out, t);
  }
  return rc;
}

/* ---- the string model (string_model.h) ---- */

/* Edge e's body weights from the cells' loops, times w; with `pressure`
** also the energy -p A of bodies with a prescribed pressure. */
static inline __attribute__((always_inline)) int
str_bodies(const tds_surf *s, tds_id e, double w, int pressure, sink *o) {
  const tds_strings *st = s->str;
  const tds_mesh *m = &s->m;
  int n = 0;
  double pw = 0;
  for (int32_t k = st->eb_start[e]; k < st->eb_start[e + 1]; k++) {
    if (n == MAX_SINKS - 1) return -1;
    tds_id b = st->eb_body[k];
    o[n++] = (sink){b, k + 1, w * st->eb_w[k], 0};
    if (pressure && (m->bflags[b] & TDS_PRESSURE)) pw -= w * st->eb_w[k] * m->bpressure[b];
  }
  if (pw != 0) o[n++] = (sink){TDS_NONE, 0, pw, 0};
  return n;
}

static inline __attribute__((always_inline)) int
s_str_area(const tds_surf *s, const term *t, tds_id e, sink *o) {
  (void)t;
  return str_bodies(s, e, 1, 1, o);
}

/* Torus: the lattice lifts of the cells' loops (string_model.h's
** eb_lift), weights (-t_y) of the edge_shift row with k = 0 (x1 - x0). */
static int s_str_lift(const tds_surf *s, const term *t, tds_id e, sink *o) {
  const tds_strings *st = s->str;
  const tds_mesh *m = &s->m;
  (void)t;
  int n = 0;
  double pw = 0;
  for (int32_t k = st->eb_start[e]; k < st->eb_start[e + 1]; k++) {
    double c = -st->eb_lift[k];
    if (c == 0) continue;
    if (n == MAX_SINKS - 1) return -1;
    tds_id b = st->eb_body[k];
    o[n++] = (sink){b, k + 1, c, 0};
    if (m->bflags[b] & TDS_PRESSURE) pw -= c * m->bpressure[b];
  }
  if (pw != 0) o[n++] = (sink){TDS_NONE, 0, pw, 0};
  return n;
}

/* G density int int y dA per body, from the same weights. */
static int s_str_gravity(const tds_surf *s, const term *t, tds_id e, sink *o) {
  const tds_strings *st = s->str;
  (void)t;
  double w = 0;
  for (int32_t k = st->eb_start[e]; k < st->eb_start[e + 1]; k++)
    w += st->eb_w[k] * s->m.bdensity[st->eb_body[k]];
  o[0] = (sink){TDS_NONE, 0, s->gravity * w, 0};
  return w != 0;
}

/* Constraint content at the ends of the cells' edges: + at an edge's head
** on the constraint, - at its tail (so the ends of a loop that stops on a
** constraint remain, Evolver's string-model content). */
static int on_vcon(const tds_surf *s, const term *t, tds_id v) {
  return (s->m.vcon[v] & ((tds_cmask)1 << t->slot)) != 0;
}
static int s_str_head(const tds_surf *s, const term *t, tds_id e, sink *o) {
  if (!on_vcon(s, t, s->m.ev[e][1])) return 0;
  return str_bodies(s, e, 1, 0, o);
}
static int s_str_tail(const tds_surf *s, const term *t, tds_id e, sink *o) {
  if (!on_vcon(s, t, s->m.ev[e][0])) return 0;
  return str_bodies(s, e, -1, 0, o);
}

/* Body areas, pressures, gravity and constraint contents of the string
** model; with `tension` also the edges' tension (plain lengths), in the
** areas' pass. */
static int string_terms(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, int tension) {
  int rc = tds_strings_index(ctx, s);
  if (rc != TDS_OK) return rc;
  tds_fixq *fq = out->fq;
  if (fq && fq->emap_kind == TDS_EL_EDGE &&
      (fq->emap_gen != s->str->idx_gen || fq->emap_topo != s->str->idx_topo ||
       fq->emap_ne != s->str->idx_ne))
    fq->emap_kind = 0; /* the index was made again: search */
  if (s->m.nb == 0)
    return tension ? energy_term(ctx, s, out, make(s, TDS_M_EDGE_LENGTH, s_edge_tension, NULL, 0))
                   : TDS_OK;
  term area = make(s, TDS_M_EDGE_AREA, s_str_area, NULL, 0);
  if (tension) { /* fused with the areas: one gather per edge */
    term ten = make(s, TDS_M_EDGE_LENGTH, s_edge_tension, NULL, 0);
    if (!out->grad) area.gq = ten.gq = -2;
    rc = assemble_k(ctx, s, out, TDS_EL_EDGE, &area, tds_mk_edge_area, s_str_area, &ten,
                    tds_mk_length, s_edge_tension, 0);
    out->energy += ten.total + area.total;
  } else {
    rc = energy_term(ctx, s, out, area);
  }
  if (rc == TDS_OK && s->m.torus && s->str->eb_lift) {
    term t = make(s, TDS_M_EDGE_SHIFT, s_str_lift, NULL, 0);
    t.L.k = 0; /* x1 - x0: a shift t_y changes -(y0 + y1) dx / 2 by -t_y dx */
    rc = energy_term(ctx, s, out, t);
  }
  if (rc == TDS_OK && s->gravity_on && s->gravity != 0)
    rc = energy_term(ctx, s, out, make(s, TDS_M_STRING_GRAVITY, s_str_gravity, NULL, 0));
  for (int c = 0; c < TDS_MAX_CON && rc == TDS_OK; c++) {
    const tds_constraint *con = &s->con[c];
    if (!con->number || !con->content[0]) continue;
    term th = make(s, TDS_M_VERTEX_HEAD, s_str_head, con->content, 0);
    term tt = make(s, TDS_M_VERTEX_TAIL, s_str_tail, con->content, 0);
    th.slot = tt.slot = c;
    rc = energy_term(ctx, s, out, th);
    if (rc == TDS_OK) rc = energy_term(ctx, s, out, tt);
  }
  return rc;
}

/* Edge tension, constraint and boundary integrals, gap energy. */
static int edge_terms(tds_ctx *ctx, tds_surf *s, tds_eval_out *out) {
  int rc = TDS_OK;
  int anyten = 0;
  /* in blocks without a branch per edge, on the bits (so that it
  ** vectorises): x != 0 exactly when x's bits other than the sign are not
  ** all 0 (NaN included). Foams have no edge tension: every edge is read */
  for (tds_id e0 = 0; e0 < s->m.ne && !anyten; e0 += 256) {
    tds_id e1 = s->m.ne - e0 > 256 ? e0 + 256 : s->m.ne;
    uint64_t any = 0;
    for (tds_id e = e0; e < e1; e++) {
      uint64_t u;
      memcpy(&u, &s->m.eten[e], sizeof u);
      any |= u << 1;
    }
    anyten = any != 0;
  }
  if (anyten && s->klein) /* KLEIN_METRIC: hyperbolic lengths */
    rc = energy_term(ctx, s, out, make(s, TDS_M_KLEIN_LENGTH, s_edge_tension, NULL, 0));
  else if (anyten && s->metric_on) /* METRIC: lengths in the metric */
    rc = energy_term(ctx, s, out, make(s, TDS_M_METRIC_LENGTH, s_edge_tension, s->metric, 0));
  else if (anyten && s->str) /* string_terms: fused with the cells' areas */
    return string_terms(ctx, s, out, 1);
  else if (anyten)
    rc = energy_term(ctx, s, out, make(s, TDS_M_EDGE_LENGTH, s_edge_tension, NULL, 0));
  if (s->str) return rc == TDS_OK ? string_terms(ctx, s, out, 0) : rc;
  for (int c = 0; c < TDS_MAX_CON && rc == TDS_OK; c++) {
    const tds_constraint *con = &s->con[c];
    if (!con->number) continue;
    rc = integrand_terms(ctx, s, out, c, con->energy, con->content, con->npts, s_con_energy,
                         s_con_content);
    if (rc == TDS_OK && (con->flags & TDS_CON_CONVEX) && con->formula && s->gap_constant != 0) {
      term t = make(s, TDS_M_EDGE_GAP, s_gap, &con->formula, 0);
      t.slot = c;
      t.L.k = s->gap_constant;
      rc = energy_term(ctx, s, out, t);
    }
  }
  for (int b = 0; b < s->nbdry && rc == TDS_OK; b++) {
    const tds_boundary *B = &s->bdry[b];
    rc = integrand_terms(ctx, s, out, b, B->energy, B->content, B->npts, s_bdry_energy,
                         s_bdry_content);
  }
  return rc;
}

/* Named quantities: value = modulus * (sum of instance modulus * method
** value + volconst), as Evolver has it. ENERGY ones add to the energy (and its gradient),
** FIXED ones fill their fixq gradient (their q indices follow the
** bodies'), INFO_ONLY ones are only reported. */
static int quantity_terms(tds_ctx *ctx, tds_surf *s, tds_eval_out *out) {
  int32_t qfixed = 0; /* fixq index of the next FIXED quantity */
  if (out->fq)
    while (qfixed < out->fq->nq && out->fq->qbody[qfixed] != TDS_NONE) qfixed++;
  for (int i = 0; i < s->nquant; i++) {
    tds_quantity *Q = &s->quant[i];
    int32_t gq = -2;
    if (Q->kind == TDS_Q_FIXED && out->fq) gq = qfixed++;
    else if (Q->kind == TDS_Q_ENERGY && out->grad) gq = -1;
    double v = 0;
    for (int j = 0; j < Q->ninst; j++) {
      const tds_method_inst *mi = &Q->inst[j];
      if (mi->modulus == 0 || Q->modulus == 0) continue;
      if (tds_methods[mi->method].iter != TDS_IT_ELEMENT) {
        double tot = 0;
        int rc = tds_eval_global_row(ctx, s, out, mi->method, Q->modulus * mi->modulus, gq,
                                     &tot);
        if (rc != TDS_OK) return rc;
        v += tot;
        continue;
      }
      int dens = tds_methods[mi->method].flags & TDS_MF_DENSITY;
      term t = make(s, mi->method, dens ? s_quantity_density : s_quantity, mi->integrand,
                    mi->npts);
      t.w = Q->modulus * mi->modulus;
      t.gq = gq;
      int rc = assemble(ctx, s, out, &t);
      if (rc != TDS_OK) return rc;
      v += t.total;
    }
    Q->value = v + Q->modulus * Q->volconst;
    if (Q->kind == TDS_Q_ENERGY) out->energy += Q->value;
    if (gq >= 0) out->fq->value[gq] = Q->value;
  }
  return TDS_OK;
}

int tds_eval_terms(tds_ctx *ctx, tds_surf *s, tds_eval_out *out, int facet_core) {
  int rc = facet_core ? facet_terms(ctx, s, out) : TDS_OK;
  if (rc == TDS_OK) rc = edge_terms(ctx, s, out);
  if (rc == TDS_OK) rc = quantity_terms(ctx, s, out);
  if (rc != TDS_OK) return rc;
  if (out->fq)
    for (int32_t q = 0; q < out->fq->nq; q++) {
      tds_id b = out->fq->qbody[q];
      if (b != TDS_NONE) out->fq->value[q] = s->m.bvol[b];
    }
  if (!isfinite(out->energy))
    return tds_seterr(ctx, TDS_ENUM, "energy is not finite (%s)",
                      isnan(out->energy) ? "NaN" : out->energy > 0 ? "inf" : "-inf");
  /* a volume can be NaN with a finite energy (a constraint's content
  ** integrand at a point where it is not defined) */
  for (tds_id b = 0; b < s->m.nb; b++)
    if (tds_alive(s->m.bflags, b) && !isfinite(s->m.bvol[b]))
      return tds_seterr(ctx, TDS_ENUM, "body %d: volume is not finite (%s)", (int)b + 1,
                        isnan(s->m.bvol[b]) ? "NaN" : s->m.bvol[b] > 0 ? "inf" : "-inf");
  return TDS_OK;
}

/* The total edge length of a string surface (in the metric with METRIC). */
static double string_length(const tds_surf *s) {
  const tds_mesh *m = &s->m;
  double sum = 0;
  for (tds_id e = 0; e < m->ne; e++) {
    if (m->eflags[e] & TDS_DEAD) continue;
    tds_corners C;
    tds_gather_edge(m, TDS_OREF(e, 0), &C);
    if (s->klein) {
      sum += tds_klein_dist(C.x[0], C.x[1]);
    } else if (s->metric_on) {
      tds_mlocal L = {.x = {C.x[0], C.x[1]}, .ig = s->metric, .param = s->parval,
                      .G = s->gravity_on ? s->gravity : 0};
      sum += tds_methods[TDS_M_METRIC_LENGTH].eval(&L, NULL, NULL);
    } else {
      double d[3];
      v3_sub(d, C.x[1], C.x[0]);
      sum += v3_norm(d);
    }
  }
  return sum;
}

int tds_eval(tds_ctx *ctx, tds_surf *s, tds_eval_out *out) {
  tds_mesh *m = &s->m;
  out->energy = 0;
  out->area = 0;
  if (out->grad) memset(out->grad, 0, (size_t)m->nv * sizeof *out->grad);
  if (out->fq) tds_fixq_clear(out->fq);
  for (tds_id b = 0; b < m->nb; b++)
    m->bvol[b] = (m->bflags[b] & TDS_DEAD) ? 0 : m->bvolconst[b];
  return tds_eval_terms(ctx, s, out, 1);
}

double tds_surf_area(const tds_surf *s) {
  return s->str ? string_length(s) : s->area;
}

int tds_surf_update(tds_ctx *ctx, tds_surf *s) {
  tds_eval_out out = {0};
  int rc = tds_eval(ctx, s, &out);
  s->energy = out.energy;
  s->area = out.area;
  if (s->str) s->area = string_length(s);
  return rc;
}
