/*
** symgroup.h: Evolver's built-in symmetry groups (SYMMETRY_GROUP "name").
**
** The domain is the quotient of space by a group of isometries; an edge's
** wrap (tds_mesh.ewrap) is a group element g, and the true head of the
** edge seen from its tail is g(x[head]). Walking round a facet composes the
** wraps: corner k+1 seen from the first corner is (w0 w1 ... wk)(x), so a
** facet closes when the product of its edges' wraps is the identity, and
** the product here, tds_sym_mul(a, b), is the map "b first, then a" (the
** torus's wrap addition in the translation groups). The identity is always
** 0, so a mesh without wraps reads zeros.
**
** Internal codes (what ewrap holds) per group, p[] the group's parameters:
**   TORUS        packed lattice counts as in the torus model (wrap.h);
**   ROTATE       power k of the generator, 0 <= k < n (n = p[0],
**                rotation_order); the element rotates about the z axis by
**                -2 pi k p[1] / n (p[1] = generator_power; Evolver's sense,
**                measured: power 1 of order 6 takes (1,0,0) to (0.5,-0.87,0));
**   FLIP_ROTATE  as ROTATE, with z -> -z for odd k (n even);
**   CUBOCTA      Evolver's code: bits 1,2,4 change the signs of x, y, z
**                first, (code&24)/8 = c (0..2) powers of the cycle
**                (x,y,z) -> (z,x,y), then bit 32 swaps x and y (measured
**                against Evolver 2.70 on all 48 elements);
**   XYZ          power k (0..2) of the cycle C (x,y,z) -> (z,x,y): the
**                point (x,y,z) goes to (z,x,y); any integer code counts
**                mod 3. Evolver's manual calls xyz the orientation-
**                preserving subgroup of cubocta, but Evolver 2.70 does
**                this (measured on codes 0..63); tds does as Evolver;
**   CUBELAT      the CUBOCTA code in bits 0..5 and then a lattice
**                translation, three signed 8-bit counts from bit 6 (Evolver
**                writes them in 6-bit fields: tds_sym_code);
**   CENTRAL      0 or 1 (x -> -x);
**   SCREW        power k (any int): rotation by k p[1] degrees about z and
**                translation k p[0] along z (screw_angle, screw_height);
**   QUARTER_TURN x^a y^b z^c packed as the torus's counts (a, b, c): the
**                map p -> Q^c (p + (a, b, 0)) + (0, 0, c p[0]), Q the
**                quarter turn (x, y) -> (-y, x), p[0] = quarter_turn_period;
**   GENUS2       Evolver's code byte a + 16 b, the run G_a ... G_(b-1) of
**                the octagon's eight translations in the Klein model
**                (symgroup_g2.c); not affine: projective maps of the
**                Klein disk (tds_sym_jacobian). A product that is no run
**                is TDS_SYM_OUTSIDE (Evolver: "Wrap outside known range").
** No Lua, no globals: pure functions of (group, parameters, codes).
*/
#ifndef TDS_SYMGROUP_H
#define TDS_SYMGROUP_H

#include <stdint.h>

enum {
  TDS_SYM_NONE = 0,
  TDS_SYM_TORUS,        /* translations by the periods (the torus model) */
  TDS_SYM_ROTATE,
  TDS_SYM_FLIP_ROTATE,
  TDS_SYM_CUBOCTA,
  TDS_SYM_XYZ,
  TDS_SYM_CUBELAT,
  TDS_SYM_CENTRAL,
  TDS_SYM_SCREW,
  TDS_SYM_QUARTER_TURN,
  TDS_SYM_GENUS2,
  TDS_SYM_COUNT
};

/* What tds_sym_mul returns for a product the group's codes cannot name
** (GENUS2 only): never a valid code, never 0. */
#define TDS_SYM_OUTSIDE INT32_MIN

/* The group of Evolver's name (case-insensitive): its TDS_SYM_* id, 0 for
** an unknown name, -1 for a group Evolver has that tds does not (genus2,
** dodecahedron). */
int tds_sym_lookup(const char *name);
/* Evolver's name of group id. */
const char *tds_sym_name(int id);

/* Names of the global parameters group id reads into p[0..1] (NULL when it
** reads fewer) and their defaults (Evolver's). */
const char *tds_sym_param_name(int id, int k);
double tds_sym_param_default(int id, int k);
/* Check the parameters: NULL if usable, else what is wrong. */
const char *tds_sym_param_check(int id, const double p[2]);

/* Product a b (b first, then a), inverse, as internal codes. */
int32_t tds_sym_mul(int id, const double p[2], int32_t a, int32_t b);
int32_t tds_sym_inv(int id, const double p[2], int32_t a);

/* Whether group id's elements are affine maps x -> R x + t (all but
** GENUS2, whose maps are projective). */
int tds_sym_affine_group(int id);

/* The isometry of code w: x -> R x + t (affine groups; the identity for
** GENUS2). period: the torus's period rows (TORUS only). */
void tds_sym_affine(int id, const double p[2], const double (*period)[3], int32_t w,
                    double R[3][3], double t[3]);
/* out = R x + t for the isometry of code w (out may not be x). */
void tds_sym_apply(int id, const double p[2], const double (*period)[3], int32_t w,
                   const double x[3], double out[3]);

/* out = g(x) for the element g of code w, with J (when not NULL) its
** Jacobian dg_i/dx_j at x and T (when not NULL, with J) its second
** derivatives d2 g_i / dx_j dx_k (zero for affine groups). */
void tds_sym_jacobian(int id, const double p[2], const double (*period)[3], int32_t w,
                      const double x[3], double out[3], double J[3][3], double T[3][3][3]);

/* GENUS2 (symgroup_g2.c): the element's 4x4 matrix on (x, y, z, 1), its
** product, inverse, code (0 or -1: no element), and action with
** derivatives as in tds_sym_jacobian. */
void tds_g2_matrix(int32_t w, double M[4][4]);
int32_t tds_g2_mul(int32_t x, int32_t y);
int32_t tds_g2_inv(int32_t w);
int tds_g2_from_code(double code, int32_t *w);
void tds_g2_apply(int32_t w, const double x[3], double out[3], double J[3][3], double T[3][3][3]);

/* Evolver's integer code of internal code w (datafile, dump, the wrap
** attribute), and back: TDS_OK, or TDS_ERANGE when code is no element of
** the group (not an integer, a bit Evolver does not use). */
double tds_sym_code(int id, int32_t w);
int tds_sym_from_code(int id, const double p[2], double code, int32_t *w);

#endif
