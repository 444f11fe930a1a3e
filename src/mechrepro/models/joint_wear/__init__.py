"""joint_wear: four-bar with one clearance revolute joint, Archard wear, interval method.

Lai, Liu, Ji, Wang, Zhang, J. Vibroengineering 20 (2018), DOI 10.21595/jve.2018.18979.
Modules: geometry (Table 1-2, Eqs. 12-13), kinematics (ideal four-bar), loads (minimal-
coordinate equations of motion), contact (Eqs. 5-15, 18-20), quasistatic (continuous
contact), dynamics (stiff clearance contact), wear (Eqs. 16-34, Sec. 3.3), effects (the
effects a scene names), solver (the solvers a scene names), dataset (result -> Dataset),
accuracy (cost-of-accuracy errors), figures (the draw function of every declared figure).
"""
# imported on first use (mechrepro.lazy): the notebook, which reads datasets, does not
# import the solvers and scipy
from mechrepro.lazy import lazy_exports  # noqa: E402

#: public name -> submodule that defines it
_LAZY = {'EFFECTS': 'effects', 'SOLVERS': 'solver', 'context': 'solver', 'setup': 'solver', 'variables': 'solver', 'warm': 'solver'}

__all__ = list(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)
