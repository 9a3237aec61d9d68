"""Tests of number and type synthesis, units, mechanisms and R/P variants."""
