gogo := { g 5; r; g 5; u; V }
gogo
g 10 // comment
G -5
m 0.1
U
v
print total_energy
angle := 45; recalc
print pi
print sqrt(2)
set body[1] target 2
foreach vertex vv where z > 0.9 do printf "%d\n", vv.id
list facet where area > 0.1
histogram(edge, length)
for (ii := 1; ii < 3; ii++) { r; g 2 }
procedure p(real a) { printf "%g\n", a*2 }
p(3)
function real f(real x) { return x^2 }
print f(3)
define vertex attribute weight real
set vertex weight x+y
print sum(vertex, weight)
print -2^2, 2^3^2, 1 < 2 < 3
