#!/usr/bin/env bash
# The run that matters on a real GPU, within about 8 minutes on one modern GPU: info, the occupancy
# study, register vs local sorts, the Knowles 2014 resolves and Brüll's approximate OIT at the papers'
# sizes; then the report page. Results go to results/<driver>/ (the `driver` column, e.g. nvidia-h200).
#
#   scripts/gpu-run.sh [--smoke] [--driver NAME] [--out DIR]
#
#   --smoke        the same steps at tiny sizes, to check the script and a driver in a minute or two
#   --driver NAME  passed to oitbench (default, llvmpipe, zink, egl-device-N; see: oitbench info --drivers)
#   --out DIR      write here instead of results/<driver>/ (results/<driver>-smoke/ with --smoke)
#
# The steps (GPU sizes; --smoke in brackets):
#   info           oitbench info and info --drivers (info.txt)
#   device         oitbench info --backend egl-device --device auto: the device it picks (device.txt)
#   occupancy      dynamic and unrolled, 800x600, 64 draws, sizes 1-256        [64x48, 4 draws, 1 33]
#   sort           800x800, n 8-32, both memories, every sort (fragment pass)  [32x32, n 8, 3 sorts]
#   knowles2014    1920x1080, planes and hairball fwd/rev, the engine grid V1-V3: BASE-IS, BASE-RBS-L,
#                  BMA-IS, BMA-RBS-L, BMA-AUTO, CS-RBS-L, blocks of 32          [64x64, the small scenes]
#   bruell2018-approx  the preset at 1920x1080                                 [48x48]
#   report         scripts/report.py OUT -o OUT/report
# Each step's rows are in OUT/presets/STEP.csv (and STEP_raw.csv), with the preset column naming the
# paper preset, so scripts/tables.py puts them beside the papers' tables. At the end, the time account
# ("gpu-run.sh: time: ..."): each step's shares (timed samples, compile, warm-up, reference+validation,
# scene, other), all steps', and what their cases leave of the script's own wall time. --smoke then
# projects the full run's wall time on a GPU ("gpu-run.sh: projection: ..."; docs/measurement.md).
#
# OITBENCH=path/to/oitbench runs that binary (default: build/oitbench beside this script's folder, or
# bin/oitbench in an unpacked bundle). Exit codes: 0 every step ran (rows may still be invalid: the
# summary says how many); 1 a step failed (the others still ran); 2 usage error; 130 interrupted.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; }

