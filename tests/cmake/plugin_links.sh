#!/usr/bin/env bash
# touchcloud_check_plugin_links on a tiny tree (plugin_links/): configuring
# fails, naming the target and the folder, when a plugin links another
# plugin folder's library directly or through its own library, or when a
# library outside plugins/ does; it passes when nothing does, or a test does.
# Usage: plugin_links.sh CMAKE TOUCHCLOUD_CMAKE_DIR FIXTURE_DIR
set -euo pipefail
cmake=$1 modules=$2 fixture=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

configure() {  # OFFEND; prints cmake's output, returns its status
  "$cmake" -S "$fixture" -B "$work/$1" -DTOUCHCLOUD_CMAKE_DIR="$modules" -DOFFEND="$1" > "$work/$1.log" 2>&1
}
expect_pass() {
  if ! configure "$1"; then
    echo "OFFEND=$1: configuring failed, expected it to pass:" >&2; cat "$work/$1.log" >&2; failures=$((failures + 1))
  fi
}
expect_refusal() {  # OFFEND, text the message must hold
  if configure "$1"; then
    echo "OFFEND=$1: configuring passed, expected the check to refuse it" >&2; failures=$((failures + 1))
  elif ! tr -s ' \n' ' ' < "$work/$1.log" | grep -qF "$2"; then
    echo "OFFEND=$1: refused without naming '$2':" >&2; cat "$work/$1.log" >&2; failures=$((failures + 1))
  fi
}

expect_pass none
expect_pass test
expect_refusal plugin "touchcloud_pictures (plugins/pictures) links dots_lib, defined in plugins/dots"
expect_refusal indirect "touchcloud_pictures (plugins/pictures) links dots_lib, defined in plugins/dots"
expect_refusal library "shared_code (library) links dots_lib, defined in plugins/dots"
[ "$failures" -eq 0 ] && echo "plugin links: 2 trees pass, 3 refused as expected"
exit $(( failures > 0 ))
