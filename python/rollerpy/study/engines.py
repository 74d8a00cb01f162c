"""Where the points run: serially in this process (no Dask: timing studies, tests), or as Dask
tasks — on a LocalCluster of --jobs single-threaded worker processes by default, or on a running
distributed scheduler (--scheduler tcp://HOST:8786) whose workers share this file system. The
caller's on_done(record) sees every finished point as it finishes, in this process."""
import logging
import os
import signal
import sys

from .point import lost_record

CONNECT_TIMEOUT = 10  # [s] for --scheduler: a wrong address fails in seconds, not after Dask's 30 s


class SchedulerUnreachable(Exception):
    """No Dask scheduler answered at the --scheduler address; the message says which and why."""


def run_serial(tasks, run_point, on_done):
    for task in tasks:
        on_done(run_point(task))


def run_dask(tasks, run_point, on_done, jobs=None, scheduler=None):
    # Distributed's own notes (an event loop slowed down by a busy machine, workers coming and
    # going) are not the user's business: errors only, here and in the workers this process starts
    # (they read the environment when they import distributed).
    os.environ.setdefault("DASK_LOGGING__DISTRIBUTED", "error")
    import cloudpickle
    from distributed import Client, LocalCluster, as_completed

    import rollerpy
    # Workers started by hand need not import this package: run_point and what it calls travel
    # by value. Distributed pickles a function by value only when the function's own module is
    # registered (a registered parent package is not enough: tests/test_dask_cluster.py), and
    # cloudpickle then takes whatever of the package it calls by value too.
    cloudpickle.register_pickle_by_value(rollerpy)
    cloudpickle.register_pickle_by_value(sys.modules[run_point.__module__])
    cluster = None
    if scheduler:
        try:
            client = Client(scheduler, timeout=CONNECT_TIMEOUT)
        except ValueError as e:
            raise SchedulerUnreachable("--scheduler %s: not an address (%s); expected tcp://HOST:PORT"
                                       % (scheduler, e))
        except OSError as e:
            raise SchedulerUnreachable("--scheduler %s: no Dask scheduler answered within %d s (%s); start one "
                                       "there (dask-scheduler --port PORT, docs/studies.md) or give its address"
                                       % (scheduler, CONNECT_TIMEOUT, e))
    else:
        # One roller process per worker, each single-threaded (the 2-core machine: --jobs 2).
        # Ctrl-C at a terminal reaches the whole process group: the worker processes are started
        # with SIGINT ignored (an ignored signal stays ignored across exec, and Python then keeps
        # it so), so that the study alone answers it and stops them, without their tracebacks.
        previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
        try:
            # The dashboard's port picked free (":0"): two studies at once must not meet at 8787.
            cluster = LocalCluster(n_workers=jobs or os.cpu_count(), threads_per_worker=1, processes=True,
                                   dashboard_address=":0")
        finally:
            signal.signal(signal.SIGINT, previous)
        client = Client(cluster)
    try:
        futures = {client.submit(run_point, task, pure=False): task for task in tasks}
        for future in as_completed(futures):
            try:
                record = future.result()
            except Exception as e:  # the point did not run there (a worker that died, ...): recorded, not fatal
                record = lost_record(futures[future], "not run on the cluster: %s: %s" % (type(e).__name__, e))
            on_done(record)
    finally:
        # Closing while points run (Ctrl-C) makes the scheduler log the results it could not
        # gather: nothing the user must act on, and the study says in one line what happened.
        logging.getLogger("distributed").setLevel(logging.CRITICAL)
        client.close()
        if cluster is not None:
            cluster.close()
