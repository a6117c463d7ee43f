#!/usr/bin/env bash
# Every option of every command has a description in its `fe COMMAND --help` list (CLI11 puts
# it at column 31, or on the next line when the option's name is longer).
# Usage: cli_help_describes_every_option.sh FE
set -euo pipefail
fe=$1
status=0
for command in info render view bench conformance capture replay bisect; do
  "$fe" "$command" --help | awk -v command="$command" '
    function flush() { if (pending != "") { missing = missing " " pending; pending = "" } }
    /^Options:/ { options = 1; next }
    options && /^$/ { flush(); options = 0; next }
    options && /^  -/ {
      flush()
      if (length($0) > 30 && substr($0, 31, 1) != " ") next
      pending = $1
      next
    }
    options && length($0) > 30 && substr($0, 1, 30) ~ /^ *$/ { pending = ""; next }
    END {
      flush()
      if (missing != "") { print "fe " command " --help: no description for" missing; exit 1 }
      print "fe " command " --help: every option described"
    }' || status=1
done
exit $status
