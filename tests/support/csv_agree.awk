# Two CSV series row by row (header skipped): each value within
# rel x its column's largest magnitude + floor x the largest value of the
# first file after its first two columns (step, time); the same row count.
#   awk -F, -v rel=1e-6 -v floor=1e-15 -v name=LABEL -f csv_agree.awk A.csv B.csv
# Exit 1 (with a line naming the first difference) when they differ.
FNR == 1 { next }
NR == FNR {
  for (k = 1; k <= NF; k++) {
    a[FNR, k] = $k
    v = $k < 0 ? -$k : $k
    if (v > big[k]) big[k] = v
    if (k > 2 && v > all) all = v
  }
  rows = FNR
  next
}
{
  for (k = 1; k <= NF; k++) {
    d = $k - a[FNR, k]
    d = d < 0 ? -d : d
    if (d > rel * big[k] + floor * all) {
      printf "%s: row %d column %d: %s vs %s\n", name, FNR, k, $k, a[FNR, k]
      bad = 1
      exit 1
    }
  }
  seen = FNR
}
END { if (!bad && seen != rows) { printf "%s: %d rows, against %d\n", name, seen, rows; exit 1 } }
