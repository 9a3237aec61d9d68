"""Gear trains: lever analogues and planetary trains."""
