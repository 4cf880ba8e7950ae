"""
Speed against accuracy
======================

Every method on the same random instances (``make bench`` measures them and writes
docs/bench/results.csv): the median time per solve against the share of reference modes
each method found, one point per method and link count.
"""

import csv
import statistics
from pathlib import Path

import matplotlib.pyplot as plt

RESULTS = Path(__file__).resolve().parents[1] / "bench" / "results.csv"
with RESULTS.open(encoding="utf-8") as handle:
    rows = list(csv.DictReader(handle))
print(len(rows), "runs;", "columns:", ", ".join(rows[0]))

figure, axis = plt.subplots(figsize=(7, 4.5))
methods = sorted({row["method"] for row in rows})
for number, method in enumerate(methods):
    for links in sorted({int(row["links"]) for row in rows if row["method"] == method}):
        mine = [row for row in rows if row["method"] == method and int(row["links"]) == links
                and row["status"] == "ok"]
        if not mine:
            continue
        seconds = statistics.median(float(row["median_time_s"]) for row in mine)
        found = sum(int(row["found"]) for row in mine) / max(1, sum(int(row["reference_modes"]) for row in mine))
        axis.scatter(seconds, found, color=f"C{number}", label=method if links == 3 or len(mine) and
                     links == min(int(r["links"]) for r in rows if r["method"] == method) else None)
        axis.annotate(str(links), (seconds, found), fontsize=7, xytext=(3, 3), textcoords="offset points")
axis.set_xscale("log")
axis.set_xlabel("median seconds per solve (the label: links)")
axis.set_ylabel("share of the reference modes found")
axis.legend(fontsize=8)
plt.show()
