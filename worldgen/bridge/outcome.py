"""A run, whatever its transport: the options it takes, the processes it starts (:class:`NodeSpec`), what came
of it (:class:`Outcome`), and the findings about the nodes that every transport reports the same way."""

from __future__ import annotations

from dataclasses import dataclass, field
import json
import time
from pathlib import Path
from typing import Sequence

from ..core.errors import InputError, WorldgenError
from ..core.findings import Finding
from .metrics import compute
from .rubrics import DEFAULT_DURATION, person_loop
from .logtail import TAIL, amount
from .supervise import Child, Leftover, Supervisor, check_stopping

CRASH_GRACE = 5.0   # s of real time a node whose output ends in a traceback gets to finish exiting (finish_run)


@dataclass
class NodeSpec:
    """One process to start: its display name, the command, and the ``name:=value`` arguments it gets; from a
    launch file also the parameters that file sets (full name → value, set on the master before any node starts),
    its environment, whether it is ``required`` (its exit ends the run, as it ends a roslaunch) or asked to
    ``respawn`` (not done here), and the launch file's findings about them."""

    name: str
    command: list[str]
    args: list[str] = field(default_factory=list)
    source: str = ""
    params: dict = field(default_factory=dict)
    env: dict = field(default_factory=dict)
    required: bool = False
    respawn: bool = False
    launch: str = ""          # the launch file and line that start it, for findings
    notes: list = field(default_factory=list)

    @property
    def argv(self) -> list[str]:
        return self.command + self.args


def group_args(items: Sequence[str]) -> list[tuple[str, list[str]]]:
    """NODE arguments each with the ``name:=value`` items after it; InputError when one comes first."""
    grouped: list[tuple[str, list[str]]] = []
    for item in items:
        if ":=" in item and grouped:
            grouped[-1][1].append(item)
        elif ":=" in item:
            raise InputError(f"{item!r} comes before any node", hint="write NODE first, then its name:=value arguments")
        else:
            grouped.append((item, []))
    return grouped


def check_python_file(path: Path) -> None:
    """InputError unless ``path`` is a readable Python node file (UTF-8 text, ``.py`` or a ``#!`` script)."""
    if not path.exists():
        raise InputError("no such node file", path=path, hint="give the path of the node's .py file")
    if path.is_dir():
        raise InputError("is a folder, not a node", path=path, hint="give the node's .py file")
    try:
        data = path.read_bytes()
    except OSError as err:
        raise InputError(f"cannot read the node: {err.strerror}", path=path) from None
    if path.suffix != ".py" and not data.startswith(b"#!") or b"\0" in data:
        raise InputError("is not a Python node", path=path, hint="give a rospy node's .py file, PKG/TYPE or a .launch file")
    try:
        data.decode("utf-8")
    except UnicodeDecodeError:
        raise InputError("is not a Python node (not UTF-8 text)", path=path,
                         hint="give a rospy node's .py file") from None


@dataclass
class RunOptions:
    duration: float = 20.0
    rate: float = 1.0                # 0: as fast as it goes
    no_hit: str = "inf"
    task: str | None = None
    target: float | None = None
    bag: Path | None = None
    person: dict | None = None
    robot_ns: str | None = None      # the robot graded, of several (its namespace or model name)
    record_scans: bool = False       # each robot's trace keeps every published scan (for a replay)


@dataclass
class Outcome:
    """One run: the metrics, the findings about the nodes, the trace, and each node's output."""

    metrics: dict
    findings: list[Finding] = field(default_factory=list)
    trace: dict = field(default_factory=dict)
    logs: dict[str, str] = field(default_factory=dict)


def launch_params(nodes: list[NodeSpec]) -> dict:
    """Every parameter the nodes' launch files set, in the order roslaunch sets them (a later file wins)."""
    params: dict = {}
    for node in nodes:
        params.update(node.params)
    return params


def launch_findings(nodes: list[NodeSpec], ended_by: Child | None, metrics: dict) -> list[Finding]:
    """What the launch files said about their parameters, nodes asked to respawn (not done here), and the
    required node whose exit ended the run."""
    findings: list[Finding] = []
    for node in nodes:
        findings += [f for f in node.notes if f not in findings]
        if node.respawn:
            findings.append(Finding("launch", "info", f"node {node.name} has respawn=\"true\": worldgen does not "
                                                      "start it again when it exits", where=node.launch))
    if ended_by is not None:
        findings.append(Finding("launch", "info", f"required node {ended_by.name} exited at "
                                                  f"{metrics.get('sim_time_s', 0.0):.1f} s of simulated time, "
                                                  "which ends the run (as roslaunch stops everything)",
                                where=next(n.launch for n in nodes if n.name == ended_by.name)))
    return findings


