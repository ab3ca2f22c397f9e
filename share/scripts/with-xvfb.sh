#!/usr/bin/env bash
# Runs a command on a private Xvfb display (1280x1024, 24 bits) and stops the
# server afterwards; exits with the command's status. The server picks its
# own display number (-displayfd), so parallel runs never collide:
# `xvfb-run -a` races for the number, and 2 of 4 parallel runs measured here
# failed with "Unable to initialize GTK+". Used by the live-view tests
# (tests/gui) and share/scripts/gui-screenshot.sh.
set -euo pipefail
if [ "$#" -eq 0 ]; then
  echo "usage: with-xvfb.sh COMMAND [ARGS...]" >&2
  exit 2
fi
if ! command -v Xvfb >/dev/null 2>&1; then
  echo "with-xvfb.sh: Xvfb not found (apt-get install xvfb)" >&2
  exit 1
fi
dir=$(mktemp -d -t with-xvfb.XXXXXX)
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$dir/display" >"$dir/log" 2>&1 &
xpid=$!
cleanup() {
  kill "$xpid" 2>/dev/null || true
  wait "$xpid" 2>/dev/null || true
  rm -rf "$dir"
}
trap cleanup EXIT
for _ in $(seq 100); do
  [ -s "$dir/display" ] && break
  if ! kill -0 "$xpid" 2>/dev/null; then
    echo "with-xvfb.sh: Xvfb failed to start: $(tail -n 1 "$dir/log")" >&2
    exit 1
  fi
  sleep 0.1
done
if [ ! -s "$dir/display" ]; then
  echo "with-xvfb.sh: Xvfb gave no display within 10 s" >&2
  exit 1
fi
set +e
DISPLAY=":$(head -n 1 "$dir/display")" "$@"
rc=$?
set -e
exit "$rc"
