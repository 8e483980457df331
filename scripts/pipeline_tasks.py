"""Tasks of the main-job pipeline (scripts/pipeline.py): what a task reads and writes, when it is
up to date, and running it with a log, a heartbeat and an error that names the input at fault.

A task is up to date when its record (OUT/.records/<stage>/<task>.json) holds the same options
and the same content hashes of its inputs, and all its outputs exist. Content hashes, not
modification times: `sffcal sff` writes its tables into the run file it reads, and configs are
rewritten on every start, so times would say "changed" when nothing did. The hashes are taken
after the task has run, so a file the task itself updates does not make it stale.
"""
import concurrent.futures
import dataclasses
import datetime
import hashlib
import json
import os
import shutil
import subprocess
import time

HEARTBEAT_S = 30.0  # how often a running task's last log line is shown
# stdout line by line into the logs, so that the heartbeat is current and errors (stderr) stay
# in order with the output
LINE_BUFFERED = ["stdbuf", "-oL"] if shutil.which("stdbuf") else []


@dataclasses.dataclass
class Task:
    stage: str
    name: str
    inputs: list          # files read (hashed)
    outputs: list         # files written (must exist afterwards)
    commands: list        # argument lists, run one after the other
    options: str = ""     # everything else that changes the result (hashed)
    # exit codes of the first command that mean "ran, wrote its outputs, and some of its checks
    # failed": a result to report, not a broken stage (sffcal fe-check: 1 and 2)
    check_codes: tuple = ()
    made_by: dict = dataclasses.field(default_factory=dict)  # input -> stage that writes it


class StageFailed(Exception):
    pass


