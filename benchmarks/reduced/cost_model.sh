#!/usr/bin/env bash
# The runs the reduced model's cost model is fitted to
# (source/stage/cost_estimate.cc, estimate_reduced_cost; doc/reduced-model.md
# §4): the seed stage on 2 ranks with its coarse model and contacts varied
# (one and two discs, one and both flanks, 2 and 4 axial slices, 1 and 2 mm
# far field; 2D with finer flanks or contact zones). Prints per run the
# coarse DoFs, the contacts, the condensation's time ("reduced: solves"),
# the peak memory summed over the ranks and the whole command's time.
# Usage (from the repository, after the build; idle machine):
#   bash benchmarks/reduced/cost_model.sh [WORKDIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
exe=$root/build/cycloid-contact
work=${1:-/tmp/reduced-cost-model}
mkdir -p "$work" && cd "$work"
flags=(); [ "$(id -u)" -eq 0 ] && flags+=(--allow-run-as-root)
echo "case,dofs,contacts,condensation_s,peak_memory_MB,wall_s"
run() {
  name=$1; shift
  printf '%s\n' "include $root/prm/seed-case.prm" "set Output directory = out/$name" "$@" >"$name.prm"
  start=$(date +%s.%N)
  mpirun "${flags[@]}" -np 2 "$exe" "$name.prm" >"$name.log" 2>&1
  wall=$(echo "$(date +%s.%N) - $start" | bc)
  dofs=$(sed -n 's/.*coarse model: \([0-9]*\) DoFs.*/\1/p' "$name.log")
  contacts=$(sed -n 's/^  \([0-9]*\) contacts on .*/\1/p' "$name.log")
  solves=$(sed -n 's/.*reduced: solves \([0-9.e+-]*\) s.*/\1/p' "$name.log")
  memory=$(/usr/bin/python3 -c "import csv,sys; print(next(csv.DictReader(open(sys.argv[1])))['peak_memory_MB'])" "out/$name/stiffness.csv")
  echo "$name,$dofs,$contacts,$solves,$memory,$wall"
}
two_d=("subsection Scene" "set Dimension = 2" "set Number of discs = 1" "end")
cycle=("subsection Loading" "set Torque cycle = true" "set Torque cycle steps = 8" "end")
run 3d-seed
run 3d-both-flanks "${cycle[@]}"
run 3d-4-slices "subsection Reduced" "set Axial slices per disc = 4" "end"
run 3d-one-disc "subsection Scene" "set Number of discs = 1" "end"
run 3d-1mm-far-field "subsection Mesh" "set Flank element size = 1" "set Pin element size = 1" "end"
run 2d "${two_d[@]}"
run 2d-both-flanks "${two_d[@]}" "${cycle[@]}"
run 2d-fine-flanks "${two_d[@]}" "subsection Mesh" "set Flank element size = 0.5" "set Pin element size = 0.5" "end"
run 2d-fine-contacts "${two_d[@]}" "subsection Mesh" "set Contact element size = 0.125" "end"
