// facetedge.cmd: the facetedge generator (a facet's sides, each with its
// edge oriented as the facet runs it). tds numbers facetedges its own way,
// so only sums over all of them are compared.
tot := 0; foreach facetedge fe do tot += fe.edge[1].length
printf "K1 %d %.12g\n", count(facetedge, 1), tot
tot := 0; foreach facetedge fe do tot += fe.facet[1].area
printf "K2 %.12g\n", tot
tot := 0; foreach facetedge fe do tot += fe.edge[1].vertex[1].z * fe.edge[1].x - fe.edge[1].y
printf "K3 %.12g\n", tot
r
tot := 0; foreach facetedge fe where fe.facet[1].area > 0.01 do tot += fe.edge[1].vertex[2].x
printf "K4 %d %.12g\n", count(facetedge, 1), tot
