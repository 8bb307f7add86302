-- twocubes.lua: two unit cubes stacked in z, sharing face 6 (the top of
-- body 1, listed with its sign reversed in body 2), so the four edges of
-- face 6 are triple junctions. SIGNS, if set, gives the sign of each of
-- body 2's six faces (1 or -1 for faces 7..11 and 6) to make wrong ones.
vertices {
  {0,0,0}, {1,0,0}, {1,1,0}, {0,1,0},
  {0,0,1}, {1,0,1}, {1,1,1}, {0,1,1},
  {0,0,2}, {1,0,2}, {1,1,2}, {0,1,2},
}
edges {
  {1,2}, {2,3}, {3,4}, {4,1}, {5,6}, {6,7}, {7,8}, {8,5},
  {9,10}, {10,11}, {11,12}, {12,9},
  {1,5}, {2,6}, {3,7}, {4,8}, {5,9}, {6,10}, {7,11}, {8,12},
}
faces {
  {1,14,-5,-13}, {2,15,-6,-14}, {3,16,-7,-15}, {4,13,-8,-16},
  {-4,-3,-2,-1}, {5,6,7,8},
  {5,18,-9,-17}, {6,19,-10,-18}, {7,20,-11,-19}, {8,17,-12,-20},
  {9,10,11,12},
}
local s = SIGNS or {1, 1, 1, 1, 1, -1}
bodies {
  {1,2,3,4,5,6, volume = 1},
  {7*s[1], 8*s[2], 9*s[3], 10*s[4], 11*s[5], 6*s[6], volume = 1},
}
