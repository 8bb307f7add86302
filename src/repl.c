/* repl.c: the read-eval-print loop (Lua and Evolver lines, lua/evolver.lua). */
#include "repl.h"

#include <ctype.h>
#include <readline/history.h>
#include <readline/readline.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PROMPT1 "tds> "
#define PROMPT2 "...> "
#define HISTORY_MAX 1000

/* Message handler of every chunk (as lua.c's): an error object that is not
** a string becomes one through its __tostring, inside the protected call, so
** a __tostring that raises cannot escape (it gives LUA_ERRERR instead of a
** PANIC). q()'s quit table passes through. */
/* Append to the message on top a short traceback of the user's code: the
** frames of scripts, -e code and Evolver text (not C, not tds's embedded
** modules), innermost first, when there are two or more (a message of
** code at the top level has its position already). At most TB_MAX lines. */
#define TB_MAX 12
static void user_traceback(lua_State *L) {
  lua_Debug ar;
  int n = 0, shown = 0;
  for (int level = 1; lua_getstack(L, level, &ar); level++) {
    lua_getinfo(L, "S", &ar);
    if (ar.what[0] != 'C' && strncmp(ar.source, "=[tds ", 6) != 0) n++;
  }
  if (n < 2) return;
  lua_pushliteral(L, "\nstack traceback (your code):");
  lua_concat(L, 2);
  for (int level = 1; lua_getstack(L, level, &ar); level++) {
    lua_getinfo(L, "Sln", &ar);
    if (ar.what[0] == 'C' || strncmp(ar.source, "=[tds ", 6) == 0) continue;
    if (++shown > TB_MAX) {
      lua_pushliteral(L, "\n\t...");
      lua_concat(L, 2);
      break;
    }
    lua_pushfstring(L, "\n\t%s:%d: in ", ar.short_src, ar.currentline);
    if (*ar.what == 'm') lua_pushliteral(L, "main chunk");
    else if (ar.name) lua_pushfstring(L, "function '%s'", ar.name);
    else lua_pushfstring(L, "function <%s:%d>", ar.short_src, ar.linedefined);
    lua_concat(L, 3);
  }
}

/* A message positioned in tds's embedded Lua ("[tds pg]:113: ...", an
** error the module did not foresee) gets the user's position instead. */
static void user_position(lua_State *L) {
  const char *msg = lua_tostring(L, -1), *p;
  if (strncmp(msg, "[tds ", 5) != 0 || !(p = strstr(msg, "]:"))) return;
  p += 2;
  while (isdigit((unsigned char)*p)) p++;
  if (p[0] != ':' || p[1] != ' ') return;
  tds_lua_where(L);
  lua_pushstring(L, p + 2);
  lua_concat(L, 2);
  lua_remove(L, -2);
}

/* Does the message's first line carry a position ("file:12: ...")? */
static int positioned(const char *msg) {
  for (const char *p = msg; *p && *p != '\n'; p++) {
    if (*p != ':' || !isdigit((unsigned char)p[1])) continue;
    const char *q = p + 1;
    while (isdigit((unsigned char)*q)) q++;
    if (q[0] == ':' && (q[1] == ' ' || q[1] == 0)) return 1;
  }
  return 0;
}

/* A message without a position (raised by C code, or by error(msg, 2)
** whose caller is C) gets the position of the innermost user code: every
** error of a chunk names its file and line ("stdin:1: ..." at the prompt). */
static void ensure_position(lua_State *L) {
  if (positioned(lua_tostring(L, -1))) return;
  tds_lua_where(L);
  /* none on the stack: the chunk's frame was left by a tail call (the
  ** prompt's `return f(x);`): the chunk's own position, the upvalue */
  if (!*lua_tostring(L, -1) && lua_isstring(L, lua_upvalueindex(1))) {
    lua_pop(L, 1);
    lua_pushvalue(L, lua_upvalueindex(1));
  }
  lua_insert(L, -2);
  lua_concat(L, 2);
}

static int message_handler(lua_State *L) {
  if (tds_lua_is_quit(L, 1, NULL)) return 1;
  if (lua_type(L, 1) != LUA_TSTRING &&
      !(luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING))
    lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  if (lua_gettop(L) == 1) lua_pushvalue(L, 1);
  user_position(L);
  if (lua_type(L, 1) == LUA_TSTRING) ensure_position(L);
  user_traceback(L);
  return 1;
}

static void print_error(lua_State *L) {
  const char *msg = lua_tostring(L, -1);
  if (!msg) msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, -1));
  fprintf(stderr, "%s\n", msg);
  fflush(stderr);
}

int tds_run_chunk(lua_State *L, tds_state *st, int *quit_code) {
  return tds_run_chunk_at(L, st, quit_code, NULL);
}

