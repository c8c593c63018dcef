# Shared by the scripts that drive the window with real input (gui_input.sh, gui_play.sh):
# failing with what the window last said, and waiting for a condition while the program lives.
# The sourcing script sets case_name, widgets (the PERIFLEX_GUI_WIDGETS file), log (the
# program's standard error) and pid (the program, once started).

# prints the reason, the window's last state and log, stops the program, exits 1
fail() {
  echo "FAIL ($case_name): $*" >&2
  [[ -f "$widgets" ]] && sed 's/^/  widgets: /' "$widgets" >&2
  [[ -f "$log" ]] && tail -n 20 "$log" | sed 's/^/  log: /' >&2
  if [[ -n "$pid" ]] && kill -0 "$pid" 2>/dev/null; then kill -9 "$pid" 2>/dev/null; fi
  exit 1
}

# waits up to SECONDS for a shell condition to hold; fails with MESSAGE otherwise
wait_until() {
  local seconds=$1 message=$2
  shift 2
  local end=$((SECONDS + seconds))
  until eval "$*"; do
    kill -0 "$pid" 2>/dev/null || fail "the program ended early while waiting for: $message"
    ((SECONDS < end)) || fail "timed out after ${seconds}s waiting for: $message (is the window frozen?)"
    sleep 0.1
  done
}
