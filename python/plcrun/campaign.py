"""Verification campaigns: ``plcrun compare`` over many random seeds,
cut into chunks and run through any ``concurrent.futures``-style executor
— a local process pool, a Dask ``distributed.Client`` (local or on a
cluster), or anything with ``submit(fn, *args)`` returning futures with
``result()``.

Each worker compiles the two programs once (the pair is kept per thread)
and runs its chunks of seeds; the driver merges the differing seeds and
writes the report that ``plcrun compare`` prints for the same seeds (the
lowest differing seed is run again there and its plan shrunk)::

    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor
    from plcrun import campaign

    spawn = multiprocessing.get_context("spawn")  # the caller has threads
    with ProcessPoolExecutor(2, mp_context=spawn) as pool:
        result = campaign.compare("programs/alg01.il", "programs/alg02.il",
                                  seeds=range(1, 1001), cycles=3000, executor=pool)
    print(result.report)
"""

from __future__ import annotations

import os
import threading
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from ._plcrun import ComparePair

Sources = Union[str, os.PathLike, Sequence[Union[str, os.PathLike]], Mapping[str, str]]

#: The pairs compiled by this thread, by their specification: one per
#: thread, since a pair runs one chunk at a time (a thread pool, or Dask
#: workers with several threads, would otherwise share it).
_LOCAL = threading.local()


def _as_texts(sources: Sources) -> Tuple[Dict[str, str], str]:
    """The sources as ``{name: text}`` (so that workers elsewhere need no
    files) and their label in the report: the file names as given, joined
    by spaces, as ``plcrun compare`` names them."""
    if isinstance(sources, Mapping):
        return dict(sources), " ".join(sources)
    paths = [sources] if isinstance(sources, (str, os.PathLike)) else list(sources)
    texts = {}
    for p in paths:
        with open(p, encoding="utf-8") as f:
            texts[os.fspath(p)] = f.read()
    return texts, " ".join(os.fspath(p) for p in paths)


def _spec_key(spec: Tuple[Any, ...]) -> str:
    a, b, labels, options = spec
    return repr((sorted(a.items()), sorted(b.items()), labels, sorted(options.items())))


def _pair(spec: Tuple[Any, ...]) -> ComparePair:
    """This thread's pair for ``spec``, compiled on first use."""
    pairs: Dict[str, ComparePair] = _LOCAL.__dict__.setdefault("pairs", {})
    key = _spec_key(spec)
    pair = pairs.get(key)
    if pair is None:
        a, b, (a_label, b_label), options = spec
        pair = ComparePair(a, b, a_label=a_label, b_label=b_label, **options)
        pairs[key] = pair
    return pair


def run_chunk(spec: Tuple[Any, ...], start: int, stop: int) -> Tuple[List[int], int, float]:
    """One chunk on a worker: ``(differing seeds, cycles run, seconds)``."""
    t0 = time.perf_counter()
    differing, cycles = _pair(spec).run_seeds(start, stop)
    return differing, cycles, time.perf_counter() - t0


@dataclass
class CampaignResult:
    """What a campaign found; ``report`` is ``plcrun compare``'s text."""

    seeds: range
    differing: List[int]
    cycles_run: int
    report: str
    chunks: int
    seconds: float
    worker_seconds: float = 0.0
    chunk_seconds: List[float] = field(default_factory=list)

    @property
    def same(self) -> bool:
        """True when no seed made the programs differ."""
        return not self.differing

    @property
    def first_seed(self) -> Optional[int]:
        """The lowest differing seed (the counterexample's), if any."""
        return self.differing[0] if self.differing else None

    def __str__(self) -> str:
        return self.report


def compare(
    a: Sources,
    b: Sources,
    *,
    seeds: Union[range, int],
    cycles: int,
    executor: Any = None,
    chunk_size: int = 100,
    **options: Any,
) -> CampaignResult:
    """Compares programs ``a`` and ``b`` over random stimuli, as
    ``plcrun compare A -- B --random START --seeds K --cycles N`` does.

    ``seeds``: a ``range`` of seeds (or a count, from 0). ``executor``: where
    the chunks run (``None``: here, one after the other). ``options``:
    ``cycle_time``, ``program_a``, ``program_b``, ``map``, ``ignore``,
    ``lag``, ``change_prob``, ``min_hold``, ``max_hold``, as the command
    line's. The report is the same for any executor and chunk size.
    """
    if isinstance(seeds, int):
        seeds = range(seeds)
    if seeds.step != 1 or seeds.start < 0 or len(seeds) == 0:
        raise ValueError("seeds: a non-empty range of non-negative seeds with step 1")
    if chunk_size < 1:
        raise ValueError("chunk_size must be at least 1")
    a_texts, a_label = _as_texts(a)
    b_texts, b_label = _as_texts(b)
    spec = (a_texts, b_texts, (a_label, b_label), dict(options, cycles=cycles))
    # Compiled here first: a program that does not compile fails before
    # any work is sent, and the driver needs the pair for the report.
    driver = _pair(spec)
    bounds = [(s, min(s + chunk_size, seeds.stop)) for s in range(seeds.start, seeds.stop, chunk_size)]
    t0 = time.perf_counter()
    if executor is None:
        results = [run_chunk(spec, s, e) for s, e in bounds]
    else:
        futures = [executor.submit(run_chunk, spec, s, e) for s, e in bounds]
        results = [f.result() for f in futures]
    elapsed = time.perf_counter() - t0
    differing = sorted(seed for r in results for seed in r[0])
    report = driver.report(seeds.start, seeds.stop, differing)
    return CampaignResult(
        seeds=seeds,
        differing=differing,
        cycles_run=sum(r[1] for r in results),
        report=report,
        chunks=len(bounds),
        seconds=elapsed,
        worker_seconds=sum(r[2] for r in results),
        chunk_seconds=[r[2] for r in results],
    )
