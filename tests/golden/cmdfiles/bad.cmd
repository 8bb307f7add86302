print "first"
print 1 +
   nosuch
print "never printed"
