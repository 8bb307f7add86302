/*
** fuzz_tds.c: libFuzzer harness of .tds scripts: declarations and commands
** through the tds library and its prelude.
**
** Each input runs as a Lua chunk (text only) in a fresh state; if it does
** not compile, each line goes through the REPL's Evolver-style reader
** (tds.translate) instead. The state is a sandbox: no os.execute, io,
** dofile, loadfile, require, package or debug; load takes text only;
** dump/load_datafile/write_text (so write_fe) are pointed at one scratch
** file of this process; tds functions not on an allowlist are refused;
** print and progress output are dropped. Work is bounded: a Lua
** instruction budget, a Lua memory limit, g() and pg() capped at a few
** iterations, r() only on small surfaces.
**
** Checked after every tds command (success or failure): the mesh passes
** tds.check(), and the check mode (TDS_CHECK=1, lua/check.lua) holds: no
** NaN or infinity after a command that succeeded, the surface exactly as
** before after one that failed. A crash, sanitizer report, broken mesh or
** check-mode report (the process exits) is a bug; a Lua error is the
** normal way to refuse bad input.
*/
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>

#include "fuzz_util.h"
#include "lua_tds.h"

enum { LUA_MEM_LIMIT = 128 << 20, BUDGET_STEPS = 5000, HOOK_EVERY = 1000 };

typedef struct { size_t used; } mem_t;

static void *limited_alloc(void *ud, void *ptr, size_t osize, size_t nsize) {
  mem_t *m = ud;
  size_t old = ptr ? osize : 0;
  if (nsize == 0) {
    free(ptr);
    m->used -= old;
    return NULL;
  }
  if (nsize > old && m->used - old + nsize > LUA_MEM_LIMIT) return NULL;
  void *p = realloc(ptr, nsize);
  if (p) m->used = m->used - old + nsize;
  return p;
}

static int steps;
static void budget_hook(lua_State *L, lua_Debug *ar) {
  (void)ar;
  if (++steps > BUDGET_STEPS) {
    /* From now on every instruction fails, so a pcall loop cannot go on. */
    lua_sethook(L, budget_hook, LUA_MASKCOUNT, 1);
    luaL_error(L, "fuzz: instruction budget spent");
  }
}

static int fuzz_abort(lua_State *L) {
  fprintf(stderr, "fuzz invariant failed: %s\n", luaL_optstring(L, 1, "?"));
  abort();
}

