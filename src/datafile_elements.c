/*
** datafile_elements.c: the lines of the VERTICES, EDGES, FACES and BODIES
** sections (contracts in datafile_int.h). Each line is an element id, its
** data (coordinates or boundary parameters, vertex ids, signed edge or
** face ids) and attribute words with their values. Elements are numbered
** in the order they come, as Evolver does (the file's id is kept as
** `original`; KEEP_ORIGINALS keeps the ids). Faces are collected and
** built when their section ends, after reserving facet slots up to the
** highest face id, so split-off facets come after every declared one.
*/
#include "datafile_int.h"
#include "string_model.h"

#include <stdio.h>
#include <string.h>

#include "attr.h"
#include "method.h"
#include "model.h"
#include "topo.h"

/* ---- shared pieces ---- */

/* Refuse attribute word w (at `at`) of `what`: "not supported yet" for
** Evolver features tds lacks and for named quantities, else unknown. */
static int unknown_attr(df *d, const char *at, const char *w, const char *what) {
  char u[64];
  if (df_unsupported(w))
    return df_err(d, at, TDS_ESYNTAX, "%s: %s is not supported yet", what,
                  df_upper(w, u, sizeof u));
  if (tds_model_quantity_find(d->s, w) >= 0)
    return df_err(d, at, TDS_ESYNTAX,
                  "%s: named quantities on single elements (%s) are not supported yet",
                  what, w);
  if (!*w) {
    char b[64];
    return df_err(d, at, TDS_ESYNTAX, "%s: unexpected %s", what,
                  df_describe(at, b, sizeof b));
  }
  return df_err(d, at, TDS_ESYNTAX, "%s: unknown attribute '%s'", what, w);
}

/* ORIGINAL n: the element's `original` (Evolver writes it into dumps
** when it differs from the id). */
static int read_original(df *d, const char *what) {
  int64_t o;
  const char *a = d->p;
  int rc = df_read_int(d, 1, what, &o);
  if (rc) return rc;
  if (o < 0 || o > INT32_MAX)
    return df_err(d, a, TDS_ERANGE, "%s: ORIGINAL %lld is not an element id or 0", what,
                  (long long)o);
  d->orig = o;
  return TDS_OK;
}

/* CONSTRAINT(S) c1 c2 ...: *rev set if a number is negative. */
/* The slot of the named constraint at the cursor (optionally after '-'),
** or -1 (nothing consumed). */
static int named_con(df *d, int *neg) {
  df_ws(d);
  const char *p = d->p + (*d->p == '-');
  size_t n = df_word_len(p);
  int slot = n ? tds_surf_con_named(d->s, p, n) : -1;
  if (slot >= 0) {
    *neg = *d->p == '-';
    d->p = p + n;
  }
  return slot;
}

static int con_list(df *d, const char *what, tds_cmask *mask, int *rev) {
  int n = 0, neg, named;
  while ((named = named_con(d, &neg)) >= 0 || df_looks_int(d)) {
    if (named >= 0) {
      if (neg && rev) *rev = 1;
      *mask |= (tds_cmask)1 << named;
      n++;
      continue;
    }
    int64_t c;
    const char *a = d->p;
    int rc = df_read_int(d, 1, what, &c);
    if (rc) return rc;
    if (c < 0) {
      if (rev) *rev = 1;
      c = -c;
    }
    int slot = c > 0 && c <= 1000000000 ? tds_surf_con_slot(d->s, (int)c) : -1;
    if (slot < 0)
      return df_err(d, a, TDS_ERANGE, "%s: constraint %lld is not defined", what,
                    (long long)c);
    *mask |= (tds_cmask)1 << slot;
    n++;
  }
  if (!n) {
    char b[64];
    return df_err(d, d->p, TDS_ESYNTAX, "%s: expected constraint numbers, found %s", what,
                  df_describe(d->p, b, sizeof b));
  }
  return TDS_OK;
}

