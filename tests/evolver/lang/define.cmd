// define.cmd: run-time definitions of constraints, boundaries and named
// quantities, as in a datafile's top section, then used at once.
define constraint 8 formula: z = 0.25; printf "K1 %d\n", 1
define quantity elen energy method edge_length global
recalc
printf "K2 %.12g %.12g\n", elen.value, total_energy
define quantity farea info_only method facet_area global
recalc
printf "K3 %.12g %.12g\n", farea.value, total_energy
define constraint 9 formula: x = 0 energy: e1: 0 e2: 0 e3: y
foreach vertex vv where x == 0 do set vv constraint 9
recalc
printf "K4 %.12g\n", total_energy
set vertex[1] constraint 8
recalc
printf "K5 %.12g %.12g %.12g\n", vertex[1].z, total_energy, body[1].volume
define boundary 3 parameters 1 x1: p1 x2: 0.5 x3: 0.5
printf "K6 %d\n", 6
elen.modulus := 0.5
elen.volconst := 1
recalc
printf "K7 %.12g %.12g %.12g %.12g\n", elen.modulus, elen.volconst, elen.value, total_energy
define quantity fixa fixed = 7 method facet_area global
fixa.target := 6.5
printf "K8 %.12g %.12g\n", fixa.target, fixa.value
printf "K9 %d %d %d %d %d\n", valid_constraint(8), valid_constraint(10), valid_boundary(3), valid_boundary(1), valid_constraint(-2)
// a definition continues on the next line after an operator
define constraint 11 formula: x +
   y = 1 // a comment
printf "K10 %d\n", valid_constraint(11)
// a ':' at the end of a line or before '}' ends a command (3ds.cmd has one)
kk := 3:
setk := { kk := 4: }
setk
printf "K11 %d %d\n", kk, transform_count
