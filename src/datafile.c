/*
** datafile.c: the Surface Evolver datafile reader's driver (contract in
** datafile.h): the load entry points, the dispatch of each logical line to
** the top section, a section keyword or an element line, the finishing
** touches after the last section, cleanup on failure, and detection of
** datafiles. The pieces are listed in datafile_int.h.
*/
#include "datafile_int.h"
#include "ring.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "model.h"
#include "motion.h"
#include "string_model.h"

static const char *const section_name[] = {"top", "VERTICES", "EDGES", "FACES",
                                           "BODIES"};

/* ---- sections ---- */

static int end_section(df *d) {
  int rc = d->section == S_FACES ? df_build_faces(d) : TDS_OK;
  d->noe = 0;
  return rc;
}

static int section_of(const char *w) {
  if (!strcmp(w, "vertices")) return S_VERTICES;
  if (!strcmp(w, "edges")) return S_EDGES;
  if (!strcmp(w, "faces") || !strcmp(w, "facets")) return S_FACES;
  if (!strcmp(w, "bodies")) return S_BODIES;
  return -1;
}

/* Start section sec at the keyword at `at`. */
static int begin_section(df *d, int sec, const char *at) {
  if (sec == d->section)
    return df_err(d, at, TDS_ESYNTAX, "%s section given twice", section_name[sec]);
  if (sec < d->section)
    return df_err(d, at, TDS_ESYNTAX, "%s section after the %s section",
                  section_name[sec], section_name[d->section]);
  if (sec > S_VERTICES && !d->seen_vertices)
    return df_err(d, at, TDS_ESYNTAX, "%s section before the VERTICES section",
                  section_name[sec]);
  int rc = end_section(d);
  if (rc) return rc;
  d->section = sec;
  if (sec == S_VERTICES) {
    d->seen_vertices = 1;
    if ((rc = df_torus_start(d, at))) return rc;
    if ((rc = df_klein_check(d))) return rc;
    /* the model, now that the top section has said which */
    if (d->string_model) {
      rc = tds_strings_enable(d->ctx, d->s, d->space_dim ? d->space_dim : 3);
      if (rc) return df_core(d, df_line_of(d, at), rc, NULL);
      if ((rc = df_string_model(d))) return rc;
    } else if (d->space_dim == 2) {
      return df_err(d, at, TDS_ESYNTAX,
                    "SPACE_DIMENSION 2 is supported only in the string model (STRING)");
    }
  }
  if (!df_at_eol(d)) {
    char b[64];
    return df_err(d, d->p, TDS_ESYNTAX, "unexpected %s after %s",
                  df_describe(d->p, b, sizeof b), section_name[sec]);
  }
  return TDS_OK;
}

/* Whether the rest of text has anything but whitespace and comments. */
static int has_commands(const char *s, size_t n) {
  size_t i = 0;
  while (i < n) {
    if (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r') {
      i++;
    } else if (i + 1 < n && s[i] == '/' && s[i + 1] == '/') {
      while (i < n && s[i] != '\n') i++;
    } else if (i + 1 < n && s[i] == '/' && s[i + 1] == '*') {
      i += 2;
      while (i + 1 < n && !(s[i] == '*' && s[i + 1] == '/')) i++;
      i += 2;
    } else {
      return 1;
    }
  }
  return 0;
}

