"""Small shared helpers (sparsity patterns, complex-step helpers)."""
