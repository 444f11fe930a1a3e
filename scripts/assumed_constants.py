"""Print the README's table of assumed constants from the paper configs (single source).

    .venv/bin/python scripts/assumed_constants.py > /tmp/assumed.md
"""
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "src"))

import yaml  # noqa: E402

from mechrepro.config import load_paper  # noqa: E402


def main():
    papers = yaml.safe_load((ROOT / "config/config.yaml").read_text())["papers"]
    print("| paper | parameter | value | unit | plausible range / calibration | why |")
    print("|---|---|---|---|---|---|")
    for paper in papers:
        cfg = load_paper(ROOT / "config" / "papers" / f"{paper}.yaml")
        for name, p in cfg.assumed().items():
            why = " ".join(str(p["why"]).split()).replace("|", "/")
            how = (f"{p['range'][0]} … {p['range'][1]}" if "range" in p else
                   f"calibrated on `{p['calibrated_on']}`" if "calibrated_on" in p else
                   "numerical setting" if p.get("numerical") else "")
            print(f"| {paper} | `{name}` | {p['value']} | {p['unit']} | {how} | {why} |")


if __name__ == "__main__":
    main()
