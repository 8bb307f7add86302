/*
** xattr.h: element attributes read by expressions, Evolver's
** `define edge attribute angle real` used in a constraint's energy
** integrand (`e1: -cos(angle*pi/180)*y`). Such a name evaluates to the
** attribute of the element being integrated: the edge for constraint and
** boundary integrands and edge quantities, the facet for facet quantities,
** the vertex for constraint formulas.
**
** How: the expression compiler asks the surface's lookup for a name; an
** attribute of the element kind the expression lives on gets an
** attribute slot j (one per kind and attribute, kept in the surface), and
** compiles to a parameter read at index -1-j. The surface's parameter
** array has room in front of index 0 for these slots (surf.h's parval),
** so every evaluator keeps reading `s->parval`; before evaluating an
** expression on an element, the caller writes that element's values into
** the slots of its kind (tds_xattr_fill). An attribute is a constant of
** each element: only the coordinates vary, so gradients and Hessians are
** those of the coordinates, exactly.
**
** Which attributes: user attributes of the kind that are scalars (real or
** integer), and the built-in scalar ones that do not depend on the
** geometry: `original`, the flags (`fixed`, `bare`, `no_refine`,
** `noncontent`, `nodisplay`), `tension` (`density`), `color` and `wrap`.
*/
#ifndef TDS_XATTR_H
#define TDS_XATTR_H

#include <stddef.h>

#include "surf.h"

struct tds_attr;

typedef struct tds_xattr {
  int kind;                  /* TDS_VERTEX, TDS_EDGE or TDS_FACET */
  int col;                   /* user attribute column, or -1 */
  const struct tds_attr *row;/* built-in row (attr_rows.c), or NULL */
} tds_xattr;

/* The slot of attribute name[0..len) of `kind` for an expression, adding
** one if needed: j >= 0. -1 when no attribute of any kind has that name.
** -2 when it is not usable here; why[0..cap) then says why ("a facet
** attribute, and this expression is evaluated on edges", "an array
** attribute"). TDS_ENOMEM is -3 (why says "out of memory"). */
int tds_xattr_slot(tds_surf *s, int kind, const char *name, size_t len, char *why,
                   size_t cap);

/* Write element el's values into the slots of `kind` (s->parval[-1-j]:
** scratch memory of the surface, so a const surface is fine). Cheap when
** the surface has none (one test). */
void tds_xattr_fill_slow(const tds_surf *s, int kind, tds_id el);
static inline void tds_xattr_fill(const tds_surf *s, int kind, tds_id el) {
  if (s->nxa_kind[kind]) tds_xattr_fill_slow(s, kind, el);
}

/* Release the slot table (tds_surf_free). */
void tds_xattr_free(tds_surf *s);

#endif
