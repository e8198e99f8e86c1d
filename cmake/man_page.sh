#!/usr/bin/env bash
# softtrace.1 from the built program's own help (the one source of the options and their
# words): `softtrace --help`, then `softtrace SUBCOMMAND --help` for every subcommand it lists,
# each as a section of the page, verbatim and unfilled, with roff's special characters escaped.
#   man_page.sh SOFTTRACE_CORE VERSION OUT
set -euo pipefail
core=$1 version=$2 out=$3

# Escapes a help text for roff: backslashes, and lines that would start a request.
roff_text() {
  sed -e 's/\\/\\e/g' -e "s/^\\([.']\\)/\\\\\\&\\1/" -e 's/-/\\-/g'
}

top=$("$core" --help)
# The subcommands: the lines of the "Subcommands:" block, first word each.
mapfile -t commands < <(printf '%s\n' "$top" | sed -n '/^Subcommands:/,/^$/p' |
  sed -n 's/^  \([a-z][a-z-]*\) .*/\1/p')
[ ${#commands[@]} -gt 0 ] || { echo "man_page.sh: '$core --help' lists no subcommands" >&2; exit 1; }

tmp=$(mktemp "$out.XXXXXX")
trap 'rm -f "$tmp"' EXIT
{
  echo ".TH SOFTTRACE 1 \"\" \"softtrace $version\" \"User Commands\""
  echo ".SH NAME"
  echo "softtrace \\- render, evaluate, compare and benchmark implicit soft-object scenes"
  echo ".SH SYNOPSIS"
  echo ".B softtrace"
  echo "[\\-\\-help | \\-\\-help\\-all | \\-\\-version] SUBCOMMAND [OPTIONS] ARGS"
  echo ".SH DESCRIPTION"
  echo "This page is"
  echo ".B softtrace \\-\\-help"
  echo "and the help of every subcommand, as the program prints them."
  echo ".PP"
  echo ".nf"
  printf '%s\n' "$top" | roff_text
  echo ".fi"
  echo ".SH SUBCOMMANDS"
  for c in "${commands[@]}"; do
    echo ".SS $c"
    echo ".nf"
    "$core" "$c" --help | roff_text
    echo ".fi"
  done
  echo ".SH SEE ALSO"
  echo "The documentation installed in share/doc/softtrace/ (cli.md: every option with examples;"
  echo "scene\\-format.md: the scene files; tutorial.md: a first scene step by step), and the"
  echo "example scenes in share/softtrace/scenes/."
} >"$tmp"
chmod 644 "$tmp"
mv "$tmp" "$out"
trap - EXIT
