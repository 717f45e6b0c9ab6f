#!/usr/bin/python3
"""Reads a contour DXF with ezdxf (an independent reader) and checks it against the CSV mechgraph
wrote beside it: the audit finds no errors, $INSUNITS is millimetres, every curve is one closed
polyline on its layer with the CSV's points (in mm) to 1e-9 mm; a layer given as LAYER:open is one
open polyline (a part drawn at rest). Usage: read_dxf.py DXF CSV LAYER[:open]..."""
import csv
import sys

import ezdxf


def main():
    dxf_file, csv_file = sys.argv[1], sys.argv[2]
    layers = [a.split(":")[0] for a in sys.argv[3:]]
    open_layers = {a.split(":")[0] for a in sys.argv[3:] if a.endswith(":open")}
    doc = ezdxf.readfile(dxf_file)
    auditor = doc.audit()
    if auditor.has_errors:
        sys.exit("audit errors: " + "; ".join(e.message for e in auditor.errors))
    if doc.header.get("$INSUNITS") != 4:
        sys.exit("$INSUNITS is %r, not 4 (mm)" % doc.header.get("$INSUNITS"))
    with open(csv_file) as f:
        rows = list(csv.reader(f))
    header = rows[0]
    polylines = {e.dxf.layer: e for e in doc.modelspace() if e.dxftype() in ("LWPOLYLINE", "POLYLINE")}
    if sorted(polylines) != sorted(layers):
        sys.exit("layers %s, expected %s" % (sorted(polylines), sorted(layers)))
    for layer in layers:
        prefix = "" if layer == "CONTOUR" else layer.lower() + "_"
        ix, iy = header.index(prefix + "x [mm]"), header.index(prefix + "y [mm]")
        expected = [(float(r[ix]), float(r[iy])) for r in rows[1:]]
        e = polylines[layer]
        if e.is_closed == (layer in open_layers):
            sys.exit(layer + (" is closed" if e.is_closed else " is not closed"))
        points = [(p[0], p[1]) for p in (e.get_points() if e.dxftype() == "LWPOLYLINE" else e.points())]
        if len(points) != len(expected):
            sys.exit("%s: %d points, the CSV has %d" % (layer, len(points), len(expected)))
        worst = max(max(abs(a[0] - b[0]), abs(a[1] - b[1])) for a, b in zip(points, expected))
        if worst > 1e-9:
            sys.exit("%s: a point differs from the CSV by %g mm" % (layer, worst))
        print("%s: %d points, %s, within %g mm of the CSV" % (layer, len(points), "open" if layer in open_layers else "closed", worst))


main()
