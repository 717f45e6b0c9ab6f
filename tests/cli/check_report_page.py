#!/usr/bin/python3
"""Checks a `mechgraph report` page the way a reader meets it: opened in a real browser (Debian's
headless chromium) it renders (the screenshot is not blank) without console errors, it loads
nothing from outside (every plot inline), it holds one inline SVG per plot CSV, and every CSV it
names is in the folder. Usage: check_report_page.py DIR MIN_PLOTS"""
import glob
import os
import re
import subprocess
import sys

from PIL import Image


def fail(message):
    sys.exit("report page: " + message)


def main():
    folder, min_plots = sys.argv[1], int(sys.argv[2])
    page = os.path.join(folder, "report.html")
    html = open(page, encoding="utf-8").read()
    # Self-contained: no src/href/url() that would fetch anything.
    external = re.findall(r'(?:src|href)\s*=\s*"([^"#][^"]*)"|url\(([^)#][^)]*)\)', html)
    if external:
        fail("refers to outside resources: %s" % external[:3])
    if "<script" in html:
        fail("carries a script (gnuplot's mouse script?)")
    plots = sorted(glob.glob(os.path.join(folder, "plot_*.csv")))
    svgs = html.count("<svg")
    if len(plots) < min_plots or svgs != len(plots):
        fail("%d inline SVG plots for %d plot CSVs (at least %d expected)" % (svgs, len(plots), min_plots))
    for name in re.findall(r"data: ([^<]+\.csv)", html):
        if not os.path.exists(os.path.join(folder, name.strip())):
            fail("names %s, which is not in the folder" % name)
    for csv in plots:
        lines = open(csv).read().splitlines()
        if len(lines) < 2:
            fail(csv + " has no data")

    shot = os.path.join(folder, "..", os.path.basename(folder.rstrip("/")) + ".png")
    run = subprocess.run(
        ["timeout", "120", "chromium", "--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
         "--window-size=1000,2400", "--enable-logging=stderr", "--v=0", "--screenshot=" + shot,
         "file://" + os.path.abspath(page)],
        capture_output=True, text=True)
    console = [line for line in run.stderr.splitlines() if ":CONSOLE" in line or "Uncaught" in line]
    if console:
        fail("console messages: " + " | ".join(console[:3]))
    if not os.path.exists(shot):
        fail("chromium took no screenshot (exit %d): %s" % (run.returncode, run.stderr[-500:]))
    image = Image.open(shot).convert("RGB")
    pixels = image.getdata()
    inked = sum(1 for p in pixels if p != (255, 255, 255))
    colours = len(set(pixels))
    share = inked / float(image.size[0] * image.size[1])
    if share < 0.02 or colours < 20:
        fail("the screenshot is (nearly) blank: %.3f of it inked, %d colours" % (share, colours))
    print("report page: %d plots inline, no outside resources, rendered (%.1f %% inked, %d colours), no console errors"
          % (svgs, 100 * share, colours))


main()
