"""mechrepro: reproducible re-derivation of five machine-dynamics papers.

Shared framework (one way to do each thing):

- :mod:`mechrepro.config`     -- the one scene loader (schema validation, studies -> runs)
- :mod:`mechrepro.effects`    -- effect registry: a solver composes only the effects a scene names
- :mod:`mechrepro.io`         -- the one netCDF writer (provenance, atomic) and study gather
- :mod:`mechrepro.validation` -- the one validation-table writer
- :mod:`mechrepro.accuracy`   -- the one cost-of-accuracy helper (timing, errors, plot)
- :mod:`mechrepro.notebook`   -- the one notebook runner (jupytext + papermill)
- :mod:`mechrepro.report`, :mod:`mechrepro.archive` -- report page, archive, reference check
"""
__version__ = "0.1.0"
