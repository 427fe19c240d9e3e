"""The theory: equations of the model only (trap, creep, static, steady, Dieterich, linear
stability, units). Pure functions over arrays; no I/O, no protocol dictionaries, no plotting."""
