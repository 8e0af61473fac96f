"""The program, ``worldgen`` and ``python -m worldgen``: what starts before the command line is read, then the
command line (:func:`worldgen.cli.run`).

``worldgen validate`` simulates each world in a fork of a server that has imported pybullet and the simulator
(:mod:`worldgen.sim.forkserver`). Forked here, before click, the checks and the launch-file readers are imported,
the server imports its share on the second core while this process reads the command line and plans, and the
first simulation starts sooner (``benchmarks/bench_speed.py``). Only the command's name and its flags that say
it will not simulate are looked at, and only to decide that: the command parses its options as always and uses
the server when one is running (:func:`worldgen.sim.forkserver.active`); one started for a command that then
does not simulate (a usage error, say) costs only its CPU, and is ended with the command.
"""

import sys

NO_SIMULATION = ("--skip-sim", "-h", "--help")


def run() -> None:
    if not may_simulate(sys.argv[1:]):
        from .cli import run as command_line

        return command_line()
    from .check.preload import SHARED_MODULES, SIM_MODULES
    from .sim.forkserver import forking, one_blas_thread

    one_blas_thread()   # before numpy is imported here or there: the server must fork single-threaded
    with forking(SHARED_MODULES + SIM_MODULES):
        from .cli import outcome

        code = outcome()
    from .cli import leave

    leave(code)


def may_simulate(args: list) -> bool:
    """Whether the command line ``args`` (without the program's name) is a ``validate`` that may simulate."""
    return args[:1] == ["validate"] and not any(arg in NO_SIMULATION for arg in args[1:])


if __name__ == "__main__":
    run()