/* BOUNDARY b: its slot. */
static int bdry_ref(df *d, const char *what, int32_t *slot) {
  int64_t b;
  const char *a = d->p;
  int rc = df_read_int(d, 0, what, &b);
  if (rc) return rc;
  *slot = b > 0 && b <= 1000000000 ? tds_model_boundary_slot(d->s, (int)b) : -1;
  if (*slot < 0)
    return df_err(d, a, TDS_ERANGE, "%s: boundary %lld is not defined", what, (long long)b);
  return TDS_OK;
}

void df_free_ids(df *d) {
  for (int k = 0; k < 4; k++) {
    tds_free(&d->ctx->alloc, d->idmap[k]);
    d->idmap[k] = NULL;
    d->capmap[k] = 0;
  }
}

/* The slot of the element of `kind` the file calls v, or TDS_NONE if the
** file has not declared it (the caller checks a kept id is alive). */
static tds_id slot_of(const df *d, int kind, int64_t v) {
  if (v < 1 || v > d->maxid) return TDS_NONE;
  if (d->keep_ids) return (tds_id)(v - 1);
  return v < d->capmap[kind] ? d->idmap[kind][v] - 1 : TDS_NONE;
}

/* The element id at the start of a line of `kind` (named `name`): its
** slot into *id, the next one in order unless ids are kept; what = "name
** N" with the file's N for later messages. */
static int element_id(df *d, int kind, const char *name, tds_id *id, char *what,
                      size_t cap) {
  int64_t v;
  const char *a = d->p;
  snprintf(what, cap, "%s id", name);
  int rc = df_read_int(d, 0, what, &v);
  if (rc) return rc;
  if (v < 1 || v > d->maxid)
    return df_err(d, a, TDS_ERANGE, "%s id %lld is out of range (1 to %lld)", name,
                  (long long)v, (long long)d->maxid);
  snprintf(what, cap, "%s %lld", name, (long long)v);
  d->fid = v;
  d->orig = -1;
  if (d->keep_ids) {
    *id = (tds_id)(v - 1);
    return TDS_OK;
  }
  if (slot_of(d, kind, v) != TDS_NONE)
    return df_err(d, a, TDS_ERANGE, "%s is declared twice", what);
  if (v >= d->capmap[kind]) {
    int32_t cap0 = d->capmap[kind];
    if (tds_grow(&d->ctx->alloc, (void **)&d->idmap[kind], sizeof *d->idmap[kind],
                 &d->capmap[kind], (int32_t)v + 1))
      return df_err(d, a, TDS_ENOMEM, "out of memory");
    memset(d->idmap[kind] + cap0, 0, (size_t)(d->capmap[kind] - cap0) * sizeof *d->idmap[kind]);
  }
  *id = d->nread[kind]++;
  d->idmap[kind][v] = *id + 1;
  return TDS_OK;
}

/* The `original` of the element on the current line. */
static int32_t line_file_id(const df *d) {
  return (int32_t)(d->orig >= 0 ? d->orig : d->fid);
}

/* The next attribute word of an element line into w (lowercase): 1, or 0
** at the end of the line; a non-word is refused as "unexpected". */
static int next_attr(df *d, char *w, size_t cap, const char **at, const char *what,
                     int *rc) {
  *rc = TDS_OK;
  if (df_at_eol(d)) return 0;
  *at = d->p;
  if (!df_take_word(d, w, cap)) {
    char b[64];
    *rc = df_err(d, *at, TDS_ESYNTAX, "%s: unexpected %s", what,
                 df_describe(*at, b, sizeof b));
    return 0;
  }
  return 1;
}

/* ---- attribute words, through the registry (attr.h) ---- */

/* Push one value onto the pending list d->pv. */
static int push_pv(df *d, double v) {
  if (tds_grow(&d->ctx->alloc, (void **)&d->pv, sizeof *d->pv, &d->cappv, d->npv + 1))
    return df_err(d, NULL, TDS_ENOMEM, "out of memory");
  d->pv[d->npv++] = v;
  return TDS_OK;
}

