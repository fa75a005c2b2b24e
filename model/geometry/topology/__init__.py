"""Topology of pixel sets: connected components (labeling) and crack boundaries (cracks)."""
