"""Make a moved or copied project's .venv work where it now is.

A venv holds absolute paths: the shebang of every console script (.venv/bin/snakemake,
.venv/bin/mechrepro, pip, ...) names the old .venv/bin/python, and the editable install of
mechrepro (a .pth file) names the old src/.  After `mv`/`cp -r` of the project with its
.venv, those scripts fail ("required file not found") or, worse, import the old copy's
code while it still exists.  `.venv/bin/python -m snakemake` and `make` keep working (the
interpreter itself is relative to the venv, the workflow puts its own src/ first), but run

    python3 scripts/relocate_venv.py          # in the moved project

to rewrite those paths to this project's (idempotent; prints what it changed).
"""
from __future__ import annotations

import sys
from pathlib import Path


def relocate(project: Path) -> list[str]:
    venv = (project / ".venv").absolute()
    if not (venv / "pyvenv.cfg").exists():
        raise SystemExit(f"{venv}: not a venv (run `make venv` to create it)")
    changed = []
    python = venv / "bin" / "python3"
    for script in sorted((venv / "bin").iterdir()):
        if script.is_symlink() or not script.is_file():
            continue
        data = script.read_bytes()
        if not data.startswith(b"#!") or b"/.venv/bin/python" not in data.split(b"\n", 1)[0]:
            continue
        first, rest = data.split(b"\n", 1)
        new = b"#!" + str(python).encode()
        if first != new:
            script.write_bytes(new + b"\n" + rest)
            changed.append(f"{script.relative_to(project)}: shebang -> {python}")
    for pth in venv.glob("lib/python*/site-packages/__editable__*mechrepro*.pth"):
        src = str((project / "src").absolute())
        if pth.read_text().strip() != src:
            pth.write_text(src + "\n")
            changed.append(f"{pth.relative_to(project)}: mechrepro -> {src}")
    return changed


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        raise SystemExit(0)
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent
    lines = relocate(root)
    print("\n".join(lines) if lines else f"{root / '.venv'}: already relocated")