int tds_run_chunk_at(lua_State *L, tds_state *st, int *quit_code, const char *where) {
  fflush(stdout);
  int base = lua_gettop(L); /* the chunk */
  if (where) lua_pushstring(L, where);
  else lua_pushnil(L);
  lua_pushcclosure(L, message_handler, 1);
  lua_insert(L, base);
  tds_lua_sigint(L, st, 1);
  int status = lua_pcall(L, 0, LUA_MULTRET, base);
  tds_lua_sigint(L, st, 0);
  lua_remove(L, base);
  if (st->after_chunk) st->after_chunk(st->after_ud);
  fflush(stdout);
  if (status == LUA_OK) return 0;
  if (tds_lua_is_quit(L, -1, quit_code)) {
    lua_pop(L, 1);
    return 2;
  }
  print_error(L);
  lua_pop(L, 1);
  return 1;
}

/* One line of input (without the newline), malloc'd; NULL at end of input. */
static char *read_line(int tty, const char *prompt) {
  if (tty) {
    signal(SIGINT, SIG_IGN); /* Ctrl-C at the prompt does nothing */
    char *line = readline(prompt);
    signal(SIGINT, SIG_DFL);
    return line;
  }
  size_t cap = 256, n = 0;
  char *buf = malloc(cap);
  if (!buf) return NULL;
  int c;
  while ((c = getchar()) != EOF && c != '\n') {
    if (n + 1 == cap) {
      char *b = realloc(buf, cap *= 2);
      if (!b) {
        free(buf);
        return NULL;
      }
      buf = b;
    }
    buf[n++] = (char)c;
  }
  if (c == EOF && n == 0) {
    free(buf);
    return NULL;
  }
  buf[n] = 0;
  return buf;
}

/* Syntax error caused only by the end of the chunk: more input may fix it. */
static int incomplete(lua_State *L, int status) {
  if (status != LUA_ERRSYNTAX) return 0;
  size_t len;
  const char *msg = lua_tolstring(L, -1, &len);
  return len >= 5 && strcmp(msg + len - 5, "<eof>") == 0;
}

/* A line that is just a name whose value is a function: call it (Evolver
** habit: `r`, `gogo`). Pushes the function and returns 1 if so. */
static int bare_function(lua_State *L, const char *line) {
  const char *p = line, *start;
  while (isspace((unsigned char)*p)) p++;
  start = p;
  if (!isalpha((unsigned char)*p) && *p != '_') return 0;
  while (isalnum((unsigned char)*p) || *p == '_') p++;
  const char *end = p;
  while (isspace((unsigned char)*p)) p++;
  if (*p) return 0;
  lua_pushglobaltable(L);
  lua_pushlstring(L, start, (size_t)(end - start));
  lua_gettable(L, -2);
  lua_remove(L, -2);
  if (lua_isfunction(L, -1)) return 1;
  lua_pop(L, 1);
  return 0;
}

/* Append a continuation line to *buf (returns 0 at end of input). */
static int more_input(int tty, char **buf) {
  char *more = read_line(tty, PROMPT2);
  if (!more) return 0;
  size_t n = strlen(*buf) + strlen(more) + 2;
  char *joined = malloc(n);
  if (!joined) {
    free(more);
    return 0;
  }
  snprintf(joined, n, "%s\n%s", *buf, more);
  free(more);
  free(*buf);
  *buf = joined;
  return 1;
}

/* Translate Evolver text (reading more lines while it is incomplete) and
** compile it. Leaves a function and returns 1, or prints the Evolver
** message (after lua_err, Lua's message, when the line was tried as Lua
** first) and returns 0. */
static int compile_evolver(lua_State *L, int tty, char **text, const char *lua_err) {
  for (;;) {
    lua_getglobal(L, "tds");
    lua_getfield(L, -1, "translate");
    lua_remove(L, -2);
    lua_pushstring(L, *text);
    if (lua_pcall(L, 1, 3, 0) != LUA_OK) {
      print_error(L);
      lua_pop(L, 1);
      return 0;
    }
    if (lua_isstring(L, -3)) {
      const char *code = lua_tostring(L, -3);
      int st = luaL_loadbuffer(L, code, strlen(code), "=stdin");
      lua_replace(L, -4);
      lua_pop(L, 2);
      if (st == LUA_OK) return 1;
      print_error(L);
      lua_pop(L, 1);
      return 0;
    }
    int incomplete_ev = lua_toboolean(L, -1);
    if (incomplete_ev && more_input(tty, text)) {
      lua_pop(L, 3);
      continue;
    }
    lua_pop(L, 1);
    if (lua_err) {
      fprintf(stderr, "%s\n", lua_err);
      lua_pushfstring(L, "  (as an Evolver command: %s)", lua_tostring(L, -1));
      lua_replace(L, -2);
    }
    print_error(L);
    lua_pop(L, 2);
    return 0;
  }
}

