"""Independent checkers: slow, obviously correct methods that import nothing from the engines.

Every test named ``test_*_vs_oracle.py`` compares an engine with one of these.
"""
