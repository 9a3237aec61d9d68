"""Structural analysis of codes and chains, and the directed repair of defective ones."""
