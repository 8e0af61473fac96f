"""A ROS master: is one answering at a URI, and starting a private one (``rosmaster --core``'s master, without
its log file) on a free port.

The master is a child in a process group of its own (see :mod:`.supervise`), waited for until it answers, and
stopped with everything it started.
"""

from __future__ import annotations

import os
import shutil
import socket
import time
import xmlrpc.client
from pathlib import Path
from typing import Callable

from ..core.errors import InputError
from ..bridge.supervise import Child, Supervisor, check_stopping
from .rosenv import distro_package

CALLER = "/worldgen"
START_TIMEOUT = 20.0   # s for a master to answer


def master_answers(uri: str, timeout: float = 1.0) -> bool:
    """Whether a ROS master answers ``getSystemState`` at ``uri``."""
    old = socket.getdefaulttimeout()
    socket.setdefaulttimeout(timeout)
    try:
        code, _, _ = xmlrpc.client.ServerProxy(uri).getSystemState(CALLER)
        return code == 1
    except (OSError, xmlrpc.client.Error, ValueError):
        return False
    finally:
        socket.setdefaulttimeout(old)


def running_node(uri: str, name: str, timeout: float = 1.0) -> int | None:
    """The pid of the node ``name`` registered with the master at ``uri``, when it answers there; None when no
    such node is registered, or its registration is stale (the node is gone)."""
    old = socket.getdefaulttimeout()
    socket.setdefaulttimeout(timeout)
    try:
        code, _, node_uri = xmlrpc.client.ServerProxy(uri).lookupNode(CALLER, name)
        if code != 1:
            return None
        code, _, pid = xmlrpc.client.ServerProxy(node_uri).getPid(CALLER)
        return pid if code == 1 else None
    except (OSError, xmlrpc.client.Error, ValueError):
        return None
    finally:
        socket.setdefaulttimeout(old)


def checked_master_uri(value: str) -> tuple[str, str, int]:
    """``ROS_MASTER_URI`` as (the URI, its host, its port); InputError when it is not ``http://HOST:PORT``."""
    from urllib.parse import urlparse

    try:
        parsed = urlparse(value)
        scheme, host, port = parsed.scheme, parsed.hostname, parsed.port
    except ValueError:   # a port that is no number, or out of range
        scheme = host = port = None
    if scheme != "http" or not host:
        raise InputError(f"ROS_MASTER_URI={value} is not a ROS master's address",
                         hint="set it as http://HOST:PORT (export ROS_MASTER_URI=http://localhost:11311), or unset it")
    return value, host, port or 11311


def is_this_machine(host: str) -> bool:
    """Whether ``host`` names this machine (a master can be started for it here)."""
    try:
        addresses = {info[4][0] for info in socket.getaddrinfo(host, None, proto=socket.IPPROTO_TCP)}
    except (OSError, UnicodeError):
        return False
    for address in addresses:
        family = socket.AF_INET6 if ":" in address else socket.AF_INET
        try:
            with socket.socket(family) as sock:
                sock.bind((address, 0))   # only an address of this machine can be bound
            return True
        except OSError:
            continue
    return False


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def port_in_use(port: int) -> bool:
    with socket.socket() as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            sock.bind(("", port))
        except OSError:
            return True
    return False


ROSMASTER_PLACES = ("/usr/bin/rosmaster", "/opt/ros/noetic/bin/rosmaster")   # Debian's, ROS's own


def rosmaster_command() -> str:
    """``rosmaster`` on PATH, else where Debian's or ROS's own package puts it (a venv's or pipx's PATH may lack
    /usr/bin or /opt/ros/noetic/bin); InputError naming the PATH looked through and the package otherwise."""
    found = shutil.which("rosmaster") or next((p for p in ROSMASTER_PLACES if os.access(p, os.X_OK)), None)
    if found is None:
        package = "python3-rosmaster" if distro_package() == "python3-rospy" else "ros-noetic-rosmaster"
        raise InputError(f"rosmaster (the ROS master) is neither on PATH ({os.environ.get('PATH', '')}) nor in "
                         f"{' or '.join(ROSMASTER_PLACES)}: install {package}",
                         hint=f"apt install {package}, or source /opt/ros/noetic/setup.bash")
    return found


# What ``rosmaster --core -p PORT`` runs, less its log file: rosmaster's own Master on the port, until stopped.
# (rosmaster's main first reads a logging configuration and opens master.log under ROS_LOG_DIR, a tenth of a
# second of the master's start, which every run waits for; a private master's log is thrown away with its run.)
MASTER_MAIN = """import sys, time
import rosmaster.master, rosmaster.master_api
master = rosmaster.master.Master(int(sys.argv[sys.argv.index('-p') + 1]), rosmaster.master_api.NUM_WORKERS)
try:
    master.start()
    while master.ok():
        time.sleep(0.1)
except KeyboardInterrupt:
    pass
finally:
    master.stop()
"""


