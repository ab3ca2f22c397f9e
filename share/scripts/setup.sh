#!/usr/bin/env bash
# One entry point for a fresh Debian bookworm machine (run as root):
#   share/scripts/setup.sh demo   install, build, run SLAM on a generated sequence, print its error
#   share/scripts/setup.sh test   install, build, run the test suite (unit + integration)
#   share/scripts/setup.sh sanitize  install, build the sanitizer set with ASan + UBSan
#                                 (build-asan), run it under them
#   share/scripts/setup.sh fuzz   install, build the libFuzzer targets with clang (build-fuzz),
#                                 run each for ROISLAM_FUZZ_SECONDS (ctest -L fuzz)
#   share/scripts/setup.sh ci     test, sanitize, fuzz (what .ci/run runs), with timings
# Environment: BUILD_DIR (default build), JOBS (default nproc),
#              ROISLAM_TEST_LABELS (ctest label regex, default "unit|integration"),
#              ROISLAM_FUZZ_SECONDS (default 60),
#              ROISLAM_SANITIZE_SET (all: every unit + integration test under the
#              sanitizers instead of the set), ROISLAM_SANITIZE_EXCLUDE (ctest -E regex
#              for the sanitizer run).
# CI's budget (.ci/run, fresh 2-core machine, 90 min, aim <= 60): README
# "Reliability" has the measured cold time of each stage (wall and CPU) and
# what the sanitizer set covers and why.
set -euo pipefail
mode="${1:-}"
case "$mode" in
  demo | test | sanitize | fuzz | ci) ;;
  *)
    echo "usage: $0 demo|test|sanitize|fuzz|ci" >&2
    exit 2
    ;;
esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
build="${BUILD_DIR:-build}"
jobs="${JOBS:-$(nproc)}"
labels="${ROISLAM_TEST_LABELS:-unit|integration}"
shared="$root/../shared/data"

bash share/scripts/install-deps.sh

# timed LABEL CMD...: runs CMD, then prints its wall time and the CPU time of
# it and its children (user + sys; on an idle 2-core machine a -j2 build has
# wall ~ CPU / 2, on a shared one the CPU figure is the one to compare).
timed() {
  local label="$1" TIMEFORMAT
  shift
  TIMEFORMAT="setup.sh: $label: wall %0R s, user %0U s, sys %0S s"
  time "$@"
}

if [ "$mode" = ci ]; then
  # Each stage timed; the first failure stops the run (set -e).
  timed "ci, all stages" bash -c 'for stage in test sanitize fuzz; do
      TIMEFORMAT="setup.sh: ci, stage $stage: wall %0R s, user %0U s, sys %0S s"
      time bash "$0" "$stage" || exit 1
    done' "$0"
  exit 0
fi

if [ "$mode" = sanitize ]; then
  # The sanitizer set (tests/CMakeLists.txt, ROISLAM_SANITIZER_SET, says which
  # tests and why) with AddressSanitizer and UndefinedBehaviorSanitizer: only
  # those tests, the libraries and apps they need and the synthetic fixture
  # are built (target sanitizer_set), at -O1 (AddressSanitizer's advice for
  # usable speed; cheaper to compile than Release's -O3). Cold, that build
  # measured 1884 s of CPU (user + sys) against 1808 s for the whole Release
  # build: instrumented code costs more to compile, hence the set. Any report
  # fails the test. Leaks inside third-party libraries are suppressed
  # (share/scripts/lsan.supp says which). ROISLAM_SANITIZE_SET=all builds
  # everything and runs the unit and integration tests instead.
  asan="${BUILD_DIR_ASAN:-build-asan}"
  cmake -S . -B "$asan" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
    -DROISLAM_SANITIZE=address,undefined -DROISLAM_BUILD_BENCHMARKS=OFF -DROISLAM_WITH_GUI=OFF \
    -DROISLAM_SHARED_DATA_DIR="$shared"
  if [ "${ROISLAM_SANITIZE_SET:-}" = all ]; then
    timed "sanitize, build" cmake --build "$asan" -j"$jobs"
    select=(-L "$labels")
  else
    timed "sanitize, build" cmake --build "$asan" --target sanitizer_set -j"$jobs"
    select=(-L sanitize)
  fi
  # allocator_may_return_null: an impossible malloc returns null as without
  # ASan, so MRPT's allocator (MrptAlignedMalloc.cpp) throws std::bad_alloc.
  export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1:check_initialization_order=1"
  export LSAN_OPTIONS="suppressions=$root/share/scripts/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$root/share/scripts/ubsan.supp"
  exclude=()
  [ -n "${ROISLAM_SANITIZE_EXCLUDE:-}" ] && exclude=(-E "$ROISLAM_SANITIZE_EXCLUDE")
  timed "sanitize, tests" ctest --test-dir "$asan" "${select[@]}" "${exclude[@]}" -j"$jobs" \
    --output-on-failure --timeout 1800
  exit $?
fi

if [ "$mode" = fuzz ]; then
  # clang-14 and libclang-rt-14-dev come from install-deps.sh. Only the fuzz
  # targets and the libraries they need are built.
  fz="${BUILD_DIR_FUZZ:-build-fuzz}"
  cmake -S . -B "$fz" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++-14 \
    -DROISLAM_BUILD_FUZZERS=ON -DROISLAM_BUILD_BENCHMARKS=OFF -DROISLAM_SHARED_DATA_DIR="$shared" \
    -DROISLAM_FUZZ_SECONDS="${ROISLAM_FUZZ_SECONDS:-60}"
  timed "fuzz, build" cmake --build "$fz" --target fuzzers -j"$jobs"
  timed "fuzz, run" ctest --test-dir "$fz" -L fuzz -j"$jobs" --output-on-failure
  exit $?
fi

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
timed "$mode, build" cmake --build "$build" -j"$jobs"

if [ "$mode" = test ]; then
  timed "test, tests" ctest --test-dir "$build" -L "$labels" -j"$jobs" --output-on-failure \
    --timeout 900
  exit $?
fi

# Demo: a synthetic textured loop generated here (no download), SLAM with the
# big-ROI front end, then the trajectory error against the generated ground truth.
out="$root/out/demo"
rm -rf "$out"
mkdir -p "$out"
"$build/apps/rgbd-simul/rgbd-simul" --output "$out/sequence" --scene textured --frames 90 --seed 1
"$build/apps/tum2rawlog/tum2rawlog" --input "$out/sequence" --output "$out/sequence.rawlog"
rawlog-edit --info -i "$out/sequence.rawlog" | tail -n 5 || true
"$build/apps/roi-graphslam/roi-graphslam" --ini config/roi_big.ini --input "$out/sequence.rawlog" \
  --output-dir "$out/slam" --feature orb
"$build/apps/roi-eval/roi-eval" --gt "$out/sequence/groundtruth.txt" --est "$out/slam/trajectory.txt"
echo "demo outputs in $out/slam: trajectory.txt, graph.graph, summary.json;"
echo "  pictures (floor at the bottom, the ground truth's frame): snapshot.png, scene.3Dscene"
echo "  (SceneViewer3D), map.bt; error plots: ate.png, errors.png"
