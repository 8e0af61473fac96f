"""worldgen preview command (placeholder until implemented)."""

COMMANDS = []
