"""packlab.study: the SPEC's expansion (product, zip, ranges, derived seeds), skipping finished
tasks, kill -9 of the runner and resume, failing tasks, a changed SPEC, the Dask path, and one
real study (examples/study/quick.toml) with the packlab binary.

Most tests run a stand-in for the packlab binary (a small Python script) that sleeps a little,
writes report.json atomically like packlab, and appends one line to a marker file each time a
run completes: the marker counts the runs that finished."""

import csv
import json
import os
import shutil
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from packlab import studies

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PYTHON_DIR = os.path.join(REPO, "python")

FAKE = textwrap.dedent("""\
    #!/usr/bin/env python3
    # A stand-in for packlab: <command words> --value X [--fail-above Y] [--sleep S] --seed N --out DIR
    import json, os, sys, time
    argv = sys.argv[1:]
    opts = {}
    k = 0
    while k < len(argv):
        if argv[k].startswith("--"):
            if k + 1 < len(argv) and not argv[k + 1].startswith("--"):
                opts[argv[k][2:]] = argv[k + 1]; k += 2
            else:
                opts[argv[k][2:]] = True; k += 1
        else:
            k += 1
    if os.environ.get("FAKE_STARTED"):  # who runs it (the parent: a runner or a Dask worker) and where
        with open(os.environ["FAKE_STARTED"], "a") as f:
            f.write(str(os.getppid()) + " " + opts.get("out", "-") + "\\n")
    if "resume" in opts:  # packlab COMMAND --resume DIR: refused with FAKE_RESUME_ERROR, else as a run into DIR
        if os.environ.get("FAKE_RESUME_ERROR"):
            print("packlab: error: " + os.environ["FAKE_RESUME_ERROR"], file=sys.stderr)
            sys.exit(2)
        opts["out"] = opts["resume"]
    time.sleep(float(opts.get("sleep", 0.05)))
    value = float(opts.get("value", 0))
    if "fail-above" in opts and value > float(opts["fail-above"]):
        print("packlab: error: --value " + str(value) + " is too large", file=sys.stderr)
        sys.exit(2)
    out = opts["out"]
    os.makedirs(out, exist_ok=True)
    inp = [a for a in argv if a.endswith("report.json")]
    base = json.load(open(inp[0]))["results"]["value"] if inp else 0.0
    report = {"results": {"value": base + value + int(opts.get("seed", 0)) % 7, "flag": "flag" in opts},
              "seconds": 0.01}
    with open(os.path.join(out, ".r.tmp"), "w") as f:
        json.dump(report, f)
    os.replace(os.path.join(out, ".r.tmp"), os.path.join(out, "report.json"))
    with open(os.environ["FAKE_MARKER"], "a") as f:
        f.write(out + "\\n")
    """)


@pytest.fixture
def fake(tmp_path, monkeypatch):
    """The stand-in binary and its marker file (one line per completed run: its folder)."""
    path = tmp_path / "fake-packlab"
    path.write_text(FAKE.replace("/usr/bin/env python3", sys.executable))
    path.chmod(0o755)
    marker = tmp_path / "marker.txt"
    marker.write_text("")
    monkeypatch.setenv("FAKE_MARKER", str(marker))
    return {"binary": str(path), "marker": marker}


def runs(fake):
    return fake["marker"].read_text().split()


def write_spec(path, text):
    path.write_text(textwrap.dedent(text))
    return str(path)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


SIMPLE = """\
    command = "generate fake"
    realizations = 3
    seed = 7
    collect = ["results.value", "seconds"]
    [options]
    sleep = 0.05
    [sweep]
    value = [1, 2]
    """


