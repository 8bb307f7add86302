# paper_summary.awk: the generated inputs of bench/paper.sh, one table per
# family and its worst input. Input lines: "FAMILY/CASE MODE RESULT ...
# key=value ..." with MODE tds, gloop (Evolver g;u;V) or relax (Evolver
# u;V;hessian_seek).
# Columns: reached = first iteration with r < 1e-13 x mean edge ("never":
# not reached); |K| tds/relax = the RMS of Meyer's |K| error, tds and
# Evolver's relaxed run, and their ratio; K.n = tds's K.n RMS; mean angle
# tds and Evolver's best (of its two runs) and the difference; min angle
# tds and Evolver's best.
function val(key,   i, kv) {
  for (i = 4; i <= NF; i++) { split($i, kv, "="); if (kv[1] == key) return kv[2] }
  return ""
}
{
  split($1, fc, "/"); fam = fc[1]; c = fc[2] + 0
  if (!(fam in seen)) { seen[fam] = 1; order[++nf] = fam }
  if (c > ncase[fam]) ncase[fam] = c
  k = fam SUBSEP c

  if ($2 == "tds") {
    tname[k] = $4; titer[k] = val("iters"); treach[k] = val("reached")
    tstat[k] = val("status"); tk[k] = val("crms"); tn[k] = val("nrms")
    tmean[k] = val("mean"); tmin[k] = val("min"); have[k] = 1
  } else {
    m = val("mean") + 0; mn = val("min") + 0
    if (!(k in emean) || m > emean[k]) emean[k] = m
    if (!(k in emin) || mn > emin[k]) emin[k] = mn
    if ($2 == "relax") ek[k] = val("crms")
  }
}
END {
  for (i = 1; i <= nf; i++) {
    fam = order[i]
    printf "\n== generated: %s\n", fam
    printf "%-28s %7s %7s %-10s %9s %9s %6s %9s %6s %6s %6s %6s %6s\n", "input", "iters",
      "reached", "status", "|K|.tds", "|K|.relax", "ratio", "K.n.tds", "mean", "ev.mean",
      "diff", "min", "ev.min"
    wr = -1; wratio = -1; wdiff = 1e9; nr = 0
    for (c = 1; c <= ncase[fam]; c++) {
      k = fam SUBSEP c
      if (!(k in have)) continue
      r = (treach[k] == "" || treach[k] == 0) ? "never" : treach[k]
      ratio = (ek[k] != "" && ek[k] > 0) ? tk[k] / ek[k] : 0
      diff = tmean[k] - emean[k]
      printf "%-28s %7s %7s %-10s %9.2e %9.2e %6.2f %9.2e %6.2f %6.2f %+6.2f %6.2f %6.2f\n",
        tname[k], titer[k], r, tstat[k], tk[k], ek[k], ratio, tn[k], tmean[k], emean[k],
        diff, tmin[k], emin[k]
      rr = (r == "never") ? 1e12 : r + 0
      if (rr > wr) { wr = rr; wrn = tname[k] }
      if (ratio > wratio) { wratio = ratio; wrat = tname[k] }
      if (diff < wdiff) { wdiff = diff; wdn = tname[k] }
      if (r != "never" && rr <= (fam == "drop" ? 3000 : 1000)) nr++
    }
    printf "worst: reached %s (%s); |K| ratio %.2f (%s); mean angle %+.2f (%s); r < 1e-13 x edge within %d iterations: %d inputs\n",
      (wr >= 1e12) ? "never" : wr, wrn, wratio, wrat, wdiff, wdn, (fam == "drop") ? 3000 : 1000, nr
  }
}
