"""
Speed against accuracy
======================

Every method on the same instances (``make bench`` solves them and writes
docs/bench/results.csv, one row per method and instance): the median time per solve
against the share of the reference modes found, and against the largest residual, one
point per method and link count. Drawn here from the committed rows by the benchmark's
own chart (``bench/speed_vs_accuracy.py``).
"""

import csv
import io
import sys
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
from _paths import REPOSITORY

sys.path.insert(0, str(REPOSITORY / "bench"))
from speed_vs_accuracy import chart, summary  # noqa: E402

with (REPOSITORY / "docs" / "bench" / "results.csv").open(newline="", encoding="utf-8") as handle:
    rows = list(csv.DictReader(handle))
print(len(rows), "runs of", len({row["method"] for row in rows}), "methods on",
      len({row["instance"] for row in rows}), "linkages")

with tempfile.TemporaryDirectory() as folder:
    path = Path(folder) / "chart.png"
    chart(summary(rows), path, "Assembly modes: the project's backends vs baselines")
    picture = plt.imread(io.BytesIO(path.read_bytes()))
figure, axis = plt.subplots(figsize=(11, 5.5))
axis.imshow(picture)
axis.set_axis_off()
plt.show()
