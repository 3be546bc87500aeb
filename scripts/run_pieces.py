"""Reading a run's CSV outputs, and joining the pieces of one run continued by -restart
(imported by valve_report.py, valve_history.py and compare_runs.py)."""
import csv
import os


def read_rows(d, name="monitor.csv"):
    """Rows of DIR/NAME (or NAME.partial, a run still going or stopped) as floats; [] if absent."""
    for f in (name, name + ".partial"):
        p = os.path.join(d, f)
        if os.path.exists(p):
            return [{k: float(v) for k, v in r.items() if v not in ("", None)} for r in csv.DictReader(open(p))]
    return []


def stitch(pieces, key):
    """Rows of consecutive pieces; a piece's rows stop where the next piece starts (by key)."""
    out = []
    for i, rows in enumerate(pieces):
        nxt = next((p for p in pieces[i + 1:] if p), None)
        stop = nxt[0][key] if nxt else float("inf")
        out += [r for r in rows if r[key] < stop]
    return out
