#!/usr/bin/env bash
# The repository stands on its own: no file points at material outside it (the specification
# and papers the project was written from live beside the repository, not in it). Prints each
# offending line and exits 1 if there is one.
set -euo pipefail
cd "$(dirname "$0")/../.."
pattern='\.\./shared|MATH\.md|SCENE\.md'
if out=$(grep -rnE "$pattern" --exclude-dir=.git --exclude-dir='build*' --exclude-dir=out \
  --exclude=check_self_contained.sh . ); then
  echo "$out"
  echo "check_self_contained: the lines above point outside the repository" >&2
  exit 1
fi
echo "check_self_contained: no file points outside the repository"
