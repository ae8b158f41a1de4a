"""Identification of a pile's impedance profile from a head record (issue 24)."""
