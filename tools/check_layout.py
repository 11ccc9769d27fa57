#!/usr/bin/env python3
"""Checks that the code keeps the module table: docs/layout.md's "Layout" table names, for each
folder of src/, the folders it may use (directly; what those may use comes with them). Every
`#include "folder/..."` in src/F and every aerobox library F's CMakeLists.txt links must be F's
own or one it may use, every folder of src/ must have a row, and no row may name a folder that
is not there.

Usage: check_layout.py SOURCE_DIR     (exit 0: kept; 1: the violations, one per line)
"""

import pathlib
import re
import sys

# CMake targets that are not named aerobox_<folder>
TARGET_FOLDERS = {"aerobox_python_seams": "python", "aerobox_python_embedded": "python",
                  "_aerobox": "python", "aerobox_bench_lib": "bench", "aerobox-bench": "bench",
                  "aerobox": "app"}


def module_table(page):
    """{folder: set of folders it may use directly}, from the Layout table's last column (the
    table under a heading "# Layout" or "## Layout", up to the next heading)."""
    table, inside = {}, False
    for line in page.read_text(encoding="utf-8").splitlines():
        if line.startswith("# ") or line.startswith("## "):
            inside = line.strip() in ("# Layout", "## Layout")
            continue
        match = re.match(r"\| `src/([a-z_]+)` \|.*\| ([^|]*) \|$", line) if inside else None
        if match:
            uses = match.group(2).strip()
            table[match.group(1)] = set() if uses == "-" else {
                name.strip() for name in uses.split(",")}
    return table


def closure(table, folder):
    seen, todo = set(), list(table.get(folder, ()))
    while todo:
        name = todo.pop()
        if name not in seen:
            seen.add(name)
            todo.extend(table.get(name, ()))
    return seen


def target_folder(name):
    if name in TARGET_FOLDERS:
        return TARGET_FOLDERS[name]
    return name[len("aerobox_"):] if name.startswith("aerobox_") else None


def main(top):
    top = pathlib.Path(top)
    src = top / "src"
    folders = sorted(p.name for p in src.iterdir() if p.is_dir())
    page = top / "docs" / "layout.md"
    if not page.exists():
        print("check_layout: docs/layout.md is missing: it holds the module table")
        return 1
    table = module_table(page)
    problems = []
    if not table:
        problems.append("docs/layout.md: no Layout table with a 'may use' column")
    for folder in folders:
        if folder not in table:
            problems.append(f"docs/layout.md: src/{folder} has no row in the Layout table")
    for folder, uses in table.items():
        for name in sorted(uses | {folder}):
            if name not in folders:
                problems.append(f"docs/layout.md: the Layout table names src/{name}, "
                                "which is not there")
    for folder in folders:
        allowed = closure(table, folder) | {folder}
        for path in sorted((src / folder).rglob("*")):
            if path.suffix not in (".h", ".cpp", ".cc", ".hpp"):
                continue
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                match = re.match(r'\s*#\s*include\s+"([a-z_]+)/', line)
                if match and match.group(1) in folders and match.group(1) not in allowed:
                    problems.append(f"{path.relative_to(top)}:{number}: src/{folder} may not "
                                    f"include src/{match.group(1)} ({line.strip()})")
        cmake = src / folder / "CMakeLists.txt"
        if not cmake.exists():
            continue
        text = re.sub(r"#.*", "", cmake.read_text(encoding="utf-8"))
        for call in re.finditer(r"target_link_libraries\s*\(([^)]*)\)", text):
            words = call.group(1).split()
            for name in words[1:]:
                used = target_folder(name)
                if used in folders and used not in allowed:
                    problems.append(f"{cmake.relative_to(top)}: {words[0]} may not link {name} "
                                    f"(src/{folder} may not use src/{used})")
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_layout: {len(problems)} violation(s) of the module table (docs/layout.md)")
        return 1
    print(f"check_layout: {len(folders)} folders keep the module table")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
