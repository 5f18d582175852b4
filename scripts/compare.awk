# Puts our numbers beside the papers' and says whether each lies within the stated tolerance.
# Usage: awk -F, -f scripts/compare.awk REFERENCE.csv OURS.csv > table.md
#   REFERENCE.csv: quantity,paper,tolerance,source   (header line first)
#     tolerance: "10%" relative, "0.05" absolute, ">" or "<" (ours must exceed / stay below paper),
#     "context" (shown, not judged)
#   OURS.csv: quantity,value,error   (header line first; error may be empty)
# Writes a Markdown table; the exit status is 0 whatever the verdicts (the table states them).
FNR == 1 { next }
FNR == NR { paper[$1] = $2; tol[$1] = $3; src[$1] = $4; order[++n] = $1; next }
{ ours[$1] = $2; err[$1] = $3 }
END {
  print "| quantity | ours | paper | tolerance | verdict | source |"
  print "|---|---|---|---|---|---|"
  for (k = 1; k <= n; k++) {
    q = order[k]
    if (!(q in ours)) { printf "| %s | (not measured) | %s | %s | missing | %s |\n", q, paper[q], tol[q], src[q]; continue }
    v = ours[q] + 0; p = paper[q] + 0; t = tol[q]
    if (t == "context") verdict = "context"
    else if (t == ">") verdict = (v > p) ? "yes" : "NO"
    else if (t == "<") verdict = (v < p) ? "yes" : "NO"
    else if (t ~ /%$/) { r = substr(t, 1, length(t) - 1) / 100; d = v - p; if (d < 0) d = -d; a = p < 0 ? -p : p; verdict = (d <= r * a) ? "yes" : "NO" }
    else { d = v - p; if (d < 0) d = -d; verdict = (d <= t + 0) ? "yes" : "NO" }
    shown = (err[q] != "") ? sprintf("%.4g ± %.2g", v, err[q]) : sprintf("%.4g", v)
    printf "| %s | %s | %s | %s | %s | %s |\n", q, shown, paper[q], t, verdict, src[q]
  }
}
