#!/usr/bin/python3
"""Lists the C++ functions of src/ and apps/ whose bodies are longer than a limit (100 lines).

A function is a brace block at namespace or class level whose opening follows a parameter list (after `)`,
possibly `const`, `noexcept`, `override`, `final`, a trailing return type or a constructor's initialisers);
its length is the lines from its opening to its closing brace. Lambdas and nested blocks count with the
function that holds them. Comments, strings and character literals are skipped when matching braces. (A
constructor whose initialisers use braces, `a_{x}`, is not recognised: a heuristic, not a parser.)

usage: scripts/function-sizes.py [--limit N] [--baseline FILE] [PATH ...]
  --baseline FILE: the functions allowed over the limit for now ("path:name" per line, "#" comments); the
  check fails on any other function over the limit, and on a listed one that is no longer over it (so that
  the list only shrinks).
"""
import argparse
import pathlib
import re
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent


def blank_out(text):
    """The text with comments, strings and character literals replaced by spaces (newlines kept)."""
    out, i, n = [], 0, len(text)
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
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                end = text.find(")" + m.group(1) + '"', i)
                end = n if end < 0 else end + len(m.group(1)) + 2
                out.append(re.sub(r"[^\n]", " ", text[i:end]))
                i = end
            else:
                out.append(c)
                i += 1
        elif c in "\"'":
            # A digit separator (1'000'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum():
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            j = min(n, j + 1)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


NAME = re.compile(r"([~\w:]+(<[^<>]*>)?|operator\s*[^\s(]+)\s*\($")


def function_name(head):
    """The name before the parameter list that ends `head`, or None when `head` is not a function's."""
    depth, k = 0, len(head) - 1
    # Step back over a constructor's initialisers: "Foo(int x) : a_(x), b_{} " ends in ")" or "}".
    while k >= 0:
        if head[k] == ")":
            depth += 1
        elif head[k] == "(":
            depth -= 1
            if depth == 0:
                m = NAME.search(head[:k + 1])
                if not m:
                    return None
                name = m.group(1)
                if name.split("::")[-1] in ("if", "for", "while", "switch", "catch", "return", "sizeof",
                                            "decltype", "alignas", "static_assert"):
                    return None
                before = head[:m.start()].rstrip()
                if before.endswith((":", ",")) and not before.endswith("::"):
                    # an initialiser a_(x) of a constructor: keep stepping back
                    k = m.start() - 1
                    depth = 0
                    continue
                return name
        k -= 1
    return None


def functions_of(path):
    """(name, first line, lines) of every function defined at namespace or class level."""
    text = blank_out(path.read_text(encoding="utf-8", errors="replace"))
    found, stack, i = [], [], 0
    statement_start = 0
    for i, c in enumerate(text):
        if c in ";":
            statement_start = i + 1
        elif c == "{":
            head = text[statement_start:i]
            in_function = any(kind == "function" for kind, _, _ in stack)
            kind = "block"
            name = None
            if not in_function:
                # Qualifiers and a trailing return type after the parameter list do not change the name.
                stripped = re.sub(r"\)\s*(const|noexcept(\([^)]*\))?|override|final|\s)*(->\s*[\w:<>,\s*&]+)?$", ")",
                                  head.rstrip())
                if stripped.endswith(")"):
                    name = function_name(stripped)
                    if name:
                        kind = "function"
            stack.append((kind, name, i))
            statement_start = i + 1
        elif c == "}":
            if stack:
                kind, name, opened = stack.pop()
                if kind == "function":
                    first = text.count("\n", 0, opened) + 1
                    last = text.count("\n", 0, i) + 1
                    found.append((name, first, last - first + 1))
            statement_start = i + 1
    return found


def sources(paths):
    for root in paths:
        root = pathlib.Path(root)
        if root.is_file():
            yield root
            continue
        for path in sorted(root.rglob("*")):
            if path.suffix in (".cpp", ".hpp", ".h", ".cc"):
                yield path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--limit", type=int, default=100)
    parser.add_argument("--baseline")
    parser.add_argument("paths", nargs="*", default=[str(REPO / "src"), str(REPO / "apps")])
    args = parser.parse_args()
    over = {}
    for path in sources(args.paths):
        relative = path.resolve().relative_to(REPO) if path.resolve().is_relative_to(REPO) else path
        for name, first, lines in functions_of(path):
            if lines > args.limit:
                over[f"{relative}:{name}"] = (first, lines)
    for key, (first, lines) in sorted(over.items(), key=lambda kv: -kv[1][1]):
        path, name = key.split(":", 1)
        print(f"{path}:{first}: {name}: {lines} lines")
    if not args.baseline:
        print(f"function-sizes: {len(over)} functions over {args.limit} lines")
        return 0
    allowed = set()
    for line in pathlib.Path(args.baseline).read_text(encoding="utf-8").split("\n"):
        line = line.split("#", 1)[0].strip()
        if line:
            allowed.add(line)
    new = sorted(set(over) - allowed)
    gone = sorted(allowed - set(over))
    for key in new:
        print(f"function-sizes: {key} is over {args.limit} lines: split it", file=sys.stderr)
    for key in gone:
        print(f"function-sizes: {key} is no longer over {args.limit} lines: take it off {args.baseline}",
              file=sys.stderr)
    print(f"function-sizes: {len(over)} functions over {args.limit} lines ({len(allowed)} allowed for now)")
    return 1 if new or gone else 0


if __name__ == "__main__":
    sys.exit(main())
