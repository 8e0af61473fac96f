"""Validation: a world, spec, launch file or package → scene → checks (geometric, libsdformat, the simulator
child) → a report in text, JSON or JUnit."""
