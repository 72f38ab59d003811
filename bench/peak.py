"""Run a module as ``python -m MODULE ARGS`` would, then report the process's peak memory.

    python -m bench.peak OUTFILE MODULE [ARGS...]

writes the peak resident set size of this process (``VmHWM`` of /proc/self/status, in MB) to
OUTFILE when the module finishes, however it finishes. VmHWM belongs to the process's own address
space: unlike ``getrusage``'s ``ru_maxrss``, which Linux carries over ``execve`` from the forking
parent (so a small child of a large benchmark process would report the parent's size), it counts
only what this process touched.
"""

from __future__ import annotations

import runpy
import sys
from pathlib import Path

__all__ = ["peak_rss_mb"]


def peak_rss_mb() -> float:
    """Peak resident set size of this process (MB), from /proc/self/status (Linux)."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024.0
    import resource

    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def main() -> None:
    out, module, *args = sys.argv[1:]
    sys.argv = [module, *args]
    try:
        runpy.run_module(module, run_name="__main__", alter_sys=True)
    finally:
        Path(out).write_text(f"{peak_rss_mb():.3f}\n")


if __name__ == "__main__":
    main()
