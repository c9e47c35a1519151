#!/usr/bin/env python3
"""Every relative link and anchor in the repository's Markdown resolves.

usage: check_links.py REPO_ROOT

Reads every tracked *.md file (git ls-files; outside a checkout, every *.md below REPO_ROOT), finds its inline links [text](target) and
reference definitions ([label]: target), skips absolute URLs (scheme:) and checks that each
relative target names a file or folder of the repository and, when it has an #anchor into a
Markdown file, that the file has a heading with that anchor as GitHub makes it: lowercase,
punctuation dropped but for '-' and '_', spaces to '-', a repeated heading gets -1, -2, ...
Prints one line per broken link (file:line: target: why) and exits 1 if there is one.
"""
import os
import re
import subprocess
import sys

INLINE = re.compile(r"\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_CODE = re.compile(r"`[^`]*`")


def slug(heading):
    text = re.sub(r"<[^>]+>", "", heading)  # inline HTML
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link keeps its text
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)  # \w is Unicode: letters and digits stay
    return text.replace(" ", "-")


def lines_outside_code(path):
    """Yields (line number, line) of the lines that are not inside a fenced block."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if not fenced:
                yield number, line


def anchors(path, cache={}):
    if path not in cache:
        seen = {}
        found = set()
        for _, line in lines_outside_code(path):
            match = HEADING.match(line)
            if not match:
                continue
            base = slug(match.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else f"{base}-{count}")
        for _, line in lines_outside_code(path):  # explicit <a name="..."> / id="..."
            for name in re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", line):
                found.add(name)
        cache[path] = found
    return cache[path]


def check(root, md, problems):
    folder = os.path.dirname(md)
    for number, line in lines_outside_code(os.path.join(root, md)):
        text = INLINE_CODE.sub("", line)
        targets = INLINE.findall(text)
        reference = REFERENCE.match(text)
        if reference:
            targets.append(reference.group(1))
        for target in targets:
            if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):  # http:, mailto:, ...
                continue
            path, _, anchor = target.partition("#")
            path = path.split("?", 1)[0]
            resolved = os.path.normpath(os.path.join(root, folder, path)) if path else os.path.join(root, md)
            where = f"{md}:{number}: {target}"
            if resolved != root and not resolved.startswith(root + os.sep):
                problems.append(f"{where}: leaves the repository")
            elif not os.path.exists(resolved):
                problems.append(f"{where}: no such file")
            elif anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
                problems.append(f"{where}: no heading with anchor #{anchor}")


def markdown_files(root):
    """The tracked *.md files of a git checkout; every *.md under ROOT elsewhere."""
    listed = subprocess.run(["git", "-C", root, "ls-files", "*.md"], capture_output=True, text=True)
    if listed.returncode == 0:
        return [f for f in listed.stdout.split("\n") if f and os.path.exists(os.path.join(root, f))]
    found = []
    for folder, _, names in os.walk(root):
        found += [os.path.relpath(os.path.join(folder, n), root) for n in names if n.endswith(".md")]
    return sorted(found)


def main():
    if len(sys.argv) != 2:
        print("usage: check_links.py REPO_ROOT", file=sys.stderr)
        return 2
    root = os.path.abspath(sys.argv[1])
    files = markdown_files(root)
    problems = []
    for md in files:
        check(root, md, problems)
    for problem in problems:
        print(problem)
    print(f"check_links: {len(files)} files, {len(problems)} broken links")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