/* The values of an array attribute: `{ v, v, ... }`, braces nested as
** the user likes (Evolver writes `{1,2,3}`; commas are blanks). */
static int read_array(df *d, const tds_attr *a, const char *what, int depth, int *n) {
  df_ws(d);
  if (*d->p != '{') {
    char b[64];
    return df_err(d, d->p, TDS_ESYNTAX, "%s: %s needs %d values in braces {...}, found %s",
                  what, a->name, a->size, df_describe(d->p, b, sizeof b));
  }
  d->p++;
  for (;;) {
    df_ws(d);
    if (*d->p == '}') {
      d->p++;
      return TDS_OK;
    }
    int rc;
    if (*d->p == '{' && depth < TDS_ATTR_MAXDIM) {
      rc = read_array(d, a, what, depth + 1, n);
    } else if (!*d->p) {
      return df_err(d, d->p, TDS_ESYNTAX, "%s: %s: missing '}'", what, a->name);
    } else if (*n >= a->size) {
      return df_err(d, d->p, TDS_ESYNTAX, "%s: %s takes %d values, got more", what, a->name,
                    a->size);
    } else {
      double v;
      rc = df_read_value(d, &v, what);
      if (!rc) rc = push_pv(d, v);
      (*n)++;
    }
    if (rc) return rc;
  }
}

/* The value of attribute a after its word, appended to d->pv as
** [row, n, values...] and checked against a's type. */
static int read_attr_value(df *d, int kind, int row, const tds_attr *a, const char *what,
                           const char *at) {
  int32_t start = d->npv;
  int rc = push_pv(d, row);
  if (!rc) rc = push_pv(d, 0);
  if (rc) return rc;
  int n = 0;
  if (a->type == TDS_AT_FLAG) {
    rc = push_pv(d, 1);
    n = 1;
  } else if (a->type == TDS_AT_COLOR) {
    int16_t c;
    rc = df_read_color(d, &c, what);
    if (!rc) rc = push_pv(d, c);
    n = 1;
  } else if (a->size > 1) {
    rc = read_array(d, a, what, 0, &n);
  } else {
    double v;
    rc = df_read_value(d, &v, what);
    if (!rc) rc = push_pv(d, v);
    n = 1;
  }
  if (rc) return rc;
  d->pv[start + 1] = n;
  rc = tds_attr_check(d->ctx, a, what, d->pv + start + 2, n);
  (void)kind;
  return rc ? df_core(d, df_line_of(d, at), rc, NULL) : TDS_OK;
}

/* The attribute words of an element line of `kind`: flags collected into
** *flags, constraints into *con (*rev when one is negative), a boundary
** into *bd (bdat: where), the others' values onto d->pv for apply_attrs.
** ORIGINAL (any kind) goes to d->orig. Words tds reads and ignores: a vertex's COLOR (a
** display option), a facet's BACKCOLOR, a body's CENTEROFMASS. */
static int attr_words(df *d, int kind, const char *what, uint32_t *flags, tds_cmask *con,
                      int *rev, int32_t *bd, const char **bdat) {
  char w[64];
  const char *at;
  int rc;
  while (next_attr(d, w, sizeof w, &at, what, &rc)) {
    tds_attr a;
    if (!strcmp(w, "original")) {
      rc = read_original(d, what);
    } else if ((kind == TDS_VERTEX && (!strcmp(w, "color") || !strcmp(w, "colour"))) ||
               (kind == TDS_FACET && !strcmp(w, "backcolor"))) {
      int16_t c; /* vertices have no colour; tds keeps one colour per facet */
      rc = df_read_color(d, &c, what);
    } else if (kind == TDS_BODY && !strcmp(w, "centerofmass")) {
      /* display option of Evolver's dumps */
    } else if (kind == TDS_FACET && !strcmp(w, "boundary")) {
      return df_err(d, at, TDS_ESYNTAX, "%s: faces on a BOUNDARY are not supported yet", what);
    } else if (!tds_attr_find_fe(&d->s->m, kind, w, &a)) {
      return unknown_attr(d, at, w, what);
    } else if (a.type == TDS_AT_CONS && con) {
      rc = con_list(d, what, con, rev);
    } else if (a.type == TDS_AT_BDRY && bd) {
      if (bdat) *bdat = at;
      rc = bdry_ref(d, what, bd);
    } else if (a.type == TDS_AT_CONS || a.type == TDS_AT_BDRY) {
      return unknown_attr(d, at, w, what);
    } else if (a.type == TDS_AT_FLAG) {
      *flags |= a.flag;
    } else {
      int row = 0;
      while (row < tds_attr_count(&d->s->m, kind)) {
        tds_attr b;
        tds_attr_at(&d->s->m, kind, row, &b);
        if (b.name == a.name) break; /* the same row: names are shared strings */
        row++;
      }
      rc = read_attr_value(d, kind, row, &a, what, at);
    }
    if (rc) return rc;
  }
  return rc;
}

