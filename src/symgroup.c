/* symgroup.c: Evolver's built-in symmetry groups (contracts in symgroup.h). */
#include "symgroup.h"

#include <math.h>
#include <string.h>
#include <strings.h>

#include "tds.h"
#include "vec3.h"
#include "torus.h"
#include "wrap.h"

static const char *const names[TDS_SYM_COUNT] = {
    [TDS_SYM_TORUS] = "torus",         [TDS_SYM_ROTATE] = "rotate",
    [TDS_SYM_FLIP_ROTATE] = "flip_rotate", [TDS_SYM_CUBOCTA] = "cubocta",
    [TDS_SYM_XYZ] = "xyz",             [TDS_SYM_CUBELAT] = "cubelat",
    [TDS_SYM_CENTRAL] = "central_symmetry", [TDS_SYM_SCREW] = "screw_symmetry",
    [TDS_SYM_QUARTER_TURN] = "quarter_turn", [TDS_SYM_GENUS2] = "genus2"};

int tds_sym_lookup(const char *name) {
  for (int i = 1; i < TDS_SYM_COUNT; i++)
    if (!strcasecmp(name, names[i])) return i;
  if (!strcasecmp(name, "dodecahedron")) return -1;
  return 0;
}

const char *tds_sym_name(int id) {
  return id > 0 && id < TDS_SYM_COUNT ? names[id] : "none";
}

const char *tds_sym_param_name(int id, int k) {
  switch (id) {
  case TDS_SYM_ROTATE:
  case TDS_SYM_FLIP_ROTATE: return k == 0 ? "rotation_order" : k == 1 ? "generator_power" : NULL;
  case TDS_SYM_SCREW: return k == 0 ? "screw_height" : k == 1 ? "screw_angle" : NULL;
  case TDS_SYM_QUARTER_TURN: return k == 0 ? "quarter_turn_period" : NULL;
  default: return NULL;
  }
}

double tds_sym_param_default(int id, int k) {
  switch (id) {
  case TDS_SYM_ROTATE:
  case TDS_SYM_FLIP_ROTATE: return k == 0 ? 4 : 1;
  case TDS_SYM_SCREW: return k == 0 ? 1 : 0;
  case TDS_SYM_QUARTER_TURN: return 1;
  default: return 0;
  }
}

const char *tds_sym_param_check(int id, const double p[2]) {
  switch (id) {
  case TDS_SYM_ROTATE:
  case TDS_SYM_FLIP_ROTATE:
    if (!(p[0] >= 1 && p[0] <= 1e6 && p[0] == floor(p[0])))
      return "rotation_order must be a whole number from 1 to 1000000";
    if (id == TDS_SYM_FLIP_ROTATE && fmod(p[0], 2) != 0)
      return "rotation_order must be even for flip_rotate";
    if (!(fabs(p[1]) <= 1e6 && p[1] == floor(p[1])))
      return "generator_power must be a whole number";
    return NULL;
  case TDS_SYM_SCREW:
    return isfinite(p[0]) && isfinite(p[1]) ? NULL : "screw_height and screw_angle must be finite";
  case TDS_SYM_QUARTER_TURN:
    return isfinite(p[0]) ? NULL : "quarter_turn_period must be finite";
  default: return NULL;
  }
}

/* ---- signed permutations (CUBOCTA, XYZ, CUBELAT) ---- */

typedef struct sperm {
  int m[3][3];
} sperm;

static sperm sp_mul(const sperm *a, const sperm *b) {
  sperm r;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      r.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] + a->m[i][2] * b->m[2][j];
  return r;
}

/* W^s C^c S of Evolver's code (symgroup.h). */
static sperm sp_of(int32_t code) {
  sperm r = {{{0}}}, cyc = {{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}}, sw = {{{0, 1, 0}, {1, 0, 0}, {0, 0, 1}}};
  for (int i = 0; i < 3; i++) r.m[i][i] = (code >> i) & 1 ? -1 : 1;
  for (int c = (code >> 3) & 3; c > 0; c--) r = sp_mul(&cyc, &r);
  if (code & 32) r = sp_mul(&sw, &r);
  return r;
}

