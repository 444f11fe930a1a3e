"""The blocks of docs/disk_tension.md (issue 29: numbers from a run, not typed), made from
``results/disk_tension`` (validation.csv, claim.json, cost_of_accuracy.csv,
effect_cold_warm.csv, identifiability.csv) and filled by :mod:`mechrepro.docs`::

    .venv/bin/python -m mechrepro.docs docs/disk_tension.md results

Run it on the default profile's results after the last change; tests/test_disk_tension_docs.py
checks the verdict table against the committed default reference.
"""
from __future__ import annotations

import json
from pathlib import Path

from mechrepro.docs import number, table_rows

# one formatter for every paper page (mechrepro.docs)
_rows, _g = table_rows, number


def counts(root: Path) -> str:
    c = json.loads((root / "claim.json").read_text())
    ind = c["independent"]
    return (f"Claim **{c['claim']}**. Independent: **{ind['pass']} pass, {ind['fail']} fail, "
            f"{ind['inconclusive']} inconclusive, {ind['not_converged']} not converged** "
            f"(counts by evidence class: "
            + "; ".join(f"{k} " + ", ".join(f"{n} {s}" for s, n in sorted(v.items()))
                        for k, v in sorted(c["counts"].items())) + ").")


def verdicts(root: Path, evidence=("independent", "determined")) -> str:
    """Every pass/fail/inconclusive row of the given evidence classes, with its error bar
    and its rivals' outcomes."""
    out = ["| row | evidence | paper | ours | ± error | verdict | rivals |",
           "|---|---|---|---|---|---|---|"]
    for r in _rows(root / "tables" / "validation.csv"):
        if r["evidence"] in evidence and r["status"] not in ("info",):
            out.append(f"| `{r['quantity']}` | {r['evidence']} | {_g(r['paper_value'])} | "
                       f"{_g(r['reproduced_value'], 6)} | {_g(r['error_estimate'], 2)} | "
                       f"{r['status']} | {r['rivals'] or '—'} |")
    return "\n".join(out)


def construction(root: Path) -> str:
    """The independent passes the framework demoted: no rival fails them."""
    rows = [r for r in _rows(root / "tables" / "validation.csv")
            if r["evidence"] == "not_discriminating"]
    return "\n".join(f"* `{r['quantity']}`: {r['status']}, rivals {r['rivals'] or 'none'}"
                     for r in rows)


def cost(root: Path) -> str:
    rows = _rows(root / "tables" / "cost_of_accuracy.csv")
    out = ["| entry | quantity | reference | knob values | errors | times [s] | order |",
           "|---|---|---|---|---|---|---|"]
    keys = list(dict.fromkeys((r["accuracy"], r["quantity"]) for r in rows))
    for acc, q in keys:
        pts = [r for r in rows if r["accuracy"] == acc and r["quantity"] == q]
        out.append(f"| {acc} | {q} | {pts[0]['reference']} | "
                   + " / ".join(r["knob_value"] for r in pts) + " | "
                   + " / ".join(f"{float(r['error']):.1e}" for r in pts) + " | "
                   + " / ".join(f"{float(r['time_s']):.2g}" for r in pts) + " | "
                   + f"{float(pts[0]['observed_order']):.2f} |")
    return "\n".join(out)


def cold_warm(root: Path) -> str:
    out = ["| scene | effect | warm [s] | cold [s] |", "|---|---|---|---|"]
    for r in _rows(root / "tables" / "effect_cold_warm.csv"):
        out.append(f"| {r['scene']} | {r['effect']} | {float(r['warm_s']):.1e} | "
                   f"{float(r['cold_s']):.1e} |")
    return "\n".join(out)


def notes(root: Path, quantities) -> str:
    by = {r["quantity"]: r for r in _rows(root / "tables" / "validation.csv")}
    return "\n".join(f"* `{q}` = {_g(by[q]['reproduced_value'], 6)} {by[q]['unit']}: "
                     f"{by[q]['note']}" for q in quantities if q in by)


def _table(path: Path, fmt=lambda c, v: v) -> list[str]:
    rows = _rows(path)
    cols = list(rows[0])
    out = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    return out + ["| " + " | ".join(fmt(c, r[c]) for c in cols) + " |" for r in rows]


