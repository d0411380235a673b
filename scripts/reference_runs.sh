#!/usr/bin/env bash
# Regenerates the reference results on the embedded default (EGL surfaceless; Mesa llvmpipe where there
# is no GPU) in results/llvmpipe/: every preset in presets/*.json but the opt-in list (presets/NAME.csv
# and NAME_raw.csv), `oitbench info` (info.txt), a few rendered images (images/), the report page
# (report/index.html) and FINDINGS.md (scripts/findings.py: every measured number, generated from the CSVs).
#
#   scripts/reference_runs.sh                      build, every preset but the opt-in list, info, images,
#                                                  report, findings
#   scripts/reference_runs.sh --with-opt-in        the same and the opt-in list (OPT_IN below: oit-scale,
#                                                  splats, error-vs-time), timed apart
#   scripts/reference_runs.sh --only P1,P2         build, those presets (opt-in ones too), info, report,
#                                                  findings ("images" renders them)
#   scripts/reference_runs.sh --report-only        the report and the findings from the CSVs already there
#   scripts/reference_runs.sh --target-ci 3        repeat each case until its median's 95% interval is
#                                                  within +-3% (default here 5: the reference runs' bound;
#                                                  oitbench's own default is 3; a case that misses it says so)
#   scripts/reference_runs.sh --max-case-s 5 --max-reps 20
#                                                  the stopping rule's limits for every preset (oitbench's
#                                                  defaults, 10 s and 30, unless given): fewer minutes, more
#                                                  rows flagged outside the target (docs/scripts.md)
#   scripts/reference_runs.sh --driver zink --only default,knowles2014-quick,bruell2018-approx
#                                                  the same on another driver, into results/<its driver>/
#                                                  (zink over lavapipe: results/zink-lavapipe/)
#
# At the end it prints each preset's wall time, the total of the default list and of the opt-in list, and
# each list's time account (timed samples, compile, warm-up, reference+validation, scene, other) from its
# rows' phase columns. The CSVs of presets not run (the opt-in list's, by default) stay as they are, and
# the report and the findings still read them.
#
# OITBENCH=path/to/oitbench runs that binary instead of building build/oitbench; it reads presets,
# shaders and scenes from its own source tree unless OITBENCH_PRESETS / OITBENCH_SHADERS / OITBENCH_SCENES
# say otherwise. Exit codes: 0 everything ran; 1 a preset or a render failed (the others still ran and the
# report is still written) or the build failed; 2 usage error; 130 interrupted (Ctrl-C stops everything).
set -uo pipefail
cd "$(dirname "$0")/.."

OUT=""
driver=llvmpipe
PYTHON=/usr/bin/python3
RENDER_RESOLUTION=256x256
# name | render arguments: the papers' hard cases (the hairball back to front) with an exact resolve,
# BMA, one per-pixel-array approximation and a weighted blend, and one view of each other scene.
RENDERS=(
  "hairball-rev-BASE-IS|--scene hairball --view rev --technique BASE-IS"
  "hairball-rev-BMA-RBS-L|--scene hairball --view rev --technique BMA-RBS-L"
  "hairball-rev-MLAB-8|--scene hairball --view rev --technique MLAB --set nodes=8"
  "hairball-rev-WBOIT|--scene hairball --view rev --technique WBOIT"
  "planes-rev-BASE-IS|--scene planes --view rev --technique BASE-IS"
  "smoke-fwd-BMA-IS|--scene smoke --view fwd --technique BMA-IS"
  "engine-grid-V1-BASE-IMS|--scene engine-grid --view V1 --technique BASE-IMS"
)

# The opt-in list: presets whose cost is inherent in what they measure, run only with --with-opt-in or
# when --only names them (docs/scripts.md, "reference_runs.sh", has their measured times):
#   oit-scale      exact OIT at 1920x1080 up to 7680x4320 with pools of 100 M+ fragments: the allocations,
#                  captures and CPU references at those sizes (~12 min; 6 of them set-up alone);
#   splats         10^5, 10^6 and 4*10^6 splats beside the global sort: the analytic splat references of
#                  millions of splats (over half of its ~40 min is reference and validation);
#   error-vs-time  every approximate technique beside complete depth peeling (a frame of peeling the
#                  hairball, planes-deep or the engine grid takes minutes on llvmpipe), 141 cases (~19 min).
OPT_IN=(oit-scale splats error-vs-time)

usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; }

mapfile -t ALL_PRESETS < <(for f in presets/*.json; do basename "$f" .json; done)
only=""
with_opt_in=0
report_only=0
target_ci=5
limits=()  # --max-reps / --max-case-s, passed to every preset
while [ $# -gt 0 ]; do
  case "$1" in
    --only) [ $# -ge 2 ] || { echo "reference_runs.sh: --only needs PRESET[,PRESET...]" >&2; exit 2; }
            only=$2; shift 2 ;;
    --only=*) only=${1#--only=}; shift ;;
    --report-only) report_only=1; shift ;;
    --with-opt-in) with_opt_in=1; shift ;;
    --target-ci) [ $# -ge 2 ] || { echo "reference_runs.sh: --target-ci needs a percentage" >&2; exit 2; }
                 target_ci=$2; shift 2 ;;
    --max-reps|--max-case-s)
      [ $# -ge 2 ] || { echo "reference_runs.sh: $1 needs a number" >&2; exit 2; }
      pattern='^[0-9]+([.][0-9]+)?$'
      [ "$1" = --max-reps ] && pattern='^[0-9]+$'
      [[ $2 =~ $pattern ]] || { echo "reference_runs.sh: $1 needs a number, not '$2'" >&2; exit 2; }
      limits+=("$1" "$2"); shift 2 ;;
    --driver) [ $# -ge 2 ] || { echo "reference_runs.sh: --driver needs a name" >&2; exit 2; }
              driver=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    *) echo "reference_runs.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
  esac
done

is_opt_in() { local p; for p in "${OPT_IN[@]}"; do [ "$p" = "$1" ] && return 0; done; return 1; }
for name in "${OPT_IN[@]}"; do
  [ -f "presets/$name.json" ] || { echo "reference_runs.sh: the opt-in list names '$name', which is no preset" >&2; exit 2; }
done
if [ $with_opt_in -eq 1 ] && [ -n "$only" ]; then
  echo "reference_runs.sh: --with-opt-in runs every preset; with --only, name the opt-in presets (${OPT_IN[*]}) in --only instead" >&2
  exit 2
fi

# Every preset but the opt-in list, then (--with-opt-in) the opt-in list.
presets=()
for name in "${ALL_PRESETS[@]}"; do is_opt_in "$name" || presets+=("$name"); done
[ $with_opt_in -eq 1 ] && presets+=("${OPT_IN[@]}")
render_images=1
if [ -n "$only" ]; then
  presets=()
  render_images=0
  IFS=, read -r -a wanted <<< "$only"
  for name in "${wanted[@]}"; do
    if [ "$name" = images ]; then
      render_images=1
    elif [ -f "presets/$name.json" ]; then
      presets+=("$name")
    else
      echo "reference_runs.sh: no preset '$name'; presets: ${ALL_PRESETS[*]} (or 'images'; opt-in: ${OPT_IN[*]})" >&2
      exit 2
    fi
  done
fi

if [ -z "${OITBENCH:-}" ] && [ $report_only -eq 0 ]; then
  echo "[reference] build: scripts/build.sh"
  scripts/build.sh || { echo "reference_runs.sh: the build failed" >&2; exit 1; }
  OITBENCH=build/oitbench
fi
# results/<driver>/, named by the driver column the rows will carry (llvmpipe, zink-lavapipe, ...).
if [ "$driver" = llvmpipe ]; then
  OUT=results/llvmpipe
elif [ $report_only -eq 1 ]; then
  OUT=results/$driver
else
  slug=$("$OITBENCH" info --driver "$driver" 2>/dev/null | awk -F': *' '/^driver:/ { split($2, a, " "); print a[1]; exit }')
  [ -n "$slug" ] || { echo "reference_runs.sh: driver '$driver' gives no context (oitbench info --drivers)" >&2; exit 1; }
  OUT=results/$slug
fi

started=$SECONDS
say() { printf '[reference %s +%dm%02ds] %s\n' "$(date -u +%H:%M:%S)" $(((SECONDS - started) / 60)) \
  $(((SECONDS - started) % 60)) "$*"; }
trap 'echo; say "interrupted: stopping (the finished rows are in the CSVs)"; exit 130' INT
failed=()

write_report() {
  # The driver's A/B comparisons (scripts/ab_bench.sh writes results/ab-<driver>/) get a section of the page.
  local ab=()
  [ -d "results/ab-${OUT#results/}" ] && ab=(--ab "results/ab-${OUT#results/}")
  say "report: $PYTHON scripts/report.py $OUT ${ab[*]} -o $OUT/report"
  "$PYTHON" scripts/report.py "$OUT" "${ab[@]}" -o "$OUT/report"
  local rc=$?
  [ $rc -eq 0 ] || failed+=("report (exit $rc)")
  say "findings: $PYTHON scripts/findings.py $OUT -o $OUT/FINDINGS.md"
  "$PYTHON" scripts/findings.py "$OUT" -o "$OUT/FINDINGS.md"
  rc=$?
  [ $rc -eq 0 ] || failed+=("findings (exit $rc)")
}

finish() {
  if [ ${#failed[@]} -gt 0 ]; then
    say "done; failed: ${failed[*]}"
    exit 1
  fi
  say "done: $OUT/report/index.html"
  exit 0
}

if [ $report_only -eq 1 ]; then
  write_report
  finish
fi

[ -x "$OITBENCH" ] || { echo "reference_runs.sh: $OITBENCH is not an executable (OITBENCH=...)" >&2; exit 2; }

mkdir -p "$OUT/presets"
i=0
timed=()  # LIST PRESET SECONDS CSV, four words per preset run, for the time account at the end
for name in "${presets[@]}"; do
  i=$((i + 1))
  csv=$OUT/presets/$name.csv
  raw=$OUT/presets/${name}_raw.csv
  rm -f "$csv" "$raw"  # --out appends to a file with the same header: start from nothing
  say "preset $i/${#presets[@]}: $name"
  t0=$SECONDS
  "$OITBENCH" run --preset "$name" --driver "$driver" --target-ci "$target_ci" "${limits[@]}" --out "$csv" --raw "$raw"
  rc=$?
  [ $rc -eq 130 ] && { say "interrupted during $name"; exit 130; }
  say "preset $name: exit $rc after $(((SECONDS - t0) / 60))m$(((SECONDS - t0) % 60))s"
  [ $rc -eq 0 ] || failed+=("$name (exit $rc)")
  list=default
  is_opt_in "$name" && list=opt-in
  timed+=("$list" "$name" "$((SECONDS - t0))" "$csv")
done
presets_s=$((SECONDS - started))

say "info: $OITBENCH info > $OUT/info.txt"
# The data folders it names relative to the repository (no machine's paths in a committed file).
"$OITBENCH" info --driver "$driver" | sed "s|$PWD/||g" > "$OUT/info.txt" || failed+=("info")

if [ $render_images -eq 1 ]; then
  rm -rf "$OUT/images"
  mkdir -p "$OUT/images"
  for entry in "${RENDERS[@]}"; do
    name=${entry%%|*}
    read -r -a render_args <<< "${entry#*|}"
    say "render $name ($RENDER_RESOLUTION)"
    "$OITBENCH" render "${render_args[@]}" --driver "$driver" --resolution "$RENDER_RESOLUTION" --out "$OUT/images/$name.png"
    rc=$?
    [ $rc -eq 130 ] && { say "interrupted during render $name"; exit 130; }
    [ $rc -eq 0 ] || failed+=("render $name (exit $rc)")
  done
  # The float images (.pfm, 0.75 MB each at 256x256) are not shown; `oitbench render` writes them again.
  rm -f "$OUT"/images/*.pfm
fi

write_report
# Where the time went (docs/measurement.md "Where a run's time goes"): per preset, per list.
if [ ${#timed[@]} -gt 0 ]; then
  say "time: the presets $((presets_s / 60))m$((presets_s % 60))s of the script's $(((SECONDS - started) / 60))m$(((SECONDS - started) % 60))s"
  PYTHONPATH="scripts${PYTHONPATH:+:$PYTHONPATH}" "$PYTHON" -c 'import sys
from oitbench import timeaccount
a = sys.argv[1:]
print("\n".join(timeaccount.list_lines([(a[i], a[i + 1], float(a[i + 2]), a[i + 3]) for i in range(0, len(a), 4)])))' \
    "${timed[@]}" || failed+=("time account")
fi
finish
