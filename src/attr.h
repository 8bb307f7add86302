/*
** attr.h: the attribute registry — one list per element kind of every
** attribute an element has (name, spellings, type, default, getter and
** the setter that owns its rules), built-in rows and user attributes
** (Evolver's `define vertex attribute weight real`) alike.
**
** Everything that reads or writes element attributes iterates this list:
** the Lua getters and setters (lua_attr.c), the declarations (lua_decl.c),
** the datafile reader (datafile_elements.c) and the dump writer (dump.c).
** A new attribute is one row here; it is then readable and settable from
** Lua, read from datafiles and dumped (as its flags say).
**
** Values travel as doubles: a flag is 0 or 1, an element reference its
** 1-based id (0 = none), a constraint list its numbers, an array its
** values in row-major order. A getter reports n = 0 for "no value" (nil:
** a body without a target volume, a vertex on no boundary).
*/
#ifndef TDS_ATTR_H
#define TDS_ATTR_H

#include "surf.h"

enum {                 /* value types */
  TDS_AT_FLAG = 0,     /* boolean: a bit of the element's flags */
  TDS_AT_REAL,         /* finite real */
  TDS_AT_INT,          /* whole number */
  TDS_AT_COLOR,        /* whole number in -32768..32767 (Evolver colours) */
  TDS_AT_VERTEX,       /* reference to a vertex (read only) */
  TDS_AT_BODY,         /* reference to a body, 0 = none */
  TDS_AT_CONS,         /* list of constraint numbers */
  TDS_AT_BDRY          /* a boundary number, none allowed */
};

enum {                 /* where an attribute appears (tds_attr.io) */
  TDS_AT_FE = 1,       /* a word of datafile element lines, written by dump */
  TDS_AT_DECL = 2,     /* a key of Lua declarations (vertices{} ...) */
  TDS_AT_USER = 4      /* a user attribute (a column of the mesh) */
};

#define TDS_ATTR_MAXDIM 8     /* array dimensions of a user attribute */
#define TDS_ATTR_MAXSIZE 4096 /* values per element of a user attribute */
#define TDS_ATTR_NAMELEN 32   /* longest user attribute name + 1 */

struct tds_attr;
/* Read attribute a of element id (live) into v (room for a->size values;
** TDS_MAX_CON for TDS_AT_CONS); *n gets the number of values, 0 = none.
** TDS_OK or a status with the message in ctx. */
typedef int (*tds_attr_get)(tds_ctx *ctx, tds_surf *s, const struct tds_attr *a,
                            tds_id id, double *v, int *n);
/* Set it from v[0..n) (n = 0: unset, where the attribute allows it).
** The setter owns the rules (a body's target volume and prescribed
** pressure exclude each other, ...). All or nothing: on failure the
** element is unchanged and ctx says "kind N: what is wrong". */
typedef int (*tds_attr_set)(tds_ctx *ctx, tds_surf *s, const struct tds_attr *a,
                            tds_id id, const double *v, int n);

typedef struct tds_attr {
  const char *name;    /* the name in Lua and in the Evolver command language */
  const char *alias;   /* a second accepted spelling, or NULL */
  const char *fe;      /* datafile word if not name (TDS_AT_FE) */
  const char *fe_alias;/* a second datafile spelling, or NULL */
  int kind;            /* TDS_VERTEX ... TDS_BODY */
  int type;            /* TDS_AT_* */
  int size;            /* values per element (1 for a scalar) */
  unsigned io;         /* TDS_AT_FE | TDS_AT_DECL | TDS_AT_USER */
  uint32_t flag;       /* the flag bit of a TDS_AT_FLAG row */
  double dflt;         /* value of a new element */
  tds_attr_get get;
  tds_attr_set set;    /* NULL: read only */
  /* Whether dump writes it for element id (NULL: value differs from
  ** dflt, for a flag: set). */
  int (*dumped)(const tds_surf *s, tds_id id);
  /* user attributes: the column and its shape */
  int col;             /* -1 for built-in rows */
  int ndim;
  const int32_t *dim;
  size_t off;          /* built-in rows over one mesh column: its offset */
  const char *excl;    /* names (blank-separated) it cannot be given with in
                          one declaration (a target volume, a pressure) */
} tds_attr;

