"""Toy contact laws, one module each, that tests/test_contact_laws.py registers through the
public route (`LAWS.register(Law(...))`) to show that a new law needs nothing else."""
