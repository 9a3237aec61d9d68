"""Tests of gear trains."""
