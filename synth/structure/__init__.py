"""Core types of a structure and the exact sub-chain test: codes, chains, mechanisms."""