/* Dispatch each logical line, up to the end of the text or READ: in the
** top section to its keyword's reader, in element sections to the element
** reader, which must use the whole line. */
static int parse(df *d) {
  char w[64], b[64];
  for (;;) {
    int have, rc;
    if (d->section == S_HEADER) {
      if ((rc = df_more(d, &have))) return rc;
    } else {
      /* element sections: one element per logical line */
      while (df_at_eol(d)) {
        int r = df_next_line(d);
        if (r < 0) return -r;
        if (r == 0) break;
      }
      have = !df_at_eol(d);
    }
    if (!have) break;
    const char *at = d->p;
    if (d->section != S_HEADER && is_digit((unsigned char)*d->p)) {
      d->split = 1;
      rc = df_element_line(d);
      d->split = 0;
      if (rc) return rc;
      if (!df_at_eol(d))
        return df_err(d, d->p, TDS_ESYNTAX, "unexpected %s",
                      df_describe(d->p, b, sizeof b));
      continue;
    }
    if (!df_take_word(d, w, sizeof w)) {
      if (d->section == S_HEADER)
        return df_err(d, at, TDS_ESYNTAX, "expected a keyword, found %s",
                      df_describe(at, b, sizeof b));
      return df_err(d, at, TDS_ESYNTAX, "%s section: expected an element id, found %s",
                    section_name[d->section], df_describe(at, b, sizeof b));
    }
    int sec = section_of(w);
    if (sec >= 0) {
      if ((rc = begin_section(d, sec, at))) return rc;
      continue;
    }
    if (!strcmp(w, "read")) {
      if ((rc = end_section(d))) return rc;
      d->has_read = 1;
      d->read_at = df_lex_read_start(&d->lx);
      return TDS_OK;
    }
    if (d->section != S_HEADER) {
      char u[64];
      if (df_header_word(w))
        return df_err(d, at, TDS_ESYNTAX, "%s must come before the VERTICES section",
                      df_upper(w, u, sizeof u));
      return df_err(d, at, TDS_ESYNTAX, "%s section: expected an element id, found %s",
                    section_name[d->section], df_describe(at, b, sizeof b));
    }
    if ((rc = df_header_keyword(d, w, at))) return rc;
  }
  return end_section(d);
}

/* After parsing: global constraints, gravity, consistency. */
static int finish(df *d) {
  tds_surf *s = d->s;
  tds_mesh *m = &s->m;
  if (!d->seen_vertices)
    return df_err(d, NULL, TDS_ESYNTAX, "no VERTICES section (is this a datafile?)");
  tds_cmask global = 0;
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (s->con[c].number && (s->con[c].flags & TDS_CON_GLOBAL))
      global |= (tds_cmask)1 << c;
  if (global)
    for (tds_id v = 0; v < m->nv; v++) {
      if (!tds_alive(m->vflags, v) || (m->vcon[v] & global) == global) continue;
      m->vcon[v] |= global;
      if (m->vbdry[v] == TDS_NONE && tds_motion_enforce(s, v) != TDS_OK)
        tds_warnf(d->ctx, "%s: vertex %d: projection onto its constraints did not converge\n",
                  d->name, v + 1);
    }
  /* gravity_on: set by the body density setter (attr_rows.c) */
  if (!s->str) tds_ring_sort_angular(m, d->ne0); /* Evolver's facet order (ring.h) */
  if (s->str) {
    int rc = df_string_finish(d);
    if (rc) return rc;
  }
  if (tds_mesh_check(d->ctx, m) != TDS_OK) {
    char msg[sizeof d->ctx->errmsg];
    memcpy(msg, d->ctx->errmsg, sizeof msg);
    msg[sizeof msg - 1] = 0;
    return tds_seterr(d->ctx, TDS_ETOPO, "%s: inconsistent surface: %.900s", d->name, msg);
  }
  char where[300];
  snprintf(where, sizeof where, "%.280s: ", d->name);
  tds_mesh_body_warnings(d->ctx, m, where);
  if (m->torus) {
    int rc = df_torus_finish(d);
    if (rc) return rc;
  }
  if (d->has_read && !d->app) { /* addload: the new file's read section is not run */
    const char *r = d->lx.src + d->read_at;
    size_t n = d->lx.n - d->read_at;
    if (has_commands(r, n)) {
      s->read_text = tds_malloc(&s->m.alloc, n + 1);
      if (!s->read_text) return tds_seterr(d->ctx, TDS_ENOMEM, "out of memory");
      memcpy(s->read_text, r, n);
      s->read_text[n] = 0;
    }
  }
  m->topo_gen++;
  m->coord_gen++;
  return TDS_OK;
}

