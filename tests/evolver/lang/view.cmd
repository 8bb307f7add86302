// view.cmd: view transforms from the datafile, transform_expr and
// transform_depth on its generators, view_transforms[i][j][k] and
// view_transform_swap_colors[i]. tds lists the generated transforms in
// another order than Evolver: only counts and sums over all transforms
// are compared.
vsum := { s1 := 0; s2 := 0; s3 := 0; sw := 0;
  for ( ii := 1 ; ii <= transform_count ; ii += 1 )
  { s1 += view_transforms[ii][1][4] * (ii == 1 ? 1 : 1);
    s2 += view_transforms[ii][1][1] + 2*view_transforms[ii][2][2] + 4*view_transforms[ii][3][3];
    s3 += view_transforms[ii][1][4]^2 + view_transforms[ii][4][4];
    sw += view_transform_swap_colors[ii] };
  printf "K %d %g %g %g %d\n", transform_count, s1, s2, s3, sw }
vsum
printf "K1 %g %g %d %d\n", view_transforms[2][1][1], view_transforms[3][1][4], view_transform_swap_colors[2], view_transform_swap_colors[3]
transform_expr "a"
vsum
transform_expr "ab"
vsum
transform_expr "3(a|b|c)"
vsum
transform_expr "!a!a!a!a"
vsum
transform_expr "abc"
vsum
transform_expr "ccc"
vsum
transform_expr "2c"
vsum
transform_expr "!(ab)"
vsum
transform_expr "a|!c"
vsum
transform_expr ""
vsum
transform_expr "2(a|b)c"
vsum
transform_expr "ac|ca"
vsum
transform_expr "12C"
vsum
transform_expr "!ac"
vsum
// transform_depth n: as n(a|b|c); Evolver 2.70 drops the swap_colors
// flags there, and for n >= 3 it stops at 11 transforms on this file
// (doc/command-language.md), so depths 1 and 2 and no flags are compared
transform_depth 1
printf "K2 %d\n", transform_count
transform_depth 2
vsum2 := { s1 := 0; s2 := 0;
  for ( ii := 1 ; ii <= transform_count ; ii += 1 )
  { s1 += view_transforms[ii][1][4]; s2 += view_transforms[ii][1][1] + 2*view_transforms[ii][2][2] };
  printf "K3 %d %g %g\n", transform_count, s1, s2 }
vsum2
transforms off
print transforms
transforms
