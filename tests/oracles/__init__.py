"""Slow, independent, obviously-correct reference implementations used as test oracles."""
