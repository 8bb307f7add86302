// name := command, without braces: a command definition (Evolver's rule);
// name := expression stays a variable.
kk := printf "K %d %d %d\n", vertex_count, edge_count, facet_count
kk
rr := r
rr
kk
vv := set vertex x x+0.125 where id == 1
vv
vv
printf "K %.12g\n", vertex[1].x
zz := 3
printf "K %g\n", zz
ww := sqrt(4) + zz
printf "K %g\n", ww
all := show facet   // defined only: running show waits for graphics commands
uu := u
uu
kk
