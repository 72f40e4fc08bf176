"""Studies: one packlab command (or a chain of stages, generate -> bond -> test) swept over
option values and realizations, run on a local process pool or a Dask distributed cluster,
resumable, and aggregated into DIR/tasks.csv and DIR/summary.csv (docs/study.md).

``packlab study SPEC.toml --out DIR`` runs ``python3 -m packlab.studies``; from Python,
``packlab.study(spec, out)``. (The module is not called ``packlab.study`` so that the name
``packlab.study`` is the function, not a module shadowed by it.)

Every run of one stage for one parameter point and seed is a *unit* with its own folder
DIR/runs/STAGE-KEY, KEY a hash of the stage's command, its options with the seed, and the keys
of the stages it reads from. A unit is done when its report.json exists (packlab writes it
atomically, last). While a packlab process runs a unit it holds an exclusive lock on the
unit's lock file (the runner passes the locked descriptor on to it), so a runner killed with
-9 leaves its children running and locked: the next runner waits for them instead of running
the same unit a second time.
"""

import argparse
import csv
import fcntl
import hashlib
import itertools
import json
import math
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

from packlab.tables import atomic_output

RUNS = "runs"
LOCK_NAME = ".study-lock"
STDOUT_NAME = "study-stdout.txt"
STDERR_NAME = "study-stderr.txt"
FAILURE_NAME = "study-failure.json"
WALL_NAME = "study-wall.json"
STDERR_TAIL_LINES = 20
CHECKPOINT_NAME = "checkpoint.bin"
# A killed run of these commands goes on from the checkpoint it left in its folder
# (`packlab COMMAND --resume DIR`, cli/checkpoint.hpp) instead of starting again. `relax` keeps
# its checkpoint where --checkpoint says, `generate vem` its own: those start again.
RESUMABLE = {"test compress", "test shear", "calibrate compress", "calibrate shear", "generate fba", "generate bd",
             "shake"}
# The flags a resumed run takes besides --resume: output only (the settings, the threads
# included, come from the checkpoint).
RESUME_FLAGS = {"--quiet", "--no-plots", "--no-vtu"}
# What packlab says (exit code 2) when it cannot resume from a checkpoint: damaged, of another
# version or command (cli/checkpoint.cpp, the methods' "checkpoint is damaged").
CHECKPOINT_REFUSED = re.compile(r"checkpoint\.bin|checkpoint is damaged")
SPEC_KEYS = {"command", "args", "options", "seed_option", "out_option", "out_file", "stage", "sweep", "combine", "seed",
             "realizations", "seeds", "collect", "name"}
STAGE_KEYS = {"name", "command", "args", "options", "seed_option", "out_option", "out_file"}
RANGE_KEYS = {"start", "stop", "num", "step"}


class SpecError(Exception):
    """Bad input in a SPEC: one line naming the key, the value and what is allowed."""


# ---------------------------------------------------------------- the SPEC


def _require(condition, message):
    if not condition:
        raise SpecError(message)


def _expand_range(key, value):
    """``{start, stop, num}`` (num values, both ends included) or ``{start, stop, step}`` (start,
    start + step, ... up to stop included within 1e-9 of a step) -> a list of values."""
    _require(set(value) <= RANGE_KEYS and {"start", "stop"} <= set(value) and len(set(value) & {"num", "step"}) == 1,
             f"sweep '{key}' = {value}: a range needs start, stop and one of num, step")
    start, stop = value["start"], value["stop"]
    for name in ("start", "stop") + (("step",) if "step" in value else ()):
        _require(isinstance(value[name], (int, float)) and not isinstance(value[name], bool),
                 f"sweep '{key}'.{name} = {value[name]!r}: must be a number")
    integral = all(isinstance(value[k], int) for k in value)
    if "num" in value:
        num = value["num"]
        _require(isinstance(num, int) and num >= 1, f"sweep '{key}'.num = {num!r}: must be an integer >= 1")
        if num == 1:
            return [start]
        values = [start + (stop - start) * k / (num - 1) for k in range(num)]
    else:
        step = value["step"]
        _require(step != 0 and (stop - start) / step >= 0, f"sweep '{key}'.step = {step!r}: must go from start to stop")
        count = int(math.floor((stop - start) / step + 1e-9)) + 1
        values = [start + k * step for k in range(count)]
    if integral and all(float(v).is_integer() for v in values):
        return [int(v) for v in values]
    return [float(f"{v:.12g}") for v in values]  # 0.1 + 2 * 0.1 is 0.3, not 0.30000000000000004


