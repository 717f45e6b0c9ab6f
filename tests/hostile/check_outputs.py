#!/usr/bin/env python3
"""Parses every file mechgraph wrote into a folder with a real parser of its format and fails on the
first that does not parse, or that carries active content a hostile scene could have put there.

  check_outputs.py DIR [--expect-text TEXT ...]

HTML: html.parser over the whole page; no <script>, <iframe>, <object>, <embed>, no on* attribute,
no javascript: URL; each --expect-text must appear in the page's text content exactly (so it went in
escaped, as text, not as markup). Inline and separate SVG: xml.etree. CSV: the csv module, every row.
JSON: json with NaN and Infinity refused. DOT: Graphviz's dot -Tjson, then json. DXF: ezdxf audit.
"""
import csv
import html.parser
import json
import pathlib
import subprocess
import sys
import xml.etree.ElementTree as ET

FORBIDDEN_TAGS = {"script", "iframe", "object", "embed", "base", "form", "link"}


class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.text = []
        self.problems = []
        self.svg_depth = 0
        self.svg_chunks = []

    def handle_starttag(self, tag, attrs):
        if tag in FORBIDDEN_TAGS:
            self.problems.append(f"<{tag}> element")
        for name, value in attrs:
            if name.lower().startswith("on"):
                self.problems.append(f"{name} attribute on <{tag}>")
            if value and "javascript:" in value.lower():
                self.problems.append(f"javascript: URL in {name} of <{tag}>")

    def handle_data(self, data):
        self.text.append(data)


def refuse_constant(name):
    raise ValueError(f"JSON holds {name}")


def check_html(path, expected):
    text = path.read_text(encoding="utf-8")
    page = Page()
    page.feed(text)
    page.close()
    if page.problems:
        raise AssertionError(f"{path}: active content: {page.problems}")
    content = "".join(page.text)
    for e in expected:
        if e not in content:
            raise AssertionError(f"{path}: the text {e!r} is not in the page's text content")
    # Every inline SVG is well-formed XML on its own.
    start = 0
    while (begin := text.find("<svg", start)) >= 0:
        end = text.find("</svg>", begin)
        if end < 0:
            raise AssertionError(f"{path}: an <svg> is not closed")
        ET.fromstring(text[begin:end + len("</svg>")])
        start = end
    return 1


def check_csv(path):
    with path.open(newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f, strict=True))
    if not rows:
        raise AssertionError(f"{path}: empty CSV")
    return 1


def check_json(path):
    text = path.read_text(encoding="utf-8")
    for line in ([text] if path.suffix == ".json" else text.splitlines()):
        if line.strip():
            json.loads(line, parse_constant=refuse_constant)
    return 1


def check_dot(path):
    result = subprocess.run(["dot", "-Tjson", str(path)], capture_output=True, text=True, timeout=60)
    if result.returncode != 0:
        raise AssertionError(f"{path}: dot refused it: {result.stderr}")
    json.loads(result.stdout)
    return 1


def check_dxf(path):
    import ezdxf
    doc = ezdxf.readfile(str(path))
    auditor = doc.audit()
    if auditor.has_errors:
        raise AssertionError(f"{path}: ezdxf audit: {[str(e) for e in auditor.errors]}")
    return 1


def main():
    folder = pathlib.Path(sys.argv[1])
    expected = []
    args = sys.argv[2:]
    while args:
        if args[0] == "--expect-text" and len(args) > 1:
            expected.append(args[1])
            args = args[2:]
        else:
            sys.exit(f"unknown argument {args[0]!r}")
    checked = 0
    for path in sorted(folder.rglob("*")):
        if not path.is_file():
            continue
        if path.suffix == ".html":
            checked += check_html(path, expected)
        elif path.suffix == ".svg":
            ET.parse(path)
            checked += 1
        elif path.suffix == ".csv":
            checked += check_csv(path)
        elif path.suffix in (".json", ".jsonl"):
            checked += check_json(path)
        elif path.suffix == ".dot":
            checked += check_dot(path)
        elif path.suffix == ".dxf":
            checked += check_dxf(path)
    if checked == 0:
        sys.exit(f"{folder}: no file to check")
    print(f"checked {checked} files")


if __name__ == "__main__":
    main()
