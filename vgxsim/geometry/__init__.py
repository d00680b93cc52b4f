"""vgxsim.geometry."""
