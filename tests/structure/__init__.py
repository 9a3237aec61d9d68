"""Tests of codes, chains and the exact sub-chain test."""
