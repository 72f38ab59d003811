"""The crankshaft as a structure and its strength check (issue 38)."""
