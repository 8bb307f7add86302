# tds: build, test and benchmark. `make demo`, `make test` work on a fresh
# Debian machine: missing packages are installed by scripts/deps.sh (the
# build needs a compiler, Lua 5.4, readline, cairo, libmicrohttpd and npm
# for three.js; Surface Evolver, the browser and Python's mesh readers are
# installed by the targets that test against them, clang by `make fuzz`).

CC ?= cc
BUILD ?= build
OPT ?= -O2
SAN ?=
WARN = -Wall -Wextra -Wshadow -Wmissing-prototypes -Wstrict-prototypes -Wwrite-strings \
  -Wdouble-promotion -Wcast-qual
CFLAGS_ALL = -std=c11 $(OPT) -g $(WARN) -D_POSIX_C_SOURCE=200809L $(SAN) $(CFLAGS)
# pg's passes use OpenMP (la_chol.c only to turn CHOLMOD's off); the
# program and unit tests link its runtime.
OMP_SRC := src/pg.c src/pg_pass.c src/la_chol.c
# The assembly loop (eval.c, and the torus's facet pass eval_torus.c) at
# -O3 when the build is -O2: 20-28% faster evaluations on the periodic foam
# bench (doc/performance.md); the same floating-point results (no
# -ffast-math; ISO C contracts no a*b+c).
O3_SRC := src/eval.c src/eval_torus.c
O3 = $(if $(and $(filter $(O3_SRC),$1),$(filter -O2,$(OPT))),-O3)
# Evaluated when a recipe runs, so after `deps` has installed pkg-config/Lua.
LUA_CFLAGS = $(shell pkg-config --cflags lua5.4)
LUA_LIBS = $(shell pkg-config --libs lua5.4)
CAIRO_CFLAGS = $(shell pkg-config --cflags cairo)
CAIRO_LIBS = $(shell pkg-config --libs cairo)
# The sparse symmetric solvers (la_mumps.c, la_chol.c) and LAPACK (small dense eigenproblems).
LA_LIBS = -ldmumps_seq -lcholmod -llapack
LIBS = $(LUA_LIBS) $(CAIRO_LIBS) $(LA_LIBS) -lreadline -lm

