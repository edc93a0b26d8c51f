"""Campaign throughput: seeds per second of `plcrun.campaign.compare` on
1 and 2 local worker processes (ProcessPoolExecutor; with Dask installed,
also a LocalCluster of 2 workers), and the overhead of one chunk. Run from
the repository's root with a release build installed:

    pip install ./python && python python/bench/campaign.py
"""

import multiprocessing
import time
from concurrent.futures import ProcessPoolExecutor

from plcrun import campaign

# A program against itself: no seed differs, so every seed runs all its cycles.
A, B = "programs/alg01.il", "programs/alg01.il"
SEEDS, CYCLES, CHUNK = range(1000), 1000, 50
# Clean worker processes: this one has threads (the watchdogs).
SPAWN = multiprocessing.get_context("spawn")


def timed(**kw):
    t0 = time.perf_counter()
    r = campaign.compare(A, B, seeds=SEEDS, cycles=CYCLES, chunk_size=CHUNK, **kw)
    return r, time.perf_counter() - t0


def main():
    ref, t = timed()
    print(f"in process          : {len(SEEDS) / t:7.0f} seeds/s ({ref.cycles_run} cycles, same={ref.same})")
    for n in (1, 2):
        with ProcessPoolExecutor(n, mp_context=SPAWN) as pool:
            pool.submit(int).result()  # start the workers before timing
            r, t = timed(executor=pool)
        assert r.report == ref.report
        print(f"{n} worker process(es): {len(SEEDS) / t:7.0f} seeds/s")
    try:
        import distributed
    except ImportError:
        print("dask.distributed    : not installed")
    else:
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster:
            with distributed.Client(cluster) as client:
                r, t = timed(executor=client)
        assert r.report == ref.report
        print(f"Dask, 2 workers     : {len(SEEDS) / t:7.0f} seeds/s")
    # Overhead of a chunk: 2000 one-cycle seeds in 2000 chunks against one chunk.
    with ProcessPoolExecutor(1, mp_context=SPAWN) as pool:
        pool.submit(int).result()
        t0 = time.perf_counter()
        campaign.compare(A, B, seeds=2000, cycles=1, chunk_size=2000, executor=pool)
        one = time.perf_counter() - t0
        t0 = time.perf_counter()
        campaign.compare(A, B, seeds=2000, cycles=1, chunk_size=1, executor=pool)
        many = time.perf_counter() - t0
    print(f"overhead per chunk  : {(many - one) / 1999 * 1e6:7.0f} us (process pool, 1 worker)")


if __name__ == "__main__":
    main()
