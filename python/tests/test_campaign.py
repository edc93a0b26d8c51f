"""Campaigns: `plcrun compare` over many seeds through executors; the
merged report must not depend on the executor or the chunk size, and must
be the command line's for the same seeds."""

import multiprocessing
import os
import subprocess
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from pathlib import Path

import pytest

from plcrun import CompileError, PlcError, campaign

from conftest import REPO

A = "PROGRAM A VAR_INPUT start, stop : BOOL; END_VAR VAR_OUTPUT run : BOOL; END_VAR run := (start OR run) AND NOT stop; END_PROGRAM"
B = "PROGRAM B VAR_INPUT start, stop : BOOL; END_VAR VAR_OUTPUT run : BOOL; END_VAR run := start OR run; END_PROGRAM"


def test_a_difference_is_found_whatever_the_executor():
    one = campaign.compare({"a.st": A}, {"b.st": B}, seeds=range(40), cycles=200, chunk_size=40)
    assert not one.same and one.first_seed == one.differing[0]
    assert "differ" in one.report
    with ThreadPoolExecutor(3) as pool:
        threads = campaign.compare({"a.st": A}, {"b.st": B}, seeds=range(40), cycles=200, executor=pool, chunk_size=7)
    assert threads.chunks == 6
    assert (threads.differing, threads.cycles_run, threads.report) == (one.differing, one.cycles_run, one.report)


def test_the_same_program_agrees_with_itself():
    result = campaign.compare({"a.st": A}, {"a2.st": A}, seeds=50, cycles=100, chunk_size=20)
    assert result.same and result.first_seed is None
    assert result.cycles_run == 50 * 100


def test_a_process_pool_gives_the_same_report():
    alg01, alg02 = REPO / "programs" / "alg01.il", REPO / "programs" / "alg02.il"
    here = campaign.compare(str(alg01), str(alg02), seeds=range(1, 21), cycles=500)
    # spawn: the test process has threads (watchdogs), and fork copies
    # only the forking one.
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        there = campaign.compare(str(alg01), str(alg02), seeds=range(1, 21), cycles=500, executor=pool, chunk_size=3)
    assert there.report == here.report
    assert there.differing == here.differing


def _cli():
    """The command line built by `cargo test` (CI runs this after it), if any."""
    given = os.environ.get("PLCRUN_BIN")
    if given and Path(given).exists():
        return given
    for profile in ("debug", "release"):
        exe = REPO / "target" / profile / "plcrun"
        if exe.exists():
            return str(exe)
    return None


@pytest.mark.parametrize("a, b", [("alg01.il", "alg02.il"), ("alg01.il", "alg01.sfc")])
def test_the_report_is_the_command_lines(a, b):
    exe = _cli()
    if exe is None:
        pytest.skip("no plcrun binary (target/debug/plcrun is built by cargo test)")
    args = [f"programs/{a}", "--", f"programs/{b}", "--cycles", "400", "--random", "3", "--seeds", "30"]
    cli = subprocess.run([exe, "compare", *args], cwd=REPO, capture_output=True, text=True)
    assert cli.returncode in (0, 1), cli.stderr
    old = os.getcwd()
    os.chdir(REPO)
    try:
        with ThreadPoolExecutor(2) as pool:
            result = campaign.compare(f"programs/{a}", f"programs/{b}", seeds=range(3, 33), cycles=400,
                                      executor=pool, chunk_size=4)
    finally:
        os.chdir(old)
    assert result.report == cli.stdout
    assert result.same == (cli.returncode == 0)


def test_dask_local_cluster():
    distributed = pytest.importorskip("distributed")
    alg01, alg02 = REPO / "programs" / "alg01.il", REPO / "programs" / "alg02.il"
    here = campaign.compare(str(alg01), str(alg02), seeds=range(1, 101), cycles=300)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            there = campaign.compare(str(alg01), str(alg02), seeds=range(1, 101), cycles=300,
                                     executor=client, chunk_size=10)
    assert there.report == here.report


def test_bad_campaigns_are_refused():
    with pytest.raises(CompileError):
        campaign.compare({"a.st": A}, {"b.st": "PROGRAM B x := ; END_PROGRAM"}, seeds=5, cycles=10)
    with pytest.raises(ValueError):
        campaign.compare({"a.st": A}, {"b.st": B}, seeds=range(0), cycles=10)
    with pytest.raises(PlcError):
        campaign.compare({"a.st": A}, {"b.st": B}, seeds=5, cycles=10, change_prob=2.0)
    with pytest.raises(PlcError):
        campaign.compare({"a.st": A}, {"b.st": B}, seeds=5, cycles=10, ignore=["nope"])


def test_a_dask_campaign_over_1000_seeds_is_the_command_lines():
    distributed = pytest.importorskip("distributed")
    exe = _cli()
    if exe is None:
        pytest.skip("no plcrun binary (target/debug/plcrun is built by cargo test)")
    args = ["programs/alg01.il", "--", "programs/alg02.il", "--cycles", "300", "--random", "0", "--seeds", "1000"]
    cli = subprocess.run([exe, "compare", *args], cwd=REPO, capture_output=True, text=True)
    assert cli.returncode in (0, 1), cli.stderr
    old = os.getcwd()
    os.chdir(REPO)
    try:
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            with distributed.Client(cluster) as client:
                result = campaign.compare("programs/alg01.il", "programs/alg02.il", seeds=range(1000), cycles=300,
                                          executor=client, chunk_size=50)
    finally:
        os.chdir(old)
    assert result.report == cli.stdout
