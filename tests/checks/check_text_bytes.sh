#!/usr/bin/env bash
# Text files hold no control characters but tab and newline. A script that writes "\r" or "\t"
# into a document unescaped (LaTeX's \rvert, \times) leaves a carriage return or a tab that
# renders as a broken formula; this has happened twice in docs/math.md. The bad scenes that test
# CR line endings on purpose are the exceptions. Prints each offending file:line, exits 1 if any.
set -euo pipefail
cd "$(dirname "$0")/../.."
bad=0
while IFS= read -r -d '' f; do
  case "$f" in
    tests/bad_scenes/*cr_line_endings.json | tests/bad_scenes/*crlf_line_endings.json) continue ;;
  esac
  if out=$(grep -nP '[\x00-\x08\x0b-\x1f\x7f]' "$f" | cut -c1-80); then
    sed "s|^|$f:|" <<<"$out"
    bad=1
  fi
done < <(git ls-files -z -- '*.md' '*.h' '*.cpp' '*.py' '*.json' '*.sh' '*.txt' '*.cmake' '*.pov' 2>/dev/null)
if [ "$bad" -ne 0 ]; then
  echo "check_text_bytes: the lines above hold control characters" >&2
  exit 1
fi
echo "check_text_bytes: no control characters"
