// errors.cmd: a run-time error abandons the rest of the command file
printf "K1 %d\n", 1
zero := 0
badcmd := { printf "K2 %g\n", 1/zero }
printf "K3 %d\n", 3
badcmd
printf "K4 never printed\n"