/* The canonical code (cycle power 0..2) of a signed permutation. */
static int32_t sp_code(const sperm *M) {
  int32_t code = 0;
  sperm P = *M;
  for (int j = 0; j < 3; j++) { /* column j's sign is the sign change of j */
    int neg = P.m[0][j] + P.m[1][j] + P.m[2][j] < 0;
    if (neg) {
      code |= 1 << j;
      for (int i = 0; i < 3; i++) P.m[i][j] = -P.m[i][j];
    }
  }
  int det = P.m[0][0] * (P.m[1][1] * P.m[2][2] - P.m[1][2] * P.m[2][1]) -
            P.m[0][1] * (P.m[1][0] * P.m[2][2] - P.m[1][2] * P.m[2][0]) +
            P.m[0][2] * (P.m[1][0] * P.m[2][1] - P.m[1][1] * P.m[2][0]);
  if (det < 0) { /* undo the swap: rows 0 and 1 */
    code |= 32;
    for (int j = 0; j < 3; j++) {
      int t = P.m[0][j];
      P.m[0][j] = P.m[1][j];
      P.m[1][j] = t;
    }
  }
  int c = P.m[0][0] ? 0 : P.m[1][0] ? 1 : 2; /* C^c e0 = e_c */
  return code | (c << 3);
}

/* CUBELAT's translation counts (signed 8 bits each from bit 6). */
static void lat_unpack(int32_t w, int k[3]) {
  for (int i = 0; i < 3; i++) {
    int v = (int)(((uint32_t)w >> (6 + 8 * i)) & 255u);
    k[i] = v >= 128 ? v - 256 : v;
  }
}
static int32_t lat_pack(int32_t point, const int k[3]) {
  uint32_t w = (uint32_t)point & 63u;
  for (int i = 0; i < 3; i++) w |= ((uint32_t)k[i] & 255u) << (6 + 8 * i);
  return (int32_t)w;
}

/* ---- cyclic groups ---- */

static int32_t mod_n(int64_t k, const double p[2]) {
  int64_t n = (int64_t)p[0];
  if (n < 1) n = 1;
  int64_t r = k % n;
  return (int32_t)(r < 0 ? r + n : r);
}

/* QUARTER_TURN: Q^-c (a, b) */
static void qt_unturn(int c, int *a, int *b) {
  for (c = ((c % 4) + 4) % 4; c > 0; c--) { /* Q^-1 (x, y) = (y, -x) */
    int t = *a;
    *a = *b;
    *b = -t;
  }
}

int32_t tds_sym_mul(int id, const double p[2], int32_t a, int32_t b) {
  if (a == TDS_SYM_OUTSIDE || b == TDS_SYM_OUTSIDE) return TDS_SYM_OUTSIDE;
  switch (id) {
  case TDS_SYM_GENUS2: return tds_g2_mul(a, b);
  case TDS_SYM_TORUS: return tds_wrap_add(a, b);
  case TDS_SYM_ROTATE:
  case TDS_SYM_FLIP_ROTATE: return mod_n((int64_t)a + b, p);
  case TDS_SYM_XYZ: return (a + b) % 3;
  case TDS_SYM_CUBOCTA: {
    sperm A = sp_of(a), B = sp_of(b), r = sp_mul(&A, &B);
    return sp_code(&r);
  }
  case TDS_SYM_CUBELAT: { /* (A,s)(B,t) = (AB, A t + s) */
    sperm A = sp_of(a), B = sp_of(b), r = sp_mul(&A, &B);
    int s[3], t[3], k[3];
    lat_unpack(a, s);
    lat_unpack(b, t);
    for (int i = 0; i < 3; i++)
      k[i] = A.m[i][0] * t[0] + A.m[i][1] * t[1] + A.m[i][2] * t[2] + s[i];
    return lat_pack(sp_code(&r), k);
  }
  case TDS_SYM_CENTRAL: return (a ^ b) & 1;
  case TDS_SYM_SCREW: return (int32_t)((uint32_t)a + (uint32_t)b);
  case TDS_SYM_QUARTER_TURN: { /* c = c1 + c2, u = u2 + Q^-c2 u1 */
    int ka[3], kb[3];
    tds_wrap_unpack(a, ka);
    tds_wrap_unpack(b, kb);
    qt_unturn(kb[2], &ka[0], &ka[1]);
    int k[3] = {ka[0] + kb[0], ka[1] + kb[1], ka[2] + kb[2]};
    return tds_wrap_pack(k);
  }
  default: return 0;
  }
}