smoke=0
driver=default
out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --smoke) smoke=1 ;;
    --driver) [ $# -ge 2 ] || { echo "gpu-run.sh: --driver needs a name" >&2; exit 2; }; driver=$2; shift ;;
    --out) [ $# -ge 2 ] || { echo "gpu-run.sh: --out needs a folder" >&2; exit 2; }; out=$2; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "gpu-run.sh: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
  shift
done

exe=${OITBENCH:-}
if [ -z "$exe" ]; then
  for c in "$here/../build/oitbench" "$here/../../../bin/oitbench" "$here/../bin/oitbench"; do
    [ -x "$c" ] && { exe=$c; break; }
  done
fi
[ -n "$exe" ] && [ -x "$exe" ] || { echo "gpu-run.sh: no oitbench binary (build it, or set OITBENCH=path)" >&2; exit 2; }
PYTHON=/usr/bin/python3
[ -x "$PYTHON" ] || PYTHON=$(command -v python3 || true)

info=$("$exe" info --driver "$driver" 2>&1) || { echo "gpu-run.sh: no GL context on driver '$driver':" >&2; echo "$info" >&2; exit 1; }
slug=$(printf '%s\n' "$info" | awk -F': *' '/^driver:/ { split($2, a, " "); print a[1]; exit }')
[ -n "$slug" ] || slug=unknown
if [ -z "$out" ]; then
  out="$here/../results/$slug"
  [ $smoke -eq 1 ] && out="$out-smoke"
fi
mkdir -p "$out/presets" || exit 1
echo "gpu-run.sh: $(printf '%s\n' "$info" | awk -F': *' '/^GL_RENDERER:/ { print $2; exit }') -> $out"

stopped=0
trap 'stopped=1' INT TERM
failed=()
run_step() {  # NAME PRESET_NAME oitbench-run-arguments...
  local name=$1 preset=$2
  shift 2
  [ $stopped -eq 1 ] && return
  local csv="$out/presets/$name.csv" raw="$out/presets/${name}_raw.csv"
  rm -f "$csv" "$raw"
  local t0=$SECONDS
  "$exe" run --driver "$driver" --preset-name "$preset" --out "$csv" --raw "$raw" "$@"
  local rc=$?
  echo "gpu-run.sh: $name: exit $rc in $((SECONDS - t0)) s"
  [ $rc -eq 130 ] && stopped=1
  [ $rc -ne 0 ] && [ $rc -ne 130 ] && failed+=("$name (exit $rc)")
}

{
  printf '%s\n\n' "$info"
  "$exe" info --drivers 2>&1
} >"$out/info.txt"

# Which EGL device --device auto picks under this scheduler binding (docs/ci.md "Device selection"):
# untestable without a GPU, so every GPU run records it (device.txt; a failure here fails nothing else).
{
  env | grep -E '^(CUDA_VISIBLE_DEVICES|SLURM_STEP_GPUS|SLURM_JOB_GPUS|GPU_DEVICE_ORDINAL)=' || echo "(no scheduler GPU variables)"
  "$exe" info --backend egl-device --device auto 2>&1 || echo "exit $?"
} >"$out/device.txt"
echo "gpu-run.sh: --device auto: $(grep -m1 -- '--device auto ->' "$out/device.txt" || grep -m1 -- '--device' "$out/device.txt")"

techniques=BASE-IS,BASE-RBS-L,BMA-IS,BMA-RBS-L,BMA-AUTO,CS-RBS-L
steps="occupancy sort knowles2014 knowles2014-engine-grid bruell2018-approx"
full_step() {  # STEP: its preset name and its oitbench-run arguments at GPU sizes (preset, args)
  case "$1" in
    occupancy) preset=gpu-run-occupancy
      args=(occupancy --set variant=dynamic,unrolled --set size=1,2,4,8,16,24,32,33,48,64,96,128,192,256
        --set draws=64 --resolution 800x600 --reps 5 --warmup 1) ;;
    sort) preset=gpu-run-sort
      args=(sort --set n=8,12,16,20,24,28,32 --set memory=local,registers --set stage=fragment
        --resolution 800x800 --reps 5 --warmup 1) ;;
    knowles2014) preset=knowles2014
      args=(oit --set scene=planes,hairball --set view=fwd,rev --set technique=$techniques --set block=32
        --resolution 1920x1080 --reps 5 --warmup 1) ;;
    knowles2014-engine-grid) preset=knowles2014
      args=(oit --set scene=engine-grid --set view=V1,V2,V3 --set technique=$techniques --set block=32
        --resolution 1920x1080 --reps 5 --warmup 1) ;;
    bruell2018-approx) preset=bruell2018-approx
      args=(--preset bruell2018-approx --resolution 1920x1080 --reps 5 --warmup 1) ;;
  esac
}
if [ $smoke -eq 1 ]; then
  run_step occupancy gpu-run-occupancy occupancy --set variant=dynamic,unrolled --set size=1,33 --set draws=4 \
    --resolution 64x48 --reps 2 --warmup 1
  run_step sort gpu-run-sort sort --set variant=insertion-naive,insertion-v2,rbs --set n=8 --set memory=local,registers \
    --set stage=fragment --resolution 32x32 --reps 2 --warmup 1
  run_step knowles2014 knowles2014 oit --set scene=planes,hairball --set view=fwd,rev --set detail=small \
    --set technique=$techniques --set block=32 --resolution 64x64 --reps 2 --warmup 1
  run_step knowles2014-engine-grid knowles2014 oit --set scene=engine-grid --set view=V1 --set detail=small \
    --set technique=BASE-IS,BMA-RBS-L --set block=32 --resolution 64x64 --reps 2 --warmup 1
  run_step bruell2018-approx bruell2018-approx --preset bruell2018-approx --resolution 48x48 --reps 2 --warmup 1
