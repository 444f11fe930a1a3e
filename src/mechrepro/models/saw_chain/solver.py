"""Compose the saw_chain effects named by a scene into one xarray Dataset."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from mechrepro.timing import time_call
from mechrepro.effects import EffectRegistry

from .difference import (backward_differences, check_roundoff, roundoff_limit,
                         roundoff_load, truncation_load)
from .geometry import check_meshing, initial_points, pitch_radius, stage_angles
from .kinematics import stage_derivatives, stage_jerks, stage_positions
from .loads import dynamic_load, textbook_velocity_load, tight_side_mass

EFFECTS = EffectRegistry("saw_chain")


@dataclass(frozen=True)
class Chain:
    """Geometry, masses and the time grid of one period (2K steps, Eqs. 5-6)."""
    p1: float
    p2: float
    z: int
    omega: float
    m_L: float
    m_C: float
    M: int
    N: int
    K: int

    @property
    def R(self):
        return pitch_radius(self.p1, self.p2, self.z)

    @property
    def Tx(self):
        return initial_points(self.p1, self.p2)["T"]

    @property
    def phases(self):
        return stage_angles(self.p1, self.p2, self.R)

    @property
    def m_tight(self):
        return tight_side_mass(self.M, self.N, self.m_L, self.m_C)

    def stages(self):
        """(lead-link length, link mass, local angles phi_i, i = 0..K) for each stage."""
        phi1, phi2 = self.phases
        return [(self.p2, self.m_C, np.linspace(0.0, phi1, self.K + 1)),
                (self.p1, self.m_L, np.linspace(0.0, phi2 - phi1, self.K + 1))]

    def stage_times(self):
        """Durations t1 and t2 - t1 of the two stages [s]."""
        phi1, phi2 = self.phases
        return phi1 / self.omega, (phi2 - phi1) / self.omega

    def load_jerk_max(self, n=129):
        """max |dF_dx/dt| of the exact load in each stage [N/s].

        The jerk is smooth within a stage, so a fixed grid of ``n`` angles (ends
        included) gives its maximum to ~1e-6, independently of K.
        """
        out = []
        for L, m_link, phi in self.stages():
            j = stage_jerks(np.linspace(0.0, phi[-1], n), self.R, L, self.omega)
            out.append(float(np.max(np.abs(m_link * j["mid_jx"] + self.m_tight * j["trail_jx"]))))
        return out

    def roundoff_mass(self):
        """Mass multiplying second differences in one load sample (tight side + seating link)."""
        return self.m_tight + max(self.m_L, self.m_C)

    def roundoff_limit(self):
        """K beyond which round-off dominates the loads (see :mod:`.difference`)."""
        return roundoff_limit(self.stage_times(), self.load_jerk_max(), self.Tx + self.R,
                              self.roundoff_mass())

    def time(self):
        """Sample times: t = 0, then K steps of each stage [s]."""
        phi1, phi2 = self.phases
        return np.concatenate([np.linspace(0.0, phi1, self.K + 1),
                               np.linspace(phi1, phi2, self.K + 1)[1:]]) / self.omega


def chain_from_run(run: dict) -> Chain:
    p = run["parameters"]
    check_meshing(p["tie_strap_pitch"], p["drive_link_pitch"], p["teeth"])  # before int()
    return Chain(p1=p["tie_strap_pitch"], p2=p["drive_link_pitch"], z=int(p["teeth"]),
                 omega=p["sprocket_speed"], m_L=p["tie_strap_mass"],
                 m_C=p["drive_link_mass"], M=int(p["tie_straps_tight_side"]),
                 N=int(p["drive_links_tight_side"]), K=int(run["resolution"]["K"]))


def _join(stage1, stage2):
    """One period from two stages: stage 2's index 0 duplicates t1 and is dropped."""
    return np.concatenate([stage1, stage2[1:]])


