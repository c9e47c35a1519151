#!/usr/bin/env bash
# The link check fails on each kind of broken link and passes on good ones: run on a folder
# of Markdown files made here (outside any git checkout, so it walks the folder).
set -euo pipefail
check=$(dirname "$0")/check_links.py
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir -p "$dir/docs"
cat >"$dir/README.md" <<'MD'
# Arena
## The game: Asteroids
## `arena-sim`: the world from the command line
[ok](docs/A.md) [ok](docs/A.md#one-two) [ok](#the-game-asteroids) [ok](#arena-sim-the-world-from-the-command-line)
[web](https://example.com/x#y) `[not a link](nowhere.md)`
```
[in a code block](nowhere.md)
```
MD
printf '# A\n## One, two\n## One, two\n[back](../README.md#arena) [second](#one-two-1)\n' >"$dir/docs/A.md"
python3 "$check" "$dir" >"$dir/out" || { cat "$dir/out"; echo "FAIL: good links refused"; exit 1; }
printf '[gone](docs/B.md)\n[bad anchor](docs/A.md#three)\n[out](../../etc/passwd)\n' >>"$dir/README.md"
if python3 "$check" "$dir" >"$dir/out"; then cat "$dir/out"; echo "FAIL: broken links passed"; exit 1; fi
grep -q 'README.md:9: docs/B.md: no such file' "$dir/out" || { cat "$dir/out"; echo "FAIL: missing file"; exit 1; }
grep -q 'README.md:10: docs/A.md#three: no heading with anchor #three' "$dir/out" || { cat "$dir/out"; echo "FAIL: anchor"; exit 1; }
grep -q 'README.md:11: ../../etc/passwd: leaves the repository' "$dir/out" || { cat "$dir/out"; echo "FAIL: escape"; exit 1; }
echo "check_links self-test: passed"
