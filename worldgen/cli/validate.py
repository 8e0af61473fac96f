"""worldgen validate commands (placeholder until implemented)."""

COMMANDS = []
