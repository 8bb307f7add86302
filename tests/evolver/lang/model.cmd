// model.cmd: the element model commands tds accepts (it has linear
// elements only): linear, lagrange 1, M 1, with Evolver's messages, and
// lagrange_order; the energy is the same in both models.
printf "K1 %d %d %.12g\n", lagrange_order, linear, total_energy
linear
printf "K2 %d\n", lagrange_order
lagrange 1
printf "K3 %d %.12g\n", lagrange_order, total_energy
lagrange 1
linear
lagrange 1
M 1
M 1
linear
recalc
printf "K4 %d %d %.12g\n", lagrange_order, vertex_count, total_energy