def test_product_zip_ranges_and_seeds():
    spec = studies.load_spec({"command": "generate fba", "sweep": {"a": [1, 2], "b": {"start": 0.1, "stop": 0.3,
                                                                                      "step": 0.1}},
                              "realizations": 2, "seed": 5})
    assert spec["sweep"]["b"] == [0.1, 0.2, 0.3]
    pts = studies.points(spec)
    assert len(pts) == 6 and pts[0] == {"a": 1, "b": 0.1} and pts[-1] == {"a": 2, "b": 0.3}
    assert spec["seeds"] == [studies.derive_seed(5, 0), studies.derive_seed(5, 1)]
    assert spec["seeds"][0] != spec["seeds"][1] and all(1 <= s < 2**31 for s in spec["seeds"])
    # The seeds depend on the study seed and the realization only (not on the count).
    assert studies.load_spec({"command": "x", "realizations": 3, "seed": 5})["seeds"][:2] == spec["seeds"]
    assert studies.load_spec({"command": "x", "realizations": 1, "seed": 6})["seeds"] != spec["seeds"][:1]
    zipped = studies.load_spec({"command": "x", "combine": "zip",
                                "sweep": {"a": [1, 2, 3], "b": {"start": 10, "stop": 30, "num": 3}}})
    assert studies.points(zipped) == [{"a": 1, "b": 10}, {"a": 2, "b": 20}, {"a": 3, "b": 30}]
    units, tasks = studies.plan(zipped, "/tmp/x")
    assert len(units) == 3 and len(tasks) == 3
    assert units[tasks[0]["units"][0]]["argv"][:6] == ["x", "--a", "1", "--b", "10", "--seed"]
    # The key does not depend on the output folder; it does on every option and the seed.
    again, _ = studies.plan(zipped, "/elsewhere")
    assert set(again) == set(units)


@pytest.mark.parametrize("table, words", [
    ({"command": "x", "combine": "zip", "sweep": {"a": [1, 2], "b": [1]}}, ["zip", "differ in length"]),
    ({"command": "x", "combine": "cross"}, ["combine", "'cross'", "product, zip"]),
    ({"command": "x", "sweep": {"a": {"start": 1}}}, ["sweep 'a'", "start, stop"]),
    ({"command": "x", "realizations": 0}, ["realizations = 0", ">= 1"]),
    ({"command": "x", "bogus": 1}, ["unknown SPEC key 'bogus'"]),
    ({"stage": [{"name": "a", "command": "x", "args": ["{b}/p.vtu"]}, {"name": "b", "command": "y"}]},
     ["{b}/p.vtu", "does not run before it"]),
])
def test_spec_errors_name_the_key(table, words):
    with pytest.raises(studies.SpecError) as error:
        studies.plan(studies.load_spec(table), "/tmp/x")
    for word in words:
        assert word in str(error.value)


def test_cli_spec_error_exit_code_2(tmp_path, fake):
    spec = write_spec(tmp_path / "s.toml", 'command = "x"\ncombine = "cross"\n')
    result = subprocess.run([sys.executable, "-m", "packlab.studies", spec, "--out", str(tmp_path / "o"), "--packlab",
                             fake["binary"]], capture_output=True, text=True, env={**os.environ, "PYTHONPATH": PYTHON_DIR})
    assert result.returncode == 2
    assert result.stderr.strip().splitlines() == [
        "packlab: error: combine = 'cross': must be one of product, zip"]


def test_runs_aggregates_and_skips_finished(tmp_path, fake):
    spec = write_spec(tmp_path / "s.toml", SIMPLE)
    out = tmp_path / "study"
    outcome = studies.study(spec, out, workers=2, packlab=fake["binary"], quiet=True)
    assert outcome["failed"] == 0 and outcome["ran"] == 6 and len(runs(fake)) == 6
    rows = read_csv(out / "tasks.csv")
    assert [r["value"] for r in rows] == ["1", "1", "1", "2", "2", "2"]
    assert all(r["status"] == "done" and float(r["wall_seconds"]) > 0 for r in rows)
    seeds = [int(r["seed"]) for r in rows]
    assert seeds[:3] == seeds[3:] and len(set(seeds[:3])) == 3  # the same seeds at every point
    for r in rows:
        assert float(r["results.value"]) == float(r["value"]) + int(r["seed"]) % 7
    summary = read_csv(out / "summary.csv")
    assert [s["value"] for s in summary] == ["1", "2"]
    values = [float(r["results.value"]) for r in rows[:3]]
    mean = sum(values) / 3
    assert float(summary[0]["results.value_mean"]) == pytest.approx(mean)
    assert int(summary[0]["results.value_count"]) == 3
    sd = (sum((v - mean) ** 2 for v in values) / 2) ** 0.5
    assert float(summary[0]["results.value_sd"]) == pytest.approx(sd)
    assert float(summary[0]["results.value_se"]) == pytest.approx(sd / 3**0.5)
    # A rerun runs nothing and writes the same tables.
    again = studies.study(spec, out, workers=2, packlab=fake["binary"], quiet=True)
    assert again["ran"] == 0 and len(runs(fake)) == 6
    assert read_csv(out / "tasks.csv") == rows


