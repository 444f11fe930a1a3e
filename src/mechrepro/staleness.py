"""Results decide their own staleness: what made a result is recorded in it and compared
before every run.

Every job of the workflow is declared once (:class:`Job`): its result inputs, its outputs
and the digests of everything else that made them, its **parts**: the resolved run records
(``record``), the bytes of the project modules it imports (``code``), its config and
sources (``config``, ``source``, ``reference``) and the package set (``packages``).  A job
gets its parts as ``MECHREPRO_MADE_BY`` and the paths of its result inputs as
``MECHREPRO_INPUTS``; every file it writes through :func:`mechrepro.io.atomic_path`
records ``made_by`` = the parts plus the digest of the inputs' contents (as their own
records give them), beside it (``.<name>.sum``) and, for netCDF, among its attributes.

Before Snakemake decides any job, :func:`stale` compares each job's outputs' recorded
``made_by`` with today's and names what differs.  :func:`steer` then forces exactly
those jobs and allows Snakemake to run only them and what depends on them: neither a time
stamp (a ``touch``, a ``cp -p`` of an edited source, a copy without time stamps) nor
Snakemake's metadata (absent after a restore or ``rm -rf .snakemake``) decides.  As
DVC's ``dvc.lock`` does, but kept with each result, so an archive carries it.
"""
from __future__ import annotations

import functools
import hashlib
import json
import os
import tarfile
from dataclasses import dataclass, field
from pathlib import Path

from .io import ENV_PARTS, digest_inputs, read_sum, write_text
from .provenance import file_sha256, json_hash, package_versions



@functools.cache
def _file_digest(path: str) -> str:
    return file_sha256(Path(path)) if os.path.isfile(path) else "missing"


def digest_files(paths, root: str | Path = ".") -> str:
    """sha256 over the bytes of ``paths`` (relative to the project ``root``) and their
    names as given, so a moved or copied project keeps its digests."""
    h = hashlib.sha256()
    for p in sorted(str(p) for p in paths):
        h.update(f"{p}\0{_file_digest(os.path.join(root, p))}\n".encode())
    return h.hexdigest()


@functools.cache
def packages() -> str:
    """The digest of the package set every job runs with (provenance.package_versions)."""
    return json_hash(package_versions())


@dataclass
class Job:
    """One job of the workflow: its result inputs, its outputs, the files whose bytes made
    them besides (``sources``: part -> paths) and its run records' digest."""
    rule: str
    inputs: list[str]
    outputs: list[str]
    sources: dict[str, list[str]] = field(default_factory=dict)
    record: str | None = None
    root: str = "."     # the project the sources' paths are relative to

    @functools.cached_property
    def parts(self) -> dict[str, str]:
        out = {k: digest_files(v, self.root) for k, v in self.sources.items()}
        if self.record is not None:
            out["record"] = self.record
        return {**out, "packages": packages()}

    @property
    def env(self) -> str:
        """The shell prefix that hands the job its parts (``{input}`` is added by the rule)."""
        return f"{ENV_PARTS}='{json.dumps(self.parts, sort_keys=True)}'"

    def made_by(self, results: str | Path) -> dict:
        return {**self.parts, "inputs": digest_inputs(self.inputs, results)}

    def as_dict(self, results: str | Path) -> dict:
        rel = lambda fs: [os.path.relpath(f, results) for f in fs]   # noqa: E731
        return {"rule": self.rule, "inputs": rel(self.inputs), "outputs": rel(self.outputs),
                "sources": self.sources, "record": self.record}

    @classmethod
    def from_dict(cls, d: dict, results: str | Path, root: str | Path = ".") -> "Job":
        return cls(d["rule"], [str(Path(results, f)) for f in d["inputs"]],
                   [str(Path(results, f)) for f in d["outputs"]], d["sources"], d["record"],
                   str(root))


def write_table(jobs: list[Job], results: str | Path, path: str | Path) -> None:
    """The job table of this workflow start (read by the archive job), written only when
    it differs from what is there."""
    text = json.dumps([j.as_dict(results) for j in jobs], sort_keys=True)
    path = Path(path)
    try:
        if path.read_text() == text:
            return
    except OSError:
        pass
    write_text(path, text, record=False)


def read_table(path: str | Path, results: str | Path) -> list[Job]:
    return [Job.from_dict(d, results) for d in json.loads(Path(path).read_text())]


def uncertified(jobs: list[Job], results: str | Path, files) -> list[str]:
    """Each of ``files`` that is not current: no job declares it, or what its record says
    made it is not what today's code, config, packages and inputs would (recomputed from
    the files now, so an edit during the run is seen)."""
    _file_digest.cache_clear()
    of = {os.path.normpath(o): j for j in jobs for o in j.outputs}
    now, problems = {}, []
    for f in files:
        job = of.get(os.path.normpath(f))
        if job is None:
            problems.append(f"{f}: no job of the workflow makes it")
            continue
        if id(job) not in now:
            now[id(job)] = job.made_by(results)
        rec = read_sum(f)
        why = _why(rec.get("made_by") if rec else None, now[id(job)])
        if why:
            problems.append(f"{f}: {why}")
    return problems


def _why(recorded: dict | None, now: dict) -> str | None:
    if recorded is None:
        return "no record of what made it"
    changed = sorted(k for k in set(recorded) | set(now) if recorded.get(k) != now.get(k))
    if not changed:
        return None
    names = {"record": "its run records", "code": "the code it imports",
             "packages": "the package set", "inputs": "its inputs' contents",
             "config": "its config", "source": "its notebook source",
             "reference": "the reference numbers"}
    return "changed since it was made: " + ", ".join(names.get(k, k) for k in changed)


