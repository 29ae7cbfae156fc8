"""The GIL is released while decimating: other threads run, two simplifications run at
once, a Cancel from another thread and Ctrl-C stop a run within a second."""

import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import decimate
from conftest import icosphere


@pytest.fixture(scope="module")
def big():
    return icosphere(6)  # 81920 triangles


def test_two_threads_at_once_give_the_sequential_results(big):
    v, f = big
    small = icosphere(5)
    expected = [decimate.simplify(v, f, ratio=0.1), decimate.simplify(*small, ratio=0.2)]
    results = [None, None]

    def one(i, mesh, ratio):
        results[i] = decimate.simplify(*mesh, ratio=ratio)

    threads = [threading.Thread(target=one, args=(0, big, 0.1)),
               threading.Thread(target=one, args=(1, small, 0.2))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for got, want in zip(results, expected):
        assert np.array_equal(got.vertices, want.vertices)
        assert np.array_equal(got.faces, want.faces)


def test_other_threads_run_while_it_decimates(big):
    v, f = big
    ticks = [0]
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    start = time.perf_counter()
    decimate.simplify(v, f, ratio=0.05)
    elapsed = time.perf_counter() - start
    stop.set()
    t.join()
    # Held GIL: the counter would stall for the whole call. Released: it ticks all along
    # (each tick sleeps a millisecond; a tenth of that rate is plenty of margin).
    assert ticks[0] > 0.1 * elapsed / 0.001


def test_cancel_from_another_thread(big):
    v, f = big
    cancel = decimate.Cancel()
    timer = threading.Timer(0.02, cancel.request)
    timer.start()
    start = time.perf_counter()
    with pytest.raises(decimate.Cancelled):
        decimate.simplify(v, f, ratio=0.001, cancel=cancel)
    assert time.perf_counter() - start < 1.0
    timer.join()
    assert cancel.requested
    # A requested token stops the next run at once; a fresh one lets it finish.
    with pytest.raises(decimate.Cancelled):
        decimate.simplify(v, f, ratio=0.5, cancel=cancel)
    assert decimate.simplify(v, f, ratio=0.5, cancel=decimate.Cancel()).faces.shape[0] == 40960


SCRIPT = """
import signal, sys, time
# A process started in the background by a non-interactive shell (as CI may run the suite)
# inherits SIGINT ignored, and Python then installs no handler: install Python's own.
signal.signal(signal.SIGINT, signal.default_int_handler)
sys.path.insert(0, {tests!r})
import decimate
from conftest import icosphere
v, f = icosphere(7)
print("ready", flush=True)
start = time.perf_counter()
try:
    # Calls in a row, so that the signal finds one running however fast the machine is:
    # nearly all the time is spent inside them.
    for _ in range(200):
        decimate.simplify(v, f, ratio=0.0001)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted %.3f" % (time.perf_counter() - start), flush=True)
"""


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT is a POSIX signal")
def test_ctrl_c_interrupts_within_a_second():
    tests = os.path.dirname(os.path.abspath(__file__))
    p = subprocess.Popen([sys.executable, "-c", SCRIPT.format(tests=tests)],
                         stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "ready"
    time.sleep(0.3)
    sent = time.perf_counter()
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=30)
    waited = time.perf_counter() - sent
    assert out.startswith("interrupted"), out
    assert waited < 1.0 + 0.5  # the interpreter's own exit included


def test_any_thread_count_gives_the_same_mesh_and_a_bad_count_is_refused(big, tmp_path):
    v, f = big
    default = decimate.simplify(v, f, ratio=0.1)
    for n in (1, 2, 3):
        got = decimate.simplify(v, f, ratio=0.1, threads=n)
        assert np.array_equal(got.vertices, default.vertices), n
        assert np.array_equal(got.faces, default.faces), n
    src = tmp_path / "in.ply"
    decimate.write((v, f), src)
    reports = [decimate.simplify_file(src, tmp_path / f"out{n}.ply", ratio=0.1, threads=n)
               for n in (1, 2)]
    assert reports[0].triangles_after == reports[1].triangles_after == len(default.faces)
    assert (tmp_path / "out1.ply").read_bytes() == (tmp_path / "out2.ply").read_bytes()
    for bad in (0, -1, 1.5, True, "2"):
        with pytest.raises(ValueError, match="threads"):
            decimate.simplify(v, f, ratio=0.1, threads=bad)
