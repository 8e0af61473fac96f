"""worldgen drive command (placeholder until implemented)."""

COMMANDS = []
