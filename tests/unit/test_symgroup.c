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

/* Names: Evolver's, any case; genus2 and dodecahedron known but absent. */
static void group_names(void) {
  CHECK(tds_sym_lookup("ROTATE") == TDS_SYM_ROTATE);
  CHECK(tds_sym_lookup("Central_Symmetry") == TDS_SYM_CENTRAL);
  CHECK(tds_sym_lookup("genus2") == -1 && tds_sym_lookup("dodecahedron") == -1);
  CHECK(tds_sym_lookup("rotation") == 0);
  for (int id = 1; id < TDS_SYM_COUNT; id++) CHECK(tds_sym_lookup(tds_sym_name(id)) == id);
}

int main(void) {
  RUN(group_laws);
  RUN(group_names);
  return check_done();
}
