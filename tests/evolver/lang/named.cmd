// named.cmd: named constraints (numbered with the smallest free number),
// used by name in set, on_constraint and expressions.
define constraint circle_con formula: x^2 + y^2 = 4
set vertex[2] constraint circle_con
printf "K1 %d %d %d\n", vertex[2].on_constraint circle_con, vertex[2].on_constraint 1, circle_con
define constraint 3 formula: z = 2
define constraint other_con formula: z = 1
printf "K2 %d %d\n", other_con, valid_constraint(2)
g 1
printf "K3 %.10g\n", sqrt(vertex[2].x^2 + vertex[2].y^2)
