#!/usr/bin/python3
"""Doxygen's input filter for include/curvemesh/*.hpp: hands the headers' plain comments to
Doxygen as the documentation they are, so that the headers keep one comment style.

The public headers document each name with ordinary `//` comments: a block of comment lines right
above a declaration, or a comment after it on the same line (continued on the lines below it, at
the same column). Doxygen reads only `///` and `///<`, so this filter, given a file name, prints
the file with
  - a comment block directly above a declaration turned into `///` lines (a block above a
    preprocessor line, a blank line or another comment is left alone: the file's own introduction);
  - a comment after code turned into `///<`, and the comment lines that continue it at its column
    turned into `///<` too;
  - a block above a declaration that carries its own trailing comment left alone (a heading such
    as "// §4: feature processing." above the fields it introduces);
  - in the comments turned into documentation, a "<" that opens an element name (<use>, <svg>)
    written as "&lt;", since Doxygen would read it as an HTML tag, and an option's "--" as "\\--",
    which Doxygen's Markdown would print as a dash.
Nothing else changes: line numbers stay as they are, so Doxygen's warnings point at the header.
"""
import re
import sys

TAG = re.compile(r"<(?=[A-Za-z/!])")  # "<use>" in a comment is the SVG element, not an HTML tag
DASHES = re.compile(r"(?<!-)--(?!-)")  # an option's "--", which Markdown would print as a dash
TRAILING = re.compile(r"^(?P<code>.*?\S.*?)(?P<gap>\s+)//(?!/)(?P<text>.*)$")
LEADING = re.compile(r"^(?P<indent>\s*)//(?!/)(?P<text>.*)$")


def escape(text):
    """A comment's text with element names such as <use> written as text for Doxygen."""
    return DASHES.sub(r"\\--", TAG.sub("&lt;", text))


def trailing_comment(line):
    """(code, column of //, comment text) for code followed by a `//` comment, else None."""
    if line.lstrip().startswith("//") or line.lstrip().startswith("#"):
        return None
    m = TRAILING.match(line)
    if not m or m.group("code").count('"') % 2:  # a // inside a string literal is not a comment
        return None
    return m.group("code"), len(m.group("code")) + len(m.group("gap")), m.group("text")


def is_declaration(line):
    stripped = line.strip()
    return bool(stripped) and not stripped.startswith(("//", "#", "}")) and stripped not in ("public:", "private:",
                                                                                           "protected:")


def convert(lines):
    out = list(lines)
    i = 0
    while i < len(lines):
        # A comment after code, and the lines that continue it at the same column.
        t = trailing_comment(lines[i])
        if t:
            code, column, text = t
            out[i] = f"{lines[i][:column]}///<{escape(text)}"
            j = i + 1
            while j < len(lines):
                m = LEADING.match(lines[j])
                if not m or len(m.group("indent")) != column:
                    break
                out[j] = f"{m.group('indent')}///<{escape(m.group('text'))}"
                j += 1
            i = j
            continue
        # A block of comment lines: documentation of the declaration right below it.
        if LEADING.match(lines[i]):
            j = i
            while j < len(lines) and LEADING.match(lines[j]) and not out[j].lstrip().startswith("///"):
                j += 1
            below = lines[j] if j < len(lines) else ""
            if is_declaration(below) and not trailing_comment(below):
                for k in range(i, j):
                    m = LEADING.match(lines[k])
                    out[k] = f"{m.group('indent')}///{escape(m.group('text'))}"
            i = max(j, i + 1)
            continue
        i += 1
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: doxygen-filter.py HEADER")
    with open(sys.argv[1], encoding="utf-8") as f:
        lines = f.read().split("\n")
    sys.stdout.write("\n".join(convert(lines)))


if __name__ == "__main__":
    main()
