# A torus datafile whose bodies do not close up in space (twointor.fe with
# a face of each body listed with the wrong sign): the load warns once per
# inconsistent edge and once that the 2 bodies wrap round the torus (the
# count is of bodies; it was of the facet walks that failed, 14 for the 2
# bodies of a tangled twointor). tds.load_replace, which parses the file
# into a scratch surface first, printed every warning twice.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed 's/^1    -1 -2 -3 -4  -5/1    -1 -2 3 -4  -5/; s/^2     2 -6 -7  8/2     2 -6 -7  -8/' \
  /usr/share/doc/evolver/examples/twointor.fe > "$tmp/bad.fe"
"$TDS" -q -e "tds.load_replace('$tmp/bad.fe') print(body_count, facet_count)" > "$tmp/out" 2>&1
echo "exit $?"
sed "s|$tmp/||" "$tmp/out"
