"""Command-line glue for the workflow's bookkeeping rules (one entry point).

    python -m mechrepro.cli gather OUT.nc RUN.nc ...
    python -m mechrepro.cli validate PAPER RESULTS CONFIG_FILE PROFILE
    python -m mechrepro.cli summary PNG CSV RESULTS CONFIG_DIR PROFILE PAPER ...
    python -m mechrepro.cli report HTML RESULTS CONFIG_DIR PROFILE PAPER ...
    python -m mechrepro.cli archive TAR MANIFEST RESULTS CONFIG_DIR PROFILE PAPER ...
    python -m mechrepro.cli check-reference OUT RESULTS REFERENCE_DIR PROFILE PAPER ...
    python -m mechrepro.cli verify RESULTS [MANIFEST]

These are shell rules on purpose: Snakemake 9 runs a `run:` block in a fresh Snakemake
subprocess that re-parses the whole workflow, which costs seconds per job.
"""
from __future__ import annotations

import sys


def main(argv: list[str]) -> int:
    cmd, args = argv[0], argv[1:]
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

        tar, manifest, results, config_dir, profile, *papers = args
        try:
            write_archive(tar, manifest, results, config_dir, papers, profile)
        except ArchiveRefused as exc:
            sys.stderr.write(f"{exc}\n")
            return 1
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
        from .archive import verify

        results = args[0]
        manifest = args[1] if len(args) > 1 else f"{results}/archive/manifest.json"
        problems = verify(results, manifest)
        print("\n".join(problems) if problems else f"{results}: every file matches {manifest}")
        return 1 if problems else 0
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
