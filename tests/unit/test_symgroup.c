/* test_symgroup.c: the algebra of Evolver's built-in symmetry groups
** (symgroup.h) on random elements of every group: the product is the
** composition of the isometries (b first, then a), inverses undo,
** products associate, codes round-trip, and every element is an
** isometry. (What each code means is compared with Evolver in
** tests/evolver/symmetry.sh.) */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "symgroup.h"

typedef struct {
  int id;
  double p[2];
  int lo, hi; /* random codes from [lo, hi) (cubelat and quarter_turn: built) */
} grp;

static const grp groups[] = {
    {TDS_SYM_ROTATE, {6, 1}, -20, 20},       {TDS_SYM_ROTATE, {5, 2}, -20, 20},
    {TDS_SYM_FLIP_ROTATE, {8, 1}, -20, 20},  {TDS_SYM_CUBOCTA, {0, 0}, 0, 64},
    {TDS_SYM_XYZ, {0, 0}, -9, 64},           {TDS_SYM_CUBELAT, {0, 0}, 0, 0},
    {TDS_SYM_CENTRAL, {0, 0}, 0, 2},         {TDS_SYM_SCREW, {0.7, 50}, -30, 30},
    {TDS_SYM_QUARTER_TURN, {1.3, 0}, 0, 0},
};

/* A random element of g (its internal code). */
static int32_t rand_elem(const grp *g, uint64_t *st) {
  double code;
  if (g->id == TDS_SYM_CUBELAT || g->id == TDS_SYM_QUARTER_TURN) {
    code = g->id == TDS_SYM_CUBELAT ? floor(h_uniform(st, 0, 64)) : 0;
    for (int i = 0; i < 3; i++) { /* counts -3..3 in 6-bit fields */
      int k = (int)floor(h_uniform(st, -3, 4));
      code += (double)((unsigned)k & 31u) * pow(64, i + (g->id == TDS_SYM_CUBELAT));
    }
  } else {
    code = floor(h_uniform(st, g->lo, g->hi));
  }
  int32_t w = 0;
  CHECK(tds_sym_from_code(g->id, g->p, code, &w) == TDS_OK);
  return w;
}

/* |(A, s) x - (B, t) x| over a few points: 0 when the maps agree. */
static double map_diff(const double A[3][3], const double s[3], const double B[3][3],
                       const double t[3]) {
  static const double xs[3][3] = {{0.3, -1.2, 2.0}, {1, 0, 0}, {-0.7, 0.4, 1.1}};
  double d = 0;
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 3; i++) {
      double a = s[i], b = t[i];
      for (int j = 0; j < 3; j++) a += A[i][j] * xs[k][j], b += B[i][j] * xs[k][j];
      d = fmax(d, fabs(a - b));
    }
  return d;
}

