// feattr.cmd: facetedge attributes (define facetedge attribute, set,
// read, aggregates; refine leaves the new facetedges at 0, as Evolver).
// tds numbers facetedges its own way: only order-free results compared.
define facetedge attribute fw real
define facetedge attribute fv integer[2]
printf "K1 %d %d\n", facetedge_count, sum(facetedge, fw)
set facetedge fw 2.5
printf "K2 %.12g\n", sum(facetedge, fw)
foreach facetedge fe do fe.fw := fe.edge[1].length * 10 + fe.facet[1].area
printf "K3 %.12g %.12g %.12g\n", sum(facetedge, fw), max(facetedge, fw), min(facetedge, fw)
set facetedge fw fw*2 where fw > 6
printf "K4 %.12g %d\n", sum(facetedge, fw), count(facetedge where fw > 10, 1)
foreach facetedge fe do { fe.fv[1] := fe.facet[1].id; fe.fv[2] := 3 }
printf "K5 %.12g %.12g\n", sum(facetedge, fv[1]), max(facetedge, fv[2])
foreach facetedge fe where fe.edge[1].length > 0.6 do fe.fw := 11
printf "K6 %d\n", count(facetedge where fw == 11, 1)
set facetedge fw 0 where fw < 6
printf "K7 %.12g %d\n", sum(facetedge, fw), count(facetedge where fw == 0, 1)
foreach facet ff do ff.color := 1
printf "K8 %d\n", count(facetedge where fw > 0, 1)
r
printf "K9 %.12g %d %d\n", sum(facetedge, fw), count(facetedge where fw == 0, 1), facetedge_count
