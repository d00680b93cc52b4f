"""Naive pure-Python reference pipeline: the test oracle for the Numba kernels."""