def _sweep_values(key, value):
    if isinstance(value, dict):
        return _expand_range(key, value)
    _require(isinstance(value, list) and value, f"sweep '{key}' = {value!r}: must be a non-empty list or a range "
             "{start, stop, num} / {start, stop, step}")
    for v in value:
        _require(isinstance(v, (int, float, str, bool)), f"sweep '{key}' value {v!r}: must be a number, text or boolean")
    return list(value)


def _stage(table, where):
    for key in table:
        _require(key in STAGE_KEYS, f"{where}: unknown key '{key}': must be one of {', '.join(sorted(STAGE_KEYS))}")
    command = table.get("command")
    _require(isinstance(command, str) and command.split(),
             f"{where}.command = {command!r}: must be a packlab command such as \"generate fba\"")
    args = table.get("args", [])
    _require(isinstance(args, list) and all(isinstance(a, (str, int, float)) for a in args),
             f"{where}.args = {args!r}: must be a list of positional arguments")
    options = table.get("options", {})
    _require(isinstance(options, dict), f"{where}.options = {options!r}: must be a table option = value")
    for name, value in options.items():
        _require(isinstance(value, (str, int, float, bool)),
                 f"{where}.options.{name} = {value!r}: must be a number, text or boolean (true: a flag)")
    out_file = table.get("out_file", "")
    _require(isinstance(out_file, str) and "/" not in out_file and out_file not in (".", "..", "report.json"),
             f"{where}.out_file = {out_file!r}: must be a file name such as \"bonded.vtu\" (no folder, not report.json)")
    _require(not out_file or table.get("out_option", "out"),
             f"{where}.out_file = {out_file!r} needs an out_option to pass it with")
    return {"name": table.get("name", command.split()[-1]), "command": command.split(), "args": [str(a) for a in args],
            "options": dict(options), "seed_option": table.get("seed_option"),
            "out_option": table.get("out_option", "out"), "out_file": out_file}