def identifiability(root: Path) -> str:
    def num(c, v):
        try:
            return f"{float(v):.3g}" if c not in ("data", "reading", "inplane_bc") else v
        except ValueError:
            return v
    return "\n".join(_table(root / "tables" / "identifiability.csv") + [""]
                     + _table(root / "tables" / "identifiability_readings.csv", num))


def design_map(root: Path) -> str:
    """The design table (tables/design_map.csv): per flange radius, cutting heat and buckling
    margin."""
    keep = {"r_f_mm": "r_f [mm]", "rim_temperature_rise_degc": "rim ΔT [°C]",
            "buckling_margin": "m", "r_c_opt_mm": "r_c* [mm]",
            "amplitude_opt_degc": "A* [°C]", "binds": "binds", "lowest_mode_nd": "N_d",
            "critical_speed_opt_rpm": "Ω_c* [rpm]", "gain_vs_untensioned": "vs untensioned",
            "gain_vs_paper": "vs r_c 65, A 50", "f_ratio_nd0": "f̃/f N_d=0",
            "f_ratio_nd1": "f̃/f N_d=1"}
    out = ["| " + " | ".join(keep.values()) + " |", "|" + "---|" * len(keep)]
    for r in _rows(root / "tables" / "design_map.csv"):
        cell = {k: r[k] for k in keep}
        for k in ("r_f_mm", "rim_temperature_rise_degc", "r_c_opt_mm", "amplitude_opt_degc",
                  "critical_speed_opt_rpm"):
            cell[k] = f"{float(r[k]):.0f}"
        for k in ("gain_vs_untensioned", "gain_vs_paper"):
            cell[k] = f"{float(r[k]):+.1%}"
        for k in ("f_ratio_nd0", "f_ratio_nd1"):
            cell[k] = f"{float(r[k]):.2f}"
        cell["buckling_margin"] = f"{float(r['buckling_margin']):g}" + (
            " (stated)" if r["stated"] == "True" else "")
        out.append("| " + " | ".join(cell.values()) + " |")
    return "\n".join(out)


def targets(root: Path) -> str:
    """The accuracy targets (framework table accuracy_targets.csv): what was asked, chosen,
    estimated and verified."""
    rows = _rows(root / "tables" / "accuracy_targets.csv")
    out = ["| scene | quantity | asked (abs.) | elements chosen | estimated error | verified error "
           "(vs exact) | fixed default: elements, error |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| `{r['run']}` | `{r['quantity']}` | {float(r['requested']):.1e} | "
                   f"{float(r['knob_value']):.0f} | {float(r['estimated_error']):.2e} | "
                   f"{float(r['verified_error']):.2e} | {float(r['default_knob_value']):.0f}, "
                   f"{float(r['default_error']):.1e} |")
    return "\n".join(out)


BLOCKS = {
    "counts": counts,
    "verdicts": verdicts,
    "construction": construction,
    "cost": cost,
    "cold_warm": cold_warm,
    "identifiability": identifiability,
    "targets": targets,
    "design_map": design_map,
    "calibration_notes": lambda root: notes(root, ["f_unrolled_nd4_rf25", "table1_diag_nd4",
                                                   "inplane_bc_evidence_free_disk",
                                                   "inplane_bc_evidence_clamped",
                                                   "delta_f_eigen_nd4_handbook_alpha"]),
    "explanation_notes": lambda root: notes(root, ["table2_nd3_mode_change_at_buckling",
                                                   "table2_nd3_pair_rotation_deg",
                                                   "paper_mesh_symmetry_order",
                                                   "rayleigh_cap_on_delta_f_eigen"]),
    "critical_speed_notes": lambda root: notes(root, ["critical_speed_untensioned_min",
                                                      "critical_speed_best_rc",
                                                      "critical_speed_vs_southwell"]),
    "design_notes": lambda root: notes(root, ["design_map_optimum_rc",
                                              "design_map_gain_over_paper_point"]),
    "beyond_notes": lambda root: notes(root, ["slotted_optimal_rc_nd3", "slotted_optimal_rc_nd4",
                                              "buckling_flag_matches_critical_load",
                                              "eq9_speedup_over_eigen"]),
}

