// drop.cmd: run on xattr/gen.lua's drops by Evolver and tds (xattr.sh)
pk := {printf "K %d %d %d %.15g %.15g %.15g\n", vertex_count, edge_count, facet_count, total_energy, vq.value, sum(vertex, cv)}
pk; g 5; pk; r; pk; g 5; pk
set edge ang 150 where on_constraint 1 and id < 20; recalc; pk
foreach facet ff where id < 30 do ff.fw := ff.fw + 0.5; recalc; pk
set vertex cv 0.3 where on_constraint 1; g 2; pk
foreach edge ee where on_constraint 1 do printf "K %d %.15g\n", ee.id, ee.ang