int32_t tds_sym_inv(int id, const double p[2], int32_t a) {
  if (a == TDS_SYM_OUTSIDE) return TDS_SYM_OUTSIDE;
  switch (id) {
  case TDS_SYM_GENUS2: return tds_g2_inv(a);
  case TDS_SYM_TORUS: return a ? tds_wrap_neg(a) : 0;
  case TDS_SYM_ROTATE:
  case TDS_SYM_FLIP_ROTATE: return mod_n(-(int64_t)a, p);
  case TDS_SYM_XYZ: return (3 - a) % 3;
  case TDS_SYM_CUBOCTA: {
    sperm A = sp_of(a), T;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) T.m[i][j] = A.m[j][i];
    return sp_code(&T);
  }
  case TDS_SYM_CUBELAT: { /* (A,s)^-1 = (A^T, -A^T s) */
    sperm A = sp_of(a), T;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) T.m[i][j] = A.m[j][i];
    int s[3], k[3];
    lat_unpack(a, s);
    for (int i = 0; i < 3; i++) k[i] = -(T.m[i][0] * s[0] + T.m[i][1] * s[1] + T.m[i][2] * s[2]);
    return lat_pack(sp_code(&T), k);
  }
  case TDS_SYM_CENTRAL: return a & 1;
  case TDS_SYM_SCREW: return (int32_t)(0u - (uint32_t)a);
  case TDS_SYM_QUARTER_TURN: { /* (c, u)^-1 = (-c, -Q^c u) */
    int k[3];
    tds_wrap_unpack(a, k);
    qt_unturn(-k[2], &k[0], &k[1]);
    k[0] = -k[0];
    k[1] = -k[1];
    k[2] = -k[2];
    return tds_wrap_pack(k);
  }
  default: return 0;
  }
}

static void rot_z(double ang, double R[3][3]) {
  double c = cos(ang), s = sin(ang);
  R[0][0] = c, R[0][1] = -s, R[1][0] = s, R[1][1] = c;
}

void tds_sym_affine(int id, const double p[2], const double (*period)[3], int32_t w,
                    double R[3][3], double t[3]) {
  memset(R, 0, 9 * sizeof(double));
  R[0][0] = R[1][1] = R[2][2] = 1;
  t[0] = t[1] = t[2] = 0;
  switch (id) {
  case TDS_SYM_TORUS: tds_wrap_vec(period, w, t); return;
  case TDS_SYM_ROTATE:
  case TDS_SYM_FLIP_ROTATE: {
    /* an exact quarter or half turn stays exact */
    int64_t n = (int64_t)p[0], k = (int64_t)w * (int64_t)p[1];
    int64_t r = n > 0 ? ((k % n) + n) % n : 0;
    if (n > 0 && (4 * r) % n == 0) {
      static const double cs[4][2] = {{1, 0}, {0, -1}, {-1, 0}, {0, 1}}; /* angle -r 2pi/n */
      int q = (int)(4 * r / n);
      R[0][0] = cs[q][0], R[0][1] = -cs[q][1], R[1][0] = cs[q][1], R[1][1] = cs[q][0];
    } else {
      rot_z(-2 * TDS_PI * (double)r / (double)n, R);
    }
    if (id == TDS_SYM_FLIP_ROTATE && (w & 1)) R[2][2] = -1;
    return;
  }
  case TDS_SYM_XYZ: /* C^w, C (x, y, z) -> (z, x, y) */
    memset(R, 0, 9 * sizeof(double));
    for (int i = 0; i < 3; i++) R[i][(i + 3 - w % 3) % 3] = 1;
    return;
  case TDS_SYM_CUBOCTA:
  case TDS_SYM_CUBELAT: {
    sperm A = sp_of(w);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) R[i][j] = A.m[i][j];
    if (id == TDS_SYM_CUBELAT) {
      int k[3];
      lat_unpack(w, k);
      for (int i = 0; i < 3; i++) t[i] = k[i];
    }
    return;
  }
  case TDS_SYM_CENTRAL:
    if (w & 1) R[0][0] = R[1][1] = R[2][2] = -1;
    return;
  case TDS_SYM_SCREW:
    rot_z((double)w * p[1] * TDS_PI / 180, R);
    t[2] = (double)w * p[0];
    return;
  case TDS_SYM_QUARTER_TURN: { /* p -> Q^c (p + u) + c P ez */
    int k[3];
    tds_wrap_unpack(w, k);
    int c = ((k[2] % 4) + 4) % 4;
    static const int qc[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}}; /* cos, sin of c/4 turns */
    R[0][0] = qc[c][0], R[0][1] = -qc[c][1], R[1][0] = qc[c][1], R[1][1] = qc[c][0];
    t[0] = R[0][0] * k[0] + R[0][1] * k[1];
    t[1] = R[1][0] * k[0] + R[1][1] * k[1];
    t[2] = k[2] * p[0];
    return;
  }
  default: return;
  }
}

