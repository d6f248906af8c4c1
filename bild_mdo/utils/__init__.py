"""Small shared helpers (sparsity patterns, complex-step helpers)."""
from bild_mdo.utils.missing_imports import remember_missing

remember_missing()
