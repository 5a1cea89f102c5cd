#!/usr/bin/env python3
"""Checks the tree's size rules: no file over 400 lines and no function over 80 in src/, include/,
apps/ and python/, except what docs/design.md names under "Size exceptions" with why.

A function's length is its whole definition, signature to closing brace (C, C++) or `def` line to
its last line (Python). C and C++ functions are found by a brace scanner, not a parser: a brace
that opens after a closing parenthesis (and qualifiers, or a constructor's initialiser list)
outside any other function opens a function's body. Lambdas count as part of the function they
are written in.

Usage: check-sizes.py [ROOT]    exit 0 when the tree keeps the rules, 1 with the list otherwise.
"""

from __future__ import annotations

import ast
import pathlib
import re
import sys

MAX_FILE_LINES = 400
MAX_FUNCTION_LINES = 80
FOLDERS = ("src", "include", "apps", "python")
CPP_SUFFIXES = {".c", ".cc", ".cpp", ".h", ".hpp"}
PY_SUFFIXES = {".py"}
EXCEPTIONS_HEADING = "### Size exceptions"


def strip_cpp(text: str) -> str:
    """The text with comments, string and character literals blanked, newlines kept."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            open_paren = text.find("(", i + 2)
            delimiter = text[i + 2:open_paren]
            close = text.find(")" + delimiter + '"', open_paren)
            j = n if close < 0 else close + len(delimiter) + 2
            out.append('""' + re.sub(r"[^\n]", " ", text[i + 2:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator: 1'000
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + re.sub(r"[^\n]", " ", text[i + 1:j - 1]) + c)
            i = j
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):
            # A preprocessor line (with its continuations) holds no function body.
            j = i
            while True:
                k = text.find("\n", j)
                if k < 0:
                    k = n
                    break
                if text[k - 1] != "\\":
                    break
                j = k + 1
            out.append(re.sub(r"[^\n]", " ", text[i:k]))
            i = k
        else:
            out.append(c)
            i += 1
    return "".join(out)


QUALIFIERS = re.compile(
    r"^(\s|const|noexcept|override|final|mutable|volatile|&|&&|\(|\)|->[^{;]*|"
    r"requires[^{;]*|try)*$")


def opens_function(head: str) -> bool:
    """Whether a brace after `head` (the text since the last ; { or }) opens a function body."""
    head = head.strip()
    if not head or ")" not in head:
        return False
    if re.match(r"^(namespace|class|struct|union|enum|extern)\b", head):
        return False
    # What follows the parameter list's closing parenthesis must be qualifiers, a trailing return
    # type or a constructor's initialiser list.
    depth = 0
    close = -1
    for index, char in enumerate(head):
        if char == "(":
            if depth == 0 and close >= 0 and re.search(r":", head[close:index]):
                break  # the initialiser list began
            depth += 1
        elif char == ")":
            depth -= 1
            if depth == 0:
                close = index
                tail = head[index + 1:]
                if QUALIFIERS.match(tail) or re.match(r"^\s*(const\s*|noexcept\s*)*:", tail):
                    break
    if close < 0:
        return False
    before = head[:head.find("(")]
    if "=" in before and not re.search(r"operator\s*\S*=", before):
        return bool(re.search(r"\[[^\]]*\]\s*$", before))  # a lambda assigned at namespace scope
    return True


def cpp_functions(text: str):
    """(first line, last line, name) of each function definition outside another function."""
    code = strip_cpp(text)
    line_starts = [0] + [m.end() for m in re.finditer("\n", code)]

    def line_of(offset: int) -> int:
        lo, hi = 0, len(line_starts) - 1
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if line_starts[mid] <= offset:
                lo = mid
            else:
                hi = mid - 1
        return lo + 1

    functions = []
    stack = []  # per open brace: "function", "other"
    head_start = 0
    in_function = False
    paren_depth = 0  # braces inside parentheses (default arguments, calls) open no body
    i = 0
    while i < len(code):
        c = code[i]
        if c in "()":
            paren_depth = max(0, paren_depth + (1 if c == "(" else -1))
        elif c in "{}" and paren_depth > 0:
            pass
        elif c == "{":
            head = code[head_start:i]
            if not in_function and opens_function(head):
                # A member initialised in braces (x_{1}) inside a constructor's initialiser list.
                if re.search(r"[A-Za-z0-9_>]\s*$", head) and re.search(r"\)\s*(noexcept\s*)?:", head):
                    depth = 1
                    j = i + 1
                    while j < len(code) and depth:
                        depth += {"{": 1, "}": -1}.get(code[j], 0)
                        j += 1
                    i = j
                    continue
                start = head_start + len(head) - len(head.lstrip())
                stack.append(("function", start, head))
                in_function = True
            else:
                stack.append(("other", i, head))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, start, head = stack.pop()
                if kind == "function" and not any(k == "function" for k, _, _ in stack):
                    in_function = False
                    name = re.sub(r"\s+", " ", head[:head.find("(")]).strip().split(" ")[-1]
                    functions.append((line_of(start), line_of(i), name))
            head_start = i + 1
        elif c == ";":
            head_start = i + 1
        i += 1
    return functions


def py_functions(text: str):
    functions = []
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            functions.append((node.lineno, node.end_lineno, node.name))
    return functions


def exceptions(root: pathlib.Path):
    """The paths (files) and path:function names docs/design.md lets past the rules."""
    design = (root / "docs" / "design.md").read_text()
    start = design.find(EXCEPTIONS_HEADING)
    if start < 0:
        return set()
    section = design[start + len(EXCEPTIONS_HEADING):]
    end = re.search(r"\n#+ ", section)
    section = section[:end.start()] if end else section
    return set(re.findall(r"^\|\s*`([^`]+)`", section, re.MULTILINE))


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent)
    allowed = exceptions(root)
    problems = []
    seen_exceptions = set()
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if not path.is_file() or "__pycache__" in path.parts:
                continue
            if path.suffix not in CPP_SUFFIXES | PY_SUFFIXES:
                continue
            relative = path.relative_to(root).as_posix()
            text = path.read_text(errors="replace")
            lines = text.count("\n") + (0 if text.endswith("\n") else 1)
            if lines > MAX_FILE_LINES:
                if relative in allowed:
                    seen_exceptions.add(relative)
                else:
                    problems.append(f"{relative}: {lines} lines (at most {MAX_FILE_LINES})")
            found = py_functions(text) if path.suffix in PY_SUFFIXES else cpp_functions(text)
            for first, last, name in found:
                length = last - first + 1
                if length <= MAX_FUNCTION_LINES:
                    continue
                key = f"{relative}:{name}"
                if key in allowed or relative in allowed:
                    seen_exceptions.add(key if key in allowed else relative)
                    continue
                problems.append(f"{relative}:{first}: {name} is {length} lines "
                                f"(at most {MAX_FUNCTION_LINES})")
    for stale in sorted(allowed - seen_exceptions):
        problems.append(f"docs/design.md names {stale} as a size exception, but it keeps the rules")
    for problem in problems:
        print(problem)
    if problems:
        print(f"check-sizes: {len(problems)} problem(s); an exception goes in docs/design.md's "
              f'"{EXCEPTIONS_HEADING[4:]}" table with why')
        return 1
    print("check-sizes: every file and function within the rules")
    return 0


if __name__ == "__main__":
    sys.exit(main())
