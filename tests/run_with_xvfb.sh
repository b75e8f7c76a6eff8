#!/usr/bin/env bash
# Runs a command on a fresh Xvfb display. The server picks a free display
# number itself and writes it to us once it accepts connections (-displayfd),
# so there is no race on lock files (as with xvfb-run -a under load).
# usage: run_with_xvfb.sh COMMAND [ARGS...]
set -u
tmp=$(mktemp -d)
fifo="$tmp/displayfd"
mkfifo "$fifo"
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3>"$fifo" 2>"$tmp/xvfb.log" &
server=$!
display=""
if ! read -r -t 30 display < "$fifo" || [ -z "$display" ]; then
    echo "run_with_xvfb: Xvfb did not start:" >&2
    cat "$tmp/xvfb.log" >&2
    kill "$server" 2>/dev/null
    rm -rf "$tmp"
    exit 1
fi
DISPLAY=":$display" "$@"
rc=$?
kill "$server" 2>/dev/null
wait "$server" 2>/dev/null
rm -rf "$tmp"
exit $rc
