// a command file: comments, several commands on a line, continuation
printf "%d %d %d\n", vertex_count,
   edge_count, facet_count
r; printf "%d facets\n", facet_count
gogo := { g 2; printf "energy %.4f\n", total_energy }
gogo
