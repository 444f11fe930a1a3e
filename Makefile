# mechrepro: `make reproduce` (everything) and `make test` (all tests) bootstrap a venv first.
SHELL := /bin/bash
.SHELLFLAGS := -o pipefail -c
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
CORES  ?= 2
STAMP  := $(VENV)/.installed
UV     := uv==0.13.9

.PHONY: reproduce test venv bytecode ci-reproduce reference benchmark costs screenshot clean

$(STAMP): requirements.lock pyproject.toml
	$(PYTHON) -m venv $(VENV)
	# uv installs the pinned set and compiles its bytecode on every core, in well under
	# half pip's time; pip only brings uv itself (the pip config here names optional
	# local indexes; hide pip's warnings about them)
	$(BIN)/pip install --quiet $(UV) 2>&1 | { grep -v "^WARNING: Location" || true; }
	$(BIN)/uv pip install --python $(BIN)/python --quiet --compile-bytecode -r requirements.lock
	$(BIN)/uv pip install --python $(BIN)/python --quiet --no-deps -e .
	$(BIN)/python -m ipykernel install --sys-prefix --name python3 > /dev/null
	touch $(STAMP)

# also after a move or copy of the project with its .venv: the console scripts' shebangs and
# the editable install are rewritten to this project (scripts/relocate_venv.py, idempotent)
venv: $(STAMP)
	$(BIN)/python scripts/relocate_venv.py "$(CURDIR)"

# The package's bytecode, compiled here once: every job, Snakemake start and test process then
# reads it instead of compiling the sources it imports again (Python does not write it itself
# where PYTHONDONTWRITEBYTECODE is set, as in many containers).  A no-op when it is up to
# date; a source edited since is compiled in memory, as always.
# Never an error: where src/ is read-only the processes compile in memory, as before.
bytecode: $(STAMP)
	@$(BIN)/python -m compileall -q src > /dev/null 2>&1 || true

## Reproduce every figure and table of every paper (full resolution): results/report/index.html
## (the workflow heals results/ itself first, under its run lock: mechrepro.heal; when no
## file changed since the last successful run, nothing starts at all: mechrepro.reproduce).
## PYTHONPATH=src: this project's package even where the venv's editable install points
## elsewhere (a project moved or copied with its .venv), as in every other target
reproduce: bytecode
	PYTHONPATH=src $(BIN)/python -m mechrepro.reproduce results -- --cores $(CORES) --rerun-incomplete

## Run every test (unit tests, config errors, pipeline + reference check on the ci profile),
## on every core (tests/conftest.py groups what must share a worker); one worker more than
## cores: the workers beside the ci pipeline's run at low priority and fill what it and the
## SLURM tests' waiting leave idle
test: bytecode
	$(BIN)/python -m pytest -q -n $$(( $(CORES) + 1 )) --dist loadgroup

## The fast profile, as CI runs it, into results-ci/
ci-reproduce: bytecode
	PYTHONPATH=src $(BIN)/python -m mechrepro.reproduce results-ci -- --cores $(CORES) --rerun-incomplete \
	  --config profile=ci results=results-ci

## Deliberately refresh the committed reference numbers of a profile (ci by default;
## `make reference REF_PROFILE=default` for the full one): the profile is run once per
## platform variant of config/reference.yaml and each tolerance is set from the spread
## measured across them (`REF_VARIANTS="native old_cpu"` to run fewer,
## `REF_PAPERS=saw_chain` for one paper)
REF_PROFILE ?= ci
REF_VARIANTS ?=
REF_PAPERS ?=
reference: bytecode
	rm -rf results-reference-$(REF_PROFILE)
	PYTHONPATH=src $(BIN)/python -m mechrepro.reference $(REF_PROFILE) results-reference-$(REF_PROFILE) \
	  $(if $(REF_PAPERS),--papers $(REF_PAPERS)) $(if $(REF_VARIANTS),--variants $(REF_VARIANTS))

## Speed benchmarks (ratios measured side by side)
benchmark: bytecode
	for f in benchmarks/bench_*.py; do echo "== $$f"; PYTHONPATH=src $(BIN)/python $$f || exit 1; done

## Refit the cost coefficients (config/costs.csv: seconds per work term of each solver, and
## each paper's job start) from the default run in results/ (after `make reproduce`)
costs: bytecode
	PYTHONPATH=src $(BIN)/python -m mechrepro.costs results

## Render the report in headless Chromium to results/report/screenshot.png
screenshot:
	bash scripts/screenshot_report.sh results/report/index.html results/report/screenshot.png

clean:
	rm -rf $(patsubst config/papers/%.yaml,results/%,$(wildcard config/papers/*.yaml)) \
	  results/report* results/archive* results/rerun_plan.* results-ci \
	  results-default .snakemake