static void group_laws(void) {
  uint64_t st = 11;
  for (size_t gi = 0; gi < sizeof groups / sizeof groups[0]; gi++) {
    const grp *g = &groups[gi];
    for (int t = 0; t < 300; t++) {
      int32_t a = rand_elem(g, &st), b = rand_elem(g, &st), c = rand_elem(g, &st);
      double Ra[3][3], ta[3], Rb[3][3], tb[3], Rab[3][3], tab[3], R0[3][3], t0[3];
      tds_sym_affine(g->id, g->p, NULL, a, Ra, ta);
      tds_sym_affine(g->id, g->p, NULL, b, Rb, tb);
      tds_sym_affine(g->id, g->p, NULL, tds_sym_mul(g->id, g->p, a, b), Rab, tab);
      /* (a b) x = a (b x) = Ra Rb x + Ra tb + ta */
      double C[3][3], u[3];
      for (int i = 0; i < 3; i++) {
        u[i] = ta[i];
        for (int j = 0; j < 3; j++) {
          C[i][j] = Ra[i][0] * Rb[0][j] + Ra[i][1] * Rb[1][j] + Ra[i][2] * Rb[2][j];
          u[i] += Ra[i][j] * tb[j];
        }
      }
      CHECK(map_diff(Rab, tab, C, u) < 1e-12);
      /* Ra is orthogonal */
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          CHECK(fabs(Ra[0][i] * Ra[0][j] + Ra[1][i] * Ra[1][j] + Ra[2][i] * Ra[2][j] - (i == j)) <
                1e-14);
      CHECK(tds_sym_mul(g->id, g->p, a, tds_sym_inv(g->id, g->p, a)) == 0);
      CHECK(tds_sym_mul(g->id, g->p, tds_sym_inv(g->id, g->p, a), a) == 0);
      CHECK(tds_sym_mul(g->id, g->p, tds_sym_mul(g->id, g->p, a, b), c) ==
            tds_sym_mul(g->id, g->p, a, tds_sym_mul(g->id, g->p, b, c)));
      tds_sym_affine(g->id, g->p, NULL, 0, R0, t0); /* 0 is the identity */
      double I[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, z[3] = {0, 0, 0};
      CHECK(map_diff(R0, t0, I, z) == 0);
      int32_t back = -1;
      CHECK(tds_sym_from_code(g->id, g->p, tds_sym_code(g->id, a), &back) == TDS_OK && back == a);
    }
  }
}

/* GENUS2 (symgroup_g2.c): the generators are Lorentz transformations
** (M^T diag(1,1,1,-1) M = the same), G_0 ... G_7 = 1, G_(k+4) = G_k^-1,
** the 49 canonical elements are distinct, products and inverses agree
** with the matrices (or are TDS_SYM_OUTSIDE), codes round-trip, and the
** action's Jacobian and second derivatives agree with central
** differences (step 1e-5: error ~1e-10 relative to entries of order 1..100;
** tolerance 1e-7 relative). */
static void genus2_laws(void) {
  const int id = TDS_SYM_GENUS2;
  double p[2] = {0, 0};
  int32_t el[49];
  int ne = 0;
  el[ne++] = 0;
  for (int a = 0; a < 8; a++)
    for (int len = 1; len < 7; len++) {
      int32_t w = 0;
      CHECK(tds_sym_from_code(id, p, a + 16 * ((a + len) % 8), &w) == TDS_OK);
      el[ne++] = w;
    }
  CHECK(ne == 49);
  double M[49][4][4];
  for (int i = 0; i < ne; i++) {
    tds_g2_matrix(el[i], M[i]);
    /* Lorentz: M^T eta M = eta */
    double worst = 0, big = 0;
    for (int r = 0; r < 4; r++)
      for (int c = 0; c < 4; c++) {
        double v = 0;
        for (int k = 0; k < 4; k++) v += (k == 3 ? -1 : 1) * M[i][k][r] * M[i][k][c];
        worst = fmax(worst, fabs(v - (r == c ? (r == 3 ? -1 : 1) : 0)));
        big = fmax(big, fabs(M[i][r][c]));
      }
    if (!(worst < 1e-14 * big * big)) printf("  element %d: Lorentz error %g (entries %g)\n", (int)el[i], worst, big);
    CHECK(worst < 1e-14 * big * big);
    for (int j = 0; j < i; j++) CHECK(el[i] != el[j]);
  }
  /* the relation and the inverses */
  int32_t w = 0, g0 = 0;
  CHECK(tds_sym_from_code(id, p, 0x10, &g0) == TDS_OK);
  for (int k = 0; k < 8; k++) {
    int32_t gk = 0, gk4 = 0;
    CHECK(tds_sym_from_code(id, p, k + 16 * ((k + 1) % 8), &gk) == TDS_OK);
    CHECK(tds_sym_from_code(id, p, (k + 4) % 8 + 16 * ((k + 5) % 8), &gk4) == TDS_OK);
    CHECK(tds_sym_inv(id, p, gk) == gk4);
    w = tds_sym_mul(id, p, w, gk);
  }
  CHECK(w == 0);
  CHECK(tds_sym_code(id, g0) == 0x10);
  /* products against the matrices */
  int named = 0, outside = 0;
  for (int i = 0; i < ne; i++) {
    CHECK(tds_sym_mul(id, p, el[i], tds_sym_inv(id, p, el[i])) == 0);
    for (int j = 0; j < ne; j++) {
      int32_t c = tds_sym_mul(id, p, el[i], el[j]);
      if (c == TDS_SYM_OUTSIDE) {
        outside++;
        continue;
      }
      named++;
      double P[4][4], C[4][4], d = 0, big = 0;
      tds_g2_matrix(c, C);
      for (int r = 0; r < 4; r++)
        for (int k = 0; k < 4; k++) {
          P[r][k] = 0;
          for (int l = 0; l < 4; l++) P[r][k] += M[i][r][l] * M[j][l][k];
          d = fmax(d, fabs(P[r][k] - C[r][k]));
          big = fmax(big, fabs(P[r][k]));
        }
      CHECK(d < 1e-10 * big);
      int32_t back = -1;
      CHECK(tds_sym_from_code(id, p, tds_sym_code(id, c), &back) == TDS_OK && back == c);
    }
  }
  CHECK(named > 49 * 2 && outside > 0);
  /* codes: 0..255 only, the nibbles mod 8 as Evolver reads them */
  CHECK(tds_sym_from_code(id, p, 256, &w) == TDS_ERANGE);
  CHECK(tds_sym_from_code(id, p, -1, &w) == TDS_ERANGE);
  CHECK(tds_sym_from_code(id, p, 0.5, &w) == TDS_ERANGE);
  CHECK(tds_sym_from_code(id, p, 0x98, &w) == TDS_OK && w == 0x10);
  CHECK(tds_sym_from_code(id, p, 0x01, &w) == TDS_OK && w == 0x54); /* G_1 ... G_7 = G_4 */
  CHECK(tds_sym_mul(id, p, TDS_SYM_OUTSIDE, 0) == TDS_SYM_OUTSIDE);
  /* derivatives of the action */
  uint64_t st = 5;
  for (int t = 0; t < 200; t++) {
    int32_t g = el[1 + (int)floor(h_uniform(&st, 0, 48))];
    double x[3] = {h_uniform(&st, -0.6, 0.6), h_uniform(&st, -0.6, 0.6), h_uniform(&st, -0.3, 0.3)};
    double y[3], J[3][3], T[3][3][3], h = 1e-5;
    tds_sym_jacobian(id, p, NULL, g, x, y, J, T);
    for (int k = 0; k < 3; k++) {
      double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, yp[3], ym[3], Jp[3][3], Jm[3][3];
      xp[k] += h;
      xm[k] -= h;
      tds_sym_jacobian(id, p, NULL, g, xp, yp, Jp, NULL);
      tds_sym_jacobian(id, p, NULL, g, xm, ym, Jm, NULL);
      double sj = 0, st2 = 0, ej = 0, et = 0;
      for (int i = 0; i < 3; i++) {
        sj = fmax(sj, fabs(J[i][k]));
        ej = fmax(ej, fabs((yp[i] - ym[i]) / (2 * h) - J[i][k]));
        for (int j = 0; j < 3; j++) {
          st2 = fmax(st2, fabs(T[i][j][k]));
          et = fmax(et, fabs((Jp[i][j] - Jm[i][j]) / (2 * h) - T[i][j][k]));
        }
      }
      CHECK(ej < 1e-7 * fmax(sj, 1e-3));
      CHECK(et < 1e-7 * fmax(st2, 1e-3));
    }
  }
}

/* Names: Evolver's, any case; dodecahedron known but absent. */
static void group_names(void) {
  CHECK(tds_sym_lookup("ROTATE") == TDS_SYM_ROTATE);
  CHECK(tds_sym_lookup("Central_Symmetry") == TDS_SYM_CENTRAL);
  CHECK(tds_sym_lookup("genus2") == TDS_SYM_GENUS2 && tds_sym_lookup("dodecahedron") == -1);
  CHECK(tds_sym_lookup("rotation") == 0);
  for (int id = 1; id < TDS_SYM_COUNT; id++) CHECK(tds_sym_lookup(tds_sym_name(id)) == id);
}

int main(void) {
  RUN(group_laws);
  RUN(genus2_laws);
  RUN(group_names);
  return check_done();
}
