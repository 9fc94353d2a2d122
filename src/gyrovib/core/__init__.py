"""Pure numpy engines. Nothing here knows about YAML, click or rich.

All rates are in one consistent unit (gyrovib passes deg/s); frequencies in Hz.
"""