/* ---- loading ---- */

static int surface_empty(const tds_surf *s) {
  if (s->m.nv || s->m.ne || s->m.nf || s->m.nb || s->npar || s->nbdry || s->nquant ||
      s->read_text)
    return 0;
  for (int c = 0; c < TDS_MAX_CON; c++)
    if (s->con[c].number) return 0;
  return 1;
}

/* Read text into d->s: a new surface, or with `append` added to the one
** there (datafile_append.c). On failure s is emptied, or put back. */
static int read_text(tds_ctx *ctx, tds_surf *s, const char *name, const char *text,
                     size_t len, int append) {
  if (len > TDS_DF_MAXFILE)
    return tds_seterr(ctx, TDS_ESYNTAX, "%s: file too large (more than %u bytes)", name,
                      TDS_DF_MAXFILE);
  df d;
  memset(&d, 0, sizeof d);
  d.ctx = ctx;
  d.s = s;
  d.name = name;
  d.p = "";
  int64_t lim = 1000000 + 16 * (int64_t)len;
  d.maxid = lim < TDS_DF_MAXID ? lim : TDS_DF_MAXID;
  if (append) {
    int rc = df_app_begin(&d);
    if (rc) return rc;
  }
  df_lex_init(&d.lx, ctx, name, text ? text : "", text ? len : 0);
  int rc = parse(&d);
  if (rc == TDS_OK) rc = finish(&d);
  df_lex_free(&d.lx);
  tds_free(&ctx->alloc, d.faces);
  tds_free(&ctx->alloc, d.oe);
  tds_free(&ctx->alloc, d.pv);
  df_free_ids(&d);
  if (rc < 0) rc = -rc;
  if (append) {
    df_app_end(&d, rc == TDS_OK);
  } else if (rc != TDS_OK) {
    tds_surf_free(s); /* leaves ctx->errmsg alone */
  }
  return rc;
}

int tds_datafile_load_buffer(tds_ctx *ctx, tds_surf *s, const char *name,
                             const char *text, size_t len) {
  TDS_REQUIRE(ctx, s && (text || !len));
  TDS_REQUIRE(ctx, tds_alloc_same(&ctx->alloc, &s->m.alloc));
  if (!name) name = "(datafile)";
  if (!surface_empty(s))
    return tds_seterr(ctx, TDS_ERANGE,
                      "%s: a surface is already loaded; datafiles load into an "
                      "empty surface", name);
  int rc = read_text(ctx, s, name, text, len, 0);
  if (rc == TDS_OK) s->evolver_ls = 1; /* a datafile's surface takes Evolver's steps */
  return rc;
}

int tds_datafile_addload_buffer(tds_ctx *ctx, tds_surf *s, const char *name,
                                const char *text, size_t len) {
  TDS_REQUIRE(ctx, s && (text || !len));
  TDS_REQUIRE(ctx, tds_alloc_same(&ctx->alloc, &s->m.alloc));
  if (!name) name = "(datafile)";
  if (s->str)
    return tds_seterr(ctx, TDS_ESYNTAX, "%s: addload in the string model is not supported yet",
                      name);
  if (s->m.torus)
    return tds_seterr(ctx, TDS_ESYNTAX, "%s: addload in the torus model is not supported yet",
                      name);
  return read_text(ctx, s, name, text, len, 1);
}

