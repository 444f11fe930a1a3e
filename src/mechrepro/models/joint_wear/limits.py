"""joint_wear's load-time declarations (read by :mod:`mechrepro.limits` before any job).

``PRODUCED_BY``: the dataset parts built from the wear result (:mod:`.dataset`
``calibration_part``, ``prediction_part``, keyed on ``res["wear"]``) exist only when a
scene names ``archard_wear`` (:func:`.solver.with_wear`); a reported quantity reading them
from a scene without it is refused at load, not in validation.
"""
PRODUCED_BY = {v: "archard_wear" for v in (
    "k_calibrated", "K_table", "K_table_mean", "K_archard_mean", "wear_factor_calibration",
    "wear_calibration_replay", "k_mean", "wear_predicted", "wear_factor_prediction",
    "wear_report", "report_is_node")}