/* Refuse attributes that exclude each other (a body's VOLUME and
** PRESSURE) among those read from d->pv[from..]. */
static int exclusive(df *d, int kind, const char *what, int32_t from) {
  const char *names[64];
  int n = 0;
  for (int32_t i = from; i < d->npv && n < 64; i += 2 + (int32_t)d->pv[i + 1]) {
    tds_attr a;
    tds_attr_at(&d->s->m, kind, (int)d->pv[i], &a);
    names[n++] = a.name;
  }
  int rc = tds_attr_exclusive(d->ctx, &d->s->m, kind, what, 1, names, n);
  return rc ? df_core(d, df_line_of(d, NULL), rc, NULL) : TDS_OK;
}

/* Set the values d->pv[from..to) (read by attr_words) on element id. */
static int apply_attrs(df *d, int kind, tds_id id, int32_t from, int32_t to, int line) {
  for (int32_t i = from; i < to;) {
    tds_attr a;
    tds_attr_at(&d->s->m, kind, (int)d->pv[i], &a);
    int n = (int)d->pv[i + 1];
    int rc = tds_attr_write(d->ctx, d->s, &a, id, d->pv + i + 2, n);
    if (rc) return df_core(d, line, rc, NULL);
    i += 2 + n;
  }
  return TDS_OK;
}

/* Append one entry to the scratch list d->oe (at: where for messages). */
static int push_oe(df *d, const char *at, int32_t v) {
  if (tds_grow(&d->ctx->alloc, (void **)&d->oe, sizeof *d->oe, &d->capoe, d->noe + 1))
    return df_err(d, at, TDS_ENOMEM, "out of memory");
  d->oe[d->noe++] = v;
  return TDS_OK;
}

/* A warning of the core, forwarded with "file:line: " in front. */
typedef struct at_line {
  tds_out_fn fn;
  void *ud;
  const char *name;
  int line;
} at_line;

static void warn_at_line(void *ud, const char *text) {
  const at_line *w = ud;
  char buf[2300];
  snprintf(buf, sizeof buf, "%.280s:%d: %.2000s", w->name, w->line, text);
  if (w->fn) {
    w->fn(w->ud, buf);
  } else {
    fputs(buf, stderr);
    fflush(stderr);
  }
}

/* ---- the four kinds of lines ---- */


/* The name of a quantity with a Klein-model method (klein_length,
** klein_area: defined inside the unit ball only), or NULL. */
static const char *klein_quantity(const tds_surf *s) {
  for (int q = 0; q < s->nquant; q++)
    for (int j = 0; j < s->quant[q].ninst; j++) {
      int m = s->quant[q].inst[j].method;
      if (m == TDS_M_KLEIN_LENGTH || m == TDS_M_KLEIN_AREA) return s->quant[q].name;
    }
  return NULL;
}

