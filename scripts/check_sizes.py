#!/usr/bin/env python3
"""Size guard (issue 40): fails when a function in packages/ or drivers/ is longer than
--max-function lines or a source file longer than --max-file lines, and lists the offenders.

Usage: scripts/check_sizes.py [--root DIR] [--max-function 80] [--max-file 600] [--report N]

A function is a brace block at namespace or class scope whose opening brace follows a
parameter list ("...) {", "...) const {", "...) -> T {", a constructor's initialiser list);
its length counts from the first line of its signature to its closing brace. Lambdas and
blocks inside a function count toward the function that holds them. Comments, string and
character literals are blanked before the braces are matched, so a brace in a comment or a
string does not count. --report N also prints the N longest functions (0: none).
Exit status: 0 within the limits, 1 offenders listed, 2 bad usage or an unreadable file.
"""
import argparse
import os
import re
import sys

SOURCE_SUFFIXES = (".cpp", ".hpp", ".h", ".cc")
SCANNED_FOLDERS = ("packages", "drivers")
# Words before a brace that open a scope rather than a function body.
SCOPE_OPENER = re.compile(r"\b(namespace|class|struct|union|enum)\b[^;{}()]*$")
# A parameter list closed before the brace, optionally followed by qualifiers, a trailing return
# type or a constructor's initialiser list (which itself ends with ")" or "}").
FUNCTION_TAIL = re.compile(
    r"\)\s*(const\s*)?(&{1,2}\s*)?(noexcept(\([^()]*\))?\s*)?(override\s*|final\s*)*(->\s*[\w:<>,\s*&]+)?$")


def blank_comments_and_literals(text):
    """Replaces comments and string/char literals by spaces, keeping the newlines."""
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
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            open_paren = text.find("(", i)
            delimiter = text[i + 2:open_paren]
            j = text.find(")" + delimiter + '"', open_paren)
            j = n if j < 0 else j + len(delimiter) + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # a digit separator (1'000)
                out.append(c)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(c + " " * (j - i - 2) + (c if j - i >= 2 else ""))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(text):
    """Yields (name, first line, last line) of every function body at namespace/class scope."""
    code = blank_comments_and_literals(text)
    stack = []  # per open brace: "scope", "function" or "block"
    segment_start = 0  # where the text before the next brace begins (after the last ; { or })
    line_of = [0] * (len(code) + 1)
    line = 1
    for i, ch in enumerate(code):
        line_of[i] = line
        if ch == "\n":
            line += 1
    open_function = None
    for i, ch in enumerate(code):
        if ch == ";":
            if not stack or stack[-1] == "scope":
                segment_start = i + 1
        elif ch == "{":
            inside_function = any(kind == "function" for kind in stack)
            head = code[segment_start:i]
            head_stripped = " ".join(head.split())
            if inside_function:
                stack.append("block")
            elif SCOPE_OPENER.search(head_stripped) or head_stripped.endswith("extern \"C\""):
                stack.append("scope")
            elif is_function_head(head_stripped):
                stack.append("function")
                first = i - len(head) + (len(head) - len(head.lstrip()))
                open_function = (function_name(head_stripped), line_of[first])
            else:
                stack.append("block")  # an initialiser, an enum body, an array
            segment_start = i + 1
        elif ch == "}":
            kind = stack.pop() if stack else "scope"
            if kind == "function" and open_function:
                yield open_function[0], open_function[1], line_of[i]
                open_function = None
            if not any(k == "function" for k in stack):
                segment_start = i + 1


def is_function_head(head):
    if not head or "(" not in head:
        return False
    if head.startswith(("=", ",")) or head.endswith(("=", ",")):
        return False
    if FUNCTION_TAIL.search(head):
        return True
    # A constructor's initialiser list: "X::X(args) : a_(b), c_{d}" ends in ")" or "}".
    return bool(re.search(r"\)\s*:\s*[\w:]+\s*[({]", head))


def function_name(head):
    before = head.split("(")[0].split()
    name = before[-1] if before else "?"
    if "operator" in head.split("(")[0]:
        name = head[head.find("operator"):].split("(")[0] + "()"
    return name


def scan(root, max_function, max_file):
    offenders, all_functions = [], []
    for folder in SCANNED_FOLDERS:
        for directory, _, files in sorted(os.walk(os.path.join(root, folder))):
            for name in sorted(files):
                if not name.endswith(SOURCE_SUFFIXES):
                    continue
                path = os.path.join(directory, name)
                relative = os.path.relpath(path, root)
                with open(path, encoding="utf-8") as source:
                    text = source.read()
                lines = text.count("\n") + (0 if text.endswith("\n") or not text else 1)
                if lines > max_file:
                    offenders.append(f"{relative}: file of {lines} lines (limit {max_file})")
                for function, first, last in functions(text):
                    length = last - first + 1
                    all_functions.append((length, f"{relative}:{first}", function))
                    if length > max_function:
                        offenders.append(f"{relative}:{first}: function {function} of {length} lines "
                                         f"(limit {max_function})")
    return offenders, all_functions


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    parser.add_argument("--max-function", type=int, default=80)
    parser.add_argument("--max-file", type=int, default=600)
    parser.add_argument("--report", type=int, default=0)
    args = parser.parse_args()
    try:
        offenders, all_functions = scan(os.path.abspath(args.root), args.max_function, args.max_file)
    except OSError as error:
        print(f"check_sizes: {error}", file=sys.stderr)
        return 2
    for length, where, name in sorted(all_functions, reverse=True)[:args.report]:
        print(f"{length:5d}  {where}  {name}")
    if offenders:
        print(f"check_sizes: {len(offenders)} over the limits (functions {args.max_function} lines, "
              f"files {args.max_file}):")
        for line in offenders:
            print("  " + line)
        return 1
    print(f"check_sizes: {len(all_functions)} functions within {args.max_function} lines, "
          f"every file within {args.max_file} lines")
    return 0


if __name__ == "__main__":
    sys.exit(main())
