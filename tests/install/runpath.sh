#!/usr/bin/env bash
# Every library search path that the CLI, the core library and the plugins
# carry, in the build tree and in an install, is absolute or relative to the
# file itself ($ORIGIN). The loader reads an empty entry, or a relative one,
# against the current directory: a library planted there would be loaded.
# Usage: runpath.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"

bad=0 checked=0
check_tree() {
  local file entries entry
  while IFS= read -r -d '' file; do
    # Only ELF files; scripts and data are skipped.
    [ "$(head -c 4 "$file" | od -An -c | tr -d ' ')" = '177ELF' ] || continue
    checked=$((checked + 1))
    entries=$(readelf -d "$file" | sed -n 's/.*(R\(UN\)\{0,1\}PATH).*\[\(.*\)\]$/\2/p')
    [ -n "$entries" ] || continue
    # Split on ':' keeping empty fields (a trailing ':' is an empty entry).
    while IFS= read -r entry; do
      case "$entry" in
        /* | '$ORIGIN' | '$ORIGIN/'*) ;;
        *) echo "$file: search path '$entries' has the entry '$entry', read against the current directory" >&2
           bad=1 ;;
      esac
    done < <(printf '%s\n' "$entries" | awk -F: '{for (i = 1; i <= NF; ++i) print $i}')
  done < <(find "$@" -type f -print0)
}
check_tree "$build/bin" "$build/lib"
check_tree "$work/prefix/bin" "$work/prefix/lib"
if [ "$checked" -lt 4 ]; then
  echo "only $checked ELF files found under $build/{bin,lib} and the install; nothing was checked" >&2; exit 1
fi
[ "$bad" -eq 0 ] || exit 1
echo "runpath: $checked ELF files, every search path absolute or \$ORIGIN-relative"
