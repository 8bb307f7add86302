// matrix.cmd: matrix_inverse, matrix_determinant and matrix_multiply on
// global arrays (vector-matrix, matrix-vector, a singular matrix).
define mm real[3][3]
define mi real[3][3]
define pp real[3][3]
define vv real[3]
define ww real[3]
mm[1][1] := 2; mm[1][2] := 1; mm[1][3] := 0.5
mm[2][1] := -1; mm[2][2] := 3; mm[2][3] := 1
mm[3][1] := 0.25; mm[3][2] := 4; mm[3][3] := -2
vv[1] := 1; vv[2] := -2; vv[3] := 0.5
rr := matrix_inverse(mm, mi)
printf "K1 %g %.12g %.12g %.12g\n", rr, mi[1][1], mi[2][3], mi[3][2]
printf "K2 %.12g\n", matrix_determinant(mm)
matrix_multiply(mm, mi, pp)
printf "K3 %.12g %.12g %.12g\n", pp[1][1], pp[1][2], pp[3][3]
matrix_multiply(vv, mm, ww)
printf "K4 %.12g %.12g %.12g\n", ww[1], ww[2], ww[3]
matrix_multiply(mm, vv, ww)
printf "K5 %.12g %.12g %.12g\n", ww[1], ww[2], ww[3]
define sg real[2][2]
sg[1][1] := 1; sg[1][2] := 2; sg[2][1] := 2; sg[2][2] := 4
define sgi real[2][2]
printf "K7 %g %g\n", matrix_inverse(sg, sgi), matrix_determinant(sg)