/* The sandbox, run after the prelude. SCRATCH is the only file used. */
static const char sandbox[] =
    "local SCRATCH, abort = ...\n"
    "local tds, pcall, error, type, select = tds, pcall, error, type, select\n"
    "local pack, unpack, min = table.pack, table.unpack, math.min\n"
    "local real_open, real_load = io.open, load\n"
    "local check = tds.check\n"
    "local function wrap(name, fix)\n"
    "  local f = tds[name]\n"
    "  tds[name] = function(...)\n"
    "    local r\n"
    "    if fix then r = pack(pcall(function(...) return f(fix(...)) end, ...))\n"
    "    else r = pack(pcall(f, ...)) end\n"
    "    local ok, err = pcall(check)\n"
    "    if not ok then abort(name .. ' left a broken mesh: ' .. tostring(err)) end\n"
    "    if not r[1] then error(r[2], 0) end\n"
    "    return unpack(r, 2, r.n)\n"
    "  end\n"
    "end\n"
    "local function small()\n"
    "  if tds.count(tds.facet) > 200 or tds.count(tds.edge) > 1000 then\n"
    "    error('fuzz: surface too big for this command', 0) end\n"
    "end\n"
    "wrap('iterate', function(n, ...)\n"
    "  small()\n"
    "  if type(n) == 'number' and n > 2 then n = 2 end\n"
    "  return n, ...\n"
    "end)\n"
    "wrap('refine', function(...) small() return ... end)\n"
    "wrap('pg', function(o, ...)\n"
    "  small()\n"
    "  if type(o) == 'table' then\n"
    "    local t = {}\n"
    "    for k, v in pairs(o) do t[k] = v end\n"
    "    if type(t.iterations) ~= 'number' or t.iterations > 2 then t.iterations = 2 end\n"
    "    if type(t.max) == 'number' and t.max > 2 then t.max = 2 end\n"
    "    o = t\n"
    "  elseif o == nil then o = { iterations = 2 } end\n"
    "  return o, ...\n"
    "end)\n"
    "for _, name in ipairs{'equiangulate', 'vertex_average', 'pg_flip_all', 'scale',\n"
    "    'optimize', 'gravity', 'param', 'setting', 'translate', 'decl_vertex',\n"
    "    'decl_edge', 'decl_face', 'decl_body', 'reserve', 'constraint', 'boundary',\n"
    "    'quantity', 'totals', 'pressures', 'curvature', 'quality', 'datafile_info'} do\n"
    "  if tds[name] then wrap(name) end\n"
    "end\n"
    "wrap('dump', function() return SCRATCH end)\n"
    "wrap('write_text', function(_, text) return SCRATCH .. '.w', text end)\n"
    "wrap('load_datafile', function() return SCRATCH end)\n"
    "wrap('load_chunk', function() return SCRATCH end)\n"
    "if tds.load_replace then wrap('load_replace', function() return SCRATCH end) end\n"
    "-- Evolver's redirection (>>, >>>, |) writes to the scratch file, never a command.\n"
    "if tds.output_open then\n"
    "  wrap('output_open', function(_, mode) return SCRATCH .. '.o', mode == '|' and 'w' or mode end)\n"
    "end\n"
    "dump = tds.dump\n"
    "-- Deny by default: a tds function added later (it might write files)\n"
    "-- is refused until it is listed here or redirected above.\n"
    "local allowed = {}\n"
    "for name in ('body boundary check check_finite check_release check_same '\n"
    "  .. 'check_snapshot constraint count curvature datafile_info decl_body decl_edge '\n"
    "  .. 'decl_face decl_vertex dump edge equiangulate facet facet_min_angle get gravity '\n"
    "  .. 'iterate load_chunk load_datafile memory methods next optimize param pg '\n"
    "  .. 'pg_flip_all pg_multipliers pressures props quality quantity quantity_info quiet '\n"
    "  .. 'refine reserve scale setting totals translate vertex vertex_average '\n"
    "  .. 'vertex_mean_curvature write_text check_options check_restore body_warnings '\n"
    "  .. 'recalc load_replace read_text datafile_name output_open output_set '\n"
    "  .. 'output_write output_close'):gmatch('%S+') do allowed[name] = true end\n"
    "for name, f in pairs(tds) do\n"
    "  if type(f) == 'function' and not allowed[name] then\n"
    "    tds[name] = function() error('fuzz: tds.' .. name .. ' is not allowed in the harness', 2) end\n"
    "  end\n"
    "end\n"
    "-- output is dropped (the Evolver runtime writes and flushes io.stdout)\n"
    "local sink = { write = function(self) return self end, flush = function() end,\n"
    "  close = function() end, setvbuf = function() end }\n"
    "io = { open = function(path, mode)\n"
    "  if mode ~= 'w' then return nil, 'fuzz: reading files is disabled' end\n"
    "  return real_open(SCRATCH .. '.w', 'w')\n"
    "end, write = function() end, stdout = sink, stderr = sink }\n"
    "os = { clock = os.clock, time = os.time }\n"
    "dofile, loadfile, require, package, debug = nil, nil, nil, nil, nil\n"
    "load = function(chunk, name, mode, ...)\n"
    "  if type(chunk) ~= 'string' then return nil, 'fuzz: load takes text only' end\n"
    "  -- an env given as nil is nil; none given is the globals (as load)\n"
    "  return real_load(chunk, name, 't', ...)\n"
    "end\n"
    "print = function() end\n"
    "string.dump = nil\n";

/* Run the input line by line through the Evolver-style reader. */
static const char evolver_lines[] =
    "local text = ...\n"
    "for line in text:gmatch('[^\\n]*') do\n"
    "  local ok, code = pcall(tds.translate, line)\n"
    "  if ok and code then\n"
    "    local f = load(code, '=line', 't')\n"
    "    if f then pcall(f) end\n"
    "  end\n"
    "end\n";

