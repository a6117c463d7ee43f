#!/bin/sh
# README's C++ quick start is examples/quickstart/main.cpp word for word (the package consumer
# test builds and runs that file against the installed package).
#   readme_snippet.sh SOURCE_DIR
src=$1
awk '/^<!-- examples\/quickstart\/main.cpp -->$/ { marker = 1; next }
     marker && /^```cpp$/ { inside = 1; next }
     inside && /^```$/ { exit }
     inside { print }' "$src/README.md" >"${TMPDIR:-/tmp}/readme_quickstart.cpp"
if diff -u "$src/examples/quickstart/main.cpp" "${TMPDIR:-/tmp}/readme_quickstart.cpp"; then
  echo "README quick start matches examples/quickstart/main.cpp"
else
  echo "README's C++ quick start differs from examples/quickstart/main.cpp"; exit 1
fi