def load_spec(spec, spec_dir=None):
    """Reads and checks a SPEC (a TOML file name or the dict it holds). Returns the normalized
    spec: stages, sweep (key -> values), combine, seeds, collect, spec_dir. Raises SpecError."""
    if isinstance(spec, (str, os.PathLike)):
        import tomllib

        path = os.fspath(spec)
        try:
            with open(path, "rb") as f:
                table = tomllib.load(f)
        except OSError as error:
            raise SpecError(f"cannot read SPEC '{path}': {error.strerror}") from None
        except tomllib.TOMLDecodeError as error:
            raise SpecError(f"SPEC '{path}' is not valid TOML: {error}") from None
        spec_dir = spec_dir or os.path.dirname(os.path.abspath(path))
    else:
        table = dict(spec)
        spec_dir = spec_dir or os.getcwd()
    for key in table:
        _require(key in SPEC_KEYS, f"unknown SPEC key '{key}': must be one of {', '.join(sorted(SPEC_KEYS))}")
    if "stage" in table:
        _require("command" not in table, "SPEC has both 'command' and [[stage]]: use one (a single command or stages)")
        _require(isinstance(table["stage"], list) and table["stage"],
                 "SPEC [[stage]]: must be an array of tables [[stage]] with name and command")
        stages = [_stage(t, f"stage[{k}]") for k, t in enumerate(table["stage"])]
        for k, t in enumerate(table["stage"]):
            _require("name" in t, f"stage[{k}]: needs a name (the others refer to its folder as {{NAME}})")
    else:
        _require("command" in table, "SPEC has no 'command' (e.g. command = \"generate fba\") and no [[stage]]")
        stages = [_stage({k: table[k] for k in STAGE_KEYS if k in table}, "SPEC")]
    names = [s["name"] for s in stages]
    _require(len(set(names)) == len(names), f"stage names {names}: must differ")
    for k, stage in enumerate(stages):
        if stage["seed_option"] is None:  # the first stage draws the random numbers, unless told otherwise
            stage["seed_option"] = "seed" if k == 0 else ""

    combine = table.get("combine", "product")
    _require(combine in ("product", "zip"), f"combine = {combine!r}: must be one of product, zip")
    sweep = {}
    multi = len(stages) > 1
    for key, value in table.get("sweep", {}).items():
        if multi and key in names and isinstance(value, dict) and not set(value) <= RANGE_KEYS:
            for option, values in value.items():  # TOML's packing.particles = [...] is a nested table
                sweep[f"{key}.{option}"] = _sweep_values(f"{key}.{option}", values)
        else:
            if multi and "." in key:
                _require(key.split(".", 1)[0] in names,
                         f"sweep '{key}': '{key.split('.', 1)[0]}' is not a stage: must be one of {', '.join(names)}")
            sweep[key] = _sweep_values(key, value)
    if combine == "zip" and sweep:
        lengths = {k: len(v) for k, v in sweep.items()}
        _require(len(set(lengths.values())) == 1, f"combine = \"zip\": the swept lists differ in length: {lengths}")

    if "seeds" in table:
        seeds = table["seeds"]
        _require(isinstance(seeds, list) and seeds and all(isinstance(s, int) and s >= 0 for s in seeds),
                 f"seeds = {seeds!r}: must be a non-empty list of integers >= 0")
        _require("realizations" not in table or table["realizations"] == len(seeds),
                 f"realizations = {table.get('realizations')!r} and seeds (length {len(seeds)}): give one of them")
    else:
        realizations = table.get("realizations", 1)
        _require(isinstance(realizations, int) and realizations >= 1,
                 f"realizations = {realizations!r}: must be an integer >= 1")
        study_seed = table.get("seed", 1)
        _require(isinstance(study_seed, int) and study_seed >= 0, f"seed = {study_seed!r}: must be an integer >= 0")
        seeds = [derive_seed(study_seed, r) for r in range(realizations)]
    collect = table.get("collect", [])
    _require(isinstance(collect, list) and all(isinstance(c, str) and c for c in collect),
             f"collect = {collect!r}: must be a list of dotted report.json paths such as \"results.porosity\"")
    return {"stages": stages, "sweep": sweep, "combine": combine, "seeds": seeds, "collect": collect,
            "spec_dir": spec_dir}


def derive_seed(study_seed, realization):
    """The seed of realization ``realization`` (0, 1, ...) of a study seeded ``study_seed``: the
    same for every parameter point (common random numbers: differences between points are not
    blurred by differences between packings), independent of the number of realizations, in
    1 ... 2^31 - 1."""
    digest = hashlib.sha256(f"packlab-study:{study_seed}:{realization}".encode()).digest()
    return int.from_bytes(digest[:4], "little") % (2**31 - 1) + 1


def points(spec):
    """The parameter points: a list of dicts sweep key -> value, as a product or zipped."""
    keys = list(spec["sweep"])
    if not keys:
        return [{}]
    lists = [spec["sweep"][k] for k in keys]
    combos = zip(*lists) if spec["combine"] == "zip" else itertools.product(*lists)
    return [dict(zip(keys, combo)) for combo in combos]


# ---------------------------------------------------------------- units and tasks


def _text(value):
    if isinstance(value, bool):  # as TOML and JSON write them
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _substitute(text, values, where):
    try:
        return str(text).format(**values)
    except (KeyError, IndexError) as error:
        raise SpecError(f"{where} = {text!r}: unknown placeholder {error}: must be one of "
                        f"{', '.join('{' + k + '}' for k in sorted(values))}") from None
    except ValueError as error:
        raise SpecError(f"{where} = {text!r}: {error} (write {{{{ and }}}} for literal braces)") from None


