"""Striker design: the best striker that can exist and be machined (issue 11)."""
