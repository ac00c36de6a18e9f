"""Print the acceptance-by-fill table of BENCHMARKS.md from a sweep's JSON, so the table's
numbers come from the sweep itself. (Not in the wheel.)

Usage: ``python -m benchmarks constructors --sweep --json SWEEP.json`` then
``python -m benchmarks.fill_table SWEEP.json``.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path


def fill_table(result: dict) -> str:
    """The Markdown table of ``by_fill`` and the practical-region line of one sweep."""
    bands = result["by_fill"]
    head = "| fill | " + " | ".join(k.replace("-", "–") for k in bands) + " |"
    rule = "|---" * (len(bands) + 1) + "|"
    row = "| accepted | " + " | ".join(bands.values()) + " |"
    ok, n = result["practical_accepted"], result["practical_specs"]
    total = f"{result['accepted']}/{result['specs']}"
    return f"{head}\n{rule}\n{row}\n\nAll specs {total}; below 0.6 L_max {ok}/{n} = {100 * ok / n:.1f} %."


if __name__ == "__main__":
    print(fill_table(json.loads(Path(sys.argv[1]).read_text(encoding="utf-8"))))
