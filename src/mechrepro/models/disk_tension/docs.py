"""The blocks of docs/disk_tension.md, numbers from a run, not typed (issue 29), filled by
``.venv/bin/python -m mechrepro.docs docs/disk_tension.md results`` from the default
profile's ``results/disk_tension``."""
from __future__ import annotations

import json
from pathlib import Path

from mechrepro.docs import number as _g, table_rows as _rows


def _md(header, rows) -> str:
    """A markdown table."""
    return "\n".join(["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
                     + ["| " + " | ".join(map(str, r)) + " |" for r in rows])


def counts(root: Path) -> str:
    c = json.loads((root / "claim.json").read_text())
    ind = c["independent"]
    return (f"Claim **{c['claim']}**. Independent: **{ind['pass']} pass, {ind['fail']} fail, "
            f"{ind['inconclusive']} inconclusive, {ind['not_converged']} not converged** "
            f"(counts by evidence class: "
            + "; ".join(f"{k} " + ", ".join(f"{n} {s}" for s, n in sorted(v.items()))
                        for k, v in sorted(c["counts"].items())) + ").")


def verdicts(root: Path, evidence=("independent", "determined")) -> str:
    """Every pass/fail/inconclusive row of ``evidence``, with its error bar and rivals."""
    return _md(["row", "evidence", "paper", "ours", "± error", "verdict", "rivals"], [
        [f"`{r['quantity']}`", r["evidence"], _g(r["paper_value"]), _g(r["reproduced_value"], 6),
         _g(r["error_estimate"], 2), r["status"], r["rivals"] or "—"]
        for r in _rows(root / "tables" / "validation.csv")
        if r["evidence"] in evidence and r["status"] != "info"])


def construction(root: Path) -> str:
    """The independent passes the framework demoted: no rival fails them."""
    rows = [r for r in _rows(root / "tables" / "validation.csv")
            if r["evidence"] == "not_discriminating"]
    return "\n".join(f"* `{r['quantity']}`: {r['status']}, rivals {r['rivals'] or 'none'}"
                     for r in rows)


def cost(root: Path) -> str:
    rows = _rows(root / "tables" / "cost_of_accuracy.csv")
    out = []
    for acc, q in dict.fromkeys((r["accuracy"], r["quantity"]) for r in rows):
        pts = [r for r in rows if r["accuracy"] == acc and r["quantity"] == q]
        out.append([acc, q, pts[0]["reference"], " / ".join(r["knob_value"] for r in pts),
                    " / ".join(f"{float(r['error']):.1e}" for r in pts),
                    " / ".join(f"{float(r['time_s']):.2g}" for r in pts),
                    f"{float(pts[0]['observed_order']):.2f}"])
    return _md(["entry", "quantity", "reference", "knob values", "errors", "times [s]", "order"],
               out)


def cold_warm(root: Path) -> str:
    return _md(["scene", "effect", "warm [s]", "cold [s]"], [
        [r["scene"], r["effect"], f"{float(r['warm_s']):.1e}", f"{float(r['cold_s']):.1e}"]
        for r in _rows(root / "tables" / "effect_cold_warm.csv")])


def notes(root: Path, quantities) -> str:
    by = {r["quantity"]: r for r in _rows(root / "tables" / "validation.csv")}
    return "\n".join(f"* `{q}` = {_g(by[q]['reproduced_value'], 6)} {by[q]['unit']}: "
                     f"{by[q]['note']}" for q in quantities if q in by)


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


BLOCKS = {
    "counts": counts,
    "verdicts": verdicts,
    "construction": construction,
    "cost": cost,
    "cold_warm": cold_warm,
    "identifiability": identifiability,
    "targets": targets,
    "design_map": design_map,
    **{f"{block}_notes": (lambda root, q=q.split(): notes(root, q)) for block, q in {
        "calibration": "f_unrolled_nd4_rf25 table1_diag_nd4 inplane_bc_evidence_free_disk "
                       "inplane_bc_evidence_clamped delta_f_eigen_nd4_handbook_alpha",
        "explanation": "table2_nd3_mode_change_at_buckling table2_nd3_pair_rotation_deg "
                       "paper_mesh_symmetry_order rayleigh_cap_on_delta_f_eigen",
        "critical_speed": "critical_speed_untensioned_min critical_speed_best_rc "
                          "critical_speed_vs_southwell",
        "design": "design_map_optimum_rc design_map_gain_over_paper_point",
        "beyond": "slotted_optimal_rc_nd3 slotted_optimal_rc_nd4 "
                  "buckling_flag_matches_critical_load eq9_speedup_over_eigen"}.items()},
}