def master_argv(command: str, port: int) -> list[str]:
    """The command line of a private master on ``port``: :data:`MASTER_MAIN` run by the Python of ``command``
    (rosmaster's ``#!`` line), or ``command --core -p PORT`` itself when that line names no Python."""
    try:
        with open(command, "rb") as handle:
            first = handle.readline(200).decode("utf-8", "replace").strip()
    except OSError:
        first = ""
    python = first[2:].strip().split()[0] if first.startswith("#!") and first[2:].strip() else ""
    if "python" in os.path.basename(python) and os.access(python, os.X_OK):
        return [python, "-c", MASTER_MAIN, "--core", "-p", str(port)]
    return [command, "--core", "-p", str(port)]


def start_master(supervisor: Supervisor, port: int | None, env: dict[str, str], log: Path | None = None,
                 meanwhile: Callable[[str], None] | None = None) -> tuple[Child, str]:
    """``rosmaster --core -p PORT`` (a free port when None; see :func:`master_argv`) under ``supervisor``, waited
    for until it answers; returns the child and its URI. InputError when the port is taken or the master does not
    come up. ``meanwhile(uri)`` is called once the master is started, before waiting for it (what can start beside
    it)."""
    child, uri = launch_master(supervisor, port, env, log)
    if meanwhile is not None:
        meanwhile(uri)
    await_master(supervisor, child, uri)
    return child, uri


def launch_master(supervisor: Supervisor, port: int | None, env: dict[str, str], log: Path | None = None
                  ) -> tuple[Child, str]:
    """The first half of :func:`start_master`: the master started, not waited for."""
    command = rosmaster_command()
    if port is None:
        port = free_port()
    elif port_in_use(port):
        raise InputError(f"port {port} is already in use, so no ROS master can start there",
                         hint="stop what listens there, or set ROS_MASTER_URI to a free port")
    uri = f"http://127.0.0.1:{port}"
    child = supervisor.start("rosmaster", master_argv(command, port), dict(env, ROS_MASTER_URI=uri), log=log,
                             last=True)
    return child, uri


def await_master(supervisor: Supervisor, child: Child, uri: str) -> None:
    """The second half of :func:`start_master`: until the master ``child`` answers at ``uri``."""
    port = uri.rsplit(":", 1)[1]
    deadline = time.monotonic() + START_TIMEOUT
    while time.monotonic() < deadline:
        if not child.running:
            raise InputError(f"rosmaster could not start on port {port}: {child.last_error_line() or 'it exited'}",
                             hint="is the port free? is python3-rosmaster installed?")
        if master_answers(uri, 0.5):
            if _master_pid(uri) != child.proc.pid:   # another master took the port first
                supervisor.stop(child)
                raise InputError(f"rosmaster could not start on port {port}: another master answers there",
                                 hint="set ROS_MASTER_URI to a free port")
            return
        check_stopping()
        time.sleep(0.01)
    supervisor.stop(child)
    raise InputError(f"rosmaster did not answer on port {port} within {START_TIMEOUT:g} s")


def _master_pid(uri: str) -> int | None:
    try:
        code, _, pid = xmlrpc.client.ServerProxy(uri).getPid(CALLER)
    except (OSError, xmlrpc.client.Error):
        return None
    return pid if code == 1 else None


def set_param(uri: str, name: str, value) -> None:
    """Set the parameter ``name`` on the master at ``uri``; InputError when it refuses it or cannot carry it."""
    try:
        code, message, _ = xmlrpc.client.ServerProxy(uri).setParam(CALLER, name, value)
    except (TypeError, OverflowError, xmlrpc.client.Error, OSError) as err:
        raise InputError(f"the ROS master at {uri} cannot hold the parameter {name}: {err}",
                         hint="give it a plain value (a number, string, bool, or a list or mapping of them)") from None
    if code != 1:
        raise InputError(f"the ROS master at {uri} refused to set {name}: {message}")


def get_param(uri: str, name: str, default=None):
    try:
        code, _, value = xmlrpc.client.ServerProxy(uri).getParam(CALLER, name)
    except (OSError, xmlrpc.client.Error):
        return default
    return value if code == 1 else default


def node_names(uri: str) -> set[str]:
    """Every node the master knows (publishing, subscribing or serving anything)."""
    try:
        code, _, state = xmlrpc.client.ServerProxy(uri).getSystemState(CALLER)
    except (OSError, xmlrpc.client.Error):
        return set()
    names = set()
    for group in state if code == 1 else ():
        for _, nodes in group:
            names.update(nodes)
    return names


def ros_env(base: dict[str, str] | None, uri: str, home: Path) -> dict[str, str]:
    """The environment of a process on the master at ``uri``: ROS_HOME and the log folder under ``home`` (so
    nothing goes to ~/.ros), unbuffered Python output."""
    env = dict(os.environ if base is None else base)
    home.mkdir(parents=True, exist_ok=True)
    env.update(ROS_MASTER_URI=uri, ROS_HOME=str(home), ROS_LOG_DIR=str(home / "log"), PYTHONUNBUFFERED="1")
    if "ROS_IP" not in env and "ROS_HOSTNAME" not in env:
        env["ROS_IP"] = "127.0.0.1"
    return env
