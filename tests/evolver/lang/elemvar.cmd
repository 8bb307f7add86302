// element commands on an element variable (foreach ... do CMD ee)
r;
foreach edge ee where id <= 4 do refine ee;
printf "K %d %d %d %.10g\n", vertex_count, edge_count, facet_count, total_area;
foreach edge ee where id > 40 and id < 50 do equiangulate ee;
printf "K %d %d %d %.10g\n", vertex_count, edge_count, facet_count, total_area;
foreach vertex vv where id > 20 and id < 30 do vertex_average vv;
printf "K %d %d %d %.10g\n", vertex_count, edge_count, facet_count, total_area;
foreach facet ff where id < 10 do reverse_orientation ff;
printf "K %d %d %d %.10g %.10g\n", vertex_count, edge_count, facet_count, total_area, sum(facet, x*id);
foreach edge ee where id > 30 and id < 36 do edgeswap ee;
printf "K %d %d %d %.10g\n", vertex_count, edge_count, facet_count, total_area;
foreach edge ee where length < 0.3 and id > 60 do delete ee;
printf "K %d %d %d %.10g\n", vertex_count, edge_count, facet_count, total_area;
foreach facet ff where id == 7 do delete ff;
printf "K %d %d %d %.10g\n", vertex_count, edge_count, facet_count, total_area;