@EFFECTS.register("difference_method")
def difference_method(chain: Chain, options: dict) -> dict:
    """Tight-side velocity and dynamic load by the paper's difference method."""
    R, w, K = chain.R, chain.omega, chain.K
    limit = chain.roundoff_limit()
    dominated = check_roundoff(K, limit, options.get("beyond_roundoff_limit", False))
    dt_min = min(chain.stage_times()) / K
    n = 2 * K + 1
    vx, ax, Fx, Fy = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    # initial values (Sec. 3.3): O2 and A1 move with R omega along x, at rest in y
    v_trail, a_trail, v_mid, a_mid = R * w, 0.0, R * w, 0.0
    for stage, (L, m_link, phi) in enumerate(chain.stages()):
        pos = stage_positions(phi, R, L, chain.Tx)
        dt = (phi[1] - phi[0]) / w
        vt, at = backward_differences(pos["trail_x"], dt, v_trail, a_trail)
        _, amx = backward_differences(pos["mid_x"], dt, v_mid, a_mid)
        _, amy = backward_differences(pos["mid_y"], dt, 0.0, 0.0)
        Fsx, Fsy = dynamic_load(m_link, amx, amy, chain.m_tight, at)
        # stage 2's index 0 repeats t1 (already stored by stage 1)
        dst = slice(0, K + 1) if stage == 0 else slice(K + 1, n)
        src = slice(0, K + 1) if stage == 0 else slice(1, K + 1)
        vx[dst], ax[dst], Fx[dst], Fy[dst] = vt[src], at[src], Fsx[src], Fsy[src]
        # stage 2 starts with O2's values at t1 for both A2 and O3 (Sec. 3.3 (2))
        v_trail = v_mid = vt[-1]
        a_trail = a_mid = at[-1]
    return {
        "tight_side_velocity": (vx, "m/s", "tight-side velocity, difference method (Eqs. 12, 18)"),
        "tight_side_acceleration": (ax, "m/s2", "tight-side acceleration, difference method (Eqs. 13, 19)"),
        "dynamic_load_x": (Fx, "N", "total tight-side dynamic load x, difference method (Eqs. 16, 22)"),
        "dynamic_load_y": (Fy, "N", "dynamic load y of the seating link, difference method (Eqs. 16, 22)"),
        "roundoff_load_bound": (roundoff_load(dt_min, chain.Tx + R, chain.roundoff_mass()), "N",
                                "bound of round-off in a load sample (second backward difference)"),
        "truncation_load_estimate": (max(truncation_load(T / K, J) for T, J in zip(
            chain.stage_times(), chain.load_jerk_max())), "N",
            "leading truncation error of a load sample, dt max|dF/dt|"),
        "roundoff_limit_K": (limit, "1", "K beyond which round-off exceeds truncation (refused unless allowed)"),
        "roundoff_dominated": (int(dominated), "1", "1 if K is beyond the round-off limit (allowed for the study)"),
    }


@EFFECTS.register("exact_reference")
def exact_reference(chain: Chain, options: dict) -> dict:
    """Analytic derivatives of the closed-form positions: the converged reference."""
    R, w = chain.R, chain.omega
    out = {"vx": [], "ax": [], "Fx": [], "Fy": []}
    for L, m_link, phi in chain.stages():
        d = stage_derivatives(phi, R, L, w)
        Fx, Fy = dynamic_load(m_link, d["mid_ax"], d["mid_ay"], chain.m_tight, d["trail_ax"])
        out["vx"].append(d["trail_vx"]); out["ax"].append(d["trail_ax"])
        out["Fx"].append(Fx); out["Fy"].append(Fy)
    return {
        "tight_side_velocity_exact": (_join(*out["vx"]), "m/s", "tight-side velocity, exact derivative"),
        "tight_side_acceleration_exact": (_join(*out["ax"]), "m/s2", "tight-side acceleration, exact derivative"),
        "dynamic_load_x_exact": (_join(*out["Fx"]), "N", "total tight-side dynamic load x, exact derivative"),
        "dynamic_load_y_exact": (_join(*out["Fy"]), "N", "dynamic load y of the seating link, exact derivative"),
    }


@EFFECTS.register("textbook")
def textbook(chain: Chain, options: dict, theta: float = 0.0, mass: float = 0.0) -> dict:
    """Textbook model, Eq. (23), on the same time grid."""
    v, a, F = textbook_velocity_load(chain.time(), chain.R, chain.omega, theta, mass)
    return {
        "tight_side_velocity_textbook": (v, "m/s", "tight-side velocity, textbook Eq. (23)"),
        "tight_side_acceleration_textbook": (a, "m/s2", "tight-side acceleration, textbook Eq. (23)"),
        "dynamic_load_x_textbook": (F, "N", "dynamic load, textbook Eq. (23)"),
    }


def stage_switch_index(K):
    """Index of the first sample of stage 2, t1 + dt (Sec. 3.3 (2)).

    Eqs. (18)-(19) start stage 2 from O2's stage-1 values at t1, so its first
    acceleration is a second difference across t1, where the exact acceleration jumps
    (the seated drive link stops, the tie strap starts seating).  That sample tends to
    the mean of the one-sided values, not to either, and its error does not shrink with K.
    """
    return K + 1