def test_failed_task_recorded_others_run(tmp_path, fake):
    spec = write_spec(tmp_path / "s.toml", SIMPLE.replace("sleep = 0.05", "sleep = 0.05\nfail-above = 1.5"))
    out = tmp_path / "study"
    outcome = studies.study(spec, out, workers=2, packlab=fake["binary"], quiet=True)
    assert outcome["failed"] == 3 and len(runs(fake)) == 3
    rows = read_csv(out / "tasks.csv")
    for r in rows:
        if r["value"] == "2":
            assert r["status"] == "failed" and "exit code 2" in r["error"] and "too large" in r["error"]
            assert r["results.value"] == ""
        else:
            assert r["status"] == "done"
    failure = json.loads((out / "runs" / f"fake-{rows[-1]['task']}" / "study-failure.json").read_text())
    assert failure["exit_code"] == 2 and "--value 2.0 is too large" in failure["stderr_tail"]
    summary = read_csv(out / "summary.csv")
    assert summary[1]["done"] == "0" and summary[1]["results.value_mean"] == ""
    # The command line says so by its exit code, after writing the tables.
    result = subprocess.run([sys.executable, "-m", "packlab.studies", spec, "--out", str(out), "--packlab",
                             fake["binary"], "--quiet"], env={**os.environ, "PYTHONPATH": PYTHON_DIR})
    assert result.returncode == 1


def test_changed_spec_reruns_only_changed_tasks(tmp_path, fake):
    spec = write_spec(tmp_path / "s.toml", SIMPLE)
    out = tmp_path / "study"
    studies.study(spec, out, workers=2, packlab=fake["binary"], quiet=True)
    assert len(runs(fake)) == 6
    write_spec(tmp_path / "s.toml", SIMPLE.replace("value = [1, 2]", "value = [1, 3]").replace(
        "realizations = 3", "realizations = 4"))
    outcome = studies.study(spec, out, workers=2, packlab=fake["binary"], quiet=True)
    # value 1: one new realization; value 3: four new tasks; value 2 is no longer in the tables.
    assert outcome["ran"] == 5 and len(runs(fake)) == 11
    rows = read_csv(out / "tasks.csv")
    assert sorted({r["value"] for r in rows}) == ["1", "3"] and len(rows) == 8


def test_stages_chain_and_share_upstream(tmp_path, fake):
    spec = write_spec(tmp_path / "s.toml", """\
        realizations = 2
        collect = ["gen.results.value", "results.value", "results.flag"]
        [[stage]]
        name = "gen"
        command = "generate fake"
        options = { value = 10 }
        [[stage]]
        name = "test"
        command = "test fake"
        args = ["{gen}/report.json"]
        [sweep]
        test.value = [1, 2]
        test.flag = [true, false]
        """)
    out = tmp_path / "study"
    outcome = studies.study(spec, out, workers=2, packlab=fake["binary"], quiet=True)
    # 2 packings (one per seed) shared by 4 test points each: 2 + 8 runs.
    assert outcome["failed"] == 0 and outcome["ran"] == 10
    rows = read_csv(out / "tasks.csv")
    assert len(rows) == 8
    for r in rows:
        assert float(r["results.value"]) == float(r["gen.results.value"]) + float(r["test.value"])
        assert r["results.flag"] == r["test.flag"]  # true: --flag given; false: left out


def _wait_for(condition, timeout=20.0):
    deadline = time.monotonic() + timeout
    while not condition():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.02)


def test_kill_9_and_resume_runs_nothing_twice(tmp_path, fake):
    spec = write_spec(tmp_path / "s.toml", SIMPLE.replace("sleep = 0.05", "sleep = 0.4").replace(
        "realizations = 3", "realizations = 4"))
    out = tmp_path / "study"
    command = [sys.executable, "-m", "packlab.studies", spec, "--out", str(out), "--workers", "2", "--packlab",
               fake["binary"], "--quiet"]
    env = {**os.environ, "PYTHONPATH": PYTHON_DIR}
    runner = subprocess.Popen(command, env=env)
    _wait_for(lambda: len(runs(fake)) >= 2)  # killed in the middle: some done, two running
    time.sleep(0.1)
    runner.send_signal(signal.SIGKILL)
    runner.wait()
    finished_before = len(runs(fake))
    assert finished_before < 8
    # Rerun at once: the orphaned children of the killed runner still hold their units' locks;
    # the new runner waits for them instead of running them again.
    assert subprocess.run(command, env=env).returncode == 0
    completed = runs(fake)
    assert len(completed) == 8 and len(set(completed)) == 8  # every task exactly once
    assert all(r["status"] == "done" for r in read_csv(out / "tasks.csv"))


