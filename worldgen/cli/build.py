"""worldgen build commands (placeholder until implemented)."""

COMMANDS = []
