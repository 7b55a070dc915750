"""Write the golden JSON files anew: ``python tests/golden/regenerate.py [CASE ...]``."""

from __future__ import annotations

import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from cases import DATA, cases, run  # noqa: E402


def main(names: list[str]) -> None:
    DATA.mkdir(exist_ok=True)
    table = cases()
    for name in names or sorted(table):
        value = run(table[name])
        (DATA / f"{name}.json").write_text(json.dumps(value, indent=1, sort_keys=True) + "\n")
        print(f"wrote {name}")


if __name__ == "__main__":
    main(sys.argv[1:])
