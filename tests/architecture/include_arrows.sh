#!/usr/bin/env bash
# Checks every #include "sandpaper/<room>/..." in the rooms' sources against the arrows block of
# docs/ARCHITECTURE.md: a room may include itself and the rooms on its line. Prints each include
# that points the wrong way as FILE:LINE: ROOM includes OTHER, and exits 1 if there is any.
#   include_arrows.sh [ROOT]     (ROOT: the source tree, default: this script's tree)
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/../.." && pwd)}
doc="$root/docs/ARCHITECTURE.md"
[ -f "$doc" ] || { echo "include_arrows: no $doc" >&2; exit 2; }

declare -A allowed
rooms=()
while IFS= read -r line; do
  room=${line%%:*}
  allowed[$room]=" $room ${line#*:} "
  rooms+=("$room")
done < <(awk '/^```arrows$/{on=1; next} /^```$/{on=0} on && NF' "$doc")
[ ${#rooms[@]} -gt 0 ] || { echo "include_arrows: no arrows block in $doc" >&2; exit 2; }

# The room a header belongs to, from its include path.
room_of_header() {
  case $1 in
    sandpaper/sandpaper.hpp | sandpaper/sandpaper.h | sandpaper/package_location.h) echo api ;;
    sandpaper/catalog/*) echo curation ;;
    sandpaper/lsp/*) echo editors ;;
    sandpaper/experiment/*) echo experiments ;;
    sandpaper/*/*) h=${1#sandpaper/}; echo "${h%%/*}" ;;
    *) echo "" ;;
  esac
}

bad=0
checked=0
for room in "${rooms[@]}"; do
  dir="$root/$room"
  [ -d "$dir" ] || { echo "include_arrows: the arrows name '$room', which is not a folder" >&2; bad=1; continue; }
  while IFS=: read -r file lineno text; do
    header=$(sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"([^"]+)".*/\1/' <<<"$text")
    other=$(room_of_header "$header")
    checked=$((checked + 1))
    [ -z "$other" ] && continue
    if [[ ${allowed[$room]} != *" $other "* ]]; then
      echo "${file#$root/}:$lineno: $room includes $other (\"$header\"), against docs/ARCHITECTURE.md's arrows"
      bad=1
    fi
  done < <(grep -rnE --include='*.cpp' --include='*.hpp' --include='*.h' --include='*.c' \
             '^[[:space:]]*#[[:space:]]*include[[:space:]]*"sandpaper/' "$dir" || true)
done
echo "include_arrows: ${#rooms[@]} rooms, $checked includes checked"
exit $bad
