"""worldgen ros commands (placeholder until implemented)."""

COMMANDS = []