def plan(spec, out):
    """The units (key -> unit dict) and the tasks (one per point and seed: the point, the seed
    and the unit key of each stage) of a study writing under ``out``."""
    out = os.path.abspath(out)
    multi = len(spec["stages"]) > 1
    stage_names = [s["name"] for s in spec["stages"]]
    units, tasks = {}, []
    # A swept key written as {KEY} in some argument or option is a variable, substituted there
    # (e.g. a config file per value); so is a multi-stage sweep's key without a stage prefix
    # (a label such as a scale factor). The others are options of their stage.
    templates = " ".join(str(v) for s in spec["stages"] for v in [*s["args"], *s["options"].values()])
    variable_keys = {k for k in spec["sweep"] if "{" + k + "}" in templates or (multi and "." not in k)}
    for point in points(spec):
        for realization, seed in enumerate(spec["seeds"]):
            # Placeholders: {seed}, {spec_dir}, the variables of the point (a multi-stage sweep's
            # keys without a stage prefix), and {STAGE}: an earlier stage's folder.
            variables = {"seed": seed, "spec_dir": spec["spec_dir"]}
            variables.update({k: v for k, v in point.items() if k in variable_keys})
            keys, dirs = {}, {}
            for stage in spec["stages"]:
                options = dict(stage["options"])
                for k, v in point.items():
                    if k in variable_keys:
                        continue
                    if not multi:
                        options[k] = v
                    elif "." in k and k.split(".", 1)[0] == stage["name"]:
                        options[k.split(".", 1)[1]] = v
                if stage["seed_option"]:
                    options.setdefault(stage["seed_option"], seed)
                # Two renderings: with the folders of earlier stages (to run) and with their keys
                # (to hash: the key does not depend on where DIR is).
                later = set(stage_names[stage_names.index(stage["name"]):])
                argv_run, argv_hash, deps = list(stage["command"]), list(stage["command"]), []
                for where, template in [(f"{stage['name']}.args", a) for a in stage["args"]] + [
                        (f"{stage['name']}.options.{k}", v) for k, v in options.items()]:
                    if isinstance(template, str):
                        used = {name for name in stage_names if "{" + name + "}" in template}
                        _require(not used & later, f"{where} = {template!r}: refers to stage {sorted(used & later)}, "
                                 f"which does not run before it: must be one of {sorted(set(stage_names) - later)}")
                        deps += [keys[name] for name in used if keys[name] not in deps]
                        run_value = _substitute(template, {**variables, **dirs}, where)
                        hash_value = _substitute(template, {**variables, **{n: f"<{keys[n]}>" for n in keys},
                                                            "spec_dir": "<spec_dir>"}, where)
                    else:
                        run_value = hash_value = template
                    if where.endswith(".args"):
                        argv_run.append(_text(run_value))
                        argv_hash.append(_text(hash_value))
                    elif template is False:  # an option switched off (a flag not given, a value left out)
                        continue
                    else:
                        flag = "--" + where.rsplit(".", 1)[1]
                        argv_run.append(flag)
                        argv_hash.append(flag)
                        if template is not True:
                            argv_run.append(_text(run_value))
                            argv_hash.append(_text(hash_value))
                if stage["out_file"]:  # a command writing one file: its name is part of the command
                    argv_hash += ["--" + stage["out_option"], stage["out_file"]]
                key = hashlib.sha256(json.dumps(argv_hash).encode()).hexdigest()[:16]
                directory = os.path.join(out, RUNS, f"{stage['name']}-{key}")
                if stage["out_option"]:
                    argv_run += ["--" + stage["out_option"], os.path.join(directory, stage["out_file"]) if
                                 stage["out_file"] else directory]
                units.setdefault(key, {"key": key, "stage": stage["name"], "argv": argv_run, "dir": directory,
                                       "deps": deps, "out_file": stage["out_file"],
                                       "command": list(stage["command"])})
                keys[stage["name"]] = key
                dirs[stage["name"]] = directory
            tasks.append({"point": point, "realization": realization, "seed": seed,
                          "units": [keys[name] for name in stage_names]})
    return units, tasks


def is_done(directory):
    return os.path.exists(os.path.join(directory, "report.json"))


def _write_json(path, value):
    with atomic_output(path, ".study-") as tmp, open(tmp, "w") as f:
        json.dump(value, f, indent=1)


def resume_argv(unit):
    """`COMMAND --resume DIR` with the unit's output flags, when its folder holds the checkpoint
    of a killed run of a resumable command; else None."""
    command = unit.get("command", [])
    if " ".join(command) not in RESUMABLE or not os.path.isfile(os.path.join(unit["dir"], CHECKPOINT_NAME)):
        return None
    return [*command, "--resume", unit["dir"], *[a for a in unit["argv"][len(command):] if a in RESUME_FLAGS]]