/* Compile the chunk in *buf (may read continuation lines, growing *buf).
** Leaves a function on the stack and returns 1, returns -1 when the line
** was a mode switch (nothing to run), or prints the error and returns 0.
** The rule for Lua versus Evolver lines is tds.repl_classify
** (lua/evolver.lua). */
static int compile(lua_State *L, int tty, char **buf) {
  const char *how = "auto";
  lua_getglobal(L, "tds");
  lua_getfield(L, -1, "repl_classify");
  lua_remove(L, -2);
  lua_pushstring(L, *buf);
  if (lua_pcall(L, 1, 2, 0) == LUA_OK && lua_isstring(L, -2) && lua_isstring(L, -1)) {
    how = lua_tostring(L, -2);
    if (!strcmp(how, "mode")) {
      printf("%s\n", lua_tostring(L, -1));
      lua_pop(L, 2);
      return -1;
    }
    char *text = strdup(lua_tostring(L, -1));
    int lua_only = !strcmp(how, "lua"), evolver_only = !strcmp(how, "evolver");
    lua_pop(L, 2);
    if (!text) return 0;
    free(*buf);
    *buf = text;
    if (evolver_only) return compile_evolver(L, tty, buf, NULL);
    if (lua_only) how = "lua";
    else how = "auto";
  } else {
    lua_pop(L, 2);
  }
  int auto_mode = !strcmp(how, "auto");
  if (auto_mode && bare_function(L, *buf)) return 1;
  lua_pushfstring(L, "return %s;", *buf);
  int status = luaL_loadbuffer(L, lua_tostring(L, -1), lua_rawlen(L, -1), "=stdin");
  lua_remove(L, -2);
  if (status == LUA_OK) return 1;
  lua_pop(L, 1);
  for (;;) {
    status = luaL_loadbuffer(L, *buf, strlen(*buf), "=stdin");
    if (!incomplete(L, status)) break;
    lua_pop(L, 1);
    if (!more_input(tty, buf)) {
      luaL_loadbuffer(L, *buf, strlen(*buf), "=stdin"); /* the error again */
      break;
    }
  }
  if (status == LUA_OK) return 1;
  if (!auto_mode) {
    print_error(L);
    lua_pop(L, 1);
    return 0;
  }
  /* Not Lua: Evolver command text. */
  char *lua_err = strdup(lua_tostring(L, -1) ? lua_tostring(L, -1) : "");
  lua_pop(L, 1);
  int ok = compile_evolver(L, tty, buf, lua_err);
  free(lua_err);
  return ok;
}

static char *history_path(void) {
  const char *env = getenv("TDS_HISTORY");
  if (env) return *env ? strdup(env) : NULL;
  const char *home = getenv("HOME");
  if (!home || !*home) return NULL;
  size_t n = strlen(home) + 16;
  char *p = malloc(n);
  if (p) snprintf(p, n, "%s/.tds_history", home);
  return p;
}

/* The prompt: tds.repl_prompt() (it names the mode), else PROMPT1. The
** string is copied into buf. */
static const char *prompt1(lua_State *L, char *buf, size_t n) {
  snprintf(buf, n, "%s", PROMPT1);
  lua_getglobal(L, "tds");
  lua_getfield(L, -1, "repl_prompt");
  lua_remove(L, -2);
  if (lua_isfunction(L, -1) && lua_pcall(L, 0, 1, 0) == LUA_OK && lua_isstring(L, -1))
    snprintf(buf, n, "%s", lua_tostring(L, -1));
  lua_pop(L, 1);
  return buf;
}

int tds_repl(lua_State *L, tds_state *st) {
  int tty = isatty(0), failed = 0, code = 0;
  char *hist = tty ? history_path() : NULL;
  if (hist) {
    stifle_history(HISTORY_MAX);
    if (read_history(hist) != 0) write_history(hist);
  }
  if (tty)
    printf("tds %s: Lua with soap films. `help()` lists commands, q quits.\n",
           TDS_VERSION);
  char *buf;
  char prompt[64];
  while ((buf = read_line(tty, prompt1(L, prompt, sizeof prompt))) != NULL) {
    const char *p = buf;
    while (isspace((unsigned char)*p)) p++;
    if (!*p) {
      free(buf);
      continue;
    }
    int base = lua_gettop(L);
    int compiled = compile(L, tty, &buf);
    if (compiled < 0) {
      free(buf);
      continue;
    }
    if (compiled) {
      if (hist) {
        add_history(buf);
        append_history(1, hist);
      }
      int rc = tds_run_chunk_at(L, st, &code, "stdin:1: ");
      if (rc == 2) {
        free(buf);
        goto done;
      }
      failed |= rc;
      int n = lua_gettop(L) - base;
      if (n > 0) { /* print results with the global print */
        lua_getglobal(L, "print");
        lua_insert(L, base + 1);
        if (lua_pcall(L, n, 0, 0) != LUA_OK) {
          print_error(L);
          lua_pop(L, 1);
        }
      }
    } else {
      failed = 1;
    }
    lua_settop(L, base);
    free(buf);
  }
  code = tty ? 0 : failed;
done:
  if (hist) {
    history_truncate_file(hist, HISTORY_MAX);
    free(hist);
  }
  return code;
}
