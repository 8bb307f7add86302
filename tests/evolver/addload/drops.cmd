printf "K1 %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count
printf "K2 %.12g %.12g\n", total_energy, zmom.value
foreach body bb do printf "K3 %d %.12g %.12g %d\n", bb.id, bb.volume, bb.target, bb.original
foreach vertex vv where id % 7 == 3 do printf "K4 %d %.12g %.12g %.12g %g %d %d\n", vv.id, vv.x, vv.y, vv.z, vv.tag, vv.original, on_constraint 1
foreach facet ff where id % 5 == 1 do printf "K5 %d %d %d %d %d\n", ff.id, ff.edge[1].oid, ff.edge[2].oid, ff.edge[3].oid, ff.original
foreach edge ee where id % 9 == 2 do printf "K6 %d %d %d %d\n", ee.id, ee.vertex[1].id, ee.vertex[2].id, ee.original
printf "K7 %d\n", sum(vertex where on_constraint 1, 1)