def _clear_unit(directory):
    for name in os.listdir(directory):  # what a killed run left behind: start clean
        if name != LOCK_NAME:
            path = os.path.join(directory, name)
            shutil.rmtree(path) if os.path.isdir(path) and not os.path.islink(path) else os.remove(path)


def run_unit(unit, packlab, dep_results=()):
    """Runs one unit (in this process's thread, or on a Dask worker) unless it is done or an
    earlier stage it reads failed. Never raises for a failing packlab: returns a dict with
    status done / skipped / failed / blocked, seconds and error."""
    directory = unit["dir"]
    for dep in dep_results:
        if dep["status"] not in ("done", "skipped"):
            return {"key": unit["key"], "stage": unit["stage"], "status": "blocked", "seconds": 0.0,
                    "error": f"stage {dep['stage']} failed"}
    result = {"key": unit["key"], "stage": unit["stage"], "status": "skipped", "seconds": 0.0, "error": ""}
    if is_done(directory):
        return result
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, LOCK_NAME), "a") as lock:
        while True:  # held by the packlab process of an earlier runner (killed) still at work on it
            try:
                fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                time.sleep(0.2)
        if is_done(directory):
            return result

        def run(argv, note=""):
            with open(os.path.join(directory, STDOUT_NAME), "a" if note else "w") as stdout, \
                    open(os.path.join(directory, STDERR_NAME), "w") as stderr:
                if note:
                    stdout.write(note)
                    stdout.flush()
                try:
                    # The child inherits the locked descriptor: the lock lives as long as the child.
                    return subprocess.run([packlab, *argv], stdout=stdout, stderr=stderr, stdin=subprocess.DEVNULL,
                                          pass_fds=(lock.fileno(),)).returncode, None
                except OSError as error:
                    return 127, f"cannot run {packlab}: {error.strerror}"

        start = time.monotonic()
        argv = resume_argv(unit)
        code = None
        if argv is not None:
            # A killed run's checkpoint: go on from it. If packlab refuses the checkpoint
            # (damaged, of another version), start clean like any other killed run; any other
            # failure of the resumed run is the run's (a folder with a report is never emptied).
            if os.path.exists(os.path.join(directory, FAILURE_NAME)):
                os.remove(os.path.join(directory, FAILURE_NAME))
            code, stderr_text = run(argv, f"study: resuming from {CHECKPOINT_NAME}: {shlex.join(argv)}\n")
            if code == 2 and not is_done(directory):
                with open(os.path.join(directory, STDERR_NAME), errors="replace") as f:
                    if CHECKPOINT_REFUSED.search(f.read()):
                        code = None
        if code is None:
            _clear_unit(directory)
            argv = unit["argv"]
            code, stderr_text = run(argv)
        seconds = time.monotonic() - start
        result["seconds"] = seconds
        out_file = unit.get("out_file")
        if code == 0 and out_file and os.path.isfile(os.path.join(directory, out_file)) and not is_done(directory):
            # A command that writes one file and no report (bond, generate lattice): the runner
            # writes the report that marks the run done, still holding the lock.
            _write_json(os.path.join(directory, "report.json"),
                        {"study_output": out_file, "bytes": os.path.getsize(os.path.join(directory, out_file)),
                         "seconds": seconds, "command": [os.path.basename(packlab), *unit["argv"]]})
        if code == 0 and is_done(directory):
            _write_json(os.path.join(directory, WALL_NAME), {"seconds": seconds})
            result["status"] = "done"
            return result
        if stderr_text is None:
            with open(os.path.join(directory, STDERR_NAME), errors="replace") as f:
                stderr_text = "".join(f.readlines()[-STDERR_TAIL_LINES:])
        if code == 0:
            stderr_text += "\n(exit code 0 but no report.json: the command does not write a report folder)"
        error = {"exit_code": code, "stderr_tail": stderr_text.strip(), "command": shlex.join([packlab, *argv])}
        _write_json(os.path.join(directory, FAILURE_NAME), error)
        result["status"] = "failed"
        result["error"] = f"exit code {code}: " + (error["stderr_tail"].splitlines() or [""])[-1]
        return result


# ---------------------------------------------------------------- progress


