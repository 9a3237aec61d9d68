"""Tests of the analysis of codes and chains and of repairs."""
