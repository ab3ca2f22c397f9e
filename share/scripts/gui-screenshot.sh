#!/usr/bin/env bash
# Takes the README's picture of the live view: runs roi-graphslam --gui on a
# sequence under a private Xvfb (with-xvfb.sh) and saves the window, as it
# is at the end of the run (whole map, last image), as a PNG.
#   gui-screenshot.sh SEQUENCE [OUTPUT_PNG] [INI]
# OUTPUT_PNG defaults to share/doc/live-view.png, INI to config/roi_small.ini;
# BUILD_DIR (default build) is where roi-graphslam was built. The run's other
# outputs go to a temporary folder, removed afterwards.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
if [ "$#" -lt 1 ] || [ "$#" -gt 3 ]; then
  echo "usage: gui-screenshot.sh SEQUENCE [OUTPUT_PNG] [INI]" >&2
  exit 2
fi
seq=$1
png=${2:-$root/share/doc/live-view.png}
ini=${3:-$root/config/roi_small.ini}
app=${BUILD_DIR:-$root/build}/apps/roi-graphslam/roi-graphslam
if [ ! -x "$app" ]; then
  echo "gui-screenshot.sh: $app not built (set BUILD_DIR)" >&2
  exit 1
fi
out=$(mktemp -d -t gui-screenshot.XXXXXX)
trap 'rm -rf "$out"' EXIT
mkdir -p "$(dirname "$png")"
"$root/share/scripts/with-xvfb.sh" "$app" --ini "$ini" --input "$seq" --output-dir "$out" \
  --no-snapshot --gui-screenshot "$png" >/dev/null
echo "gui-screenshot.sh: wrote $png"
