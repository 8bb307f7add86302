// flow.cmd: control flow, procedures, functions, locals, recursion
function real fib(integer nn) { if nn < 2 then return nn; return fib(nn-1) + fib(nn-2) }
printf "K1 %d %d\n", fib(10), fib(15)
procedure count_to(integer nn) {
  local kk;
  kk := 0;
  while kk < nn do { kk += 1; if kk imod 2 == 0 then continue; printf "K2 %d\n", kk }
}
count_to(7)
for ( ii := 1 ; ii <= 4 ; ii += 1 ) {
  for ( jj := 1 ; jj <= 4 ; jj += 1 ) {
    if jj == ii then continue 2;
    if ii == 4 then break 2;
    printf "K3 %d %d\n", ii, jj
  }
}
ii := 10; do { ii -= 3 } while ii > 0; printf "K4 %d\n", ii
cnt := 0; { cnt += 1 } 7; printf "K5 %d\n", cnt
tt := 0; while 1 do { tt += 1; if tt >= 5 then break }; printf "K6 %d\n", tt
printf "K7 %g %g %g\n", (1 < 2) ? 10 : 20, 0 ? 1 : 0 ? 2 : 3, 5 > 3 and 2 > 1
printf "K8 %s %s\n", "ab" "cd", sprintf "%03d|%5.2f", 7, pi
printf "K9 %d %d\n", is_defined("fib"), is_defined("nosuchname")
define arr real[5]
for ( ii := 1 ; ii <= 5 ; ii += 1 ) arr[ii] := ii^2
printf "K10 %g %g %d\n", arr[3], arr[5] - arr[1], sizeof(arr)
define grid integer[2][3]
grid := {{1,2,3},{4,5,6}}
printf "K11 %d %d\n", grid[2][3], grid[1][2] * grid[2][1]
mycmd := { cnt := cnt * 2 }
mycmd 3; printf "K12 %d\n", cnt
printf "K13 %g %g %g %g\n", 2^-2, -3^2, 2**3**2, 17 % 5
printf "K14 %g %g %g\n", floor(-2.5), ceil(-2.5), abs(-7)
printf "K15 %.10g %.10g %.10g\n", sinh(0.5), atan2(-1, -1), log(10)
define mm real[2][2]
mm := {{1,2},{3,4}}
define vv2 real[2]
vv2 := {1, 1}
define pr real[2][2]
pr := mm*mm
define mv real[2]
mv := vv2*mm
printf "K16 %g %g %g %g\n", pr[2][1], vv2*vv2, mv[2], pr[1][2]
mm := 0
printf "K17 %g\n", mm[2][2]
printf "K18 %.12g %.12g %.12g %.12g\n", incompleteEllipticE(4, 0.3), incompleteEllipticF(-2.5, 0.9), incompleteEllipticE(0.3, -2), ellipticK(0.5)
