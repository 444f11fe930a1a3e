#!/usr/bin/env bash
# Render the report page in headless Chromium and save a PNG, to check it really renders.
# Needs Debian's chromium (`apt-get install -y chromium`).  Usage:
#   scripts/screenshot_report.sh results/report/index.html results/report/screenshot.png
set -euo pipefail
page=$(realpath "${1:-results/report/index.html}")
out=$(realpath -m "${2:-results/report/screenshot.png}")
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "chromium not found: apt-get install -y chromium" >&2
  exit 2
fi
profile=$(mktemp -d)
trap 'rm -rf "$profile"' EXIT
"$browser" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
  --disable-background-networking --disable-component-update --disable-sync \
  --user-data-dir="$profile" --hide-scrollbars --window-size=1280,4000 \
  --screenshot="$out" "file://$page" 2>/dev/null
echo "screenshot: $out"