class Progress:
    """One line on stderr: done / running / failed and an ETA from the mean time of the units
    run so far, rewritten in place on a terminal, at most once a second otherwise."""

    def __init__(self, total, workers, quiet):
        self.total, self.workers, self.quiet = total, max(1, workers), quiet
        self.done = self.failed = self.running = 0
        self.times = []
        self.last = 0.0
        self.tty = sys.stderr.isatty()

    def update(self, result=None, force=False):
        if result is not None:
            if result["status"] in ("done", "skipped"):
                self.done += 1
            else:
                self.failed += 1
            if result["status"] == "done":
                self.times.append(result["seconds"])
        if self.quiet:
            return
        now = time.monotonic()
        if not force and not self.tty and now - self.last < 1.0:
            return
        self.last = now
        left = self.total - self.done - self.failed
        eta = ""
        if self.times and left:
            seconds = sum(self.times) / len(self.times) * math.ceil(left / self.workers)
            eta = f", ETA {int(seconds) // 60}:{int(seconds) % 60:02d}"
        line = f"study: {self.done}/{self.total} done, {self.running} running, {self.failed} failed{eta}"
        if self.tty:
            sys.stderr.write("\r" + line.ljust(70) + ("\n" if force else ""))
        else:
            sys.stderr.write(line + "\n")
        sys.stderr.flush()


# ---------------------------------------------------------------- execution


def _run_local(units, packlab, workers, progress):
    from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait

    results = {}
    waiting = dict(units)
    running = {}
    with ThreadPoolExecutor(max_workers=workers) as pool:
        while waiting or running:
            for key, unit in list(waiting.items()):
                if all(dep in results for dep in unit["deps"]):
                    del waiting[key]
                    deps = [results[dep] for dep in unit["deps"]]
                    if not any(d["status"] not in ("done", "skipped") for d in deps) and is_done(unit["dir"]):
                        results[key] = run_unit(unit, packlab, deps)  # done before: no thread needed
                        progress.update(results[key])
                        continue
                    running[pool.submit(run_unit, unit, packlab, deps)] = key
            progress.running = min(len(running), workers)  # the rest wait in the pool
            progress.update(force=False)
            if not running:
                continue
            finished, _ = wait(running, return_when=FIRST_COMPLETED, timeout=1.0)
            for future in finished:
                key = running.pop(future)
                results[key] = future.result()
                progress.running = min(len(running), workers)  # the rest wait in the pool
                progress.update(results[key])
    return results


def _remote_unit(unit, packlab, *dep_results):
    """What a Dask worker runs: the same as locally (dependencies arrive as their results)."""
    return run_unit(unit, packlab, dep_results)


def _run_dask(units, packlab, scheduler, progress):
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise SpecError(f"--scheduler {scheduler}: the Python package 'distributed' is not installed "
                        "(Debian: apt-get install python3-distributed)") from None
    try:
        client = Client(scheduler, timeout="10s")
    except (OSError, TimeoutError) as error:
        raise SpecError(f"--scheduler {scheduler}: cannot connect: {error}") from None
    with client:
        threads = sum(w.get("nthreads", 1) for w in client.scheduler_info()["workers"].values())
        progress.workers = max(1, threads)
        futures = {}
        for key, unit in units.items():  # units are in stage order: dependencies come first
            futures[key] = client.submit(_remote_unit, unit, packlab, *[futures[d] for d in unit["deps"]],
                                         key=f"packlab-study-{key}", pure=False, retries=2)
        results = {}
        remaining = len(futures)
        progress.running = min(remaining, progress.workers)  # at most one per worker thread
        for future in as_completed(list(futures.values())):
            key = future.key.removeprefix("packlab-study-")
            try:
                results[key] = future.result()
            except Exception as error:  # the worker itself died, retries spent
                results[key] = {"key": key, "stage": units[key]["stage"], "status": "failed", "seconds": 0.0,
                                "error": f"dask: {type(error).__name__}: {error}"}
            remaining -= 1
            progress.running = min(remaining, progress.workers)
            progress.update(results[key])
    return results


# ---------------------------------------------------------------- aggregation


