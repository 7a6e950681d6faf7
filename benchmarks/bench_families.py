"""Time ``rkcheck solve`` on the shipped families (the seed's Theorem 1 by computation).

    python benchmarks/bench_families.py

Each solve runs in a fresh process (start-up excluded: timed inside it); prints the
family, the equations, the dimension, the number of solutions and the seconds.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CURVE = ["b1 + b2 + b3 = 1"]
#: (file, degree, order, extra equations)
CASES = [
    ("theorem1-s2-m3.toml", 3, 6, []),
    ("theorem1-s2-m4.toml", 4, 6, []),
    ("seed-kernel-zeta-0.toml", 3, 6, []),
    ("theorem1-s3-m6.toml", 6, 7, []),
    ("theorem1-s4-m8.toml", 8, 9, []),
    ("theorem1-s3-m5.toml", 5, 6, CURVE + ["b1 = 1/4"]),  # a slice of the curve of rules
    ("theorem1-s3-m5.toml", 5, 6, CURVE),  # the whole curve of rules
    ("theorem1-s3-m5.toml", 5, 7, CURVE),
]
#: The plain route (one Gröbner basis of every condition) as well, where it finishes.
PLAIN = {"theorem1-s2-m3.toml", "theorem1-s2-m4.toml", "theorem1-s3-m6.toml"}
CHILD = """
import json, sys, time
sys.path.insert(0, {root!r})
import rkcheck
t0 = time.perf_counter()
res = rkcheck.solve({path!r}, degree={degree}, order={order}, route={route!r}, where={where!r})
print(json.dumps({{"seconds": time.perf_counter() - t0, "equations": res.equations, "dimension": res.dimension,
                  "solutions": len(res.solutions or []), "route": res.route}}))
"""


def main() -> None:
    print(f"{'family':28} {'m':>2} {'N':>2} {'route':>10} {'equations':>9} {'dim':>3} {'solutions':>9} "
          f"{'seconds':>8}")
    for name, degree, order, where in CASES:
        path = str(ROOT / "tableaux" / "families" / name)
        for route in ("auto", "plain") if name in PLAIN else ("auto",):
            code = CHILD.format(root=str(ROOT), path=path, degree=degree, order=order, route=route,
                                where=where)
            out = json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                            check=True).stdout)
            print(f"{name:28} {degree:>2} {order:>2} {out['route']:>10} {out['equations']:>9} {out['dimension']:>3} "
                  f"{out['solutions']:>9} {out['seconds']:>8.2f}")


if __name__ == "__main__":
    main()
