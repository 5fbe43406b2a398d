#!/usr/bin/python3
"""Checks that `fastron demo`'s model.fastron scores its test_points.csv as the demo's last tick did.

Usage: check_demo_model.py FASTRON DEMO_DIR; exits non-zero with a message naming the mismatch.
The demo saves the model its last tick planned on and scored, beside that tick's FCL-labelled test
configurations: `fastron eval` on the pair must give the tick's accuracy and support count again.
"""
import csv
import re
import subprocess
import sys
from pathlib import Path


def fail(message):
    sys.exit(f"check_demo_model: {message}")


fastron, out = sys.argv[1], Path(sys.argv[2])
with open(out / "ticks.csv", newline="") as f:
    rows = list(csv.DictReader(f))
if not rows:
    fail("ticks.csv has no rows")
last = rows[-1]
result = subprocess.run(
    [fastron, "eval", "--model", str(out / "model.fastron"), "--robot", "baxter", "--data",
     str(out / "test_points.csv")],
    capture_output=True, text=True, check=False)
if result.returncode != 0:
    fail(f"fastron eval exited with {result.returncode}: {result.stderr.strip()}")
accuracy = re.search(r"^accuracy +([0-9.]+)$", result.stdout, re.MULTILINE)
support = re.search(r"(\d+) support points", result.stdout)
if not accuracy or not support:
    fail(f"no accuracy or support count in fastron eval's output:\n{result.stdout}")
if abs(float(accuracy.group(1)) - float(last["accuracy"])) > 5e-5:
    fail(f"model.fastron scores accuracy {accuracy.group(1)} on test_points.csv, the last tick "
         f"(tick {last['tick']}) reported {last['accuracy']}")
if int(support.group(1)) != round(float(last["support"])):
    fail(f"model.fastron has {support.group(1)} support points, the last tick's model "
         f"{last['support']}")
print(f"model.fastron: accuracy {accuracy.group(1)} and |S| {support.group(1)}, as tick "
      f"{last['tick']}")
