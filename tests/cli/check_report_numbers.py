#!/usr/bin/python3
"""Checks that a `mechgraph report` page prints the numbers `mechgraph run --json` gives for the same
scene: every cell of the page's first report table against the run's output, converted from SI to
the unit the row shows (read from the page), and the page's notes against the run's notes.
Usage: check_report_numbers.py REPORT_DIR RUN_JSON ROW=OUTPUT[,OUTPUT...] ...
  ROW is a row label of the first table; the OUTPUTs are node.port for its columns, in order."""
import html as htmllib
import json
import math
import re
import sys

# SI -> shown, for the units the checked rows use ("(cam)"/"(crank)" name the angle, not the scale).
DEG = 180.0 / math.pi
SCALE = {"mm": 1e3, "m": 1.0, "deg": DEG, "m/s": 1.0, "m/s^2": 1.0, "mm^2": 1e6, "mm^2*s": 1e6,
         "mm^2*deg": 1e6 * DEG, "N": 1.0, "N/mm": 1e-3, "g": 1e3, "Hz": 1.0, "MPa": 1e-6, "": 1.0,
         "mm/deg": 1e3 / DEG, "mm/deg^2": 1e3 / DEG ** 2}


def fail(message):
    sys.exit("report numbers: " + message)


def first_table(page):
    table = re.search(r"<table>(.*?)</table>", page, re.S)
    if not table:
        fail("the page has no report table")
    rows = {}
    for tr in re.findall(r"<tr>(.*?)</tr>", table.group(1), re.S):
        cells = [htmllib.unescape(c) for c in re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", tr, re.S)]
        if cells and cells[0]:
            rows[cells[0]] = cells[1:]
    return rows


def main():
    folder, run_json = sys.argv[1], sys.argv[2]
    page = open(folder + "/report.html", encoding="utf-8").read()
    run = json.load(open(run_json, encoding="utf-8"))
    rows = first_table(page)
    checked = 0
    for spec in sys.argv[3:]:
        label, outputs = spec.split("=", 1)
        if label not in rows:
            fail("no row %r in the page's first table (rows: %s)" % (label, ", ".join(rows)))
        unit = re.sub(r"\s*\((cam|crank)\)$", "", rows[label][0])
        if unit not in SCALE:
            fail("row %r shows the unit %r, which this checker does not know" % (label, unit))
        for shown, output in zip(rows[label][1:], outputs.split(",")):
            expected = run["outputs"][output]["value"] * SCALE[unit]
            value = float(shown)
            # The page prints 6 significant digits.
            if not abs(value - expected) <= 5e-6 * abs(expected) + 1e-12:
                fail("row %r, %s: the page shows %s %s, the run gives %.9g %s" % (label, output, shown, unit, expected, unit))
            checked += 1
    notes = [htmllib.unescape(n) for n in re.findall(r"<li>(.*?)</li>", page, re.S)]
    for node, texts in run["notes"].items():
        for text in texts:
            if node + ": " + text not in notes:
                fail("the run's note %r of %s is not on the page" % (text, node))
            checked += 1
    if checked == 0:
        fail("nothing compared")
    print("report numbers: %d values and notes equal to the run's" % checked)


main()