def node_findings(nodes: list[NodeSpec], children: list[Child], alive: dict[str, bool], metrics: dict,
                  cmd_type: str = "geometry_msgs/Twist") -> list[Finding]:
    """A node that exited with an error (the last line of its output says why), and no /cmd_vel at all (the robot
    takes ``cmd_type``)."""
    findings = []
    for spec, child in zip(nodes, children):
        rc = child.proc.returncode
        if not alive[child.name] and rc not in (0, None):
            last = child.last_error_line() or "no output"
            how = f"exit code {rc}" if rc > 0 else f"killed by signal {-rc}"
            findings.append(Finding("node", "error", f"node {spec.name} failed ({how}): {last}", where=spec.source,
                                    fix="run it by hand against `worldgen sim` to see its whole output"))
    if not metrics.get("cmd_vel_messages"):
        names = ", ".join(n.name for n in nodes)
        findings.append(Finding("node", "error", f"no message on /cmd_vel from {names}: the robot was never "
                                                 "commanded", fix=f"publish {cmd_type} on cmd_vel"))
    return findings


def process_findings(nodes: list[NodeSpec], children: list[Child], left: Sequence[Leftover]) -> list[Finding]:
    """Processes a node left running after the run (a daemon, a child that ignored the stop), which worldgen
    ended; and a node's output cut to its first and last lines because it printed more than worldgen keeps."""
    findings = []
    sources = {n.name: n.source for n in nodes}
    if len(nodes) == 1:   # the simulator and the master start nothing: what cannot be traced is the node's
        left = [Leftover(p.owner or nodes[0].name, p.pid, p.cmd) for p in left]
    for owner in dict.fromkeys(p.owner for p in left):
        mine = [p for p in left if p.owner == owner]
        listed = "; ".join(f"pid {p.pid}: {p.cmd}" for p in mine[:5]) + ("; …" if len(mine) > 5 else "")
        who = f"node {owner}" if owner in sources else (owner or "a process of the run (its node cannot be told)")
        findings.append(Finding("node", "warning", f"{who} left {len(mine)} process{'es' if len(mine) > 1 else ''} "
                                                   f"running after the run ({listed}): worldgen ended them",
                                where=sources.get(owner or ""),
                                fix="end what the node starts when it shuts down (rospy.on_shutdown, or rclpy's "
                                    "shutdown); a node's processes must not detach from it (double fork, setsid)"))
    for spec, child in zip(nodes, children):
        kept = child.kept()
        if kept.cut:
            findings.append(Finding("node", "info", f"node {spec.name} printed {amount(kept.written)}: worldgen "
                                                    f"kept its first lines and its last {amount(TAIL)}",
                                    where=spec.source))
    return findings


def parse_duration(value: float | None, task: str | None) -> float:
    if value is not None:
        return float(value)
    return DEFAULT_DURATION.get(task or "", 20.0)


def parse_rate(text: str) -> float:
    """``--rate R|max`` → R (0 for max)."""
    if text.strip().lower() == "max":
        return 0.0
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not (value > 0 and value < 1e6):
        raise InputError(f"bad --rate value {text!r}", hint="give a positive number (1 = real time) or max")
    return value


def outcome_of(trace: dict, nodes: list[NodeSpec], children: list[Child], alive: dict[str, bool],
               ended_by: Child | None, options: RunOptions, cmd_type: str = "geometry_msgs/Twist",
               left: Sequence[Leftover] = ()) -> Outcome:
    """What a run came to, from the simulator's trace: the metrics (each robot's too, when there are several),
    the launch files' and the nodes' findings, a run the machine could not finish in time, and the processes
    ``left`` running after it (:attr:`.supervise.Supervisor.left`) said so."""
    outcome = Outcome(compute(trace), trace=trace, logs={c.name: c.output() for c in children})
    outcome.findings += [Finding(f["check"], f["severity"], f["message"], fix=f.get("fix"))
                         for f in trace.get("findings") or []]   # what the simulator saw of the nodes' endpoints
    if len(trace.get("robots") or []) > 1:   # several robots: each one's numbers, by namespace
        outcome.metrics["robots"] = {r["ns"]: dict(compute(dict(r, timing=trace.get("timing"))), name=r["name"])
                                     for r in trace["robots"]}
        outcome.metrics["graded_robot"] = trace.get("ns")
    outcome.findings += launch_findings(nodes, ended_by, outcome.metrics)
    if ended_by is None and (trace.get("timing") or {}).get("interrupted"):
        done = outcome.metrics.get("sim_time_s") or 0.0
        outcome.findings.append(Finding(
            "run", "error", f"the run was cut short at {done:.1f} of {options.duration:g} simulated seconds: "
                            "the machine could not keep the pace in the time allowed",
            fix="grade at a lower --rate, on a less loaded machine, or with fewer runs at once (-j)"))
    outcome.findings += node_findings(nodes, children, alive, outcome.metrics, cmd_type)
    outcome.findings += process_findings(nodes, children, left)
    return outcome


def end_limit(options: RunOptions) -> float:
    """Seconds of real time a run may take before it is cut short."""
    return options.duration / options.rate * 1.5 + 30 if options.rate > 0 else options.duration * 2 + 60


