# report.sh: the table and ratio lines a g benchmark prints, sourced by
# string.sh and foam3.sh. report TITLE STEPS EV_SEC EV_ENERGY TD_SEC TD_ENERGY
report() {
  echo "$1"
  printf '%-10s %14s %20s\n' program "s per step" "energy after $2"
  printf '%-10s %14s %20s\n' evolver "$3" "$4"
  printf '%-10s %14s %20s\n' tds "$5" "$6"
  awk -v e="$3" -v t="$5" -v ee="$4" -v te="$6" 'BEGIN {
    printf "speed ratio (Evolver / tds): %.1fx (goal: at least 10x)\n", e / t
    printf "energy: tds %s that of Evolver (goal: no worse)\n", (te <= ee ? "at or below" : "ABOVE") }'
}
