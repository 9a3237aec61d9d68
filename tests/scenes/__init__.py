"""Tests of the scene files and runner."""
