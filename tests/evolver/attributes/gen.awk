# gen.awk: add user attributes with seeded random values (awk -v seed=N)
# to the element lines of a datafile such as cube.fe (tests/evolver/attributes.sh).
BEGIN { srand(seed) }
function r() { return sprintf("%.6g", (rand() - 0.5) * 2000 / 7) }
function i() { return int(rand() * 41) - 20 }
/^vertices/ { print "define vertex attribute weight real"; print "define vertex attribute tri integer[3]";
  print "define edge attribute ew real[2]"; print "define facet attribute flags integer[3]";
  print "define facet attribute mat real[2][2]"; print "define body attribute bw real";
  sec = "v"; print; next }
/^edges/ { sec = "e"; print; next }
/^faces/ { sec = "f"; print; next }
/^bodies/ { sec = "b"; print; next }
/^read/ { sec = ""; print; next }
sec == "v" && /^[0-9]/ { print $0 " weight " r() " tri {" i() ", " i() ", " i() "}"; next }
sec == "e" && /^[0-9]/ { c = (NR % 3 == 0) ? " color " (NR % 16) : ""; print $0 " ew {" r() ", " r() "}" c; next }
sec == "f" && /^[0-9]/ { c = (NR % 2 == 0) ? " color " (NR % 15) : ""; print $0 " flags {" i() "," i() "," i() "} mat {{" r() ", " r() "}, {" r() ", " r() "}}" c; next }
sec == "b" && /^[0-9]/ { print $0 " bw " r(); next }
{ print }
