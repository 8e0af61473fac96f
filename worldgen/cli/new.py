"""worldgen new command (placeholder until implemented)."""

COMMANDS = []
