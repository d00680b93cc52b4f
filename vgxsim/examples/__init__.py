"""vgxsim.examples."""
