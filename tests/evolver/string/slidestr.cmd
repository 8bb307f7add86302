r
foreach edge ee do printf "L %d %d %d %.15g\n", ee.id, ee.vertex[1].id, ee.vertex[2].id, ee.length
foreach facet ff do printf "F %d %.15g\n", ff.id, ff.area
foreach facet[1].edge ee do printf "O %d\n", ee.oid
printf "N %d %d %d %d %.15g\n", vertex_count, edge_count, facet_count, body_count, body[1].volume
V
foreach vertex vv where not fixed do printf "X %d %.15g %.15g\n", vv.id, vv.x, vv.y
printf "S %.15g %d\n", sum(edge where not fixed, length), sum(vertex where on_constraint 1, 1)
