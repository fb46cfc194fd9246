"""Helpers shared by the peer scripts (run under Debian's /usr/bin/python3)."""
import os


def blas_in_use():
    """The BLAS/LAPACK libraries mapped into this process (after importing numpy)."""
    libs = set()
    try:
        with open("/proc/self/maps") as maps:
            for line in maps:
                path = line.split()[-1]
                name = os.path.basename(path)
                if name.startswith("lib") and any(k in name for k in ("blas", "lapack", "atlas", "mkl")):
                    libs.add(os.path.realpath(path))
    except OSError:
        pass
    return sorted(libs)
