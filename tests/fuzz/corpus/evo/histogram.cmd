// histogram.cmd: histogram and loghistogram in Evolver's layout
histogram(edge, length)
loghistogram(facet where id < 10, area)
histogram(vertex, z)
r
loghistogram(edge, length)
histogram(edge where length > 0.4, length)
histogram(edge where id < 0, length)
