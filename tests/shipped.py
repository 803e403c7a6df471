"""The shipped catalogs and certificates cut at a number of corners, for tests that need a
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
def small_catalog(top: int, genus: int = 0) -> Path:
    """The shipped catalog of ``genus`` and its certificate through ``top`` corners (the
    header's range and counts cut to match), in a temporary directory removed when the process
    ends."""
    real = default_catalog(genus)
    out = Path(tempfile.mkdtemp(prefix=f"polyloops-catalog-g{genus}-{top}-"))
    atexit.register(shutil.rmtree, out, True)
    write_census(read_catalog(real).through(top), out)
    cert = (real / REAL_CERT.name).read_text().splitlines()
    kept = [line for line in cert[1:] if json.loads(line)["corners"] <= top]
    header = {**json.loads(cert[0]), "max_corners": top, "classes": len(kept)}
    header.pop("unsettled", None)
    if unsettled := sum('"unsettled"' in line for line in kept):
        header["unsettled"] = unsettled
    (out / "reachability-certificate.jsonl").write_text("\n".join([json.dumps(header), *kept]) + "\n")
    return out
