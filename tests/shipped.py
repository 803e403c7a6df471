"""The shipped genus-0 catalog and certificate cut at a number of corners, for tests that need a
real catalog but not the whole of it: every reader checks every record of a catalog, and the
checker replays every record of a certificate, which for the whole shipped range takes seconds
to minutes.  Each cut is written once a test process, into a directory of its own."""

import atexit
import json
import shutil
import tempfile
from functools import cache
from pathlib import Path

from polyloops.catalog.census import default_catalog, read_catalog
from polyloops.catalog.run import write_census

REAL = default_catalog()
REAL_CERT = REAL / "reachability-certificate.jsonl"


@cache
def small_catalog(top: int) -> Path:
    """The shipped catalog and its certificate through ``top`` corners (the header's range and
    class count cut to match), in a temporary directory removed when the process ends."""
    out = Path(tempfile.mkdtemp(prefix=f"polyloops-catalog-{top}-"))
    atexit.register(shutil.rmtree, out, True)
    write_census(read_catalog(REAL).through(top), out)
    cert = REAL_CERT.read_text().splitlines()
    kept = [line for line in cert[1:] if json.loads(line)["corners"] <= top]
    header = {**json.loads(cert[0]), "max_corners": top, "classes": len(kept)}
    (out / "reachability-certificate.jsonl").write_text("\n".join([json.dumps(header), *kept]) + "\n")
    return out
