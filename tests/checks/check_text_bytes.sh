#!/usr/bin/env bash
# Text files hold no control characters but tab and newline. A script that writes "\r" or "\t"
# into a document unescaped (LaTeX's \rvert, \times) leaves a carriage return or a tab that
# renders as a broken formula; this has happened twice in docs/math.md. The bad scenes that test
# CR line endings on purpose are the exceptions. Prints each offending file:line, exits 1 if any.
set -euo pipefail
cd "$(dirname "$0")/../.."
files=()
while IFS= read -r -d '' f; do
  case "$f" in
    tests/bad_scenes/*cr_line_endings.json | tests/bad_scenes/*crlf_line_endings.json) continue ;;
  esac
  files+=("$f")
done < <(git ls-files -z -- '*.md' '*.h' '*.cpp' '*.py' '*.json' '*.sh' '*.txt' '*.cmake' '*.pov' 2>/dev/null)
# One grep over every file: a grep and a cut per file took 17 s of CPU (21 s of CI's wall, twice).
status=0
out=$(grep -nHP '[\x00-\x08\x0b-\x1f\x7f]' -- "${files[@]}") || status=$?
case $status in
  0)
    # file:line:text, the text cut as before so that one long line does not flood the log.
    awk '{ file = $0; sub(/:.*/, "", file); print file ":" substr($0, length(file) + 2, 80) }' <<<"$out"
    echo "check_text_bytes: the lines above hold control characters" >&2
    exit 1
    ;;
  1) echo "check_text_bytes: no control characters" ;;
  *)
    echo "check_text_bytes: grep failed ($status)" >&2
    exit 2
    ;;
esac
