/* main.c: command line of the tds program. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "datafile.h"
#include "repl.h"

static const char usage[] =
    "usage: tds [options] [FILE]\n"
    "Run a .tds script (Lua) or load a Surface Evolver datafile, then exit.\n"
    "FILE '-' (or a script piped in without other arguments) is a Lua\n"
    "script read from standard input as one chunk.\n"
    "\n"
    "  -i          open the interactive prompt after FILE (tds alone opens it)\n"
    "  -e CODE     run Lua CODE after FILE; may be repeated\n"
    "  -f CMDS     run the Evolver command file CMDS after FILE; may be\n"
    "              repeated and mixed with -e (they run in the given order);\n"
    "              an error abandons the rest of that file only\n"
    "  -q          quiet: no per-iteration lines\n"
    "  --safe      safe mode for files from others: no processes, no native\n"
    "              libraries, no bytecode, no file written outside the output\n"
    "              folder; only .tds/.lua files run as Lua (doc/reliability.md)\n"
    "  --out DIR   the output folder of safe mode (default: the current folder)\n"
    "  --on-interrupt dump[=PATH]\n"
    "              when Ctrl-C (or SIGTERM) stops FILE or -e code, dump the\n"
    "              surface first (default PATH: FILE with extension .dmp)\n"
    "  --help      show this help\n"
    "  --version   show the version\n"
    "\n"
    "Exit status is 0 on success, 1 after an error, or the code given to q().\n";

/* Load FILE as a chunk: a .tds script, or a datafile through tds.load;
** "-" is a Lua script on standard input, read as one chunk. */
static int load_file(lua_State *L, const char *path) {
  if (!strcmp(path, "-")) return luaL_loadfile(L, NULL);
  lua_getglobal(L, "tds");
  lua_getfield(L, -1, "load_chunk");
  lua_remove(L, -2);
  if (lua_isfunction(L, -1)) {
    lua_pushstring(L, path);
    if (lua_pcall(L, 1, 1, 0) != LUA_OK) return LUA_ERRFILE;
    return LUA_OK;
  }
  lua_pop(L, 1);
  return luaL_loadfile(L, path);
}

/* The surface so far, saved when an interruption stopped the run
** (--on-interrupt dump). */
static void dump_on_interrupt(tds_state *st, const char *path, const char *file) {
  char *name = NULL;
  if (!path) {
    const char *base = st->datafile ? st->datafile : file ? file : "tds";
    const char *slash = strrchr(base, '/'), *dot = strrchr(base, '.');
    size_t n = dot && dot > (slash ? slash : base) ? (size_t)(dot - base) : strlen(base);
    name = malloc(n + 5);
    if (!name) return;
    memcpy(name, base, n);
    memcpy(name + n, ".dmp", 5);
    path = name;
  }
  if (tds_datafile_dump(&st->ctx, &st->s, path) == TDS_OK)
    fprintf(stderr, "tds: interrupted; the surface is saved in '%s'\n", path);
  else
    fprintf(stderr, "tds: interrupted; saving the surface failed: %s\n", st->ctx.errmsg);
  free(name);
}

/* A chunk that calls upvalue 1 with upvalue 2. */
static int run_with_arg(lua_State *L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushvalue(L, lua_upvalueindex(2));
  lua_call(L, 1, 0);
  return 0;
}

