#!/bin/sh
# repro.sh: regression tests built from the reproducers of issue 12 (the
# fuzzing campaign and fault tests), copied into tests/repro/. Each case
# runs tds on one reproducer and checks the exit status and an exact line
# of its output: the clear `file:line: message` error, or the right result.
# No output may contain a sanitizer report (make test-asan builds with
# -fno-sanitize-recover) or a NaN / inf left in the surface.
# Run from the project root by tests/run.sh with $TDS set; prints PASS/FAIL.
cd "$(dirname "$0")/.." || exit 1
# Every command is verified as it returns (lua/check.lua): a failed one
# must leave the surface unchanged, a successful one nothing non-finite.
TDS_CHECK=1
export TDS_CHECK
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
T=tests/repro

# expect NAME RC LINE -- TDS ARGS...: run, then require exit status RC and
# a line of output (stdout + stderr) equal to LINE. If $REJECT is set, no
# line may match that extended regular expression.
expect() {
  name=$1 rc=$2 line=$3
  shift 4
  timeout 120 "$TDS" "$@" > "$dir/out" 2>&1
  got=$?
  if grep -q -E 'runtime error|AddressSanitizer|LeakSanitizer' "$dir/out"; then
    echo "FAIL repro/$name: sanitizer report: $(grep -m1 -E 'runtime error|Sanitizer' "$dir/out")"
  elif [ "$got" != "$rc" ]; then
    echo "FAIL repro/$name: exit status $got, expected $rc: $(tail -n 2 "$dir/out" | tr '\n' ' ')"
  elif [ -n "$REJECT" ] && grep -q -E -e "$REJECT" "$dir/out"; then
    echo "FAIL repro/$name: unexpected line: $(grep -m1 -E -e "$REJECT" "$dir/out")"
  elif ! grep -q -x -F -e "$line" "$dir/out"; then
    echo "FAIL repro/$name: no line '$line' in: $(tail -n 3 "$dir/out" | tr '\n' ' ')"
  else
    echo "PASS repro/$name"
  fi
}

# D5: element id 0 in a face or body list (read before the array).
expect fe_body_face0 1 "$T/fe_body_face0.fe:19: body 1 refers to face 0, which does not exist" \
  -- -q $T/fe_body_face0.fe
expect fe_face_edge0 1 "$T/fe_face_edge0.fe:10: face 1 refers to edge 0, which does not exist" \
  -- -q $T/fe_face_edge0.fe
expect fe_libfuzzer_crash_original 1 \
  "$T/fe_libfuzzer_crash_original.fe:54: face 4 refers to edge 0, which does not exist" \
  -- -q $T/fe_libfuzzer_crash_original.fe

# D1: a scalar method given a vector integrand, a vector method without one.
expect fe_scalar_method_vector_integrand 1 \
  "$T/fe_scalar_method_vector_integrand.fe:1: quantity q: method facet_scalar_integral needs a scalar_integrand, not a vector_integrand" \
  -- -q $T/fe_scalar_method_vector_integrand.fe
expect lua_quantity_scalar_method_vector_integrand 1 \
  "$T/lua_quantity_scalar_method_vector_integrand.tds:3: quantity q: method facet_scalar_integral needs a scalar_integrand, not a vector_integrand" \
  -- -q $T/lua_quantity_scalar_method_vector_integrand.tds
expect lua_quantity_vector_method_no_integrand 1 \
  "$T/lua_quantity_vector_method_no_integrand.tds:1: quantity q: method edge_vector_integral needs a vector_integrand" \
  -- -q $T/lua_quantity_vector_method_no_integrand.tds
# A constant-zero scalar integrand is kept (it used to become NULL): the
# integral of 0 over the unit cube is exactly 0, the energy its area 6.
cat > "$dir/zero.tds" <<'EOF'
quantity { name = 'q', info_only = true, method = 'facet_scalar_integral', scalar_integrand = '0' }
quantity { name = 'p', info_only = true, method = 'edge_scalar_integral', scalar_integrand = '0' }
dofile('scripts/cube.tds')
print('E', total_energy, (tds.quantity_info('q')), (tds.quantity_info('p')))
EOF
expect scalar_integrand_zero 0 "E	6.0	0.0	0.0" -- -q "$dir/zero.tds"