/* One of Evolver's 6-bit fields: a count in 5-bit two's complement. */
static int field_of(unsigned c, int i, int *k) {
  unsigned f = (c >> (6 * i)) & 63u;
  if (f & 32u) return TDS_ERANGE;
  *k = f >= 16 ? (int)f - 32 : (int)f;
  return TDS_OK;
}

double tds_sym_code(int id, int32_t w) {
  switch (id) {
  case TDS_SYM_TORUS:
  case TDS_SYM_QUARTER_TURN: return tds_torus_wrap_code(w);
  case TDS_SYM_CUBELAT: {
    int k[3];
    lat_unpack(w, k);
    double code = w & 63;
    for (int i = 0; i < 3; i++) code += (double)((unsigned)k[i] & 31u) * (double)(1u << (6 + 6 * i));
    return code;
  }
  default: return w;
  }
}

int tds_sym_from_code(int id, const double p[2], double code, int32_t *w) {
  if (!(fabs(code) < 2147483648.0) || code != floor(code)) return TDS_ERANGE;
  switch (id) {
  case TDS_SYM_TORUS:
  case TDS_SYM_QUARTER_TURN: return tds_torus_wrap_from_code(code, w);
  case TDS_SYM_ROTATE:
  case TDS_SYM_FLIP_ROTATE: *w = mod_n((int64_t)code, p); return TDS_OK;
  case TDS_SYM_XYZ: *w = (int32_t)(((int64_t)code % 3 + 3) % 3); return TDS_OK;
  case TDS_SYM_CUBOCTA: {
    if (code < 0 || code >= 64) return TDS_ERANGE;
    sperm A = sp_of((int32_t)code);
    *w = sp_code(&A);
    return TDS_OK;
  }
  case TDS_SYM_CUBELAT: {
    if (code < 0 || code >= (double)(1u << 24)) return TDS_ERANGE;
    unsigned c = (unsigned)code;
    int k[3];
    for (int i = 0; i < 3; i++)
      if (field_of(c >> 6, i, &k[i])) return TDS_ERANGE;
    sperm A = sp_of((int32_t)(c & 63u));
    *w = lat_pack(sp_code(&A), k);
    return TDS_OK;
  }
  case TDS_SYM_CENTRAL:
    if (code != 0 && code != 1) return TDS_ERANGE;
    *w = (int32_t)code;
    return TDS_OK;
  case TDS_SYM_SCREW: *w = (int32_t)code; return TDS_OK;
  case TDS_SYM_GENUS2: return tds_g2_from_code(code, w) ? TDS_ERANGE : TDS_OK;
  default: return TDS_ERANGE;
  }
}

int tds_sym_affine_group(int id) {
  return id != TDS_SYM_GENUS2;
}

void tds_sym_jacobian(int id, const double p[2], const double (*period)[3], int32_t w,
                      const double x[3], double out[3], double J[3][3], double T[3][3][3]) {
  if (id == TDS_SYM_GENUS2) {
    tds_g2_apply(w, x, out, J, T);
    return;
  }
  double R[3][3], d[3];
  tds_sym_affine(id, p, period, w, R, d);
  for (int i = 0; i < 3; i++) out[i] = R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2] + d[i];
  if (J) memcpy(J, R, sizeof R);
  if (J && T) memset(T, 0, 27 * sizeof(double));
}

void tds_sym_apply(int id, const double p[2], const double (*period)[3], int32_t w,
                   const double x[3], double out[3]) {
  if (id == TDS_SYM_GENUS2) {
    tds_g2_apply(w, x, out, NULL, NULL);
    return;
  }
  double R[3][3], d[3];
  tds_sym_affine(id, p, period, w, R, d);
  for (int i = 0; i < 3; i++) out[i] = R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2] + d[i];
}
