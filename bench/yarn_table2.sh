#!/usr/bin/env bash
# The 250-fibre twisted yarn of Table 2 (paper section 5.3, samples/yarn_table2.json) at full
# size: the whole procedure (equilibrium, tension, twist, settling, 150 crush steps), then its
# figures for docs/RESULTS.md ("The 250-fibre yarn (Table 2)"):
#   - per step: increments, Newton iterations per increment (mean, max), cutbacks, wall time;
#     contact elements and active ones at the step's end; the run's wall time and peak memory
#     (GNU time's maximum resident set);
#   - the median cross-section (z = 0.25 mm) at the start, after the equilibrium, after the twist
#     and at four stages of the crush (fibra section: PNGs and outlines), the fibres' spacing and
#     density at the periphery against the centre on each (bench/yarn_density.py);
#   - with OVERLAP=1, the fibres' true overlap at the end from the centrelines
#     (bench/centreline_overlap.py; over 10 minutes at this size);
#   - the crushing force against the travel (the scene's plots, drawn by fibra at the end).
# usage: bash bench/yarn_table2.sh [OUT_DIR [THREADS]]   (default out/yarn_table2, 2 threads)
# A run stopped on the way goes on with `fibra run --resume OUT_DIR`; this script's second part
# then reads what is there: FIGURES_ONLY=1 bash bench/yarn_table2.sh OUT_DIR.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-out/yarn_table2}
threads=${2:-2}
fibra=${FIBRA:-$root/build/fibra}

if [ -z "${FIGURES_ONLY:-}" ]; then
  mkdir -p "$(dirname "$out")"
  /usr/bin/time -v -o "$out.time" "$fibra" run "$root/samples/yarn_table2.json" --out "$out" \
    --threads "$threads" || echo "fibra run ended with status $? (figures of what converged follow)"
  grep -E "Maximum resident|Elapsed" "$out.time" || true
fi

history="$out/history.csv"
[ -f "$history" ] || history="$out/history.csv.part"
python3 - "$history" <<'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
names = ['equilibrium', 'tension', 'twist', 'settle', 'crush']
print('step         increments  iterations/increment (mean, max)  cutbacks  wall (s)  elements  active')
for s in sorted({int(r['step']) for r in rows}):
    rs = [r for r in rows if int(r['step']) == s]
    its = [int(r['total_iterations']) for r in rs]
    wall = sum(float(r['wall_s']) for r in rs)
    cut = sum(int(r['cutbacks']) for r in rs)
    last = rs[-1]
    print(f"{names[s - 1]:12} {len(rs):10}  {sum(its) / len(its):8.1f} {max(its):6}"
          f"{'':20}{cut:8}  {wall:8.0f}  {last['contact.elements']:>8}  {last['contact.active']:>6}")
print(f"all: {len(rows)} increments, {sum(int(r['total_iterations']) for r in rows)} Newton iterations, "
      f"{sum(float(r['wall_s']) for r in rows):.0f} s")
crush = [r for r in rows if int(r['step']) == 5]
if crush:
    print('crush: travel of each cylinder (mm), crushing force tool.top.fy (N), every 10th increment')
    for r in crush[9::10]:
        print(f"  {-float(r['tool.top.uy']):.4f}  {float(r['tool.top.fy']):.5f}")
# frames: one per converged increment, frame k after row k (frame 0 the start)
ends = {int(r['step']): i + 1 for i, r in enumerate(rows)}
frames = [0] + [ends[s] for s in (1, 3) if s in ends]
if crush:
    first = ends.get(4, 0)
    frames += sorted({first + max(1, round(len(crush) * q / 4)) for q in (1, 2, 3, 4)})
print('frames:', ','.join(map(str, frames)))
open(sys.argv[1] + '.frames', 'w').write(','.join(map(str, frames)))
EOF
frames=$(cat "$history.frames")
rm -f "$history.frames"
"$fibra" section "$out" --plane z=0.25 --frame "$frames" --out "$out/section.png" \
  --title '250-fibre yarn, median cross-section'
python3 "$root/bench/yarn_density.py" "$out"/section_*.dat
# all pairs of 250 fibres in Python: more than 10 minutes, so only when asked (OVERLAP=1)
if [ -n "${OVERLAP:-}" ]; then
  python3 "$root/bench/centreline_overlap.py" "$out/final_state.csv" --radius 0.01 --pmax 1e-4
fi
