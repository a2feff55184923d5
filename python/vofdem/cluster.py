"""Where an ensemble's members run: a Dask distributed client, made here or given by the caller.

* a `client` given: used as it is, and left open for the caller;
* a `scheduler` address (``tcp://host:8786``) or scheduler file (``*.json``): an existing cluster,
  started by ``dask scheduler`` / ``dask worker`` or by ``dask-jobqueue``; the client is closed at the
  end, the cluster is not;
* otherwise a LocalCluster of `workers` worker processes with one thread each (default: one per core
  this process may use), closed at the end with its processes.

A member runs on one thread (ensemble.run_member sets the solver's threads to 1, docs/threads.md), so
one thread per worker process keeps one member per core. Dask's nanny sets OMP_NUM_THREADS,
MKL_NUM_THREADS and OPENBLAS_NUM_THREADS to 1 in the workers it starts, so numpy does not spread either.
"""
from __future__ import annotations

import importlib.util
import os
from contextlib import contextmanager
from typing import Iterator, Optional


def default_workers() -> int:
    """The cores this process may use (the scheduler's affinity, else the machine's count)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not on Linux
        return os.cpu_count() or 1


def has_bokeh() -> bool:
    """The dashboard needs bokeh; without it a cluster runs as well, with no dashboard."""
    return importlib.util.find_spec("bokeh") is not None


@contextmanager
def ensemble_client(client=None, scheduler: Optional[str] = None, workers: Optional[int] = None,
                    dashboard: bool = True) -> Iterator:
    """A `distributed.Client` for the members (see the module's docstring)."""
    if client is not None:
        yield client
        return
    from distributed import Client

    if scheduler:
        kw = {"scheduler_file": scheduler} if scheduler.endswith(".json") else {"address": scheduler}
        with Client(**kw) as c:
            yield c
        return
    n = default_workers() if workers is None else workers
    if not isinstance(n, int) or isinstance(n, bool) or n < 1:
        raise ValueError(f"workers = {n!r} is outside the allowed range [1, ...] (worker processes)")
    import dask
    from distributed import LocalCluster

    # the scheduler's HTTP server always runs; ':0' takes a free port (8787 may be another cluster's)
    address = ":8787" if dashboard and has_bokeh() else ":0"
    # one member per worker at a time (the scheduler's queue holds the rest, so the count of tasks on
    # the workers is the count running), and a member that kills its worker twice is given up
    cfg = {"distributed.scheduler.worker-saturation": 1.0, "distributed.scheduler.allowed-failures": 1}
    with dask.config.set(cfg):
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                               dashboard_address=address)
    with cluster, Client(cluster) as c:
        yield c


def dashboard_link(client, local: bool) -> Optional[str]:
    """The dashboard's address when the scheduler serves one, else None. A local scheduler without
    bokeh serves only a page saying so: no link then."""
    if local and not has_bokeh():
        return None
    try:
        services = client.scheduler_info().get("services", {})
    except Exception:  # noqa: BLE001 - a missing link must not stop the ensemble
        return None
    return client.dashboard_link if "dashboard" in services else None


def running_count(client, keys) -> int:
    """How many of the tasks `keys` the workers run now: those they hold, at most one per thread
    (with worker-saturation 1 a worker holds only what it runs, elsewhere it may hold more)."""
    try:
        held, threads = client.processing(), client.nthreads()
    except Exception:  # noqa: BLE001 - only the progress bar's count depends on it
        return 0
    return sum(min(sum(1 for k in ks if k in keys), threads.get(w, 1)) for w, ks in held.items())