MANIFEST = "manifest.json"
ARCHIVE_FILES = (MANIFEST, "mechrepro-results.tar.gz")


def archive_record(path: Path) -> dict | None:
    """What made an archive's manifest or tarball without a record beside it (restored):
    the record the manifest keeps of its own job, when the tarball holds that very
    manifest; else None."""
    try:
        man_path = path if path.name == MANIFEST else path.with_name(MANIFEST)
        text = man_path.read_bytes()
        made_by = json.loads(text).get("made_by")
        if made_by and path.name != MANIFEST:
            with tarfile.open(path) as tar:
                member = tar.extractfile(MANIFEST)
                made_by = made_by if member is not None and member.read() == text else None
        return made_by
    except (OSError, ValueError, AttributeError, KeyError, tarfile.TarError):
        return None


def _manifests(results: Path) -> dict[str, dict[str, dict | None]]:
    """{file: {sha256: what made it, or None}} as the manifests under ``results`` give it:
    the full run's (``archive/``) and each run of some papers' (``archive-saw_chain/``),
    which may hold different good versions of one file."""
    out: dict[str, dict[str, dict | None]] = {}
    for path in sorted(results.glob("archive*/manifest.json")):
        try:
            man = json.loads(path.read_text())
            made = {o: j["made_by"] for j in man.get("jobs", []) for o in j["outputs"]}
            for rel, sha in man["files"].items():
                out.setdefault(rel, {})[sha] = made.get(rel)
        except (OSError, ValueError, KeyError, TypeError, AttributeError):
            continue
    return out


class _Recorded:
    """What made a result, as its record says; for a result without one (a restored
    archive before the heal of a run records it), as the manifest that lists its bytes
    says (:func:`mechrepro.heal.inspect` does the same), so a dry run shows what the run
    will do."""

    def __init__(self, results):
        self.results, self.manifests = Path(results), None

    def __call__(self, f) -> dict | None:
        rec = read_sum(f)
        if rec is not None:
            return rec.get("made_by")
        f = Path(f)
        if f.parent.name.startswith("archive") and f.name in ARCHIVE_FILES:
            return archive_record(f)
        if self.manifests is None:
            self.manifests = _manifests(self.results)
        made = self.manifests.get(os.path.relpath(f, self.results))
        return made.get(file_sha256(Path(f))) if made else None


def stale(jobs: list[Job], results: str | Path) -> list[tuple[Job, str, str]]:
    """(job, an output, why) for every job whose outputs are not what today's parts and
    inputs would make (an output missing, without a record, or made by something else)."""
    out = []
    recorded = _Recorded(results)
    for job in jobs:
        now = job.made_by(results)
        for f in job.outputs:
            why = "missing" if not Path(f).is_file() else _why(recorded(f), now)
            if why:
                out.append((job, f, why))
                break
    return out


def downstream(jobs: list[Job], rules: set[str]) -> set[str]:
    """``rules`` and every rule whose jobs read (directly or not) what they write."""
    producer = {o: j.rule for j in jobs for o in j.outputs}
    users: dict[str, set[str]] = {}
    for j in jobs:
        for i in j.inputs:
            if i in producer:
                users.setdefault(producer[i], set()).add(j.rule)
    todo, seen = list(rules), set(rules)
    while todo:
        for r in users.get(todo.pop(), ()):
            if r not in seen:
                seen.add(r)
                todo.append(r)
    return seen


def upstream(jobs: list[Job], targets) -> list[Job]:
    """The jobs that make ``targets`` (files or rule names) and what they read, directly
    or not; every job when no target is named (or the default rule ``all``)."""
    targets = {os.path.normpath(t) for t in targets} - {"all"}
    if not targets:
        return jobs
    producer = {os.path.normpath(o): j for j in jobs for o in j.outputs}
    todo = [j for j in jobs if j.rule in targets] + [producer[t] for t in targets
                                                       if t in producer]
    seen = {id(j) for j in todo}
    while todo:
        for i in todo.pop().inputs:
            j = producer.get(os.path.normpath(i))
            if j is not None and id(j) not in seen:
                seen.add(id(j))
                todo.append(j)
    return [j for j in jobs if id(j) in seen]


def steer(workflow, jobs: list[Job], results: str, always: tuple[str, ...] = ("all",),
          say=print) -> frozenset[str] | None:
    """Force the stale jobs; return the rules Snakemake may run: theirs and those of what
    depends on them (None: any).

    Called when Snakemake builds its DAG (in dry runs too: ``-n`` shows what a run will
    do), for the targets asked for.  A ``--forceall`` / ``-F`` run is left alone; rules
    forced with ``-R`` stay allowed."""
    st = workflow.dag_settings
    # only what the run was asked for: `snakemake results/report/index.html` is not an
    # archive run
    found = stale(upstream(jobs, st.targets), results)
    for job, f, why in found:
        say(f"[stale] {job.rule}: {f}: {why}")
    if st.forceall:
        return None
    rules = {j.rule for j in jobs}
    forced = {r for r in st.forcerun if r in rules}
    allowed = downstream(jobs, {j.rule for j, _, _ in found} | forced) | set(always)
    if st.allowed_rules:
        allowed &= set(st.allowed_rules)
    st.forcerun = frozenset(st.forcerun) | {f for j, _, _ in found for f in j.outputs}
    return frozenset(allowed)