static int vertex_line(df *d) {
  tds_id id;
  char what[48];
  int rc = element_id(d, TDS_VERTEX, "vertex", &id, what, sizeof what);
  if (rc) return rc;
  double val[3];
  int nval = 0;
  int maxc = d->s->str ? d->s->str->space_dim : 3;
  val[2] = 0; /* z of a vertex in 2-D space */
  while (df_looks_value(d)) {
    if (nval == maxc)
      return df_err(d, d->p, TDS_ESYNTAX, "%s: more than %d coordinates%s", what, maxc,
                    maxc == 3 ? " (SPACE_DIMENSION > 3 is not supported yet)" : "");
    if ((rc = df_read_value(d, &val[nval], what))) return rc;
    nval++;
  }
  uint32_t flags = 0;
  tds_cmask con = 0;
  int32_t bd = TDS_NONE;
  const char *bdat = NULL;
  int32_t pv0 = d->npv = 0;
  if ((rc = attr_words(d, TDS_VERTEX, what, &flags, &con, NULL, &bd, &bdat))) return rc;
  double x[3] = {0, 0, 0}, p[2] = {0, 0};
  if (bd != TDS_NONE) {
    int np = d->s->bdry[bd].nparams;
    if (con)
      return df_err(d, bdat, TDS_ESYNTAX,
                    "%s: a vertex on a boundary cannot also be on a constraint", what);
    if (nval != np)
      return df_err(d, NULL, TDS_ESYNTAX, "%s on boundary %d needs %d parameter%s, got %d",
                    what, d->s->bdry[bd].number, np, np > 1 ? "s" : "", nval);
    for (int k = 0; k < np; k++) p[k] = val[k];
  } else {
    if (nval != maxc)
      return df_err(d, NULL, TDS_ESYNTAX, "%s needs %d coordinates, got %d", what, maxc, nval);
    for (int k = 0; k < 3; k++) x[k] = val[k];
  }
  const char *kq = klein_quantity(d->s);
  if (kq && !d->s->klein && !(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] < 1))
    return df_err(d, NULL, TDS_ERANGE,
                  "%s: (%g, %g, %g) is not inside the unit ball, where quantity %s's Klein "
                  "model method is defined", what, x[0], x[1], x[2], kq);
  if (d->s->klein && !d->string_model && !(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] < 1))
    return df_err(d, NULL, TDS_ERANGE,
                  "%s: (%g, %g, %g) is not inside the unit ball, the Klein model of "
                  "KLEIN_METRIC", what, x[0], x[1], x[2]);
  if (d->s->klein && !(x[0] * x[0] + x[1] * x[1] + x[2] * x[2] < 1))
    return df_err(d, NULL, TDS_ERANGE,
                  "%s: (%g, %g) is not inside the unit disk, the Klein model of KLEIN_METRIC",
                  what, x[0], x[1]);
  int line = df_line_of(d, NULL);
  /* the core's warnings (a projection that did not converge) get the
  ** file and line */
  at_line w = {d->ctx->warn, d->ctx->warn_ud, d->name, line};
  d->ctx->warn = warn_at_line;
  d->ctx->warn_ud = &w;
  rc = tds_decl_vertex(d->ctx, d->s, id, x, bd, p, flags, con);
  if (rc == TDS_OK) {
    d->s->m.vfile[id] = line_file_id(d);
    rc = apply_attrs(d, TDS_VERTEX, id, pv0, d->npv, line);
    if (rc == TDS_OK && d->s->nxa_kind[TDS_VERTEX] && d->s->m.vcon[id])
      rc = tds_decl_vertex_done(d->ctx, d->s, id);
    else if (rc != TDS_OK)
      rc = -rc; /* apply_attrs's message has its line already */
  }
  d->ctx->warn = w.fn;
  d->ctx->warn_ud = w.ud;
  if (rc < 0) return -rc;
  if (rc) return df_core(d, line, rc, NULL);
  return TDS_OK;
}