else
  for step in $steps; do
    full_step "$step"
    run_step "$step" "$preset" "${args[@]}"
  done
fi

if [ $stopped -eq 0 ] && [ -n "$PYTHON" ] && [ -f "$here/report.py" ]; then
  "$PYTHON" "$here/report.py" "$out" -o "$out/report" >/dev/null || failed+=("report (exit $?)")
fi
# One line per step: how many cases ended how.
for f in "$out"/presets/*.csv; do
  case "$f" in *_raw.csv) continue ;; esac
  [ -f "$f" ] || continue
  awk -F, -v name="$(basename "$f" .csv)" '
    NR == 1 { for (i = 1; i <= NF; i++) { if ($i == "status") s = i; if ($i == "pass") p = i }; next }
    $p == "total" { n[$s]++ }
    END { line = ""; for (k in n) line = line " " n[k] " " k; print "gpu-run.sh: " name ":" line }' "$f"
done
# Where the time went (docs/measurement.md "Where a run's time goes"): per step and in all, and what the
# steps' cases leave of the script's own time.
csvs=()
for f in "$out"/presets/*.csv; do
  case "$f" in *_raw.csv) ;; *) [ -f "$f" ] && csvs+=("$f") ;; esac
done
if [ -n "$PYTHON" ] && [ -d "$here/oitbench" ] && [ ${#csvs[@]} -gt 0 ]; then
  PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}" "$PYTHON" -c 'import sys
from oitbench import timeaccount
print("\n".join(timeaccount.step_lines(sys.argv[2:], float(sys.argv[1]))))' "$SECONDS" "${csvs[@]}"
fi
# --smoke: what the full run would take on a GPU (scripts/oitbench/gpuprojection.py): its cases from
# `oitbench run --dry-run` at GPU sizes, each case's time outside its samples as measured here, its
# samples from the papers' GPU timings.
if [ $smoke -eq 1 ] && [ $stopped -eq 0 ] && [ -n "$PYTHON" ] && [ -d "$here/oitbench" ] && [ ${#csvs[@]} -gt 0 ]; then
  plans=()
  for step in $steps; do
    full_step "$step"
    "$exe" run --dry-run --driver "$driver" "${args[@]}" >"$out/presets/$step.plan" 2>/dev/null &&
      plans+=("$out/presets/$step.plan")
  done
  PYTHONPATH="$here${PYTHONPATH:+:$PYTHONPATH}" "$PYTHON" -c 'import os, sys
from oitbench import gpuprojection as gp
plans = {}
for path in sys.argv[2:]:
    with open(path, encoding="utf-8") as f:
        plans[os.path.splitext(os.path.basename(path))[0]] = gp.parse_plan(f.read())
csvs = [os.path.join(os.path.dirname(p), n + ".csv") for n, p in zip(plans, sys.argv[2:])]
print("\n".join(gp.projection_lines([c for c in csvs if os.path.isfile(c)], plans, sys.argv[1])))' \
    "$here/../results/published" "${plans[@]}"
fi
[ $stopped -eq 1 ] && { echo "gpu-run.sh: interrupted; finished rows are in $out/presets" >&2; exit 130; }
if [ ${#failed[@]} -gt 0 ]; then
  echo "gpu-run.sh: failed: ${failed[*]}" >&2
  exit 1
fi
echo "gpu-run.sh: done in $SECONDS s -> $out"
