// phview.cmd: phelanc.fe's own view commands (bunch := transform_expr
// "abc", lots, few := transforms off, dodecs := show facet ...: commands
// defined without braces; Evolver's show would start its graphics
// command mode, so dodecs is not run) and the transforms its generators make.
vs := { s1 := 0; s2 := 0; s3 := 0;
  for ( ii := 1 ; ii <= transform_count ; ii += 1 )
  { s1 += view_transforms[ii][1][4]; s2 += view_transforms[ii][2][4]^2; s3 += view_transforms[ii][3][4]*view_transforms[ii][1][4] };
  printf "K %d %g %g %g\n", transform_count, s1, s2, s3 }
vs
bunch
vs
lots
vs
transform_expr "2(a|b|c|d|e|f)"
vs
few
print transforms
