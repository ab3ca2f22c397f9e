#!/usr/bin/env bash
# One entry point for a fresh Debian bookworm machine (run as root):
#   share/scripts/setup.sh demo   install, build, run SLAM on a generated sequence, print its error
#   share/scripts/setup.sh test   install, build, run the test suite (unit + integration)
# Environment: BUILD_DIR (default build), JOBS (default nproc),
#              ROISLAM_TEST_LABELS (ctest label regex, default "unit|integration").
set -euo pipefail
mode="${1:-}"
case "$mode" in
  demo | test) ;;
  *)
    echo "usage: $0 demo|test" >&2
    exit 2
    ;;
esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
build="${BUILD_DIR:-build}"
jobs="${JOBS:-$(nproc)}"

bash share/scripts/install-deps.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" -j"$jobs"

if [ "$mode" = test ]; then
  labels="${ROISLAM_TEST_LABELS:-unit|integration}"
  ctest --test-dir "$build" -L "$labels" -j"$jobs" --output-on-failure --timeout 900
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
