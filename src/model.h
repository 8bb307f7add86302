/*
** model.h: declaring the model of a surface: constraints, boundaries,
** named quantities. Shared by the .tds bindings and the datafile reader.
**
** Expressions are compiled against the surface's parameter table
** (tds_model_compile), so parameters stay live: changing a value needs no
** recompilation. Functions that take compiled expressions take ownership
** of them, also on failure.
*/
#ifndef TDS_MODEL_H
#define TDS_MODEL_H

#include "expr.h"
#include "surf.h"

/* The element an expression is evaluated on, or'ed into the flags below:
** its names may then be that kind's attributes (xattr.h). Level-set
** formulas are evaluated on vertices, constraint and boundary integrands
** and edge quantities on edges, facet quantities on facets. Without one,
** attributes are errors ("angle is an edge attribute, not usable here"). */
enum {
  TDS_MODEL_ON_VERTEX = 1 << 8,
  TDS_MODEL_ON_EDGE = 2 << 8,
  TDS_MODEL_ON_FACET = 3 << 8,
  TDS_MODEL_ON_MASK = 3 << 8
};

/* Compile text as an expression reading the surface's parameters (and,
** with a TDS_MODEL_ON_*, the element's attributes).
** flags: TDS_EXPR_* (FORMULA for level sets, PARAMS for boundaries,
** NOCOORD for constants) | TDS_MODEL_ON_*. Errors carry the expression and
** column. */
int tds_model_compile(tds_ctx *ctx, tds_surf *s, const char *text, int flags,
                      tds_expr **out);
/* The same, parsing the longest expression at text (tds_expr_parse's
** consumed). */
int tds_model_parse(tds_ctx *ctx, tds_surf *s, const char *text, size_t *consumed,
                    int flags, tds_expr **out);

/* The lookup environment of tds_model_compile (for callers that parse
** expressions themselves); sc is its state and must outlive the parse. */
typedef struct tds_model_scope {
  tds_surf *s;
  int kind;               /* TDS_VERTEX, TDS_EDGE, TDS_FACET or -1 */
  int nomem;              /* an attribute slot could not be allocated */
  char why[160];          /* why the last name was refused, or "" */
} tds_model_scope;
void tds_model_env(tds_model_scope *sc, tds_surf *s, int flags, tds_expr_env *env);

/* Declare constraint `number` (>= 1): level set formula = 0 (required),
** flags TDS_CON_*, optional energy and content integrands (arrays of 3,
** entries may be NULL meaning 0; the array pointer may be NULL). Redeclaring
** a number replaces it. TDS_OK, TDS_ERANGE (more than 64 constraints). */
int tds_model_constraint(tds_ctx *ctx, tds_surf *s, int number, int flags,
                         tds_expr *formula, tds_expr *energy[3],
                         tds_expr *content[3]);

/* Declare boundary `number`: position x[0..2] as functions of p1 (and p2
** when nparams is 2); optional integrands as for constraints. */
int tds_model_boundary(tds_ctx *ctx, tds_surf *s, int number, int nparams,
                       int flags, tds_expr *x[3], tds_expr *energy[3],
                       tds_expr *content[3]);

/* Boundary slot of a user number, or -1. */
int tds_model_boundary_slot(const tds_surf *s, int number);

/* Declare a named quantity (kind TDS_Q_*); returns its index in *idx.
** Redeclaring a name replaces it. With `saved` not NULL, the replaced
** declaration is moved there (saved->name is NULL for a new name), so
** that tds_model_quantity_undo can put it back if adding its methods
** fails; otherwise it is freed. */
int tds_model_quantity(tds_ctx *ctx, tds_surf *s, const char *name, int kind,
                       double modulus, double target, int *idx, tds_quantity *saved);
/* Undo a tds_model_quantity that took `saved`: a new quantity is removed,
** a redeclared one gets its old definition back. */
void tds_model_quantity_undo(tds_surf *s, int idx, tds_quantity *saved);
/* Free what tds_model_quantity saved, once the new declaration stands. */
void tds_model_quantity_forget(tds_surf *s, tds_quantity *saved);

/* Add a method instance to quantity idx: method TDS_M_*, integrand
** expressions as the method needs (vector: 3, scalar: [0]), modulus. */
int tds_model_method(tds_ctx *ctx, tds_surf *s, int idx, int method,
                     double modulus, tds_expr *integrand[3]);


/* Quantity index by name (case-insensitive), or -1. */
int tds_model_quantity_find(const tds_surf *s, const char *name);

#endif
