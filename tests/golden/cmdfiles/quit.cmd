print "before"
quit 3
print "after"