@dataclass(frozen=True)
class RunRequest:
    """What the command line asks of a run, before the world is read: the task and its numbers, the pace, and
    the robot (``spawn``, ``robot``, ``launch`` override what the world says; ``robot_ns`` picks the graded one)."""

    task: str | None = None
    target: float | None = None
    duration: float | None = None      # None: the task's default
    rate: float = 1.0                  # 0: as fast as it goes
    no_hit: str = "inf"
    spawn: tuple | None = None
    robot: str | None = None
    launch: Path | None = None
    robot_ns: str | None = None

    def options(self, world, *, record_scans: bool = False) -> RunOptions:
        return RunOptions(duration=parse_duration(self.duration, self.task), rate=self.rate, no_hit=self.no_hit,
                          task=self.task, target=self.target, robot_ns=self.robot_ns, record_scans=record_scans,
                          person=person_loop(world.spawn) if self.task == "person-follow" else None)


@dataclass(frozen=True)
class Outputs:
    """The files one run writes besides its report, and the report's format."""

    fmt: str = "text"
    junit: Path | None = None
    plot: Path | None = None
    csv: Path | None = None
    bag: Path | None = None
    html: Path | None = None
    html_page: object = None          # html_page(result, world, trace) -> bytes: the replay page's maker
    force: bool = False


def wait_for_end(simulator: Child, options: RunOptions, required: list[Child], supervisor: Supervisor,
                 trace_file: Path | None = None) -> Child | None:
    """Until the simulator has written ``trace_file`` or ended (its duration run, or a time limit); a required
    node that exits first stops the simulator (which then writes its trace) and is returned."""
    deadline = time.monotonic() + end_limit(options)
    while simulator.running and time.monotonic() < deadline:
        if trace_file is not None and trace_file.is_file():
            return None
        ended = next((c for c in required if not c.running), None)
        if ended is not None:
            supervisor.stop(simulator)
            return ended
        check_stopping()
        time.sleep(0.01)
    return None


def finish_run(simulator: Child, children: list[Child], nodes: list[NodeSpec], options: RunOptions,
               supervisor: Supervisor, trace_file: Path) -> tuple[dict, dict[str, bool], Child | None]:
    """Wait for the run's end (:func:`wait_for_end`), stop everything, and read the simulator's trace: the trace,
    which nodes were still running at the end, and the required node whose exit ended it (or None). Once the
    trace is written (the simulator writes it whole, and last) every process is ended at once, nothing of theirs
    left to wait for (:meth:`.Supervisor.end_all`); otherwise each is stopped in order (the simulator, stopped,
    writes what it has)."""
    ended_by = wait_for_end(simulator, options, [c for c, n in zip(children, nodes) if n.required], supervisor,
                            trace_file)
    written = trace_file.is_file()   # the simulator writes it whole, and last
    if written:
        let_crashes_end(children)
    alive = {c.name: c.running for c in children}
    if written:
        supervisor.end_all()
    else:
        supervisor.stop_all()
    if not trace_file.is_file():   # (a simulator stopped in order writes what it has)
        raise WorldgenError(f"the simulation ended without a result: {simulator.last_error_line() or 'no output'}",
                            hint="please report this to the worldgen developers")
    return json.loads(trace_file.read_text(encoding="utf-8")), alive, ended_by


def let_crashes_end(children: list[Child], grace: float = CRASH_GRACE) -> None:
    """Wait, up to ``grace`` s, for the nodes still running whose output ends in a Python traceback: an uncaught
    exception is ending them, and rospy's or rclpy's shutdown takes a few tenths of a second, which a run at
    ``--rate max`` may finish within. Waited for, such a node's crash is reported as at any rate; a healthy node
    costs no wait."""
    crashing = [c for c in children if c.running and ends_in_traceback(c.output())]
    deadline = time.monotonic() + grace
    while any(c.running for c in crashing) and time.monotonic() < deadline:
        check_stopping()
        time.sleep(0.01)


SURVIVED = ("bad callback", "Exception in thread", "Exception ignored")   # said before a traceback a node lives on


def ends_in_traceback(output: str) -> bool:
    """Whether ``output`` ends with the traceback of an exception that ends the program: its last "Traceback (most
    recent call last):" (of a chain, the last), then the frames (indented), and last the exception's own line; not
    one that rospy logs for a callback ("bad callback: …"), nor a thread's, which the node lives on after."""
    lines = [line for line in output.splitlines() if line.strip()]
    starts = [i for i, line in enumerate(lines) if line.startswith("Traceback (most recent call last):")]
    if not starts:
        return False
    first = starts[-1]
    while first > 0 and lines[first - 1].startswith(("During handling", "The above exception")):   # a chain
        first = max([i for i in starts if i < first - 1] or [0])
    if first > 0 and any(mark in lines[first - 1] for mark in SURVIVED):
        return False
    after = lines[starts[-1] + 1:]
    unindented = [i for i, line in enumerate(after) if not line.startswith(" ")]
    return unindented == [len(after) - 1] and len(after) > 1


def check_simulator(simulator: Child) -> None:
    """WorldgenError when the simulator process has ended before its run began: its own one-line error when it
    gave one, else its last line."""
    if simulator.running:
        return
    line = simulator.last_error_line()
    if line.startswith("worldgen: error: "):
        raise WorldgenError(line[len("worldgen: error: "):])
    raise WorldgenError(f"the simulator did not start: {line or 'no output'}",
                        hint="please report this to the worldgen developers")
