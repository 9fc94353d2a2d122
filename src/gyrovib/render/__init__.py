"""Renderers: pure functions from result objects to text. No I/O here."""
