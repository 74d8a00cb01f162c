"""Where the points run: serially in this process (no Dask: timing studies, tests), or as Dask
tasks — on a LocalCluster of --jobs single-threaded worker processes by default, or on a running
distributed scheduler (--scheduler tcp://HOST:8786) whose workers share this file system. The
caller's on_done(record) sees every finished point as it finishes, in this process."""
import os

CONNECT_TIMEOUT = 10  # [s] for --scheduler: a wrong address fails in seconds, not after Dask's 30 s


class SchedulerUnreachable(Exception):
    """No Dask scheduler answered at the --scheduler address; the message says which and why."""


def run_serial(tasks, run_point, on_done):
    for task in tasks:
        on_done(run_point(task))


def run_dask(tasks, run_point, on_done, jobs=None, scheduler=None):
    import cloudpickle
    from distributed import Client, LocalCluster, as_completed

    import rollerpy
    # Workers started by hand need not import this package: ship run_point and what it calls by value.
    cloudpickle.register_pickle_by_value(rollerpy)
    cluster = None
    if scheduler:
        try:
            client = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, ValueError) as e:
            raise SchedulerUnreachable("--scheduler %s: no Dask scheduler answered within %d s (%s); start one "
                                       "there (dask-scheduler --port PORT, docs/studies.md) or give its address"
                                       % (scheduler, CONNECT_TIMEOUT, e))
    else:
        # One roller process per worker, each single-threaded (the 2-core machine: --jobs 2).
        cluster = LocalCluster(n_workers=jobs or os.cpu_count(), threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    try:
        futures = [client.submit(run_point, task, pure=False) for task in tasks]
        for future in as_completed(futures):
            on_done(future.result())
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
