// cube.cmd: addload of a second copy, then replace_load of another file
// and addload of the first again (tests/evolver/addload.sh).
aa := 5
addload "cube.fe"
printf "K1 %d %d %d %d %.12g\n", vertex_count, edge_count, facet_count, body_count, total_energy
foreach facet ff where id > 20 do printf "K2 %d %d %d %d %d\n", ff.id, ff.edge[1].oid, ff.edge[2].oid, ff.edge[3].oid, ff.original
foreach vertex vv where id > 12 do printf "K3 %d %g %g %g %d\n", vv.id, vv.x, vv.y, vv.z, vv.original
foreach body bb do printf "K4 %d %.12g %.12g %d\n", bb.id, bb.volume, bb.target, bb.original
replace_load "mound.fe"
printf "K5 %d %d %d %d %g %d %d\n", vertex_count, edge_count, facet_count, body_count, aa, is_defined("gogo"), is_defined("re")
printf "K6 %.12g %.12g %g\n", total_energy, body[1].volume, angle
foreach vertex vv do printf "K7 %d %g %g %g %d %d\n", vv.id, vv.x, vv.y, vv.z, vv.original, on_constraint 1
addload "cube.fe"
recalc
printf "K8 %d %d %d %d %.12g %.12g %.12g\n", vertex_count, edge_count, facet_count, body_count, total_energy, body[1].volume, body[2].volume
foreach edge ee where id > 36 do printf "K9 %d %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id, ee.original
