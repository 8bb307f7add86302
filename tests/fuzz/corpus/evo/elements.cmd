// elements.cmd: generators, sub-elements, attributes, aggregates, set
printf "K1 %d %d %d %d\n", vertex_count, edge_count, facet_count, body_count
printf "K2 %.12g %.12g %.12g\n", sum(facet, area), sum(edge, length), avg(vertex, z)
printf "K3 %d %d %d\n", count(vertex where fixed, 1), count(edge where valence == 2, 1), max(edge, valence)
foreach facet ff where ff.id <= 3 do printf "K4 %d %.12g %.12g %d\n", ff.id, sum(ff.edge, length), ff.area, count(ff.vertex, 1)
foreach edge ee where ee.id <= 4 do printf "K5 %d %d %d %.12g\n", ee.id, ee.vertex[1].id, ee.vertex[2].id, ee.length
printf "K6 %d %d %d\n", edge[-3].vertex[1].id, edge[3].vertex[1].id, facet[2].edge[2].oid
printf "K7 %.12g %.12g %.12g\n", facet[4].x, facet[4].y, facet[4].z
printf "K8 %.12g %.12g\n", body[1].volume, body[1].target
define vertex attribute vmark real
set vertex vmark x + 2*y where z > 0.5
printf "K9 %.12g %.12g\n", sum(vertex, vmark), max(vertex, vmark)
set edge tension 3 where length > 0.9
recalc
printf "K10 %.12g %d\n", total_energy, count(edge where tension == 3, 1)
set facet tension 0.5 where id imod 2 == 0
recalc
printf "K11 %.12g\n", total_energy
fix vertex where id <= 2
printf "K12 %d\n", sum(vertex, fixed)
unfix vertex where id == 1
printf "K13 %d %d\n", sum(vertex, fixed), vertex[2].fixed
vid := min(vertex where not fixed and on_boundary 1 == 0 and on_boundary 2 == 0, id)
vertex[vid].x := vertex[vid].x + 0.25
recalc
printf "K14 %d %.12g %.12g\n", vid, vertex[vid].x, total_area
body[1].target += 0.5
printf "K15 %.12g\n", body[1].target
nn := 0; foreach vertex vv do { foreach vv.edge ee do nn += 1 }; printf "K16 %d\n", nn
printf "K17 %.12g\n", sum(body[1].facet, area)