# D6: commands on an empty surface: nothing moves, the energy is exactly 0.
for f in fe_libfuzzer_ub_empty_iterate.fe fe_empty_then_g.fe lua_g_on_empty.tds; do
  expect "${f%.*}" 0 "E	0.0	0	0" -- -q $T/$f \
    -e 'g(2) pg(1) pg() V() r() u() print("E", total_energy, vertex_count, facet_count)'
done

# D2: a scale limit of inf, NaN, 0 or a subnormal number made g loop forever.
for w in inf:6:"finite, not inf" nan:8:"finite, not NaN" \
    zero:9:"a positive normal number, not 0.0" \
    subnormal:7:"a positive normal number, not 9.9998886718268e-321"; do
  v=${w%%:*} rest=${w#*:}
  expect "lua_hang_scale_limit_$v" 1 \
    "$T/lua_hang_scale_limit.tds:${rest%%:*}: scale limit must be ${rest#*:}" \
    -- -q $T/lua_hang_scale_limit.tds -e "run('$v')"
done
# The same limits from a datafile header, and g with a valid limit after a
# refused one (the limit is unchanged: 1, Evolver's default).
printf 'SCALE_LIMIT 1e-320\nvertices\n1 0 0 0\n' > "$dir/sub.fe"
expect fe_scale_limit_subnormal 1 "$dir/sub.fe:1: SCALE_LIMIT is too small (subnormal)" \
  -- -q "$dir/sub.fe"
expect scale_limit_unchanged 0 "limit	1.0" -- -q scripts/cube.tds \
  -e 'print(pcall(optimize, 0)) g(2) print("limit", tds.setting("scale_limit"))'
expect fixed_scale_inf 1 "(command line):1: scale must be finite, not inf" \
  -- -q scripts/cube.tds -e 'm(math.huge)'

# D3: a failing pg() or V() leaves the surface exactly as before.
REJECT='NaN vertex|non-finite vertex' expect lua_pg_leaves_nan 0 "check:	true	true	0" \
  -- -q $T/lua_pg_leaves_nan.tds
REJECT='non-finite vertex' expect lua_vavg_nonfinite 0 "check after V:	true	true	0" \
  -- -q $T/lua_vavg_nonfinite.tds
expect lua_vavg_nonfinite_message 0 \
  "V():	false	$T/lua_vavg_nonfinite.tds:6: energy is not finite (inf); the surface is as before the command" \
  -- -q $T/lua_vavg_nonfinite.tds

# D4: setters, G(), gravity_constant and parameters refuse NaN and inf.
expect lua_setter_nan 1 "$T/lua_setter_nan.tds:3: vertex 1: x must be finite, not NaN" \
  -- -q $T/lua_setter_nan.tds
expect lua_gravity_nan 1 "$T/lua_gravity_nan.tds:2: gravity constant must be finite, not NaN" \
  -- -q $T/lua_gravity_nan.tds
expect fe_gravity_nan 1 "$T/fe_gravity_nan.fe:1: GRAVITY_CONSTANT: value of '0/0' is not finite" \
  -- -q $T/fe_gravity_nan.fe

# D7: one huge Lua id is refused with the .fe reader's rule and message.
expect lua_huge_id_memory 1 "$T/lua_huge_id_memory.tds:3: vertex id 67108865 is out of range (1 to 1000016)" \
  -- -q $T/lua_huge_id_memory.tds
expect fe_max_id_memory 1 "$T/fe_max_id_memory.fe:2: vertex id 67108864 is out of range (1 to 1000384)" \
  -- -q $T/fe_max_id_memory.fe
expect lua_huge_face_id 1 "(command line):1: face id 268435455 is out of range (1 to 1000016)" \
  -- -q -e 'faces{[268435455] = {1, 2, 3}}'
# the prelude's message names the user's line and the declaration
expect lua_prelude_msg 1 "$T/lua_prelude_msg.tds:1: vertices{}: key -1 is not an id (use a list, or [id] = {...})" \
  -- -q $T/lua_prelude_msg.tds

# Macro bombs: a line too long after expansion, and many long lines (the
# expanded text is bounded in total, so loading stops within seconds).
expect fe_libfuzzer_timeout_slowunit 1 \
  "$T/fe_libfuzzer_timeout_slowunit.fe:15: line too long (more than 4194304 bytes after macro expansion)" \
  -- -q $T/fe_libfuzzer_timeout_slowunit.fe
expect fe_macro_expression_slow_load 1 \
  "$T/fe_macro_expression_slow_load.fe:75: macro expansion produces more than 67108864 bytes" \
  -- -q $T/fe_macro_expression_slow_load.fe

# D8/D9 (dump_tests.out): dumps and write_fe are written all or nothing.
w="$dir/w"
mkdir -p "$w"
old() { printf 'OLD CONTENT\n' > "$1"; }
same_old() { [ "$(cat "$1")" = "OLD CONTENT" ]; }
no_tmp() { [ -z "$(ls -A "$w" | grep -v -x -F -e old.fe -e ro.fe -e isdir -e real.fe \
  -e link.fe -e out.fe -e out.fe.tmp -e victim.txt -e perm.fe)" ]; }
big='dofile("scripts/cube.tds") r() r() r()'
# a file-size limit hit half way (as a full disk): error, old file intact,
# no temporary file left (ulimit -f counts 512-byte blocks in sh)
for cmd in 'dump' 'write_fe'; do
  old "$w/old.fe"
  (ulimit -f 16; exec "$TDS" -q -e "$big $cmd('$w/old.fe')") > "$dir/out" 2>&1
  rc=$?
  if [ $rc = 1 ] && grep -q "cannot write '$w/old.fe': File too large" "$dir/out" &&
     same_old "$w/old.fe" && no_tmp; then
    echo "PASS repro/${cmd}_file_size_limit"
  else
    echo "FAIL repro/${cmd}_file_size_limit: rc $rc, $(cat "$dir/out"), $(ls -A "$w")"
  fi
done
# a read-only (0444) target is refused, even for root; its content stays
old "$w/ro.fe"
chmod 444 "$w/ro.fe"
expect dump_read_only 1 "(command line):1: cannot write '$w/ro.fe': the file is read-only" \
  -- -q scripts/cube.tds -e "dump('$w/ro.fe')"
same_old "$w/ro.fe" && echo "PASS repro/dump_read_only_kept" || echo "FAIL repro/dump_read_only_kept"
# a folder, a missing folder, no name: errors with a non-zero status
mkdir -p "$w/isdir"
expect dump_directory 1 "(command line):1: cannot write '$w/isdir': it is a directory" \
  -- -q scripts/cube.tds -e "dump('$w/isdir')"
expect dump_missing_folder 1 "(command line):1: cannot write '/nonexistent-tds/x.fe': No such file or directory" \
  -- -q scripts/cube.tds -e "dump('/nonexistent-tds/x.fe')"
expect dump_no_name 1 "(command line):1: dump: give a file name (no datafile was loaded)" \
  -- -q scripts/cube.tds -e "dump()"
# a planted PATH.tmp symlink is not followed: the victim stays as it was
printf 'VICTIM\n' > "$w/victim.txt"
ln -s victim.txt "$w/out.fe.tmp"
expect dump_tmp_symlink 0 "ok" -- -q scripts/cube.tds -e "dump('$w/out.fe') print('ok')"
if [ "$(cat "$w/victim.txt")" = VICTIM ] && grep -q '^vertices' "$w/out.fe" && no_tmp; then
  echo "PASS repro/dump_tmp_symlink_victim"
else
  echo "FAIL repro/dump_tmp_symlink_victim: $(cat "$w/victim.txt" | head -n 1)"
fi
# a target that is a symlink: the file it names is replaced, the link kept
old "$w/real.fe"
ln -s real.fe "$w/link.fe"
"$TDS" -q scripts/cube.tds -e "dump('$w/link.fe')" > "$dir/out" 2>&1
if [ -L "$w/link.fe" ] && grep -q '^vertices' "$w/real.fe"; then
  echo "PASS repro/dump_through_symlink"
else
  echo "FAIL repro/dump_through_symlink: $(ls -l "$w")"
fi
# the target's permission bits are kept
old "$w/perm.fe"
chmod 640 "$w/perm.fe"
"$TDS" -q scripts/cube.tds -e "dump('$w/perm.fe')" > "$dir/out" 2>&1
if [ "$(stat -c %a "$w/perm.fe")" = 640 ] && grep -q '^vertices' "$w/perm.fe"; then
  echo "PASS repro/dump_keeps_mode"
else
  echo "FAIL repro/dump_keeps_mode: $(stat -c %a "$w/perm.fe")"
fi

# The fault tests (tests/repro/fault/, from fault_a.out): each report says
# whether the command failed; a failed command must leave the positions
# unchanged, and no report may show a non-finite coordinate or a failed
# mesh check. They run in the check mode, which verifies every command.
for f in a1_bigscale a2_volume a3_expr a4_sqrt a5_div0_constraint a6_collapse a7_gravity_nan; do
  (cd tests/repro/fault && TDS_CHECK=1 timeout 300 "$TDS" -q $f.tds) > "$dir/out" 2>&1
  rc=$?
  bad=$(awk '/ok=false/ { failed = 1; next }
             /positions unchanged=/ { if (failed && $0 !~ /unchanged=true/) print "changed after a failure: " $0
                                      if ($0 !~ /nonfinite coords=0 /) print "non-finite: " $0
                                      if ($0 !~ /check=ok/) print "check failed: " $0
                                      failed = 0 }' "$dir/out" | head -n 1)
  want=0
  [ $f = a7_gravity_nan ] && want=1 # its first line is now an error
  if grep -q -E 'runtime error|Sanitizer|TDS_CHECK' "$dir/out"; then
    echo "FAIL repro/fault_$f: $(grep -m1 -E 'runtime error|Sanitizer|TDS_CHECK' "$dir/out")"
  elif [ $want = 1 ] && ! grep -q -x -F "a7_gravity_nan.tds:3: gravity constant must be finite, not NaN" "$dir/out"; then
    echo "FAIL repro/fault_$f: $(tail -n 1 "$dir/out")"
  elif [ $rc != $want ] || [ -n "$bad" ]; then
    echo "FAIL repro/fault_$f: exit $rc: $bad $(tail -n 1 "$dir/out")"
  else
    echo "PASS repro/fault_$f"
  fi
done

# At the prompt a failing file operation is a clear message (not a value
# "nil  message"), and the session goes on.
printf 'dump("/nonexistent-tds/x.fe")\nprint("next", vertex_count)\n' |
  "$TDS" -q -i scripts/cube.tds > "$dir/out" 2>&1
if grep -q -x -F "stdin:1: cannot write '/nonexistent-tds/x.fe': No such file or directory" "$dir/out" &&
   grep -q -x -F "next	14" "$dir/out" && ! grep -q '^nil' "$dir/out"; then
  echo "PASS repro/prompt_dump_message"
else
  echo "FAIL repro/prompt_dump_message: $(cat "$dir/out" | tr '\n' ' ')"
fi

# D1 the other way round: a vector method given a scalar integrand.
printf 'QUANTITY q INFO_ONLY METHOD facet_vector_integral GLOBAL\nscalar_integrand: z\nvertices\n1 0 0 0\n' > "$dir/vs.fe"
expect fe_vector_method_scalar_integrand 1 \
  "$dir/vs.fe:1: quantity q: method facet_vector_integral needs a vector_integrand, not a scalar_integrand" \
  -- -q "$dir/vs.fe"
expect lua_vector_method_scalar_integrand 1 \
  "(command line):1: quantity q: method edge_vector_integral needs a vector_integrand, not a scalar_integrand" \
  -- -q -e 'quantity { name = "q", info_only = true, method = "edge_vector_integral", scalar_integrand = "z" }'
# a body with both volume and pressure is refused before it exists
expect body_volume_and_pressure 0 "false	0" -- -q -e '
vertices { {0,0,0}, {1,0,0}, {0,1,0}, {0,0,1} }
edges { {1,2}, {2,3}, {3,1}, {1,4}, {2,4}, {3,4} }
faces { {-3,-2,-1}, {1,5,-4}, {2,6,-5}, {3,4,-6} }
print(pcall(bodies, { {1,2,3,4, volume = 1, pressure = 2} }) and "" or false, body_count)'
# a quantity whose method is refused is not declared (a new name) or keeps
# its old definition (a redeclared one): 'a' still measures the cube's area 6
expect quantity_failure_atomic 0 "a	6.0	q	nil" -- -q -e '
quantity { name = "a", info_only = true, method = "facet_area" }
assert(not pcall(quantity, { name = "a", info_only = true, method = "facet_scalar_integral" }))
assert(not pcall(quantity, { name = "q", info_only = true,
  methods = { { method = "facet_area" }, { method = "edge_vector_integral" } } }))
dofile("scripts/cube.tds")
print("a", (tds.quantity_info("a")), "q", (tds.quantity_info("q")))'
