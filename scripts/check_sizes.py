#!/usr/bin/env python3
"""Checks issue 44's size targets: no source file in src/, tsp/, tests/ or shaders/ over 600
lines, and no C++ or GLSL function there over 120 lines.

A function is a brace block, outside any other function, whose head (the text since the last
';', '{' or '}') ends in ')' and optional qualifiers (const, noexcept, override, a trailing
return type) and is not a control statement (if, for, while, switch, catch, else); a lambda
counts within its function, a TEST(...) body as a function. Its length runs from its head's first
line to its closing brace. Comments, strings and character literals are skipped.

Usage: check_sizes.py [REPO_ROOT]   (default: the parent of this script's folder)
Exit 0 when nothing is over, 1 listing what is ("file PATH: N lines", "function PATH:LINE: N
lines: HEAD").
"""
import os, re, sys

MAX_FILE, MAX_FUNC = 600, 120
ROOTS = ("src", "tsp", "tests", "shaders")
CODE = (".cpp", ".h", ".hpp", ".cc", ".glsl", ".frag", ".vert", ".comp")
TEXT = CODE + (".py", ".sh")
HEAD = re.compile(r"\)\s*(const|noexcept|override|final|mutable|\s)*(->\s*[^{;()]+)?$")
CONTROL = re.compile(r"^(if|for|while|switch|catch|else\s+if)\b|^(\}\s*)?else\b|\bdo$")


def code_chars(text):
    """(char, line) of the code, comments and literals blanked."""
    i, n, line = 0, len(text), 1
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            while i < n and text[i] != "\n": i += 1
            continue
        if text.startswith("/*", i):
            j = text.find("*/", i + 2); j = n if j < 0 else j + 2
            line += text.count("\n", i, j); i = j; continue
        m = re.match(r'R"([^(]*)\(', text[i:i + 20]) if c == "R" else None
        if m:
            end = text.find(")" + m.group(1) + '"', i); end = n if end < 0 else end + len(m.group(1)) + 2
            line += text.count("\n", i, end); yield ('""', line); i = end; continue
        if c in "\"'" and not (c == "'" and i > 0 and text[i - 1].isalnum()):  # 1'000 digit marks
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            yield (c + c, line); i = j + 1; continue
        if c == "\n": line += 1
        yield (c, line); i += 1


def functions(path):
    text = open(path, errors="replace").read()
    head, head_line, stack, found = "", None, [], []
    for c, line in code_chars(text):
        if c == "{":
            h = " ".join(head.split())
            in_func = any(f for _, f in stack)
            is_func = (not in_func and bool(HEAD.search(h)) and not CONTROL.search(h)
                       and not h.endswith("]()") and "=" not in h.split("(")[0])
            stack.append((head_line or line, is_func))
            head, head_line = "", None
        elif c == "}":
            if stack:
                start, is_func = stack.pop()
                if is_func: found.append((start, line - start + 1))
            head, head_line = "", None
        elif c == ";":
            head, head_line = "", None
        else:
            if not c.isspace() and head_line is None: head_line = line
            head += c
    return found


def main(repo):
    bad = 0
    for root in ROOTS:
        for dirpath, _, files in sorted(os.walk(os.path.join(repo, root))):
            for f in sorted(files):
                p = os.path.join(dirpath, f)
                if not f.endswith(TEXT): continue
                src = open(p, errors="replace").read().split("\n")
                name = os.path.relpath(p, repo)
                n = len(src) - (1 if src and src[-1] == "" else 0)
                if n > MAX_FILE:
                    print(f"file {name}: {n} lines"); bad += 1
                if f.endswith(CODE):
                    for start, length in functions(p):
                        if length > MAX_FUNC:
                            print(f"function {name}:{start}: {length} lines: {src[start - 1].strip()[:70]}")
                            bad += 1
    print(f"{bad} over the limits ({MAX_FILE}-line files, {MAX_FUNC}-line functions)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else
                  os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
