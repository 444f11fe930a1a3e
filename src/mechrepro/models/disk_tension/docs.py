"""The blocks of docs/disk_tension.md, numbers from a run, not typed (issue 29), filled by
``.venv/bin/python -m mechrepro.docs docs/disk_tension.md results`` from the default
profile's ``results/disk_tension``."""
from __future__ import annotations

from pathlib import Path

from mechrepro.docs import markdown as _md, table_rows as _rows


def cold_warm(root: Path) -> str:
    return _md(["scene", "effect", "warm [s]", "cold [s]"], [
        [r["scene"], r["effect"], f"{float(r['warm_s']):.1e}", f"{float(r['cold_s']):.1e}"]
        for r in _rows(root / "tables" / "effect_cold_warm.csv")])


def _table(path: Path, fmt=lambda c, v: v) -> str:
    rows = _rows(path)
    return _md(list(rows[0]), [[fmt(c, r[c]) for c in rows[0]] for r in rows])


def identifiability(root: Path) -> str:
    def num(c, v):
        try:
            return f"{float(v):.3g}" if c not in ("data", "reading", "inplane_bc") else v
        except ValueError:
            return v
    return "\n\n".join([_table(root / "tables" / "identifiability.csv"),
                        _table(root / "tables" / "identifiability_readings.csv", num)])


#: the design table's columns: heading and format (tables/design_map.csv)
DESIGN = {"r_f_mm": ("r_f [mm]", ".0f"), "rim_temperature_rise_degc": ("rim ΔT [°C]", ".0f"),
          "buckling_margin": ("m", "g"), "r_c_opt_mm": ("r_c* [mm]", ".0f"),
          "amplitude_opt_degc": ("A* [°C]", ".0f"), "binds": ("binds", ""),
          "lowest_mode_nd": ("N_d", ""), "critical_speed_opt_rpm": ("Ω_c* [rpm]", ".0f"),
          "gain_vs_untensioned": ("vs untensioned", "+.1%"),
          "gain_vs_paper": ("vs r_c 65, A 50", "+.1%"), "f_ratio_nd0": ("f̃/f N_d=0", ".2f"),
          "f_ratio_nd1": ("f̃/f N_d=1", ".2f")}


def design_map(root: Path) -> str:
    """The design table: per flange radius, cutting heat and buckling margin."""
    def cell(r, k, fmt):
        text = format(float(r[k]), fmt) if fmt else r[k]
        return text + (" (stated)" if k == "buckling_margin" and r["stated"] == "True" else "")
    return _md([h for h, _ in DESIGN.values()],
               [[cell(r, k, f) for k, (_, f) in DESIGN.items()]
                for r in _rows(root / "tables" / "design_map.csv")])


def targets(root: Path) -> str:
    """The accuracy targets: what was asked, chosen, estimated and verified."""
    return _md(["scene", "quantity", "asked (abs.)", "elements chosen", "estimated error",
                "verified error (vs exact)", "fixed default: elements, error"], [
        [f"`{r['run']}`", f"`{r['quantity']}`", f"{float(r['requested']):.1e}",
         f"{float(r['knob_value']):.0f}", f"{float(r['estimated_error']):.2e}",
         f"{float(r['verified_error']):.2e}",
         f"{float(r['default_knob_value']):.0f}, {float(r['default_error']):.1e}"]
        for r in _rows(root / "tables" / "accuracy_targets.csv")])


BLOCKS = {"cold_warm": cold_warm, "identifiability": identifiability, "targets": targets,
          "design_map": design_map}

