"""What ``worldgen validate``'s simulations need imported in the fork server (:mod:`worldgen.sim.forkserver`),
by name: importing this module imports none of them.

The job and the world reader are imported by the command too (a small world's job reads it itself:
:mod:`.sim_run`); pybullet and the session only in the server, with a client connected ahead
(:func:`worldgen.sim.session.warm`)."""

SHARED_MODULES = ("worldgen.check.sim_job", "worldgen.check.sources", "worldgen.sdf.reader")
SIM_MODULES = ("worldgen.sim.session:warm", "worldgen.sim.behaviours", "worldgen.sim.lidar")