def _lookup(value, parts):
    """The value at a dotted path; a key may itself hold dots ("mean_coordination_eps_0.01"):
    the longest key that matches is taken first."""
    if not parts:
        return value
    for n in range(len(parts), 0, -1):
        head = ".".join(parts[:n])
        if isinstance(value, dict) and head in value:
            found = _lookup(value[head], parts[n:])
            if found != "":
                return found
        elif isinstance(value, list) and n == 1 and head.isdigit() and int(head) < len(value):
            return _lookup(value[int(head)], parts[1:])
    return ""


def _collect(spec, units, task, field):
    """A collected field of a task: "STAGE.path" reads STAGE's report, "path" the last stage's."""
    names = [s["name"] for s in spec["stages"]]
    head, _, rest = field.partition(".")
    if len(names) > 1 and head in names and rest:
        key = task["units"][names.index(head)]
        path = rest
    else:
        key, path = task["units"][-1], field
    try:
        with open(os.path.join(units[key]["dir"], "report.json")) as f:
            value = _lookup(json.load(f), path.split("."))
    except (OSError, ValueError):
        return ""
    return value if isinstance(value, (int, float, str)) and not isinstance(value, bool) else json.dumps(value)


def _unit_status(unit, result):
    if is_done(unit["dir"]):
        return "done", ""
    if result is not None and result["status"] in ("failed", "blocked"):
        return "failed", result["error"]
    failure = os.path.join(unit["dir"], FAILURE_NAME)
    if os.path.exists(failure):
        with open(failure) as f:
            error = json.load(f)
        return "failed", f"exit code {error['exit_code']}: " + (error["stderr_tail"].splitlines() or [""])[-1]
    return "not run", ""


def _wall(unit):
    try:
        with open(os.path.join(unit["dir"], WALL_NAME)) as f:
            return json.load(f)["seconds"]
    except (OSError, ValueError, KeyError):
        return ""


def _write_csv(path, header, rows):
    with atomic_output(path, ".study-") as tmp, open(tmp, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        writer.writerows([_text(v) for v in row] for row in rows)


def aggregate(spec, units, tasks, out, results=None):
    """Writes DIR/tasks.csv (one row per point and seed) and DIR/summary.csv (per point:
    mean, sd, se and count of each collected numeric field over its finished tasks)."""
    results = results or {}
    swept = list(spec["sweep"])
    rows = []
    for task in tasks:
        status, error, wall = "done", "", 0.0
        for key in task["units"]:
            unit_status, unit_error = _unit_status(units[key], results.get(key))
            if unit_status != "done":
                status, error = unit_status, error or f"{units[key]['stage']}: {unit_error}"
            seconds = _wall(units[key])
            wall = wall + seconds if isinstance(seconds, float) and isinstance(wall, float) else ""
        fields = [_collect(spec, units, task, f) if status == "done" else "" for f in spec["collect"]]
        rows.append([*(task["point"][k] for k in swept), task["realization"], task["seed"], *fields, status,
                     wall if status == "done" else "", task["units"][-1], error.replace("\n", " ")])
    _write_csv(os.path.join(out, "tasks.csv"),
               [*swept, "realization", "seed", *spec["collect"], "status", "wall_seconds", "task", "error"], rows)

    summary, groups = [], {}
    for task, row in zip(tasks, rows):
        groups.setdefault(tuple(_text(task["point"][k]) for k in swept), []).append(row)
    header = list(swept) + ["tasks", "done"]
    for field in spec["collect"]:
        header += [f"{field}_mean", f"{field}_sd", f"{field}_se", f"{field}_count"]
    for point, group in groups.items():
        done = [r for r in group if r[len(swept) + 2 + len(spec["collect"])] == "done"]
        line = [*group[0][:len(swept)], len(group), len(done)]
        for k, _ in enumerate(spec["collect"]):
            values = [r[len(swept) + 2 + k] for r in done]
            values = [float(v) for v in values if isinstance(v, (int, float))]
            n = len(values)
            mean = sum(values) / n if n else ""
            sd = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1)) if n > 1 else ""
            se = sd / math.sqrt(n) if n > 1 else ""
            line += [mean, sd, se, n]
        summary.append(line)
    _write_csv(os.path.join(out, "summary.csv"), header, summary)
    return rows


# ---------------------------------------------------------------- entry points


