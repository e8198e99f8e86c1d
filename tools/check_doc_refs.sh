#!/usr/bin/env bash
# Checks that every anchor of docs/math.md that the repository cites exists there with a definition:
# - section numbers "§N.M": cited as "docs/math.md §N.M", or bare "§N.M" unless a
#   paper tag precedes it ("003 §3.4", "[002] §4.5" are the papers' own sections); each must be a
#   heading "## N. ..." / "### N.M ..." of docs/math.md;
# - property IDs "[PB-1]", "[BT2-3]": each must be defined by a list item that starts with it in
#   bold, "* **[PB-1]** ...";
# - register IDs A1..A6 and R1..R24 on lines that cite the maths (math.md, AMBIGUITY, §):
#   each must be defined in bold, "**A4" / "**R14".
# Usage: tools/check_doc_refs.sh [REPO_ROOT]   (exit 0: all found; 1: some missing; 2: usage)
set -euo pipefail

root=${1:-"$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"}
doc="$root/docs/math.md"
if [[ ! -f "$doc" ]]; then
  echo "check_doc_refs: $doc: not found" >&2
  exit 2
fi
cd "$root"

# Tracked and untracked-but-not-ignored text sources; outside a git checkout, every file under root
# except build trees.
list_files() {
  if git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git -C "$root" ls-files -z --cached --others --exclude-standard
  else
    find . -path './build*' -prune -o -type f -print0 | sed -z 's|^\./||'
  fi
}
files=()
while IFS= read -r -d '' f; do
  case "$f" in
    *.cpp | *.h | *.md | *.json | *.py | *.sh | *.txt | *.cmake | *.in) [[ -f "$f" ]] && files+=("$f") ;;
  esac
done < <(list_files)

# "file:line<TAB>kind<TAB>anchor" for every citation.
refs=$(perl -ne '
  my $loc = "$ARGV:$.";
  # A bare "§" continuing a list ("[002] §4.1, §4.4.1") belongs to the same source as the one before.
  my $paper = 0;
  while (/(math\.md)?\s*§([0-9]+(?:\.[0-9]+)*)/g) {
    my ($doc, $num, $start) = ($1, $2, $-[0]);
    my $before = substr($_, 0, $start);
    if ($doc) {
      $paper = 0;
    } elsif ($before =~ /(?:\[?\b00[023]\]?|\bHsu|paper)[\x27s]*\s*$/) {
      $paper = 1;
    } elsif ($before !~ /(?:,|–|-|\band|\bor)\s*$/) {
      $paper = 0;
    }
    print "$loc\tsection\t$num\n" unless $paper;
  }
  while (/\[([A-Z]+[0-9]*-[0-9]+)\]/g) { print "$loc\tproperty\t$1\n"; }
  if (/math\.md|AMBIGUITY|§/) {
    while (/\b(A[1-6]|R[0-9]{1,2})\b/g) { print "$loc\tregister\t$1\n"; }
  }
  close ARGV if eof;
' "${files[@]}")

declare -A headings
while IFS= read -r num; do headings["$num"]=1; done < <(
  sed -nE 's/^#{2,6} ([0-9]+(\.[0-9]+)*)\.? .*/\1/p' "$doc")

missing=0
declare -A seen
count_section=0 count_property=0 count_register=0
while IFS=$'\t' read -r loc kind anchor; do
  [[ -z "$loc" ]] && continue
  case "$kind" in
    section)
      count_section=$((count_section + 1))
      found=${headings["$anchor"]:-}
      ;;
    property)
      count_property=$((count_property + 1))
      found=$(grep -cE -- "^[[:space:]]*[*-] \*\*\[$anchor\]\*\*" "$doc" || true)
      [[ "$found" == 0 ]] && found=
      ;;
    register)
      count_register=$((count_register + 1))
      found=$(grep -cE -- "\*\*$anchor([^0-9]|$)" "$doc" || true)
      [[ "$found" == 0 ]] && found=
      ;;
  esac
  if [[ -z "$found" ]]; then
    echo "check_doc_refs: $loc: cites $kind ${anchor}, which docs/math.md does not define" >&2
    missing=$((missing + 1))
  fi
  seen["$kind $anchor"]=1
done <<<"$refs"

echo "check_doc_refs: ${#files[@]} files, $count_section section, $count_property property and" \
  "$count_register register citations (${#seen[@]} distinct anchors); $missing missing"
[[ $missing == 0 ]]