#ifdef FUZZ_EVOLVER
/* fuzz_evo: the input is Evolver command text, run on the cube by the
** command-language runtime (lua/evorun.lua). */
static const char evolver_text[] =
    "local text = ...\n"
    "vertices { {0,0,0}, {1,0,0}, {1,1,0}, {0,1,0}, {0,0,1}, {1,0,1}, {1,1,1}, {0,1,1} }\n"
    "edges { {1,2}, {2,3}, {3,4}, {4,1}, {5,6}, {6,7}, {7,8}, {8,5},\n"
    "        {1,5}, {2,6}, {3,7}, {4,8} }\n"
    "faces { {1,10,-5,-9}, {2,11,-6,-10}, {3,12,-7,-11}, {4,9,-8,-12},\n"
    "        {5,6,7,8}, {-4,-3,-2,-1} }\n"
    "bodies { {1,2,3,4,5,6, volume = 1} }\n"
    "evolver(text)\n";
#endif

/* Run the harness's own chunk with the input as its argument; the stack
** is left as it was (a chunk that does not compile is the harness's bug). */
static void run_chunk(lua_State *L, const char *chunk, size_t n, const char *name,
                      const uint8_t *data, size_t size) {
  int top = lua_gettop(L);
  if (luaL_loadbuffer(L, chunk, n, name) != LUA_OK) {
    fprintf(stderr, "fuzz: %s does not compile: %s\n", name, lua_tostring(L, -1));
    abort();
  }
  lua_pushlstring(L, (const char *)data, size);
  if (lua_pcall(L, 1, 0, 0) != LUA_OK && getenv("FUZZ_VERBOSE")) /* to debug the harness */
    fprintf(stderr, "fuzz: %s\n", lua_tostring(L, -1));
  lua_settop(L, top);
}

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc;
  (void)argv;
  setenv("OMP_NUM_THREADS", "1", 1);
  /* The check mode (lua/check.lua): after every command nothing is NaN or
     infinite, and a failed command left the surface exactly as before; a
     violation ends the process, which libFuzzer records as a finding. */
  setenv("TDS_CHECK", "1", 1);
  return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  mem_t mem = {0};
  lua_State *L = lua_newstate(limited_alloc, &mem);
  if (!L) return 0;
  tds_state *st = tds_lua_open(L);
  FUZZ_CHECK(st != NULL, "tds_lua_open: %s", lua_tostring(L, -1));
  st->ctx.quiet = 1;
  st->ctx.out = fuzz_no_output;
  st->ctx.warn = fuzz_no_output;
  const char *scratch = fuzz_scratch(".fe");
  FUZZ_CHECK(luaL_loadbuffer(L, sandbox, sizeof sandbox - 1, "=sandbox") == LUA_OK, "%s",
             lua_tostring(L, -1));
  lua_pushstring(L, scratch);
  lua_pushcfunction(L, fuzz_abort);
  FUZZ_CHECK(lua_pcall(L, 2, 0, 0) == LUA_OK, "sandbox: %s", lua_tostring(L, -1));

  steps = 0;
  lua_sethook(L, budget_hook, LUA_MASKCOUNT, HOOK_EVERY);
#ifdef FUZZ_EVOLVER
  run_chunk(L, evolver_text, sizeof evolver_text - 1, "=evolver", data, size);
#else
  if (luaL_loadbufferx(L, (const char *)data, size, "=fuzz", "t") == LUA_OK)
    lua_pcall(L, 0, 0, 0);
  else
    run_chunk(L, evolver_lines, sizeof evolver_lines - 1, "=evolver", data, size);
#endif
  lua_sethook(L, NULL, 0, 0);
  tds_ctx ctx = st->ctx;
  FUZZ_CHECK(tds_mesh_check(&ctx, &st->s.m) == TDS_OK, "mesh broken: %s", ctx.errmsg);
  lua_close(L);
  /* the scratch file and its companions (io.open and redirection) */
  static const char *const companions[] = {"", ".w", ".o", ".tmp"};
  char path[600];
  for (int i = 0; i < 4; i++) {
    snprintf(path, sizeof path, "%s%s", scratch, companions[i]);
    unlink(path);
  }
  return 0;
}
