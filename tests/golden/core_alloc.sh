# Every allocation of the core goes through the allocator hook (tds.h,
# doc/design.md "Memory"): no core file calls the C library's allocator
# itself. ctx.c holds the hook's default (the C library); lua_*.c, main.c,
# repl.c and live.c are the program around the core. Prints the offending
# lines (none expected).
cd ../..
for f in src/*.c src/*.h; do
  case $f in src/lua_*|src/main.c|src/repl.c|src/live.c|src/ctx.c) continue ;; esac
  grep -nP '(?<![\w.>])(malloc|calloc|realloc|reallocarray|free|strdup|strndup|aligned_alloc|posix_memalign|asprintf|vasprintf|open_memstream|getline|getdelim)\s*\(' "$f" |
    grep -vP '^\d+:\s*(/\*|\*\*|//)' | sed "s|^|$f:|"
done
echo "core allocations checked"