BIND_SRC := $(wildcard src/lua_*.c) src/repl.c src/main.c
# The live view's server: linked into the program only (libmicrohttpd).
LIVE_SRC := src/live.c
LIVE_CFLAGS = $(shell pkg-config --cflags libmicrohttpd)
LIVE_LIBS = $(shell pkg-config --libs libmicrohttpd) -pthread
CORE_SRC := $(filter-out $(BIND_SRC) $(LIVE_SRC),$(wildcard src/*.c))
LUA_SRC := $(sort $(wildcard lua/*.lua))
CORE_OBJ := $(CORE_SRC:src/%.c=$(BUILD)/%.o)
# The core (no Lua) as a library: the program, the unit tests and the
# fuzzers link it.
LIBTDS := $(BUILD)/libtds.a
BIND_OBJ := $(BIND_SRC:src/%.c=$(BUILD)/%.o)
LIVE_OBJ := $(LIVE_SRC:src/%.c=$(BUILD)/%.o)
# The Lua module tds.so (`require "tds"` from a stock lua5.4): the core and
# the bindings compiled again as position-independent code into build/pic,
# so the program keeps its non-PIC objects (and speed). It does not link
# liblua: the interpreter that loads it provides Lua.
PIC := $(BUILD)/pic
MOD_SRC := $(CORE_SRC) $(filter-out src/main.c src/repl.c,$(BIND_SRC)) $(LIVE_SRC)
MOD_OBJ := $(MOD_SRC:src/%.c=$(PIC)/%.o)
TDS_SO := $(BUILD)/tds.so
UNIT_SRC := $(wildcard tests/unit/test_*.c)
UNIT_BIN := $(UNIT_SRC:tests/unit/%.c=$(BUILD)/%)
FUZZ_NAMES := $(patsubst tests/fuzz/fuzz_%.c,%,$(wildcard tests/fuzz/fuzz_*.c))
FUZZ_REPLAY := $(FUZZ_NAMES:%=$(BUILD)/test_fuzz_%)
TDS_BIN ?= tds

.PHONY: module all deps deps-test web demo test plan test-asan unit bench bench-paper bench-pgbig clean fuzz fuzz-bins fuzz-smoke fuzz-cov \
  random-long random-long-asan

all: $(TDS_BIN) web

deps:
	@sh scripts/deps.sh build
deps-test:
	@sh scripts/deps.sh test

$(LIBTDS): $(CORE_OBJ)
	rm -f $@
	ar rcs $@ $^

$(TDS_BIN): $(BIND_OBJ) $(LIVE_OBJ) $(LIBTDS) | deps
	$(CC) $(CFLAGS_ALL) -fopenmp -o $@ $^ $(LIBS) $(LIVE_LIBS)

# -z nodelete: Lua's dlclose at exit leaves it (and the libraries it
# pulled in) loaded, as for a program: OpenMP's idle threads never run
# unmapped code, and the caches of gnutls/p11-kit (via libmicrohttpd)
# stay reachable instead of showing as leaks under ASan.
module: $(TDS_SO)
$(TDS_SO): $(MOD_OBJ) | deps
	$(CC) $(CFLAGS_ALL) -fopenmp -shared -Wl,-z,nodelete -o $@ $^ $(CAIRO_LIBS) $(LA_LIBS) $(LIVE_LIBS) -lm

$(PIC)/%.o: src/%.c | deps $(BUILD)
	@mkdir -p $(PIC)
	$(CC) $(CFLAGS_ALL) $(call O3,$<) -fPIC $(if $(filter $(OMP_SRC),$<),-fopenmp) \
	  $(if $(filter $(BIND_SRC),$<),$(LUA_CFLAGS)) $(if $(filter $(LIVE_SRC),$<),$(LIVE_CFLAGS)) \
	  $(if $(filter src/render%,$<),$(CAIRO_CFLAGS)) \
	  -MMD -MP -Isrc -I$(BUILD) -c -o $@ $<
-include $(MOD_OBJ:.o=.d)
$(PIC)/lua_surface.o: $(BUILD)/prelude.inc

# The live view's page needs three.js from the npm registry (web/).
web: web/node_modules/.package-lock.json
web/node_modules/.package-lock.json: web/package.json web/package-lock.json | deps
	cd web && npm ci --no-audit --no-fund --loglevel=error

# Header dependencies come from the compiler (-MMD -MP).
$(BUILD)/%.o: src/%.c | deps $(BUILD)
	$(CC) $(CFLAGS_ALL) $(call O3,$<) $(if $(filter $(OMP_SRC),$<),-fopenmp) \
	  $(if $(filter $(BIND_SRC),$<),$(LUA_CFLAGS)) $(if $(filter $(LIVE_SRC),$<),$(LIVE_CFLAGS)) \
	  $(if $(filter src/render%,$<),$(CAIRO_CFLAGS)) \
	  -MMD -MP -Isrc -I$(BUILD) -c -o $@ $<
-include $(CORE_OBJ:.o=.d) $(BIND_OBJ:.o=.d) $(LIVE_OBJ:.o=.d)

# The Lua prelude is embedded in the binary.
$(BUILD)/lua_surface.o: $(BUILD)/prelude.inc
$(BUILD)/prelude.inc: $(LUA_SRC) scripts/embed.sh | $(BUILD)
	sh scripts/embed.sh $(LUA_SRC) > $@

# The unit tests link the core built again with its contract checks
# (TDS_CHECKS: TDS_REQUIRE and TDS_ASSERT, tds.h); the program does not.
CHK_OBJ := $(CORE_SRC:src/%.c=$(BUILD)/chk/%.o)
LIBTDS_CHK := $(BUILD)/chk/libtds.a
$(LIBTDS_CHK): $(CHK_OBJ)
	rm -f $@
	ar rcs $@ $^
$(BUILD)/chk/%.o: src/%.c | deps $(BUILD)/chk
	$(CC) $(CFLAGS_ALL) $(call O3,$<) -DTDS_CHECKS $(if $(filter $(OMP_SRC),$<),-fopenmp) \
	  $(if $(filter src/render%,$<),$(CAIRO_CFLAGS)) -MMD -MP -Isrc -I$(BUILD) -c -o $@ $<
-include $(CHK_OBJ:.o=.d)

$(BUILD)/test_%: tests/unit/test_%.c tests/unit/*.h $(LIBTDS_CHK) | deps
	$(CC) $(CFLAGS_ALL) -DTDS_CHECKS -fopenmp -Isrc -Itests/unit -o $@ $< $(LIBTDS_CHK) $(CAIRO_LIBS) $(LA_LIBS) -lm

$(BUILD):
	mkdir -p $(BUILD)
$(BUILD)/chk:
	mkdir -p $@

# The picture tests' PNG reader (tests/pictures/).
$(BUILD)/png2ppm: tests/pictures/png2ppm.c | deps $(BUILD)
	$(CC) $(CFLAGS_ALL) $(CAIRO_CFLAGS) -o $@ $< $(CAIRO_LIBS)

unit: $(UNIT_BIN) $(FUZZ_REPLAY) $(BUILD)/png2ppm

# T='script/declare evolver/dump' runs only those tests (doc: tests/run.sh).
test: $(TDS_BIN) unit web $(TDS_SO) | deps-test
	@sh tests/run.sh $(abspath $(TDS_BIN)) $(abspath $(BUILD)) $(T)

# Rewrite tests/plan.txt, the names a full run must print, from a run.
plan: $(TDS_BIN) unit web $(TDS_SO) | deps-test
	@PLAN_WRITE=1 sh tests/run.sh $(abspath $(TDS_BIN)) $(abspath $(BUILD))

# The whole suite under AddressSanitizer and UndefinedBehaviorSanitizer,
# with the contract checks (TDS_CHECKS) in the program too.
test-asan:
	LSAN_OPTIONS=suppressions=$(abspath tests/lsan.supp) $(MAKE) BUILD=build-asan TDS_BIN=build-asan/tds OPT=-O1 \
	  SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -DTDS_CHECKS" test

# Long runs of the seeded random testers (doc/reliability.md, "Random
# command sequences"): RANDOM_TRIALS sequences and mutants from RANDOM_SEED;
# random-long-asan runs them on the ASan/UBSan build of test-asan.
RANDOM_TRIALS ?= 3000
RANDOM_SEED ?= 1
random-long: $(TDS_BIN)
	TDS_CHECK=1 TDS_RST_TRIALS=$(RANDOM_TRIALS) TDS_RST_SEED=$(RANDOM_SEED) ./$(TDS_BIN) -q tests/scripts/random_string_torus.tds
	TDS_CHECK=1 TDS_MUT_TRIALS=$(RANDOM_TRIALS) TDS_MUT_SEED=$(RANDOM_SEED) ./$(TDS_BIN) -q tests/scripts/datafile_mutate.tds
	TDS_CHECK=1 TDS_RT1_TRIALS=$(RANDOM_TRIALS) TDS_RT1_SEED=$(RANDOM_SEED) ./$(TDS_BIN) -q tests/scripts/random_t1.tds
	TDS=$(abspath $(TDS_BIN)) TDS_CHECK=1 TDS_PE_TRIALS=$(RANDOM_TRIALS) TDS_PE_SEED=$(RANDOM_SEED) ./$(TDS_BIN) -q tests/scripts/prompt_errors.tds
random-long-asan:
	LSAN_OPTIONS=suppressions=$(abspath tests/lsan.supp) $(MAKE) BUILD=build-asan TDS_BIN=build-asan/tds OPT=-O1 \
	  SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -DTDS_CHECKS" random-long

# libFuzzer harnesses (tests/fuzz/, doc/reliability.md "Fuzzing"), built
# with clang, ASan and UBSan into build-fuzz/. fuzz-smoke runs each one for
# FUZZ_TIME seconds on its corpus (CI).
FUZZ_BUILD ?= build-fuzz
FUZZ_TIME ?= 60
FUZZ_SAN = -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -DTDS_CHECKS
# Smaller macro-expansion limits, so an input that expands to the full
# 64 MiB does not take a minute under the sanitizers (doc/reliability.md).
FUZZ_LIMITS = -DTDS_DF_MAXTOTAL='(4u<<20)' -DTDS_DF_MAXLINE='(1u<<20)'

# clang also counts NAN and INFINITY (float constants) as promotions.
CLANG_WARN = WARN="$(filter-out -Wdouble-promotion,$(WARN))"

fuzz:
	@sh scripts/deps.sh fuzz
	$(MAKE) BUILD=$(FUZZ_BUILD) CC=clang OPT=-O1 $(CLANG_WARN) SAN="-fsanitize=fuzzer-no-link $(FUZZ_SAN) $(FUZZ_LIMITS)" fuzz-bins

fuzz-bins: $(FUZZ_NAMES:%=$(BUILD)/fuzz_%)

# The harnesses without libFuzzer replay their corpora in `make test`.
FUZZ_OBJ = $(filter-out $(BUILD)/main.o,$(BIND_OBJ)) $(LIVE_OBJ) $(LIBTDS)
# fuzz_evo.c includes fuzz_tds.c, so every harness depends on all sources.
FUZZ_SRC := $(wildcard tests/fuzz/*.c tests/fuzz/*.h)
$(BUILD)/test_fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_SRC) $(FUZZ_OBJ) | deps
	$(CC) $(CFLAGS_ALL) -fopenmp $(LUA_CFLAGS) -DFUZZ_NAME='"$*"' -Isrc -o $@ $< \
	  tests/fuzz/replay.c $(filter %.o %.a,$^) $(LIBS) $(LIVE_LIBS)

$(BUILD)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_SRC) $(FUZZ_OBJ) | deps
	$(CC) $(CFLAGS_ALL) -fopenmp -fsanitize=fuzzer $(LUA_CFLAGS) -Isrc -o $@ $< \
	  $(filter %.o %.a,$^) $(LIBS) $(LIVE_LIBS)

fuzz-smoke: fuzz
	sh tests/fuzz/smoke.sh $(FUZZ_BUILD) $(FUZZ_TIME) $(FUZZ_NAMES)

# Source coverage of each harness over its corpus (FUZZ_CORPUS=dir of corpora).
fuzz-cov:
	$(MAKE) BUILD=build-fuzzcov CC=clang OPT=-O1 $(CLANG_WARN) \
	  SAN="-fsanitize=fuzzer-no-link -fprofile-instr-generate -fcoverage-mapping $(FUZZ_LIMITS)" fuzz-bins
	sh tests/fuzz/coverage.sh build-fuzzcov $(FUZZ_NAMES)

demo: $(TDS_BIN)
	./$(TDS_BIN) scripts/demo.tds

bench: $(TDS_BIN) | deps-test
	sh bench/cube.sh ./$(TDS_BIN)
	sh bench/string.sh ./$(TDS_BIN)
	sh bench/foam3.sh ./$(TDS_BIN)
	sh bench/hessian.sh ./$(TDS_BIN)
	sh bench/pictures.sh ./$(TDS_BIN)

bench-paper: $(TDS_BIN) | deps-test
	sh bench/paper.sh ./$(TDS_BIN)

# pg on 100k-vertex generated inputs (doc/paper-results.md, Large inputs)
bench-pgbig: $(TDS_BIN) | deps-test
	sh bench/pgbig.sh ./$(TDS_BIN)

clean:
	rm -rf build build-asan build-fuzz tds
