#!/usr/bin/env bash
# `comply plugin new` refuses a name that is not a C identifier, a non-empty output folder, a law
# without --lang and a C hardware backend, with exit code 2 and a message naming the problem, and
# writes nothing then.
# Usage: plugin_new_refuses_test.sh COMPLY WORKDIR
set -euo pipefail
comply=$1 work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work"
expect_refusal() {  # expect_refusal PATTERN ARGS...: exit 2, PATTERN on stderr
  local pattern=$1 status=0
  shift
  "$comply" plugin new "$@" 2>err.txt >/dev/null || status=$?
  if [ "$status" -ne 2 ] || ! grep -q "$pattern" err.txt; then
    echo "FAIL: plugin new $* returned $status:"; cat err.txt; exit 1
  fi
}
expect_refusal "not a C identifier" my-law --kind joint --lang c
expect_refusal "starts with a digit" 2law --kind joint --lang c
test ! -e my-law && test ! -e 2law
expect_refusal "does not apply to --kind hardware" arm --kind hardware --lang c
expect_refusal "lang cpp|c is required" law --kind joint
test ! -e arm && test ! -e law
mkdir taken && touch taken/keep
expect_refusal "not an empty folder" law --kind joint --lang cpp --out taken
test "$(ls taken)" = keep
mkdir empty
"$comply" plugin new law --kind joint --lang cpp --out empty >/dev/null
test -f empty/CMakeLists.txt && test -f empty/law.cpp
echo "plugin new: bad names and non-empty folders refused"
