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

/* Compile text as an expression reading the surface's parameters.
** flags: TDS_EXPR_* (FORMULA for level sets, PARAMS for boundaries,
** NOCOORD for constants). Errors carry the expression and column. */
int tds_model_compile(tds_ctx *ctx, tds_surf *s, const char *text, int flags,
                      tds_expr **out);

/* The lookup environment for the surface's parameters (for callers that
** parse expressions themselves, e.g. inside a datafile stream). */
void tds_model_env(tds_surf *s, int flags, tds_expr_env *env);

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