def file_hash(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def options_hash(task):
    """Hash of the commands and options; the programs by name only, so that another build folder
    (--sffcal) does not rerun everything (use --force after a rebuild that changes results)."""
    commands = [[os.path.basename(c[0])] + c[1:] for c in task.commands]
    return hashlib.sha256(json.dumps([task.options, commands]).encode()).hexdigest()


class Runner:
    def __init__(self, out, jobs, force, log):
        self.out, self.jobs, self.force, self.log = out, jobs, force, log
        self.started = {}  # (stage, task) -> monotonic start time, for the heartbeat
        self.shown = {}    # (stage, task) -> the log line the heartbeat showed last
        self.warnings = []  # failed checks, repeated at the end

    def record_path(self, task):
        return os.path.join(self.out, ".records", task.stage, task.name + ".json")

    def read_record(self, task):
        try:
            with open(self.record_path(task)) as f:
                return json.load(f)
        except (OSError, ValueError):
            return None

    def stale_reason(self, task):
        """Why the task must run, or None when it is up to date."""
        if self.force:
            return "--force"
        record = self.read_record(task)
        if record is None:
            return "no record of an earlier run"
        if record.get("options") != options_hash(task):
            return "its options or the scene changed"
        for path in task.inputs:
            if path not in record.get("inputs", {}):
                return f"new input {path}"
            if record["inputs"][path] != file_hash(path):
                return f"input {path} changed"
        for path in task.outputs:
            if not os.path.exists(path):
                return f"output {path} is missing"
        return None

    def check_inputs(self, task):
        for path in task.inputs:
            if not os.path.isfile(path) or os.path.getsize(path) == 0:
                maker = task.made_by.get(path)
                hint = f" (written by stage {maker}: run it first, e.g. --from {maker})" if maker else ""
                raise StageFailed(f"[{task.stage}] {task.name}: input {path} is missing or empty{hint}")

    def run_stage(self, stage, tasks):
        """Runs the stale tasks of one stage, `jobs` at a time; skips the others."""
        start = time.monotonic()
        to_run = []
        for task in tasks:
            self.check_inputs(task)
            reason = self.stale_reason(task)
            if reason is None:
                record = self.read_record(task)
                self.log(f"[{stage}] {task.name}: up to date, skipped (inputs unchanged since "
                         f"{record['finished']}, took {record['seconds']:.1f} s then)")
                if record.get("check_exit_code"):
                    self.warnings.append(f"[{stage}] {task.name}: some checks FAILED when it ran "
                                         f"(exit {record['check_exit_code']}); see {task.outputs[0]}")
            else:
                to_run.append((task, reason))
        if not to_run:
            return
        failures = []
        with concurrent.futures.ThreadPoolExecutor(max_workers=self.jobs) as pool:
            running = {pool.submit(self.run_task, task, reason): task for task, reason in to_run}
            while running:
                done, _ = concurrent.futures.wait(running, timeout=HEARTBEAT_S)
                for future in done:
                    task = running.pop(future)
                    error = future.exception()
                    if error:
                        failures.append(str(error))
                for task in running.values():
                    if (task.stage, task.name) in self.started:
                        minutes = (time.monotonic() - self.started[(task.stage, task.name)]) / 60
                        line = last_line(self.log_path(task))
                        if line == self.shown.get((stage, task.name)):
                            line = "still running, no new output"
                        else:
                            self.shown[(stage, task.name)] = line
                        self.log(f"[{stage}] {task.name}: {minutes:.1f} min: {line}")
        if failures:
            raise StageFailed("\n".join(failures))
        # the stage's wall-clock time (tasks run in parallel), for the report
        with open(os.path.join(self.out, ".records", stage, "_stage.json"), "w") as f:
            json.dump({"seconds": time.monotonic() - start, "tasks_run": len(to_run),
                       "tasks": len(tasks)}, f)

    def log_path(self, task):
        return os.path.join(self.out, "logs", f"{task.stage}_{task.name}.log")

    def run_task(self, task, reason):
        os.makedirs(os.path.dirname(self.log_path(task)), exist_ok=True)
        for path in task.outputs:
            os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
        # a run that fails half-way must not look done, nor leave old outputs looking new
        for path in [self.record_path(task)] + task.outputs:
            if os.path.exists(path):
                os.remove(path)
        self.log(f"[{task.stage}] {task.name}: running ({reason}); log {self.log_path(task)}")
        start = self.started[(task.stage, task.name)] = time.monotonic()
        check_code = 0
        with open(self.log_path(task), "w") as log_file:
            for k, command in enumerate(task.commands):
                log_file.write("$ " + " ".join(command) + "\n")
                log_file.flush()
                code = subprocess.call(LINE_BUFFERED + command, stdout=log_file, stderr=subprocess.STDOUT,
                                       env=dict(os.environ, PYTHONUNBUFFERED="1"))
                if k == 0 and code in task.check_codes and os.path.exists(task.outputs[0]):
                    check_code = code
                elif code != 0:
                    raise StageFailed(self.failure_message(task, command, code))
        missing = [p for p in task.outputs if not os.path.exists(p)]
        if missing:
            raise StageFailed(f"[{task.stage}] {task.name}: finished but did not write {', '.join(missing)}"
                              f" (log {self.log_path(task)})")
        seconds = time.monotonic() - start
        if check_code:
            self.warnings.append(f"[{task.stage}] {task.name}: some checks FAILED (exit {check_code}); "
                                 f"see {task.outputs[0]} and the report")
            self.log(self.warnings[-1])
        record = {"options": options_hash(task), "inputs": {p: file_hash(p) for p in task.inputs},
                  "outputs": task.outputs, "seconds": seconds, "check_exit_code": check_code,
                  "finished": datetime.datetime.now().isoformat(timespec="seconds")}
        os.makedirs(os.path.dirname(self.record_path(task)), exist_ok=True)
        with open(self.record_path(task), "w") as f:
            json.dump(record, f, indent=1)
        self.log(f"[{task.stage}] {task.name}: done in {seconds:.1f} s")

    def failure_message(self, task, command, code):
        with open(self.log_path(task), errors="replace") as f:
            lines = f.read().splitlines()
        lines = lines[max(i for i, line in enumerate(lines) if line.startswith("$ ")) + 1:]
        # the lines that report the error, wherever stderr put them among the (buffered) stdout:
        # sffcal's "sffcal: error: ...", Python's "...Error: ..."
        errors = [line for line in lines if "error" in line.lower()]
        named = [p for p in task.inputs if any(p in line or os.path.basename(p) in line for line in errors)]
        if not named and len(task.inputs) == 1:
            named = task.inputs
        fault = (f"input at fault: {', '.join(named)}" if named else
                 f"no input named in the message; inputs: {', '.join(task.inputs) or 'none'}")
        shown = errors[-5:] + ["..."] + lines[-8:] if errors else lines[-12:]
        return (f"[{task.stage}] {task.name}: FAILED, `{os.path.basename(command[0])} "
                f"{command[1] if len(command) > 1 else ''}` exited with {code}; {fault}\n"
                f"  log {self.log_path(task)}:\n    " + "\n    ".join(shown))


def last_line(path):
    """The last non-empty line of a log (progress lines end with \\r on a terminal only)."""
    try:
        with open(path, errors="replace") as f:
            lines = [line.strip() for line in f.read().replace("\r", "\n").splitlines() if line.strip()]
    except OSError:
        return "starting"
    if not lines:
        return "starting"
    if lines[-1].startswith("$ "):  # a command has started and printed nothing yet
        words = lines[-1].split()
        name = " ".join(os.path.basename(w) for w in words[1:3] if not w.startswith("-"))
        return f"running {name}, no output yet"
    return lines[-1]
