/*
** live_snap.h: an immutable picture of the surface for the live view.
**
** The main thread builds a snapshot (positions, triangles, edges, fields,
** totals) into one byte buffer that the server thread hands out unchanged;
** nothing in it points back into the surface. The byte layout, all
** little-endian, 4-byte aligned:
**
**   uint32 H                 length of the header (a multiple of 4)
**   H bytes                  JSON header, space padded (see below)
**   float32 pos[3 nv]        live vertices, renumbered 0..nv-1
**   uint32  tri[3 nf]        displayed facets (live, not nodisplay), as
**                            vertex numbers in the facet's orientation
**   uint32  edge[2 ne]       live edges, tail and head
**   float32 field[nf or nv]  one array per entry of header.fields, in order
**
** The header: {"version", "energy", "area", "iterations", "vertices",
** "edges", "facets", "bodies", "color", "fields": [{"name", "per":
** "vertex"|"facet", "min", "max"}...]}. min and max skip NaN (a vertex
** whose curvature is not measured); both are null when no value is finite.
**
** Fields, computed here so that they match the rest of tds:
**   mean_curvature  per vertex, k1 + k2 (tds_vertex_mean_curvature)
**   min_angle       per facet, degrees (tds_facet_min_angle)
**   body            per facet, id of the front body, else the back body,
**                   else 0
**   tension         per facet
**   color           per facet, Evolver colour number 0..15; a facet with
**                   no colour (0 in tds's store) shows Evolver's default,
**                   white (15)
*/
#ifndef TDS_LIVE_SNAP_H
#define TDS_LIVE_SNAP_H

#include <stddef.h>

#include "surf.h"

enum { TDS_LIVE_NFIELDS = 5 };

/* The field names in their order in the buffer, for validating options. */
extern const char *const tds_live_fields[TDS_LIVE_NFIELDS];

/* Index of a field name, or -1. */
int tds_live_field_index(const char *name);

/* Build a snapshot of s with the given version, energy (the caller's
** current total: iterations know it without a recomputation) and initial
** colouring field. Needs current adjacency (rebuilt here if stale).
** On TDS_OK *buf (malloc'd, caller frees) and *len hold it; TDS_ENOMEM
** otherwise, with nothing allocated. */
int tds_live_snap_build(tds_ctx *ctx, tds_surf *s, uint64_t version,
                        double energy, int color, unsigned char **buf,
                        size_t *len);

#endif
