"""What the HTML timing page costs beside the JSON report, whole process, CPU seconds.

    python bench/report.py [--lines 100000] [--level 1] [--quick]

Generates a milling job (``gen.shop_program``: raster pocket, contour, drilling) and
runs ``python -m cncc FILE -O<level> --emit=timing --report-format=json|html -o OUT``
in child processes, measuring each child's user + system CPU (``RUSAGE_CHILDREN``).
Both include reading, the passes and planning; the difference is the report.  The
target: HTML <= 1.2 x JSON.  The level is 1 by default because the -O2 planner is
much slower on this program and would only dilute the ratio.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from gen import shop_program  # noqa: E402

TARGET = 1.2


def child_cpu(cmd: list[str]) -> float:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=False, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   env={**os.environ, "PYTHONPATH": os.path.dirname(HERE)})
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lines", type=int, default=100_000)
    ap.add_argument("--level", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--quick", action="store_true", help="10 000 lines")
    args = ap.parse_args()
    lines = 10_000 if args.quick else args.lines
    with tempfile.TemporaryDirectory() as tmp:
        src = os.path.join(tmp, "job.nc")
        with open(src, "w") as f:
            f.write(shop_program(lines))
        cpu = {"json": float("inf"), "html": float("inf")}
        size: dict[str, int] = {}
        for _ in range(args.repeat):  # interleaved, so a change of load hits both
            for fmt in ("json", "html"):
                out = os.path.join(tmp, f"job.{fmt}")
                cpu[fmt] = min(cpu[fmt], child_cpu([sys.executable, "-m", "cncc", src, f"-O{args.level}",
                                                    "--emit=timing", f"--report-format={fmt}", "-o", out]))
                size[fmt] = os.path.getsize(out) if os.path.exists(out) else -1
    ratio = cpu["html"] / cpu["json"] if cpu["json"] else float("inf")
    print(f"timing report of a {lines}-line job at -O{args.level} (whole process, CPU s, best of {args.repeat}):")
    for fmt in ("json", "html"):
        print(f"  {fmt:<5} {cpu[fmt]:8.2f} s   {size[fmt] / 1e6:8.2f} MB")
    print(f"  html / json = {ratio:.2f} (target <= {TARGET})")
    return 0 if ratio <= TARGET and min(size.values()) > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