static int edge_line(df *d) {
  tds_id id;
  char what[48];
  int rc = element_id(d, TDS_EDGE, "edge", &id, what, sizeof what);
  if (rc) return rc;
  int64_t ends[2];
  tds_id vs[2];
  for (int k = 0; k < 2; k++) {
    if ((rc = df_read_int(d, 0, what, &ends[k]))) return rc;
    vs[k] = slot_of(d, TDS_VERTEX, ends[k]);
    if (vs[k] == TDS_NONE || vs[k] >= d->s->m.nv || !tds_alive(d->s->m.vflags, vs[k]))
      return df_err(d, NULL, TDS_ERANGE, "%s refers to vertex %lld, which does not exist",
                    what, (long long)ends[k]);
  }
  df_ws(d);
  if (df_looks_int(d))
    return df_err(d, d->p, TDS_ESYNTAX,
                  "%s: a third vertex (QUADRATIC midpoint) is not supported yet", what);
  int32_t wrap;
  if ((rc = df_edge_wrap(d, what, &wrap))) return rc;
  uint32_t flags = 0;
  tds_cmask con = 0;
  int rev = 0;
  int32_t bd = TDS_NONE;
  int32_t pv0 = d->npv = 0;
  if ((rc = attr_words(d, TDS_EDGE, what, &flags, &con, &rev, &bd, NULL))) return rc;
  if (rev) flags |= TDS_CONREV;
  int line = df_line_of(d, NULL);
  if (vs[0] == vs[1])
    return df_err(d, NULL, TDS_ETOPO, "%s starts and ends at vertex %lld", what,
                  (long long)ends[0]);
  rc = tds_decl_edge(d->ctx, d->s, id, vs[0], vs[1], flags, con, bd,
                     d->s->str ? 1 : 0, 0); /* strings carry tension by default */
  if (rc) return df_core(d, line, rc, NULL);
  d->s->m.efile[id] = line_file_id(d);
  if (d->s->m.ewrap) d->s->m.ewrap[id] = wrap;
  return apply_attrs(d, TDS_EDGE, id, pv0, d->npv, line);
}

/* The signed ids after an element's id (a face's edges, a body's faces),
** pushed onto d->oe as oriented references (faces) or signed 1-based ids
** (bodies); each must name a live element. *n gets their number. */
static int id_list(df *d, int kind, const char *what, int *n) {
  const tds_mesh *m = &d->s->m;
  *n = 0;
  while (df_looks_int(d)) {
    int64_t v;
    const char *a = d->p;
    int rc = df_read_int(d, 1, what, &v);
    if (rc) return rc;
    int64_t av = v < 0 ? -v : v;
    tds_id sl = slot_of(d, kind, av);
    const tds_strings *st = d->s->str;
    int ok = sl != TDS_NONE && (kind == TDS_EDGE
                 ? sl < m->ne && tds_alive(m->eflags, sl)
                 : st ? sl < st->nf && !(st->flags[sl] & TDS_DEAD)
                 : sl < m->nf && tds_alive(m->fflags, sl) && m->forig[sl] == sl);
    if (!ok)
      return df_err(d, a, TDS_ERANGE, "%s refers to %s %lld, which does not exist", what,
                    kind == TDS_EDGE ? "edge" : "face", (long long)av);
    rc = push_oe(d, a, kind == TDS_EDGE ? TDS_OREF(sl, v < 0) : (v < 0 ? -(sl + 1) : sl + 1));
    if (rc) return rc;
    (*n)++;
  }
  return TDS_OK;
}

static int face_line(df *d) {
  tds_id id;
  char what[48];
  int rc = element_id(d, TDS_FACET, "face", &id, what, sizeof what);
  if (rc) return rc;
  int32_t off = d->noe;
  int n;
  if ((rc = id_list(d, TDS_EDGE, what, &n))) return rc;
  tds_face_attr fa = {0};
  fa.tension = 1;
  fa.color = 15;
  int32_t pv0 = d->npv; /* faces keep their values until df_build_faces */
  if ((rc = attr_words(d, TDS_FACET, what, &fa.flags, &fa.con, NULL, NULL, NULL))) return rc;
  if (n < 3 && !(d->s->str && n >= 1))
    return df_err(d, NULL, TDS_ETOPO, "%s has %d edge%s; at least 3 are needed", what, n,
                  n == 1 ? "" : "s");
  if (tds_grow(&d->ctx->alloc, (void **)&d->faces, sizeof *d->faces, &d->capfaces, d->nfaces + 1))
    return df_err(d, NULL, TDS_ENOMEM, "out of memory");
  df_face *r = &d->faces[d->nfaces++];
  r->id = id;
  r->line = df_line_of(d, NULL);
  r->n = n;
  r->off = off;
  r->at = fa;
  r->pv0 = pv0;
  r->pv1 = d->npv;
  r->file = line_file_id(d);
  if (id + 1 > d->maxface) d->maxface = id + 1;
  return TDS_OK;
}

