"""Tests of grid files, atlases and the static site."""
