"""Runtime sources kept as real files and emitted into generated programs only when used."""
