foreach facet[1].vertex vv do printf "A %d\n", vv.id
printf "B %d %d\n", facet[1].body[1].id, body[1].facet[1].id
foreach body bb do printf "C %d %.15g %.15g\n", bb.id, bb.volume, bb.target
printf "D %.15g %.15g\n", max(edge, length), min(facet, area)
foreach vertex vv where valence == 3 do printf "E %d\n", vv.id
foreach edge ee where valence == 1 do printf "F %d\n", ee.id
printf "G %d\n", count(facet where area > 0, 1)
