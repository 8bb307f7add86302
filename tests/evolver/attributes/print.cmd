foreach vertex vv do printf "V %d %.17g %d %d %d\n", vv.id, vv.weight, vv.tri[1], vv.tri[2], vv.tri[3];
foreach edge ee do printf "E %d %.17g %.17g %d\n", ee.id, ee.ew[1], ee.ew[2], ee.color;
foreach facet ff do printf "F %d %d %d %d %.17g %.17g %.17g %.17g %d\n", ff.id, ff.flags[1], ff.flags[2], ff.flags[3], ff.mat[1][1], ff.mat[1][2], ff.mat[2][1], ff.mat[2][2], ff.color;
foreach body bb do printf "B %d %.17g\n", bb.id, bb.bw;
