"""The binding's behaviour while the engine runs: progress, the GIL, Ctrl-C."""
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np

import dtlab


def test_progress_callable_sees_the_run_from_start_to_end():
    points = dtlab.generate("uniform", 300000, seed=2)
    seen = []
    dtlab.triangulate(points, progress=lambda done, total: seen.append((done, total)))
    assert seen[-1] == (len(points), len(points))
    assert all(total == len(points) for _, total in seen)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)
    assert any(0 < d < len(points) for d, _ in seen), "no report while the run was going"


def test_progress_true_draws_a_bar_on_stderr(capsys):
    dtlab.triangulate(dtlab.generate("uniform", 2000), progress=True)
    err = capsys.readouterr().err
    assert "[dtlab]" in err and "2000 / 2000 points" in err


def test_an_exception_in_the_progress_callable_stops_the_run_and_propagates():
    points = dtlab.generate("uniform", 300000, seed=2)

    def fail(done, total):
        raise RuntimeError("stop here")

    try:
        dtlab.triangulate(points, progress=fail)
        raise AssertionError("the callable's exception was swallowed")
    except RuntimeError as e:
        assert "stop here" in str(e)


def test_two_python_threads_triangulate_at_once():
    points = [dtlab.generate("uniform", 250000, seed=s) for s in (1, 2)]
    events = []  # (thread, done, total) in the order the callbacks ran
    lock = threading.Lock()

    def run(k):
        def report(done, total):
            with lock:
                events.append((k, done, total))
        dtlab.triangulate(points[k], progress=report)

    threads = [threading.Thread(target=run, args=(k,)) for k in (0, 1)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    # Both runs were under way at once: some run reported partial progress after the other had
    # reported partial progress and before that other one finished. With the GIL held through a
    # run, the second could not even start before the first returned.
    running = {0: False, 1: False}
    overlapped = False
    for k, done, total in events:
        running[k] = 0 < done < total
        overlapped |= running[0] and running[1]
    assert overlapped, events


def test_the_calling_thread_runs_python_while_the_engine_works():
    points = dtlab.generate("uniform", 400000, seed=3)
    done = threading.Event()
    ticks = 0

    def run():
        dtlab.triangulate(points)
        done.set()

    worker = threading.Thread(target=run)
    worker.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.01)
    worker.join()
    assert ticks >= 20  # the run takes seconds; ticks every 10 ms unless the GIL is held


CHILD = textwrap.dedent("""
    import os, sys, time, threading
    import dtlab
    points = dtlab.generate("uniform", {n}, seed=1)
    started = []
    threads_before = len(os.listdir("/proc/self/task"))
    def report(done, total):
        if not started and done > 0:
            started.append(1)
            print("started", flush=True)
    try:
        dtlab.triangulate(points, method="{method}", threads={threads}, progress=report)
        print("finished", flush=True)
    except KeyboardInterrupt:
        caught = time.monotonic()
        sent = float(sys.stdin.readline())
        tasks = len(os.listdir("/proc/self/task"))
        print(f"interrupted {{caught - sent:.3f}} {{tasks - threads_before}} {{threading.active_count()}}", flush=True)
""")


def interrupt(method, threads):
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD.format(n=3000000, method=method, threads=threads)],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=os.environ)
    assert child.stdout.readline().strip() == "started"
    time.sleep(0.3)
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    child.stdin.write(f"{sent}\n")
    child.stdin.flush()
    out, _ = child.communicate(timeout=60)
    assert child.returncode == 0
    word, seconds, tasks, python_threads = out.split()  # tasks: OS threads added by the call
    assert word == "interrupted"
    return float(seconds), int(tasks), int(python_threads)


def test_ctrl_c_stops_a_sequential_run_within_a_second():
    seconds, tasks, python_threads = interrupt("sequential", 1)
    assert seconds < 1.0
    assert tasks == 0 and python_threads == 1  # no thread left behind beyond those before the call


def test_ctrl_c_stops_a_parallel_run_within_a_second():
    seconds, tasks, python_threads = interrupt("optimistic-detect", 2)
    assert seconds < 1.0
    assert tasks == 0 and python_threads == 1
