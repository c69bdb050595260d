"""alpha-audit."""
