#!/usr/bin/env bash
# Summary of a fidus run from its CSV output, for the stress scripts:
# steps, smallest gap, largest Uzawa and FGMRES counts per step, whether any
# value is NaN or inf, and the largest |U| and |omega| of any particle.
# Usage: contrib/benchmarks/summarize_run.sh <output directory>
set -euo pipefail
out="$1"
# rigid_velocity_change is NaN by definition after a single Uzawa iteration
# (README), so that column is not counted.
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "rigid_velocity_change") skip = i }
         NR > 1 { steps++; if ($9 < g || NR == 2) g = $9; if ($6 > u) u = $6; if ($7 > l) l = $7;
                  for (i = 1; i <= NF; i++) if (i != skip && tolower($i) ~ /nan|inf/) bad = 1 }
         END { printf "steps %d, smallest gap %.3e, max Uzawa %d, max FGMRES per step %d, NaN %s\n",
               steps, g, u, l, bad ? "yes" : "no" }' "$out/statistics.csv"
awk -F, 'NR > 1 { s = sqrt($7 * $7 + $8 * $8 + $9 * $9); if (s > u) u = s;
                  w = sqrt($10 * $10 + $11 * $11 + $12 * $12); if (w > o) o = w;
                  for (i = 1; i <= NF; i++) if (tolower($i) ~ /nan|inf/) bad = 1 }
         END { printf "max |U| %.3g, max |omega| %.3g, NaN in particles.csv %s\n",
               u, o, bad ? "yes" : "no" }' "$out/particles.csv"
