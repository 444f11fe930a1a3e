"""Command-line glue for the workflow's bookkeeping rules (one entry point).

    python -m mechrepro.cli gather OUT.nc RUN.nc ...
    python -m mechrepro.cli summary PNG CSV RESULTS CONFIG_DIR PROFILE PAPER ...
    python -m mechrepro.cli report HTML RESULTS CONFIG_DIR PROFILE PAPER ...
    python -m mechrepro.cli archive TAR MANIFEST RESULTS CONFIG_DIR PROFILE PAPER ...
    python -m mechrepro.cli check-reference OUT RESULTS REFERENCE_DIR PROFILE PAPER ...

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
    elif cmd == "summary":
        from .summary import write_summary

        png, csv, results, config_dir, profile, *papers = args
        write_summary(png, csv, results, config_dir, papers, profile)
    elif cmd == "report":
        from .report import write_report

        out, results, config_dir, profile, *papers = args
        write_report(out, results, config_dir, papers, profile)
    elif cmd == "archive":
        from .archive import write_archive

        tar, manifest, results, config_dir, profile, *papers = args
        write_archive(tar, manifest, results, config_dir, papers, profile)
    elif cmd == "check-reference":
        from .archive import DriftError, check_reference

        out, results, reference_dir, profile, *papers = args
        try:
            check_reference(out, results, reference_dir, papers, profile)
        except DriftError as exc:
            sys.stderr.write(f"{exc}\n")
            return 1
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
