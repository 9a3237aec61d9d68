"""Tests of the balancing package."""