/* The whole file at path into *buf (the caller frees it), *n bytes. */
static int slurp(tds_ctx *ctx, const char *path, char **out, size_t *nout) {
  *out = NULL;
  FILE *f = fopen(path, "rb");
  if (!f) return tds_seterr(ctx, TDS_EIO, "cannot open '%s': %s", path, strerror(errno));
  size_t cap = 1 << 16, n = 0;
  char *buf = tds_malloc(&ctx->alloc, cap);
  int rc = TDS_OK;
  while (buf) {
    if (n == cap) {
      if (cap > TDS_DF_MAXFILE) break;
      char *nb = tds_realloc(&ctx->alloc, buf, cap * 2);
      if (!nb) {
        tds_free(&ctx->alloc, buf);
        buf = NULL;
        break;
      }
      buf = nb;
      cap *= 2;
    }
    size_t got = fread(buf + n, 1, cap - n, f);
    n += got;
    if (got == 0) break;
  }
  if (!buf) {
    rc = tds_seterr(ctx, TDS_ENOMEM, "%s: out of memory", path);
  } else if (ferror(f)) {
    rc = tds_seterr(ctx, TDS_EIO, "cannot read '%s': %s", path, strerror(errno));
  } else if (n > TDS_DF_MAXFILE) {
    rc = tds_seterr(ctx, TDS_ESYNTAX, "%s: file too large (more than %u bytes)", path,
                    TDS_DF_MAXFILE);
  }
  fclose(f);
  if (rc != TDS_OK) {
    tds_free(&ctx->alloc, buf);
    return rc;
  }
  *out = buf;
  *nout = n;
  return TDS_OK;
}

int tds_datafile_load(tds_ctx *ctx, tds_surf *s, const char *path) {
  TDS_REQUIRE(ctx, s && path);
  char *buf;
  size_t n;
  int rc = slurp(ctx, path, &buf, &n);
  if (rc == TDS_OK) rc = tds_datafile_load_buffer(ctx, s, path, buf, n);
  tds_free(&ctx->alloc, buf);
  return rc;
}

int tds_datafile_addload(tds_ctx *ctx, tds_surf *s, const char *path) {
  TDS_REQUIRE(ctx, s && path);
  char *buf;
  size_t n;
  int rc = slurp(ctx, path, &buf, &n);
  if (rc == TDS_OK) rc = tds_datafile_addload_buffer(ctx, s, path, buf, n);
  tds_free(&ctx->alloc, buf);
  return rc;
}

/* ---- run-time definitions ---- */

static void free3(tds_expr **e) {
  for (int i = 0; i < 3; i++) tds_expr_free(e[i]), e[i] = NULL;
}

/* Remove what a failed definition added: constraint slots not in had,
** quantities and boundaries beyond the counts before (both append). */
static void undefine(tds_surf *s, const int *had, int nquant0, int nbdry0) {
  for (int c = 0; c < TDS_MAX_CON; c++) {
    tds_constraint *k = &s->con[c];
    if (!k->number || had[c]) continue;
    tds_expr_free(k->formula);
    free3(k->energy);
    free3(k->content);
    memset(k, 0, sizeof *k);
  }
  while (s->nbdry > nbdry0) {
    tds_boundary *bd = &s->bdry[--s->nbdry];
    free3(bd->x);
    free3(bd->energy);
    free3(bd->content);
    memset(bd, 0, sizeof *bd);
  }
  while (s->nquant > nquant0) {
    tds_quantity none;
    memset(&none, 0, sizeof none);
    tds_model_quantity_undo(s, s->nquant - 1, &none);
  }
}

