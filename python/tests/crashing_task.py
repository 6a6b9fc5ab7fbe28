"""A surfacing task that kills its own process on inputs whose name contains ``boom``: the
fault that ``surface_files`` must survive (a worker dying on one input). Imported by the
worker processes, so it lives in a module of its own."""

import os

import curvenet


def task(job):
    if "boom" in os.path.basename(job[0]):
        os._exit(9)
    return curvenet._surface_file(job)