class LocalCluster:
    """A Dask scheduler and two workers (one thread each, no nanny: a killed worker stays dead) on
    this machine, as separate processes; ``workers`` are their Popen objects."""

    def __init__(self, tmp_path, env):
        import socket

        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            port = s.getsockname()[1]
        self.address = f"tcp://127.0.0.1:{port}"
        self.logs = open(tmp_path / "dask.log", "w")
        self.scheduler = subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host",
                                           "127.0.0.1", "--port", str(port), "--no-dashboard"],
                                          env=env, stdout=self.logs, stderr=self.logs)
        self.workers = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", self.address,
                                          "--nthreads", "1", "--no-nanny", "--no-dashboard"],
                                         env=env, stdout=self.logs, stderr=self.logs) for _ in range(2)]

    def __enter__(self):
        try:
            from distributed import Client

            with Client(self.address, timeout="20s") as client:
                client.wait_for_workers(2, timeout=30)
        except BaseException:
            self.__exit__()
            raise
        return self

    def __exit__(self, *exc):
        processes = [*self.workers, self.scheduler]
        for p in processes:
            if p.poll() is None:
                p.terminate()
        for p in processes:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        self.logs.close()


def test_dask_cluster(tmp_path, fake):
    pytest.importorskip("distributed")
    env = {**os.environ, "PYTHONPATH": PYTHON_DIR, "FAKE_MARKER": str(fake["marker"])}
    with LocalCluster(tmp_path, env) as cluster:
        address = cluster.address
        spec = write_spec(tmp_path / "s.toml", SIMPLE.replace("sleep = 0.05", "sleep = 0.05\nfail-above = 1.5"))
        out = tmp_path / "study"
        outcome = studies.study(spec, out, scheduler=address, packlab=fake["binary"], quiet=True)
        assert outcome["ran"] == 3 and outcome["failed"] == 3
        rows = read_csv(out / "tasks.csv")
        assert [r["status"] for r in rows] == ["done"] * 3 + ["failed"] * 3
        again = studies.study(spec, out, scheduler=address, packlab=fake["binary"], quiet=True)
        assert again["ran"] == 0 and len(runs(fake)) == 3


def test_dask_worker_killed_every_task_once(tmp_path, fake):
    """kill -9 of one of two Dask workers while it runs a stage (and holds the result of one it
    finished): the study still ends with every stage run completed exactly once. The worker's
    orphaned packlab process finishes its run and keeps the lock; the scheduler gives the
    task to the other worker, which waits for the lock and finds the report; the lost result
    of the finished run is recomputed as a skip."""
    pytest.importorskip("distributed")
    started = tmp_path / "started.txt"
    started.write_text("")
    env = {**os.environ, "PYTHONPATH": PYTHON_DIR, "FAKE_MARKER": str(fake["marker"]), "FAKE_STARTED": str(started)}
    spec = write_spec(tmp_path / "s.toml", """\
        seeds = [1, 2]
        collect = ["gen.results.value", "results.value"]
        [[stage]]
        name = "gen"
        command = "generate fake"
        options = { value = 10, sleep = 0.3 }
        [[stage]]
        name = "test"
        command = "test fake"
        args = ["{gen}/report.json"]
        options = { sleep = 0.6 }
        [sweep]
        test.value = [1, 2, 3]
        """)
    out = tmp_path / "study"
    with LocalCluster(tmp_path, env) as cluster:
        victim = cluster.workers[0]
        runner = subprocess.Popen([sys.executable, "-m", "packlab.studies", spec, "--out", str(out), "--scheduler",
                                   cluster.address, "--packlab", fake["binary"], "--quiet"], env=env)
        try:
            def victim_runs():  # the runs the victim started, in order (the stand-in's parent is the worker)
                lines = [line.split() for line in started.read_text().splitlines()]
                return [folder for pid, folder in lines if int(pid) == victim.pid]

            def victim_busy():  # it finished one run and is in the middle of a second one
                mine = victim_runs()
                return len(mine) >= 2 and mine[-1] not in runs(fake) and mine[0] in runs(fake)

            _wait_for(lambda: victim_busy() or runner.poll() is not None, timeout=60)
            assert runner.poll() is None, "the study ended before the victim worker ran two stage runs"
            victim.send_signal(signal.SIGKILL)
            victim.wait()
            killed_in = victim_runs()[-1]
            assert runner.wait(timeout=120) == 0
        finally:
            if runner.poll() is None:
                runner.kill()
                runner.wait()
    completed = runs(fake)
    # 2 packings + 6 tests, each completed exactly once; the one the worker died in among them
    # (its orphan finished it), none started a second time to completion.
    assert len(completed) == 8 and len(set(completed)) == 8
    assert killed_in in completed
    rows = read_csv(out / "tasks.csv")
    assert len(rows) == 6 and all(r["status"] == "done" for r in rows)
    for r in rows:
        assert float(r["results.value"]) == float(r["gen.results.value"]) + float(r["test.value"])
    for folder in completed:  # the per-run records: a report, no failure
        assert os.path.exists(os.path.join(folder, "report.json"))
        assert not os.path.exists(os.path.join(folder, studies.FAILURE_NAME))


