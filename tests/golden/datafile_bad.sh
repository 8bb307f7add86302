#!/bin/sh
# datafile_bad.sh: malformed datafiles must fail cleanly: exit status 1 and
# exactly one line "FILE:LINE: message" on stderr, the message expected by
# the file's first line ("// expect: ...") or by FILE.expect. Then the
# same for large generated inputs (10 MB of elements ending in an error,
# a 10 MB line, 1 MB of pseudo-random bytes), whose messages are only
# checked for their form.
# Run by tests/run.sh with $TDS set and the current directory tests/golden.
TDS=${TDS:-tds}
cd ../datafile/bad || exit 1
for f in *.fe; do
  if [ -f "${f%.fe}.expect" ]; then
    want=$(cat "${f%.fe}.expect")
  else
    want=$(sed -n '1s|^// expect: ||p' "$f")
  fi
  got=$("$TDS" "$f" 2>&1 < /dev/null)
  status=$?
  if [ "$status" -eq 1 ] && [ "$got" = "$want" ]; then
    echo "$got"
  else
    echo "MISMATCH $f (exit status $status):"
    echo "  got:  $got"
    echo "  want: $want"
  fi
done

# Generated inputs: one message line of the form FILE:LINE: ..., status 1.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
awk 'BEGIN { print "vertices"
  for (i = 1; i <= 400000; i++) printf "%d %d.5 -%d 1e-3 fixed\n", i, i, i
  print "edges"; print "1 1 400001" }' > "$tmp/big.fe"
awk 'BEGIN { s = "x"; while (length(s) < 10000000) s = s s; print s }' > "$tmp/longline.fe"
awk 'BEGIN { srand(7); for (i = 0; i < 1000000; i++) {
  c = 1 + int(rand() * 255); if (c == 10 && rand() < 0.9) c = 65
  printf "%c", c } }' > "$tmp/junk.fe"
for f in big longline junk; do
  got=$(cd "$tmp" && "$TDS" "$f.fe" 2>&1 < /dev/null)
  status=$?
  lines=$(printf '%s\n' "$got" | wc -l)
  if [ "$status" -eq 1 ] && [ "$lines" -eq 1 ] &&
     printf '%s\n' "$got" | grep -q "^$f\.fe:[0-9][0-9]*: "; then
    case $f in
      junk) echo "$f.fe: one message line, exit status 1" ;;
      *) echo "$got" | cut -c1-120 ;;
    esac
  else
    echo "MISMATCH $f.fe (exit status $status, $lines lines): $(printf '%s' "$got" | head -c 300)"
  fi
done
