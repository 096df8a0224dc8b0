"""Pure physics functions, one module per concern; they work on floats and CasADi symbols."""
