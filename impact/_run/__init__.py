"""Running scenes: impacts, indentation tests and parameter sweeps, results in SI units."""