def finished_tasks(out):
    """The rows of ``out``/tasks.csv (a study folder) whose status is done, as dicts of strings:
    what the scripts that tabulate a study read."""
    with open(os.path.join(out, "tasks.csv"), newline="") as f:
        return [row for row in csv.DictReader(f) if row["status"] == "done"]


def study_table_arguments(argv, usage, default_data):
    """The arguments of a script that tabulates a study, ``SCRIPT STUDY_OUT [DATA]``: returns
    (STUDY_OUT, DATA or ``default_data``, its finished tasks); exits with ``usage`` when
    STUDY_OUT is missing and with a message when no task has finished."""
    if len(argv) < 2:
        sys.exit(usage)
    out = argv[1]
    data = argv[2] if len(argv) > 2 else default_data
    tasks = finished_tasks(out)
    if not tasks:
        sys.exit(f"{os.path.basename(argv[0])}: no finished task in {out}/tasks.csv")
    return out, data, tasks


def _find_packlab(packlab):
    packlab = packlab or os.environ.get("PACKLAB_BINARY") or shutil.which("packlab")
    _require(packlab and os.path.exists(packlab),
             f"packlab binary {packlab or 'packlab'!r} not found: pass packlab=PATH (--packlab) or set PACKLAB_BINARY")
    return os.path.abspath(packlab)


def study(spec, out, workers=None, scheduler=None, packlab=None, quiet=False):
    """Runs the study ``spec`` (a SPEC file name or the dict it holds) into folder ``out``:
    the units not done yet, on ``workers`` local processes (default: the cores) or on the Dask
    cluster at ``scheduler`` ("tcp://HOST:PORT"); then writes out/tasks.csv and
    out/summary.csv. ``packlab`` is the binary (default: $PACKLAB_BINARY, then PATH);
    ``quiet`` drops the progress line. Returns a dict: tasks (the rows of tasks.csv as dicts),
    failed (their count), ran (the stage runs run now). Raises SpecError for a bad SPEC. See
    docs/study.md."""
    spec = load_spec(spec)
    packlab = _find_packlab(packlab)
    workers = workers or os.cpu_count() or 1
    _require(isinstance(workers, int) and workers >= 1, f"--workers {workers!r}: must be an integer >= 1")
    os.makedirs(os.path.join(out, RUNS), exist_ok=True)
    units, tasks = plan(spec, out)
    progress = Progress(len(units), workers, quiet)
    if scheduler:
        results = _run_dask(units, packlab, scheduler, progress)
    else:
        results = _run_local(units, packlab, workers, progress)
    progress.update(force=True)
    aggregate(spec, units, tasks, out, results)
    with open(os.path.join(out, "tasks.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    failed = sum(r["status"] != "done" for r in rows)
    ran = sum(r["status"] == "done" for r in results.values())
    if not quiet:
        print(f"study: {len(rows) - failed}/{len(rows)} tasks done ({ran} runs now), {failed} failed; "
              f"wrote {os.path.join(out, 'tasks.csv')} and summary.csv", file=sys.stderr)
    return {"tasks": rows, "failed": failed, "ran": ran}


def main(argv=None):
    parser = argparse.ArgumentParser(prog="packlab study",
                                     description="Run a study: a packlab command swept over options and seeds")
    parser.add_argument("spec", help="SPEC.toml (docs/study.md)")
    parser.add_argument("--out", required=True, help="study folder (created; rerun to resume)")
    parser.add_argument("--workers", type=int, default=None, help="local processes (default: the cores)")
    parser.add_argument("--scheduler", default=None, help="Dask scheduler address tcp://HOST:PORT")
    parser.add_argument("--packlab", default=None, help="the packlab binary (default: $PACKLAB_BINARY, PATH)")
    parser.add_argument("--quiet", action="store_true", help="no progress line")
    args = parser.parse_args(argv)
    try:
        if args.workers is not None and args.workers < 1:
            raise SpecError(f"--workers {args.workers}: must be an integer >= 1")
        outcome = study(args.spec, args.out, workers=args.workers, scheduler=args.scheduler, packlab=args.packlab,
                        quiet=args.quiet)
    except SpecError as error:
        print(f"packlab: error: {error}", file=sys.stderr)
        return 2
    return 1 if outcome["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