def _summaries(ds: xr.Dataset, K: int) -> dict:
    """Scalars a study stacks: ranges of each model and errors against the reference.

    Pointwise errors exclude the stage-switch sample (reported on its own), so that they
    show the method's order and its round-off floor; errors of the extremes show what
    the paper's quoted ranges see.
    """
    out = {}
    for suffix, label in (("", "difference method"), ("_exact", "exact"), ("_textbook", "textbook")):
        for q, unit in (("tight_side_velocity", "m/s"), ("dynamic_load_x", "N")):
            name = q + suffix
            if name in ds:
                out[f"{name}_min"] = (float(ds[name].min()), unit, f"minimum of {q}, {label}")
                out[f"{name}_max"] = (float(ds[name].max()), unit, f"maximum of {q}, {label}")
    if "tight_side_velocity" in ds and "tight_side_velocity_exact" in ds:
        switch = stage_switch_index(K)
        keep = np.arange(ds.sizes["t"]) != switch
        for q in ("tight_side_velocity", "dynamic_load_x"):
            ref = ds[f"{q}_exact"].values
            scale = np.max(np.abs(ref))
            err = np.abs(ds[q].values - ref) / scale
            out[f"{q}_error_pointwise"] = (float(err[keep].max()), "1",
                                           f"max over samples (stage switch excluded) of |{q} - exact|, relative to max |exact|")
            out[f"{q}_error_pointwise_rms"] = (float(np.sqrt(np.mean(err[keep] ** 2))), "1",
                                               f"RMS over samples (stage switch excluded) of |{q} - exact|, relative to max |exact|")
            out[f"{q}_error_switch"] = (float(err[switch]), "1",
                                        f"|{q} - exact| at the stage-switch sample t1 + dt, relative to max |exact|")
            for end, fn in (("min", np.min), ("max", np.max)):
                out[f"{q}_error_of_{end}"] = (float(abs(fn(ds[q].values) - fn(ref)) / scale), "1",
                                              f"error of the {end} of {q} vs exact, relative to max |exact|")
        out["dynamic_load_x_switch"] = (float(ds["dynamic_load_x"].values[switch]), "N",
                                        "difference-method load at the stage-switch sample t1 + dt")
        out["dynamic_load_x_switch_exact"] = (float(ds["dynamic_load_x_exact"].values[switch]), "N",
                                              "exact load at the stage-switch sample t1 + dt")
    return out


def compute(run: dict) -> dict:
    """The physics of one run; only the effects the scene names are evaluated.

    Each effect is timed on its own (``wall_time_<effect>``): the cost of accuracy of the
    difference method is ``wall_time_difference_method``, without the exact reference.
    """
    chain = chain_from_run(run)
    p, options = run["parameters"], run.get("options", {})
    min_time = float(options.get("timing_min_s", 0.05))
    data = {}
    for name, fn in EFFECTS.select(run["effects"]).items():
        kw = {"theta": p["textbook_phase"], "mass": p["textbook_mass"]} if name == "textbook" else {}
        # each effect timed alone, so the method's cost is not blurred by its reference
        out, seconds = time_call(fn, chain, options, min_time=min_time, **kw)
        data.update(out)
        data[f"wall_time_{name}"] = (seconds, "s", f"wall time of the {name} effect (fastest call)")
    return {"chain": chain, "t": chain.time(), "data": data}


def to_dataset(result: dict, run: dict) -> xr.Dataset:
    """Package a :func:`compute` result as a CF-annotated Dataset with summaries."""
    chain, t = result["chain"], result["t"]
    stage = np.where(np.arange(t.size) <= chain.K, 1, 2)
    coords = {"t": ("t", t, {"units": "s", "long_name": "time since O1 left the tangent point T"})}
    variables = {"stage": ("t", stage, {"units": "1", "long_name": "stage of the period (Sec. 3.1)"})}
    for name, (val, unit, long_name) in result["data"].items():
        dims = ("t",) if np.ndim(val) else ()
        variables[name] = (dims, val, {"units": unit, "long_name": long_name})
    ds = xr.Dataset(variables, coords)
    for name, (val, unit, long_name) in _summaries(ds, chain.K).items():
        ds[name] = ((), val, {"units": unit, "long_name": long_name})
    ds["pitch_radius"] = ((), chain.R, {"units": "m", "long_name": "sprocket pitch radius, Eq. (1)"})
    ds["sprocket_speed"] = ((), chain.omega, {"units": "rad/s", "long_name": "sprocket speed omega"})
    ds["period"] = ((), t[-1], {"units": "s", "long_name": "period t2 of one tooth, Eq. (6)"})
    return ds


def solve(run: dict) -> xr.Dataset:
    return to_dataset(compute(run), run)