def test_quick_example_with_packlab(tmp_path):
    binary = os.environ.get("PACKLAB_BINARY")
    if not binary or not os.path.exists(binary):
        pytest.skip("packlab binary not found (set PACKLAB_BINARY)")
    out = tmp_path / "quick"
    result = subprocess.run([binary, "study", os.path.join(REPO, "examples", "study", "quick.toml"), "--out", str(out),
                             "--workers", "2"], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    rows = read_csv(out / "tasks.csv")
    assert len(rows) == 6 and all(r["status"] == "done" for r in rows)
    summary = read_csv(out / "summary.csv")
    assert len(summary) == 2 and all(int(s["done"]) == 3 for s in summary)
    png = tmp_path / "study.png"
    from packlab.plot import main as plot_main

    field = [k for k in rows[0] if k.startswith("results.")][0]
    sweep = list(rows[0])[0]
    assert plot_main(["study", str(out), "--x", sweep, "--y", field, "--out", str(png)]) == 0
    assert png.stat().st_size > 1000


def test_killed_static_compression_resumes_from_its_checkpoint(tmp_path, cli):
    """A study unit killed after its third checkpoint (the PACKLAB_KILL_AFTER_CHECKPOINTS hook) goes
    on from that checkpoint when the study is run again, and gives the files of an uninterrupted
    run; a damaged checkpoint (refused with exit code 2) is started again from the beginning."""
    binary = os.environ.get("PACKLAB_BINARY") or shutil.which("packlab")
    cli("generate", "fba", "--particles", 300, "--diameter", 15e-9, "--porosity", 0.45, "--periodic", "xy", "--quiet",
        "--no-plots", "--out", tmp_path / "fba")
    cli("bond", tmp_path / "fba" / "packing.vtu", "--model", "elastic", "--cutoff-ratio", 1.1, "--out",
        tmp_path / "model.vtu")
    options = ["--bond-youngs-modulus", "6.53e9", "--bond-poisson-ratio", "0.17", "--bond-strength", "94.3e6",
               "--solver", "static", "--max-strain", "0.2", "--stop-drop", "0.5", "--checkpoint-breaks", "4",
               "--checkpoint-seconds", "1e-9", "--threads", "1"]
    cli("test", "compress", tmp_path / "model.vtu", *options, "--quiet", "--no-plots", "--out", tmp_path / "straight")
    table = "\n".join(f"{options[k][2:]} = \"{options[k + 1]}\"" for k in range(0, len(options), 2))
    spec = write_spec(tmp_path / "s.toml", textwrap.dedent(f"""\
        command = "test compress"
        args = ["{tmp_path / 'model.vtu'}"]
        seed_option = ""
        seeds = [1]
        collect = ["strength"]
        [options]
        quiet = true
        no-plots = true
        """) + table + "\n")
    out = tmp_path / "study"
    command = [sys.executable, "-m", "packlab.studies", spec, "--out", str(out), "--workers", "1", "--packlab",
               binary, "--quiet"]
    env = {**os.environ, "PYTHONPATH": PYTHON_DIR}
    killed = subprocess.run(command, env={**env, "PACKLAB_KILL_AFTER_CHECKPOINTS": "3"})
    assert killed.returncode != 0
    (unit,) = [p for p in (out / "runs").iterdir()]
    assert (unit / "checkpoint.bin").exists() and not (unit / "report.json").exists()
    assert subprocess.run(command, env=env).returncode == 0
    assert "study: resuming from checkpoint.bin" in (unit / "study-stdout.txt").read_text()
    for name in ["curve.csv", "broken_bonds.csv"]:
        assert (unit / name).read_bytes() == (tmp_path / "straight" / name).read_bytes(), name
    assert read_csv(out / "tasks.csv")[0]["status"] == "done"
    # A damaged checkpoint: the resume is refused (exit code 2) and the unit runs from the start.
    (unit / "report.json").unlink()
    (unit / "checkpoint.bin").write_bytes(b"not a checkpoint")
    assert subprocess.run(command, env=env).returncode == 0
    assert "resuming" not in (unit / "study-stdout.txt").read_text()
    assert (unit / "curve.csv").read_bytes() == (tmp_path / "straight" / "curve.csv").read_bytes()


@pytest.mark.parametrize("error, outcome", [("", "resumed"),
                                            ("--resume = DIR: checkpoint.bin: damaged (checksum)", "started again"),
                                            ("calibration did not converge", "failed")])
def test_resume_of_a_killed_unit_with_a_checkpoint(tmp_path, fake, monkeypatch, error, outcome):
    """A unit of a resumable command whose folder holds checkpoint.bin runs `COMMAND --resume DIR`
    with its output flags only. A refused checkpoint (exit code 2 naming it) starts the unit
    again; any other failure of the resumed run is the unit's, and nothing is run again."""
    spec = write_spec(tmp_path / "s.toml", """\
        command = "test compress"
        args = ["model.vtu"]
        seed_option = ""
        seeds = [1]
        collect = ["results.value"]
        [options]
        value = 2
        threads = 2
        adapt-threads = true
        quiet = true
        no-plots = true
        """)
    out = tmp_path / "study"
    (unit,) = studies.plan(studies.load_spec(spec), str(out))[0].values()
    os.makedirs(unit["dir"])
    with open(os.path.join(unit["dir"], "checkpoint.bin"), "wb") as f:
        f.write(b"saved state")
    with open(os.path.join(unit["dir"], studies.FAILURE_NAME), "w") as f:
        f.write("{}")  # left by the runner that saw the run killed
    monkeypatch.setenv("FAKE_RESUME_ERROR", error)
    started = tmp_path / "started.txt"
    monkeypatch.setenv("FAKE_STARTED", str(started))
    studies.study(spec, str(out), workers=1, packlab=fake["binary"], quiet=True)
    status = read_csv(out / "tasks.csv")[0]["status"]
    stdout = open(os.path.join(unit["dir"], studies.STDOUT_NAME)).read()
    if outcome == "resumed":
        assert status == "done" and runs(fake) == [unit["dir"]]
        assert stdout.startswith(f"study: resuming from checkpoint.bin: test compress --resume {unit['dir']} "
                                 "--quiet --no-plots\n")
        assert not os.path.exists(os.path.join(unit["dir"], studies.FAILURE_NAME))
    elif outcome == "started again":
        assert status == "done" and runs(fake) == [unit["dir"]] and "resuming" not in stdout
        assert not os.path.exists(os.path.join(unit["dir"], "checkpoint.bin"))
    else:
        assert status == "failed" and runs(fake) == [] and started.read_text().count("\n") == 1
        assert os.path.exists(os.path.join(unit["dir"], "checkpoint.bin"))
        failure = json.load(open(os.path.join(unit["dir"], studies.FAILURE_NAME)))
        assert "--resume" in failure["command"] and "did not converge" in failure["stderr_tail"]


def test_plot_study(tmp_path, fake):
    spec = write_spec(tmp_path / "s.toml", SIMPLE.replace("value = [1, 2]", "value = [1, 2, 4]"))
    out = tmp_path / "study"
    studies.study(spec, out, workers=2, packlab=fake["binary"], quiet=True)
    from packlab.plot import main as plot_main
    from packlab.plot.study import figure

    png = tmp_path / "study.png"
    assert plot_main(["study", str(out), "--x", "value", "--y", "results.value", "--out", str(png)]) == 0
    assert png.stat().st_size > 1000
    line = figure(str(out), "value", "results.value").axes[0].lines[0]
    assert list(line.get_xdata()) == [1.0, 2.0, 4.0]
    with pytest.raises(SystemExit):  # a field that was not collected: argparse's error, exit 2
        plot_main(["study", str(out), "--x", "value", "--y", "results.nothing", "--out", str(png)])


def test_placeholder_variables():
    table = {"command": "generate vem", "options": {"config": "{spec_dir}/k{knv}.toml", "voids": 5},
             "sweep": {"knv": ["1e1", "1e-1"], "voids": [5, 6]}, "seeds": [3]}
    units, tasks = studies.plan(studies.load_spec(table, spec_dir="/specs"), "/tmp/x")
    argv = units[tasks[0]["units"][0]]["argv"]
    assert argv[:8] == ["generate", "vem", "--config", "/specs/k1e1.toml", "--voids", "5", "--seed", "3"]
    assert "--knv" not in argv and len(units) == 4
    # The key does not depend on where the SPEC's folder is.
    moved, _ = studies.plan(studies.load_spec(table, spec_dir="/other"), "/tmp/x")
    assert set(moved) == set(units)


def example_specs():
    """Every SPEC under examples/: the TOML files with a command or [[stage]] (the others are
    configs of single commands)."""
    import tomllib

    found = []
    for root, _, files in os.walk(os.path.join(REPO, "examples")):
        for name in files:
            if name.endswith(".toml"):
                with open(os.path.join(root, name), "rb") as f:
                    if {"command", "stage"} & set(tomllib.load(f)):
                        found.append(os.path.relpath(os.path.join(root, name), REPO))
    return sorted(found)


def test_example_specs_are_found_and_documented():
    specs = example_specs()
    assert len(specs) >= 15 and "examples/study/quick.toml" in specs
    with open(os.path.join(REPO, "docs", "study.md")) as f:
        docs = f.read()
    assert [s for s in specs if f"`{s}`" not in docs] == []  # each listed in docs/study.md


_HELP = {}


def _help(binary, command):
    if command not in _HELP:
        result = subprocess.run([binary, *command, "--help"], capture_output=True, text=True)
        assert result.returncode == 0, f"packlab {' '.join(command)} --help: {result.stderr}"
        _HELP[command] = result.stdout
    return _HELP[command]


@pytest.mark.parametrize("path", example_specs())
def test_example_spec_expands(path, tmp_path):
    """A SPEC under examples/ loads, expands into its stage runs (without running them), names
    config files that exist and, with the packlab binary, only commands and options it has."""
    spec = studies.load_spec(os.path.join(REPO, path))
    units, tasks = studies.plan(spec, tmp_path / "study")
    assert tasks and units
    assert all(len(t["units"]) == len(spec["stages"]) for t in tasks)
    assert len({(json.dumps(t["point"], sort_keys=True), t["seed"]) for t in tasks}) == len(tasks)
    for unit in units.values():
        for word in unit["argv"]:
            if word.startswith(spec["spec_dir"]):  # a file beside the SPEC (a config)
                assert os.path.exists(word), f"{path}: {word} does not exist"
    binary = os.environ.get("PACKLAB_BINARY")
    if not binary or not os.path.exists(binary):
        return
    for unit in units.values():
        command = []  # the subcommand words: up to the first option or file ("generate {method}" -> ls)
        for word in unit["argv"]:
            if not word.replace("-", "").isalpha() or word.startswith("-"):
                break
            command.append(word)
        text = _help(binary, tuple(command))
        for word in unit["argv"]:
            if word.startswith("--"):
                assert f"{word} " in text or f"{word}," in text or f"{word}\n" in text or f"{word}=" in text, \
                    f"{path}: packlab {' '.join(command)} has no option {word}"


def test_study_table_arguments_read_the_finished_tasks_or_exit(tmp_path):
    from packlab.studies import study_table_arguments

    (tmp_path / "tasks.csv").write_text("seed,status\n1,done\n2,failed\n")
    out, data, tasks = study_table_arguments(["tables.py", str(tmp_path)], "usage", "docs/data")
    assert (out, data, [t["seed"] for t in tasks]) == (str(tmp_path), "docs/data", ["1"])
    assert study_table_arguments(["tables.py", str(tmp_path), "elsewhere"], "usage", "docs/data")[1] == "elsewhere"
    with pytest.raises(SystemExit, match="usage"):
        study_table_arguments(["tables.py"], "usage", "docs/data")
    (tmp_path / "tasks.csv").write_text("seed,status\n1,failed\n")
    with pytest.raises(SystemExit, match="no finished task"):
        study_table_arguments(["tables.py", str(tmp_path)], "usage", "docs/data")
