"""The result archive: exactly the declared results, only after every paper was checked.

``write_archive`` is given the workflow's declared outputs (never a glob: a renamed
scene's leftovers in ``runs/`` are not certified) and the reference check of the run.  It
refuses unless the check passed *and* names every selected paper as checked (a paper
without a reference is not checked, so not archived).  Its outputs are ``update()`` in
the workflow: Snakemake keeps the last good archive and manifest while the job runs and
restores them when it fails.  It certifies only current results: given the workflow's job
table (:mod:`mechrepro.staleness`), every archived file's record of what made it must equal
what today's code, config, packages and inputs would make, recomputed when the archive is
written; the manifest keeps each job's record, and :func:`verify` re-hashes a results tree
against the manifest, re-checks those records against today's files and names every
mismatch.
"""
from __future__ import annotations

import io
import json
import os
import re
import tarfile
from pathlib import Path

from .config import CACHE_DIR, load_paper
from .io import ENV_INPUTS, atomic_path, job_made_by, write_json
from .provenance import code_version, file_sha256, json_hash, package_versions
from .staleness import MANIFEST, Job, _file_digest, _why, read_table, uncertified



class ArchiveRefused(RuntimeError):
    pass


def check_passed(check: Path, papers: list[str]) -> None:
    """Raise ArchiveRefused unless ``check`` says OK and names every paper as checked."""
    if not check.is_file():
        raise ArchiveRefused(f"not archiving: no reference check at {check}")
    text = check.read_text()
    lines = text.splitlines()
    if not lines or not lines[0].endswith(": OK"):
        raise ArchiveRefused(f"not archiving: the reference check did not pass ({check}):\n{text}")
    unchecked = [p for p in papers
                 if not re.search(rf"^{re.escape(p)}: \d+ quantities within tolerance", text, re.M)]
    if unchecked:
        raise ArchiveRefused(f"not archiving: {', '.join(unchecked)} not checked against a "
                             f"reference ({check})")


def manifest(results: Path, files: list[str], config_dir: Path, papers: list[str],
             profile: str) -> dict:
    configs = {p: load_paper(config_dir / "papers" / f"{p}.yaml", profile, CACHE_DIR).raw
               for p in papers}
    rels = {}
    for f in files:
        path = Path(f)
        try:
            rel = str(path.relative_to(results))
        except ValueError:
            raise ArchiveRefused(f"not archiving: {f} is not under {results}") from None
        if not path.is_file():
            raise ArchiveRefused(f"not archiving: declared output {f} is missing")
        rels[rel] = file_sha256(path)
    return {"profile": profile, "papers": papers, "code_version": code_version(),
            "package_versions": package_versions(), "config_hash": json_hash(configs),
            "files": rels}


def linked_extras(results: Path, files: dict) -> list[str]:
    """Files outside the declared outputs that an archived page links (the rerun plan that
    `make` saves after each run and the report embeds as ``../rerun_plan.html``), so the
    extracted report has no dangling link.  Archived as they were, listed under
    ``extras`` (not re-verified: the next make rewrites the plan)."""
    out = []
    for rel in files:
        if rel.endswith(".html"):
            page = (results / rel).read_text(errors="replace")
            for link in re.findall(r'(?:src|href)="([^"#:]+)"', page):
                target = (results / rel).parent / link
                try:
                    extra = str(target.resolve().relative_to(results.resolve()))
                except ValueError:
                    continue
                if extra not in files and extra not in out and target.is_file():
                    out.append(extra)
    return out


def certify(results: Path, files: list[str], table: str | Path) -> list[dict]:
    """The records of the jobs that made ``files`` (relative to ``results``), refused
    unless every file is current (:func:`mechrepro.staleness.uncertified`)."""
    jobs = read_table(table, results)
    problems = uncertified(jobs, results, files)
    if problems:
        raise ArchiveRefused("not archiving: results that are not current (a rerun makes "
                             "them so):\n  " + "\n  ".join(problems[:10])
                             + (f"\n  ... and {len(problems) - 10} more" if len(problems) > 10
                                else ""))
    wanted = {os.path.normpath(f) for f in files}
    return [{**j.as_dict(results), "made_by": j.made_by(results)} for j in jobs
            if wanted & {os.path.normpath(o) for o in j.outputs}]


def write_archive(archive: str, manifest_path: str, check: str, results: str,
                  config_dir: str, papers: list[str], profile: str, files: list[str],
                  jobs: str | None = None) -> dict:
    results = Path(results)
    check_passed(Path(check), papers)
    # what made the archive itself: the check and every file it holds
    os.environ.setdefault(ENV_INPUTS, " ".join([check, *files]))
    made = certify(results, files, jobs) if jobs else None
    man = manifest(results, files, Path(config_dir), papers, profile)
    if made is not None:
        man["jobs"] = made
        # what made the archive itself, so a restored one is current (heal.archive_record)
        man["made_by"] = job_made_by()
    extras = linked_extras(results, man["files"])
    if extras:
        man["extras"] = {rel: file_sha256(results / rel) for rel in extras}
    data = (json.dumps(man, indent=2, sort_keys=True) + "\n").encode()
    with atomic_path(archive) as tmp:
        # zlib's fastest level: the netCDF results barely compress at higher levels, and
        # the archive is the run's last job, on one core
        with tarfile.open(tmp, "w:gz", compresslevel=1) as tar:
            for rel in [*man["files"], *man.get("extras", {})]:
                tar.add(results / rel, arcname=rel)
            info = tarfile.TarInfo(MANIFEST)
            info.size, info.mode = len(data), 0o644
            tar.addfile(info, io.BytesIO(data))
    write_json(manifest_path, man)
    return man


class ManifestError(ValueError):
    pass


def verify(results: str, manifest_path: str, root: str | None = None) -> list[str]:
    """Re-hash every file of the manifest and re-check what made them against today's
    sources in the project ``root`` (by default the directory holding ``results``);
    return the mismatches (empty: all verified)."""
    _file_digest.cache_clear()
    results, manifest_path = Path(results), Path(manifest_path)
    try:
        man = json.loads(manifest_path.read_text())
        files = man["files"]
    except FileNotFoundError:
        raise ManifestError(f"{manifest_path}: no manifest (an archive is written only when "
                            f"the reference check of every paper passed)") from None
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise ManifestError(f"{manifest_path}: not a readable manifest ({exc})") from None
    problems = []
    for rel, sha in files.items():
        f = results / rel
        if not f.is_file():
            problems.append(f"{rel}: missing")
        elif file_sha256(f) != sha:
            problems.append(f"{rel}: sha256 differs from the manifest")
    if "jobs" not in man:
        problems.append(f"{manifest_path}: no record of what made the files (an archive of "
                        f"an older version): nothing certifies they are current")
        return problems
    # what made them, then and now: the manifest's record of each job against today's
    # code, config, packages and inputs (the run records as the archive saw them)

    for d in man["jobs"]:
        job = Job.from_dict(d, results, results.parent if root is None else root)
        why = _why(d["made_by"], job.made_by(results))
        if why:
            problems += [f"{o}: {why} (job {d['rule']})" for o in d["outputs"] if o in files]
    return problems
