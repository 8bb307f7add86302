// A definition that names an unknown command is refused when it is read
// (Evolver: syntax error), after the lines before it ran; definitions
// that name only what exists, what they assign, or themselves are not.
procedure countdown(integer cnt) { if cnt > 0 then { printf "K %d\n", cnt; countdown(cnt-1) } }
countdown(3)
kk := { aa := 3; printf "K aa %g\n", aa }
kk
rr := { printf "K %.12g\n", total_area }
ss := rr
ss
gg := { rr; nosuchcmd }
print "K not reached"
