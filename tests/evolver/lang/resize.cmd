// resize.cmd: redefining an array attribute with other sizes keeps the
// values at the indices both shapes have (the rest 0), as Evolver does.
define vertex attribute arr real[3]
define edge attribute mat integer[2][3]
foreach vertex vv do { vv.arr[1] := vv.id; vv.arr[2] := vv.x + 10; vv.arr[3] := vv.z * 7 }
foreach edge ee do { ee.mat[1][1] := ee.id; ee.mat[2][3] := 2 * ee.id; ee.mat[1][3] := 5 }
define vertex attribute arr real[5]
printf "K1 %.12g %.12g %.12g %.12g %.12g\n", sum(vertex, arr[1]), sum(vertex, arr[2]), sum(vertex, arr[3]), sum(vertex, arr[4]), sum(vertex, arr[5])
define vertex attribute arr real[2]
printf "K2 %.12g %.12g %d\n", sum(vertex, arr[1]), sum(vertex, arr[2]), sizeof(arr)
define edge attribute mat integer[3][2]
printf "K3 %d %d %d %d %d %d\n", sum(edge, mat[1][1]), sum(edge, mat[1][2]), sum(edge, mat[2][1]), sum(edge, mat[2][2]), sum(edge, mat[3][1]), sum(edge, mat[3][2])
define edge attribute mat integer[1][4]
printf "K4 %d %d %d %d\n", sum(edge, mat[1][1]), sum(edge, mat[1][2]), sum(edge, mat[1][3]), sum(edge, mat[1][4])
