"""Number synthesis (codes), type synthesis (stage A: branch multigraphs, stage B: binary links), mechanisms."""