int main(int argc, char **argv) {
  int interactive = 0, quiet = 0, status = 0, quit_code = 0, safe = 0;
  int on_interrupt_dump = 0;
  const char *file = NULL, *outdir = NULL, *interrupt_path = NULL;
  /* code[i]: -e text or -f file; is_cmdfile[i]: it is a -f file. One
  ** block, so each early return frees both with free(code). */
  const char **code = calloc((size_t)argc + 1, sizeof *code + 1);
  if (!code) return 1;
  char *is_cmdfile = (char *)(code + argc + 1);
  int ncode = 0;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
      fputs(usage, stdout);
      free(code);
      return 0;
    } else if (!strcmp(a, "--version")) {
      printf("tds %s (%s)\n", TDS_VERSION, LUA_RELEASE);
      free(code);
      return 0;
    } else if (!strcmp(a, "-i")) {
      interactive = 1;
    } else if (!strcmp(a, "-q")) {
      quiet = 1;
    } else if (!strcmp(a, "--safe")) {
      safe = 1;
    } else if (!strcmp(a, "--out")) {
      if (++i == argc) {
        fprintf(stderr, "tds: --out needs a folder\n%s", usage);
        free(code);
        return 1;
      }
      outdir = argv[i];
    } else if (!strcmp(a, "--on-interrupt") || !strncmp(a, "--on-interrupt=", 15)) {
      const char *v = a[14] == '=' ? a + 15 : (++i < argc ? argv[i] : NULL);
      if (!v || strncmp(v, "dump", 4) || (v[4] && (v[4] != '=' || !v[5]))) {
        fprintf(stderr, "tds: --on-interrupt takes 'dump' or 'dump=PATH'\n%s", usage);
        free(code);
        return 1;
      }
      on_interrupt_dump = 1;
      interrupt_path = v[4] ? v + 5 : NULL;
    } else if (!strcmp(a, "-e")) {
      if (++i == argc) {
        fprintf(stderr, "tds: -e needs an argument\n%s", usage);
        free(code);
        return 1;
      }
      code[ncode++] = argv[i];
    } else if (!strcmp(a, "-f")) {
      if (++i == argc) {
        fprintf(stderr, "tds: -f needs a command file\n%s", usage);
        free(code);
        return 1;
      }
      is_cmdfile[ncode] = 1;
      code[ncode++] = argv[i];
    } else if (a[0] == '-' && a[1]) {
      fprintf(stderr, "tds: unknown option '%s'\n%s", a, usage);
      free(code);
      return 1;
    } else if (!file) {
      file = a;
    } else {
      fprintf(stderr, "tds: only one FILE may be given ('%s')\n", a);
      free(code);
      return 1;
    }
  }
  /* A script piped in with nothing else to do runs as one chunk. */
  if (!file && ncode == 0 && !interactive && !isatty(0)) file = "-";
  lua_State *L = luaL_newstate();
  if (!L) {
    fprintf(stderr, "tds: cannot create Lua state\n");
    free(code);
    return 1;
  }
  tds_state *st = tds_lua_open(L);
  if (!st) {
    fprintf(stderr, "tds: %s\n", lua_tostring(L, -1));
    lua_close(L);
    free(code);
    return 1;
  }
  st->ctx.quiet = quiet;
  if (outdir && !safe) {
    fprintf(stderr, "tds: --out is the output folder of --safe; give --safe too\n");
    lua_close(L);
    free(code);
    return 1;
  }
  if (safe && !tds_lua_safe(L, st, outdir)) {
    fprintf(stderr, "tds: %s\n", lua_tostring(L, -1));
    lua_close(L);
    free(code);
    return 1;
  }
  /* A file-size limit (ulimit -f) makes writes fail with EFBIG, reported
  ** by the writer, instead of killing the process mid-file. */
  signal(SIGXFSZ, SIG_IGN);
  tds_lua_sigterm_stops(on_interrupt_dump);
  int rc = 0, stopped = 0;
  if (file) {
    if (load_file(L, file) != LUA_OK) {
      fprintf(stderr, "%s\n", lua_tostring(L, -1));
      rc = 1;
    } else {
      rc = tds_run_chunk(L, st, &quit_code);
      stopped |= rc == 1 && tds_lua_interrupted();
    }
  }
  int cmdfile_failed = 0;
  for (int i = 0; i < ncode && rc == 0; i++) {
    if (is_cmdfile[i]) { /* tds.E.run_file(path): Evolver commands */
      lua_getglobal(L, "tds");
      lua_getfield(L, -1, "E");
      lua_getfield(L, -1, "run_file");
      lua_remove(L, -2);
      lua_remove(L, -2);
      lua_pushstring(L, code[i]);
      lua_pushcclosure(L, run_with_arg, 2);
      rc = tds_run_chunk(L, st, &quit_code);
      /* As in Evolver, an error abandons the rest of that file only: what
      ** follows still runs, and the exit status is 1 at the end. */
      if (rc == 1) {
        cmdfile_failed = 1;
        rc = 0;
      }
    } else if (luaL_loadbuffer(L, code[i], strlen(code[i]), "=(command line)") != LUA_OK) {
      fprintf(stderr, "%s\n", lua_tostring(L, -1));
      lua_pop(L, 1);
      rc = 1;
    } else {
      rc = tds_run_chunk(L, st, &quit_code);
      stopped |= rc == 1 && tds_lua_interrupted();
    }
  }
  if (stopped && on_interrupt_dump) dump_on_interrupt(st, interrupt_path, file);
  if (rc == 2) {
    status = quit_code;
  } else if (interactive || (!file && ncode == 0)) {
    int r = tds_repl(L, st);
    status = rc || cmdfile_failed ? 1 : r;
  } else {
    status = rc || cmdfile_failed ? 1 : 0;
  }
  lua_close(L);
  free(code);
  return status;
}
