"""Tests of the command-line contract."""
