#!/usr/bin/python3
"""What the host presents for the shipped scenes, as text to compare: the golden of the switch from
guessing by names to declared presentation (issue 30, item 2; docs/design/sdk-1.0.md section 5).

For each scenes/*.yaml it records, with every number masked as '#' (values are other tests'
business; this one holds words, names and units):
  - `run`: the terminal text;
  - `run --json`: the keys of the result, per output its keys, a table's axis and columns with units;
  - `run --out`: the file names, the header line of every CSV, the layers of every DXF;
  - `report --out`: the file names, the header line of every CSV, and the page's words: headings,
    table headers and cells with letters, captions, and every text of the inline plots (titles, axis
    labels, legends, marks and point labels).

Usage: presentation_golden.py CLI SCENES_DIR GOLDEN_DIR [--update]
Without --update it fails (exit 1) with a unified diff when anything differs from GOLDEN_DIR.
"""
import difflib
import glob
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def masked(text):
    return NUMBER.sub("#", text)


def run(cli, args, cwd):
    done = subprocess.run([cli] + args, cwd=cwd, capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        sys.exit("%s %s failed (%d): %s" % (cli, " ".join(args), done.returncode, done.stderr[-2000:]))
    return done.stdout


def json_shape(value, out, prefix=""):
    """The keys of the result; a table's columns with their units."""
    outputs = value.get("outputs", {})
    out.append("json keys: " + ", ".join(sorted(value.keys())))
    for label in sorted(outputs):
        o = outputs[label]
        line = "json output %s: %s" % (label, ", ".join(sorted(o.keys())))
        v = o.get("value")
        if isinstance(v, dict) and "columns" in v:
            cols = []
            for name, c in v["columns"].items():
                extra = sorted(k for k in c.keys() if k not in ("values",))
                cols.append("%s[%s]{%s}" % (name, c.get("unit", ""), ",".join(extra)))
            line += "; axis %s; columns %s" % (v.get("axis"), " ".join(cols))
        if "unit" in o:
            line += "; unit " + str(o["unit"])
        if "axis_unit" in o:
            line += "; axis_unit " + str(o["axis_unit"])
        out.append(masked(line))
    for node in sorted(value.get("notes", {})):
        for n in value["notes"][node]:
            out.append(masked("json note %s: %s" % (node, n)))


def folder_files(folder, what, out):
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        out.append(masked("%s file %s" % (what, name)))
        if name.endswith(".csv"):
            with open(path, encoding="utf-8") as f:
                out.append(masked("%s csv %s: %s" % (what, name, f.readline().rstrip("\n"))))
        elif name.endswith(".dxf"):
            lines = open(path, encoding="utf-8", errors="replace").read().splitlines()
            layers = sorted({lines[i + 1].strip() for i in range(len(lines) - 1) if lines[i].strip() == "8"})
            out.append("%s dxf %s layers: %s" % (what, name, ", ".join(layers)))


TAGS = re.compile(r"<(h1|h2|th|td|caption|figcaption|p|li|text|title|tspan)\b[^>]*>(.*?)</\1>", re.S)


def page_words(page, out):
    text = open(page, encoding="utf-8").read()
    for tag, inner in TAGS.findall(text):
        words = html.unescape(re.sub(r"<[^>]+>", " ", inner))
        words = " ".join(words.split())
        if not re.search(r"[A-Za-z]", masked(words)):
            continue  # tic labels and numeric cells (1.5e-05 too: a number, not words)
        if tag == "p" and words.startswith("mechgraph "):
            continue  # version, SHA-1 and plugin versions
        out.append(masked("page %s: %s" % (tag, words)))


def scene_record(cli, scene, work):
    out = []
    cwd = os.path.dirname(os.path.abspath(scene))
    name = os.path.basename(scene)
    for line in run(cli, ["run", name], cwd).splitlines():
        out.append(masked("run: " + line.rstrip()))
    json_shape(json.loads(run(cli, ["run", "--json", name], cwd)), out)
    run_dir = os.path.join(work, "run")
    run(cli, ["run", "--out", run_dir, name], cwd)
    folder_files(run_dir, "run", out)
    report_dir = os.path.join(work, "report")
    run(cli, ["report", "--out", report_dir, name], cwd)
    folder_files(report_dir, "report", out)
    page_words(os.path.join(report_dir, "report.html"), out)
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    cli, scenes, golden = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
    update = "--update" in sys.argv[4:]
    differences = []
    os.makedirs(golden, exist_ok=True)
    found = sorted(glob.glob(os.path.join(scenes, "*.yaml")))
    if not found:
        sys.exit("presentation golden: no scene in %s: nothing would be compared" % scenes)
    # A golden whose scene is gone (renamed, removed) would no longer be compared with anything.
    stale = sorted(set(glob.glob(os.path.join(golden, "*.txt"))) -
                   {os.path.join(golden, os.path.basename(f)[:-5] + ".txt") for f in found})
    if stale and not update:
        sys.exit("presentation golden: goldens without a scene in %s: %s (remove them)" % (scenes, ", ".join(stale)))
    for scene in found:
        work = tempfile.mkdtemp(prefix="mechgraph-golden-")
        try:
            record = scene_record(cli, scene, work)
        finally:
            shutil.rmtree(work, ignore_errors=True)
        file = os.path.join(golden, os.path.basename(scene)[:-5] + ".txt")
        if update:
            with open(file, "w", encoding="utf-8") as f:
                f.write(record)
            continue
        expected = open(file, encoding="utf-8").read() if os.path.exists(file) else ""
        if expected != record:
            differences.extend(difflib.unified_diff(expected.splitlines(True), record.splitlines(True), file, "now"))
    if differences:
        sys.stdout.writelines(differences)
        sys.exit("presentation golden: what the host presents changed (above); if intended, rerun with --update "
                 "and say why in the commit")
    print("presentation golden: %d scenes %s" % (len(found), "updated" if update else "unchanged"))


if __name__ == "__main__":
    main()
