#!/usr/bin/env bash
# Render the whole report page in headless Chromium and save a PNG, to check it really
# renders.  Needs Debian's chromium (`apt-get install -y chromium`).  Usage:
#   scripts/screenshot_report.sh results/report/index.html results/report/screenshot.png
# The page records its own height after load (data-height on <body>); a first pass reads
# it, the second takes a window that tall, so the screenshot is the whole page.
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
flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
  --disable-background-networking --disable-component-update --disable-sync
  --user-data-dir="$profile" --hide-scrollbars)
height=$("$browser" "${flags[@]}" --window-size=1280,1000 --virtual-time-budget=20000 \
  --dump-dom "file://$page" 2>/dev/null | grep -o 'data-height="[0-9]*"' | grep -o '[0-9]*' || true)
height=${height:-4000}
"$browser" "${flags[@]}" --window-size=1280,"$height" --screenshot="$out" "file://$page" 2>/dev/null
echo "screenshot: $out (1280 x $height px)"
