#!/usr/bin/env python3
"""Parses every file mechgraph wrote into a folder with a real parser of its format and fails on the
first that does not parse, or that carries active content a hostile scene could have put there.

  check_outputs.py DIR [--expect-text TEXT ...] [--expect-cell TEXT ...] [--expect-label TEXT ...]

HTML: html.parser over the whole page; no <script>, <iframe>, <object>, <embed>, no on* attribute,
no javascript: URL; each --expect-text must appear in the page's text content exactly (so it went in
escaped, as text, not as markup). Inline and separate SVG: xml.etree. CSV: the csv module, every row.
Every CSV row has the header's width; each --expect-cell must be one whole cell of some CSV (so a
comma or a quote inside it was quoted, not taken for a separator). JSON: json with NaN and Infinity
refused. DOT: Graphviz's dot -Tjson, then json: no URL, href or tooltip attribute anywhere (an
attribute smuggled in through a name), and each --expect-label is the label of the graph or of a
node. DXF: ezdxf audit.
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


def check_csv(path, cells):
    with path.open(newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f, strict=True))
    if not rows:
        raise AssertionError(f"{path}: empty CSV")
    for number, row in enumerate(rows, 1):
        if len(row) != len(rows[0]):
            raise AssertionError(f"{path}:{number}: {len(row)} cells, the header has {len(rows[0])}")
    for row in rows:
        cells.update(row)
    return 1


def check_json(path):
    text = path.read_text(encoding="utf-8")
    for line in ([text] if path.suffix == ".json" else text.splitlines()):
        if line.strip():
            json.loads(line, parse_constant=refuse_constant)
    return 1


def check_dot(path, labels):
    result = subprocess.run(["dot", "-Tjson", str(path)], capture_output=True, text=True, timeout=60)
    if result.returncode != 0:
        raise AssertionError(f"{path}: dot refused it: {result.stderr}")
    graph = json.loads(result.stdout)
    found = set()

    def walk(item):
        if isinstance(item, dict):
            for key in ("URL", "href", "tooltip", "target"):
                if key in item:
                    raise AssertionError(f"{path}: a {key} attribute: {item[key]!r}")
            if isinstance(item.get("label"), str):
                found.add(item["label"].replace("\\n", "\n"))
            for value in item.values():
                walk(value)
        elif isinstance(item, list):
            for value in item:
                walk(value)

    walk(graph)
    for label in labels:
        if label not in found:
            raise AssertionError(f"{path}: no graph or node has the label {label!r} (labels: {sorted(found)[:10]})")
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
    expected, expected_cells, expected_labels = [], [], []
    args = sys.argv[2:]
    while args:
        lists = {"--expect-text": expected, "--expect-cell": expected_cells, "--expect-label": expected_labels}
        if args[0] in lists and len(args) > 1:
            lists[args[0]].append(args[1])
            args = args[2:]
        else:
            sys.exit(f"unknown argument {args[0]!r}")
    cells = set()
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
            checked += check_csv(path, cells)
        elif path.suffix in (".json", ".jsonl"):
            checked += check_json(path)
        elif path.suffix == ".dot":
            checked += check_dot(path, expected_labels)
        elif path.suffix == ".dxf":
            checked += check_dxf(path)
    if checked == 0:
        sys.exit(f"{folder}: no file to check")
    for cell in expected_cells:
        if cell not in cells:
            sys.exit(f"{folder}: no CSV has the cell {cell!r}")
    print(f"checked {checked} files")


if __name__ == "__main__":
    main()
