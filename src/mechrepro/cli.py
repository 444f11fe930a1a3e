"""Command-line glue for the workflow's bookkeeping rules (one entry point).

    python -m mechrepro.cli gather OUT.nc RUN.nc ...
    python -m mechrepro.cli validate PAPER RESULTS CONFIG_FILE PROFILE
    python -m mechrepro.cli artefact RESULTS CONFIG_DIR PROFILE ARTEFACT ...
    python -m mechrepro.cli summary PNG CSV RESULTS CONFIG_DIR PROFILE PAPER ...
    python -m mechrepro.cli report HTML RESULTS CONFIG_DIR PROFILE PAPER ...
    python -m mechrepro.cli archive TAR MANIFEST CHECK RESULTS CONFIG_DIR PROFILE PAPER ... [--jobs TABLE] --files FILE ...
    python -m mechrepro.cli check-reference OUT RESULTS REFERENCE_DIR PROFILE PAPER ...
    python -m mechrepro.cli verify RESULTS [MANIFEST]

`artefact` is the one command not run by a rule: it solves and checks the verdict rows of
some figures or tables (fig05, chain_drive-fig05) without the workflow, in seconds
(mechrepro.validation.check_artefacts; what `pytest -k fig05` runs).

The others are shell rules on purpose: Snakemake 9 runs a `run:` block in a fresh Snakemake
subprocess that re-parses the whole workflow, which costs seconds per job.
"""
from __future__ import annotations

import sys

USAGE = {
    "gather": (2, "OUT.nc RUN.nc ..."),
    "validate": (4, "PAPER RESULTS CONFIG_FILE PROFILE"),
    "artefact": (4, "RESULTS CONFIG_DIR PROFILE ARTEFACT ..."),
    "summary": (6, "PNG CSV RESULTS CONFIG_DIR PROFILE PAPER ..."),
    "report": (5, "HTML RESULTS CONFIG_DIR PROFILE PAPER ..."),
    "archive": (7, "TAR MANIFEST CHECK RESULTS CONFIG_DIR PROFILE PAPER ... [--jobs TABLE] "
                "--files FILE ..."),
    "check-reference": (5, "OUT RESULTS REFERENCE_DIR PROFILE PAPER ..."),
    "verify": (1, "RESULTS [MANIFEST]"),
}


def _usage(cmd: str | None = None) -> str:
    cmds = [cmd] if cmd else list(USAGE)
    return "usage:\n" + "".join(f"  python -m mechrepro.cli {c} {USAGE[c][1]}\n" for c in cmds)


def main(argv: list[str]) -> int:
    if not argv or argv[0] in ("-h", "--help", "help"):
        sys.stdout.write(__doc__ if argv else "")
        if not argv:
            sys.stderr.write(_usage())
        return 0 if argv else 2
    cmd, args = argv[0], argv[1:]
    if cmd not in USAGE:
        sys.stderr.write(f"unknown command {cmd!r}\n" + _usage())
        return 2
    if "-h" in args or "--help" in args:
        sys.stdout.write(_usage(cmd))
        return 0
    if len(args) < USAGE[cmd][0]:
        sys.stderr.write(f"{cmd}: needs at least {USAGE[cmd][0]} arguments, got {len(args)}\n"
                         + _usage(cmd))
        return 2
    if cmd == "gather":
        from .io import gather_study, write_dataset

        write_dataset(gather_study(args[1:]), args[0])
    elif cmd == "validate":
        from .solve import blas_threads
        from .validation import validate

        blas_threads()
        rows = validate(*args)
        for r in rows:
            print(f"{r.status:12s} {r.spec['evidence']:12s} {r.quantity}")
    elif cmd == "artefact":
        from .config import ConfigError
        from .inputs import read_yaml
        from .solve import blas_threads
        from .validation import artefact_table, check_artefacts

        blas_threads()
        results, config_dir, profile, *artefacts = args
        papers = read_yaml(f"{config_dir}/config.yaml")["papers"]
        try:
            out = check_artefacts(artefacts, results, config_dir, profile, papers)
        except ConfigError as exc:
            sys.stderr.write(f"artefact: {exc}\n")
            return 2
        for paper, rows in out.items():
            for r in rows:
                print(f"{r.status:12s} {r.spec['evidence']:12s} {paper} {r.quantity}")
            print(f"-> {artefact_table(results, paper, sorted({r.spec['artefact'] for r in rows}))}")
    elif cmd == "summary":
        from .summary import write_summary

        png, csv, results, config_dir, profile, *papers = args
        write_summary(png, csv, results, config_dir, papers, profile)
    elif cmd == "report":
        from .report import write_report

        out, results, config_dir, profile, *papers = args
        write_report(out, results, config_dir, papers, profile)
    elif cmd == "archive":
        from .archive import ArchiveRefused, write_archive

        if "--files" not in args:
            sys.stderr.write("archive: --files FILE ... (the declared outputs) is required\n"
                             + _usage(cmd))
            return 2
        i = args.index("--files")
        head, jobs = args[:i], None
        if "--jobs" in head:
            j = head.index("--jobs")
            head, jobs = head[:j] + head[j + 2:], head[j + 1]
        tar, manifest, check, results, config_dir, profile, *papers = head
        try:
            man = write_archive(tar, manifest, check, results, config_dir, papers, profile,
                                args[i + 1:], jobs)
        except ArchiveRefused as exc:
            sys.stderr.write(f"{exc}\n(the last archive that passed, if any, is kept: "
                             f"{tar})\n")
            return 1
        print(f"archived {len(man['files'])} files of {', '.join(papers)} in {tar}")
    elif cmd == "check-reference":
        # always writes its report (the report page shows it); the archive refuses drift
        from .reference import DriftError, ResultFileError, check
        from .io import write_text

        out, results, reference_dir, profile, *papers = args
        try:
            text = check(results, reference_dir, papers, profile)
            status = "OK"
        except (DriftError, ResultFileError) as exc:
            text, status = str(exc), "DRIFT"
            sys.stderr.write(text + "\n")
        write_text(out, f"reference check, profile {profile}: {status}\n" + text)
        print(text)
    elif cmd == "verify":
        from .archive import ManifestError, verify

        results = args[0]
        manifest = args[1] if len(args) > 1 else f"{results}/archive/manifest.json"
        try:
            problems = verify(results, manifest)
        except ManifestError as exc:
            sys.stderr.write(f"verify: {exc}\n")
            return 1
        print("\n".join(problems) if problems else f"{results}: every file matches {manifest}")
        return 1 if problems else 0
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