/* A user attribute's storage: `size` doubles per element slot, grown with
** the mesh (mesh.c), zero for new elements, inherited by elements split
** from an element of the same kind (refine). */
/* Evolver's facetedge attributes (`define facetedge attribute w real`)
** are the facet attribute fe__w of shape [3][...], one value per side
** (lua/evoelem.lua); a facet split off another does not inherit them
** (tds_mesh_inherit): Evolver's new facetedges start at 0. */
#define TDS_FE_ATTR_PREFIX "fe__"

typedef struct tds_ucol {
  char name[TDS_ATTR_NAMELEN];
  int type;            /* TDS_AT_REAL or TDS_AT_INT */
  int ndim;            /* 0 for a scalar */
  int32_t dim[TDS_ATTR_MAXDIM];
  int32_t size;        /* product of dim (1 for a scalar) */
  double *v;           /* capacity * size values */
} tds_ucol;

/* The built-in rows per kind (attr_rows.c); use the functions below. */
extern const tds_attr *const tds_attr_rows[TDS_NKINDS];
extern const int tds_attr_nrows[TDS_NKINDS];

/* Number of attributes of `kind` (built-in rows, then user attributes). */
int tds_attr_count(const tds_mesh *m, int kind);
/* The i-th attribute of `kind` (0 <= i < tds_attr_count) into *a. The
** copy stays valid while no user attribute of the kind is defined. */
void tds_attr_at(const tds_mesh *m, int kind, int i, tds_attr *a);
/* Find attribute `name` of `kind` by its name or alias (case-sensitive,
** as Lua) into *a: 1, else 0. */
int tds_attr_find(const tds_mesh *m, int kind, const char *name, tds_attr *a);
/* The same by datafile word (lowercase): attributes with TDS_AT_FE. */
int tds_attr_find_fe(const tds_mesh *m, int kind, const char *word, tds_attr *a);
/* The datafile word of a. */
static inline const char *tds_attr_word(const tds_attr *a) {
  return a->fe ? a->fe : a->name;
}

/* Check that v[0..n) suits a's type (finite, whole, colour range,
** n = a->size for arrays); "what: message" in ctx, TDS_ERANGE. */
int tds_attr_check(tds_ctx *ctx, const tds_attr *a, const char *what, const double *v,
                   int n);
/* Get and set through the row (set: read-only rows are refused). */
int tds_attr_read(tds_ctx *ctx, tds_surf *s, const tds_attr *a, tds_id id, double *v,
                  int *n);
int tds_attr_write(tds_ctx *ctx, tds_surf *s, const tds_attr *a, tds_id id,
                   const double *v, int n);
/* Whether dump writes a for element id. */
int tds_attr_dumped(tds_surf *s, const tds_attr *a, tds_id id);

/* Whether the attributes names[0..n) (registry names), given together in
** one declaration of an element of `kind`, include two that exclude each
** other: then "what: give either A or B, not both" (datafile words when
** fe) in ctx and TDS_ESYNTAX, else TDS_OK. */
int tds_attr_exclusive(tds_ctx *ctx, const tds_mesh *m, int kind, const char *what, int fe,
                       const char *const *names, int n);

/* Define user attribute `name` of `kind`: type TDS_AT_REAL or TDS_AT_INT,
** ndim dimensions dim[] (0 = a scalar). Every element gets zeros. Defining
** it again with the same type and shape is allowed (nothing changes);
** with the same type and number of dimensions but other sizes it is
** resized, each element keeping its values at the indices both shapes
** have, as Evolver does; another type or number of dimensions, a
** built-in name, a bad name or size is TDS_ERANGE
** with a message; TDS_ENOMEM. */
int tds_attr_define(tds_ctx *ctx, tds_mesh *m, int kind, const char *name, int type,
                    int ndim, const int32_t *dim);

/* Element kind names as Evolver spells them ("vertex", "edge", "facet",
** "body") and a kind by name (also "face"), or -1. */
extern const char *const tds_kind_name[TDS_NKINDS];
int tds_kind_find(const char *name);
/* Type name ("real", "integer", ...). */
const char *tds_attr_type_name(int type);

#endif