int tds_datafile_define(tds_ctx *ctx, tds_surf *s, const char *name, int line,
                        const char *text, size_t len) {
  if (!name) name = "(define)";
  df d;
  memset(&d, 0, sizeof d);
  d.ctx = ctx;
  d.s = s;
  d.name = name;
  d.p = "";
  df_lex_init(&d.lx, ctx, name, text ? text : "", text ? len : 0);
  d.lx.line = line > 0 ? line : 1;
  int had[TDS_MAX_CON];
  for (int c = 0; c < TDS_MAX_CON; c++) had[c] = s->con[c].number;
  int nquant0 = s->nquant, nbdry0 = s->nbdry;
  char w[64], b[64];
  int have, rc = df_more(&d, &have);
  const char *at = d.p;
  if (!rc && (!have || !df_take_word(&d, w, sizeof w)))
    rc = df_err(&d, at, TDS_ESYNTAX, "define: expected CONSTRAINT, BOUNDARY or QUANTITY, found %s",
                df_describe(at, b, sizeof b));
  else if (!rc && strcmp(w, "constraint") && strcmp(w, "boundary") && strcmp(w, "quantity"))
    rc = df_err(&d, at, TDS_ESYNTAX,
                df_unsupported(w) ? "define %s: not supported yet"
                                  : "define: expected CONSTRAINT, BOUNDARY or QUANTITY, found '%s'",
                w);
  else if (!rc)
    rc = df_header_keyword(&d, w, at);
  if (rc < 0) rc = -rc;
  if (!rc && (rc = df_more(&d, &have)) == TDS_OK && have)
    rc = df_err(&d, d.p, TDS_ESYNTAX, "define %s: unexpected %s after the definition", w,
                df_describe(d.p, b, sizeof b));
  if (rc < 0) rc = -rc;
  df_lex_free(&d.lx);
  tds_free(&ctx->alloc, d.faces);
  tds_free(&ctx->alloc, d.oe);
  if (rc != TDS_OK) {
    undefine(s, had, nquant0, nbdry0);
    return rc;
  }
  /* A new GLOBAL constraint applies to every vertex, as at load. */
  for (int c = 0; c < TDS_MAX_CON; c++) {
    if (!s->con[c].number || had[c] || !(s->con[c].flags & TDS_CON_GLOBAL)) continue;
    tds_mesh *m = &s->m;
    for (tds_id v = 0; v < m->nv; v++) {
      if (!tds_alive(m->vflags, v)) continue;
      m->vcon[v] |= (tds_cmask)1 << c;
      if (m->vbdry[v] == TDS_NONE && tds_motion_enforce(s, v) != TDS_OK)
        tds_warnf(ctx, "%s:%d: vertex %d: projection onto constraint %d did not converge\n",
                  name, line, v + 1, (int)s->con[c].number);
    }
    m->coord_gen++;
  }
  return TDS_OK;
}

/* ---- detection ---- */

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), k = strlen(suffix);
  return n >= k && strcasecmp(s + n - k, suffix) == 0;
}

int tds_datafile_detect(const char *path) {
  if (ends_with(path, ".fe") || ends_with(path, ".dmp")) return 1;
  if (ends_with(path, ".tds") || ends_with(path, ".lua")) return 0;
  FILE *f = fopen(path, "rb");
  if (!f) return 0;
  char buf[8192];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = 0;
  size_t i = 0;
  for (;;) { /* skip whitespace, comments and # lines */
    while (i < n && is_ws((unsigned char)buf[i])) i++;
    if (i + 1 < n && buf[i] == '/' && buf[i + 1] == '/') {
      while (i < n && buf[i] != '\n') i++;
    } else if (i + 1 < n && buf[i] == '/' && buf[i + 1] == '*') {
      i += 2;
      while (i + 1 < n && !(buf[i] == '*' && buf[i + 1] == '/')) i++;
      i += 2;
    } else if (i < n && buf[i] == '#') {
      while (i < n && buf[i] != '\n') i++;
    } else {
      break;
    }
  }
  if (i >= n) return 0;
  size_t wl = df_word_len(buf + i);
  if (!wl || wl >= 64) return 0;
  char w[64];
  for (size_t k = 0; k < wl; k++) w[k] = (char)(buf[i + k] | (is_alpha((unsigned char)buf[i + k]) ? 32 : 0));
  w[wl] = 0;
  size_t j = i + wl;
  while (j < n && (buf[j] == ' ' || buf[j] == '\t')) j++;
  if (j < n && (buf[j] == '{' || buf[j] == '(' || buf[j] == '=' || buf[j] == '.' ||
                buf[j] == '[' || buf[j] == '"'))
    return 0;
  return section_of(w) >= 0 || df_header_word(w);
}