int df_build_faces(df *d) {
  if (d->nfaces == 0) return TDS_OK;
  if (d->s->str) return df_string_faces(d);
  tds_mesh *m = &d->s->m;
  /* Reserve for the split-off elements at once (tds_build_face reserves
  ** exactly what each face needs, which is quadratic over many faces). */
  int64_t nv = m->nv, ne = m->ne, nf = d->maxface;
  for (int32_t i = 0; i < d->nfaces; i++)
    if (d->faces[i].n > 3) {
      nv += 1;
      ne += d->faces[i].n;
      nf += d->faces[i].n - 1;
    }
  if (nv > INT32_MAX / 8 || ne > INT32_MAX / 8 || nf > INT32_MAX / 8 ||
      tds_mesh_reserve(m, TDS_VERTEX, (int32_t)nv) ||
      tds_mesh_reserve(m, TDS_EDGE, (int32_t)ne) ||
      tds_mesh_reserve(m, TDS_FACET, (int32_t)nf) ||
      tds_mesh_extend_dead(m, TDS_FACET, d->maxface))
    return df_err(d, NULL, TDS_ENOMEM, "out of memory");
  for (int32_t i = 0; i < d->nfaces; i++) {
    df_face *r = &d->faces[i];
    int32_t nf0 = m->nf;
    int rc = tds_build_face(d->ctx, d->s, r->id, r->n, d->oe + r->off, &r->at);
    if (rc) return df_core(d, r->line, rc, NULL);
    /* the attributes on every facet built from the face */
    if ((rc = apply_attrs(d, TDS_FACET, r->id, r->pv0, r->pv1, r->line))) return rc;
    m->ffile[r->id] = (int32_t)r->file;
    for (tds_id f = nf0 > r->id ? nf0 : r->id + 1; f < m->nf; f++) {
      if (m->forig[f] != r->id) continue;
      m->ffile[f] = (int32_t)r->file;
      if ((rc = apply_attrs(d, TDS_FACET, f, r->pv0, r->pv1, r->line))) return rc;
    }
  }
  d->nfaces = 0;
  d->npv = 0;
  return TDS_OK;
}

static int body_line(df *d) {
  tds_id id;
  char what[48];
  int rc = element_id(d, TDS_BODY, "body", &id, what, sizeof what);
  if (rc) return rc;
  int32_t off = d->noe;
  int n;
  if ((rc = id_list(d, TDS_FACET, what, &n))) return rc;
  int32_t pv0 = d->npv = 0;
  uint32_t flags = 0;
  if ((rc = attr_words(d, TDS_BODY, what, &flags, NULL, NULL, NULL, NULL))) return rc;
  if ((rc = exclusive(d, TDS_BODY, what, pv0))) return rc;
  int line = df_line_of(d, NULL);
  if (d->s->str) {
    rc = df_string_body(d, id, n, d->oe + off);
    d->noe = off;
    if (rc) return rc;
  } else {
    rc = tds_decl_body(d->ctx, d->s, id, n, d->oe + off);
    d->noe = off;
    if (rc) return df_core(d, line, rc, NULL);
  }
  d->s->m.bfile[id] = line_file_id(d);
  return apply_attrs(d, TDS_BODY, id, pv0, d->npv, line);
}

int df_element_line(df *d) {
  switch (d->section) {
  case S_VERTICES: return vertex_line(d);
  case S_EDGES: return edge_line(d);
  case S_FACES: return face_line(d);
  default: return body_line(d);
  }
}
