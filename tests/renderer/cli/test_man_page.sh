#!/usr/bin/env bash
# The generated man page (cmake/man_page.sh) against the program: a section for every
# subcommand `softtrace --help` lists, every option of every subcommand's --help in it, and
# groff formats it without a warning.
#   test_man_page.sh SOFTTRACE MAN_PAGE
set -euo pipefail
softtrace=$1 page=$2
fail() {
  echo "test_man_page: FAILED: $*" >&2
  exit 1
}
[ -s "$page" ] || fail "$page does not exist or is empty"
head -n1 "$page" | grep -q '^\.TH SOFTTRACE 1 ' || fail "$page does not start with .TH SOFTTRACE 1"
# The page as a reader sees it (roff escapes undone), with groff's warnings.
text=$(groff -man -Tutf8 -ww -P -c "$page" 2>"$page.warnings" | sed 's/\x1b\[[0-9;]*m//g')
[ ! -s "$page.warnings" ] || fail "groff warns: $(head -n 3 "$page.warnings")"
mapfile -t commands < <("$softtrace" --help | sed -n '/^Subcommands:/,/^$/p' |
  sed -n 's/^  \([a-z][a-z-]*\) .*/\1/p')
[ ${#commands[@]} -ge 6 ] || fail "softtrace --help lists ${#commands[@]} subcommands"
options=0
for c in "${commands[@]}"; do
  grep -q "^\.SS $c\$" "$page" || fail "no section for '$c'"
  while read -r option; do
    grep -qF -- "$option" <<<"$text" || fail "'$c $option' is not on the page"
    options=$((options + 1))
  done < <("$softtrace" "$c" --help | grep -oE -- '--[a-z][a-z-]*' | sort -u)
done
echo "test_man_page: ${#commands[@]} subcommands, $options options, no groff warning"
