#!/usr/bin/env python3
"""Checks the folder graph of docs/architecture.md against the code.

Reads the folder map's table (its "folder" and "may include" columns) and checks every
#include "..." of every .h/.cpp directly in each listed folder: a file may include its own folder
and the folders its row lists. Includes are written "tsp/<folder>/<file>.h" everywhere and
"<folder>/<file>.h" for src/ folders; in a src/ row, "tsp" means any tsp/ folder, "everything
above" every folder of the rows above it, and a parenthesis ("cli (build)") is a note. Nothing in
tsp/ may include a src/ folder. Includes naming no project folder (a third-party header) are not
checked.

Usage: check_folders.py [REPO_ROOT]   (default: the parent of this script's folder)
Exit 0 when every include is allowed, 1 listing the violations, 2 when the table cannot be read.
"""
import pathlib
import re
import sys

DOC = pathlib.Path("docs") / "architecture.md"
SOURCE_SUFFIXES = (".h", ".cpp")
NONE_MARK = "—"
EVERYTHING_ABOVE = "everything above"
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
ROW = re.compile(r"^\|\s*`((?:tsp|src)/[^`]*)/`\s*\|")
PARENTHESIS = re.compile(r"\([^)]*\)")


def table_rows(doc_text):
    """The folder map's rows as (folder, may-include cell) in table order."""
    header = None
    rows = []
    for line in doc_text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if header is None:
            if "folder" in cells and "may include" in cells:
                header = cells
            continue
        if not line.startswith("|"):
            break
        m = ROW.match(line)
        if m:
            rows.append((m.group(1), cells[header.index("may include")]))
    return rows


def allowed_map(rows):
    """Folder → the set of folders it may include (its own included), in repo paths."""
    tsp_folders = [f for f, _ in rows if f.startswith("tsp/")]
    allowed = {}
    above = []
    for folder, cell in rows:
        names = set()
        text = PARENTHESIS.sub("", cell).strip()
        if text == EVERYTHING_ABOVE:
            names.update(above)
        elif text and text != NONE_MARK:
            for name in (n.strip() for n in text.split(",")):
                if not name:
                    continue
                if folder.startswith("tsp/"):
                    names.add("tsp/" + name)
                elif name == "tsp":
                    names.update(tsp_folders)
                else:
                    names.add("src/" + name)
        names.add(folder)
        allowed[folder] = names
        above.append(folder)
    return allowed


def include_folder(include, src_folders):
    """The repo folder an include names, or None for a header outside the project's folders."""
    parts = include.split("/")
    if len(parts) < 2:
        return None
    if parts[0] == "tsp":
        return "/".join(parts[:-1])
    if "src/" + parts[0] in src_folders:
        return "src/" + "/".join(parts[:-1])
    return None


def check(root):
    rows = table_rows((root / DOC).read_text(encoding="utf-8"))
    if not rows:
        print(f"check_folders: no folder table in {DOC}", file=sys.stderr)
        return 2
    allowed = allowed_map(rows)
    src_folders = {f for f, _ in rows if f.startswith("src/")}
    violations = []
    for folder, may in allowed.items():
        directory = root / folder
        if not directory.is_dir():
            violations.append(f"{folder}: listed in {DOC} but not a folder")
            continue
        for path in sorted(p for p in directory.iterdir() if p.suffix in SOURCE_SUFFIXES):
            for include in INCLUDE.findall(path.read_text(encoding="utf-8", errors="replace")):
                target = include_folder(include, src_folders)
                if target is None or target in may:
                    continue
                rel = path.relative_to(root)
                if folder.startswith("tsp/") and target.startswith("src/"):
                    violations.append(f'{rel}: includes "{include}" (tsp/ never includes src/)')
                else:
                    violations.append(f'{rel}: includes "{include}" ({target} is not in '
                                      f"{folder}'s may-include list)")
    for v in violations:
        print(v)
    if violations:
        print(f"check_folders: {len(violations)} include(s) against {DOC}", file=sys.stderr)
        return 1
    print(f"check_folders: {len(allowed)} folders, every include allowed")
    return 0


if __name__ == "__main__":
    top = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1]
    sys.exit(check(top))
