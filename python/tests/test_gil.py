"""Long calls release the GIL: a Python thread keeps running while the C++ works, and a Python
exception raised from a progress callback (or Ctrl-C) stops the work and reaches the caller."""

import threading
import time

import numpy as np
import pytest

import mastrom
from conftest import SCHEME1, SHORT_RUN


class Counter(threading.Thread):
    """Counts in pure Python (needs the GIL for every increment) until stopped."""

    def __init__(self):
        super().__init__(daemon=True)
        self.count = 0
        self.running = threading.Event()
        self.stop = threading.Event()

    def run(self):
        self.running.set()
        while not self.stop.is_set():
            self.count += 1


def count_during(call):
    """Python-thread increments during call(), and how long call() took [s]."""
    counter = Counter()
    counter.start()
    counter.running.wait()
    before = counter.count
    start = time.perf_counter()
    call()
    elapsed = time.perf_counter() - start
    during = counter.count - before
    counter.stop.set()
    counter.join()
    return during, elapsed


def test_thread_runs_while_screen_runs(database):
    # The thread's pace with the GIL free (the main thread asleep) is the reference.
    idle, idle_s = count_during(lambda: time.sleep(0.3))
    designs = {"interface.thickness": np.linspace(1e-3, 2e-3, 150)}
    # A 0.1 ms step keeps the screen long enough to measure on any machine (the default is 2 ms):
    # about 30 ms per design, so some 5 s here (1500 designs took over a minute and timed out
    # under a loaded ctest -j2).
    during, elapsed = count_during(lambda: database.screen(designs, step=1e-4))
    assert elapsed > 0.2, "the screen must run long enough to tell"
    # Released, the GIL leaves the thread its own pace (the screen runs on the other core, or
    # shares one); held for the whole call, the thread would count only in the few milliseconds of
    # Python around the C++ work, a few per cent of the reference at most.
    ratio = (during / elapsed) / (idle / idle_s)
    assert ratio > 0.25, f"{during} increments in {elapsed:.2f} s, {idle} in {idle_s:.2f} s idle"


def test_two_screens_in_threads_give_the_serial_result(database):
    designs = {"interface.thickness": np.linspace(1e-3, 2e-3, 50)}
    serial = database.screen(designs)["peak_rel_end_angular_acceleration"]
    results = [None, None]

    def work(i):
        results[i] = database.screen(designs)["peak_rel_end_angular_acceleration"]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(r, serial) for r in results)


def test_progress_exception_stops_simulate():
    # 20 000 steps: long enough that the first progress call (after 0.5 s) comes before the end.
    cfg = mastrom.Config.load(
        SCHEME1, set=dict(SHORT_RUN, **{"simulation.end_time": 2.0, "simulation.time_step": 1e-4}))
    calls = []

    def progress(t, end):
        calls.append((t, end))
        raise KeyboardInterrupt

    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        mastrom.simulate(cfg, progress=progress, threads=1)
    assert len(calls) == 1 and 0 < calls[0][0] < calls[0][1] == 2.0
    assert time.perf_counter() - start < 5.0


def test_progress_callback_of_screen(database):
    seen = []
    database.screen({"interface.thickness": np.linspace(1e-3, 2e-3, 20)},
                    progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1] == (20, 20)
