"""BatchValues: the arrays of one result or of a batch, read as attributes (the turbine results' common base)."""
from __future__ import annotations

__all__ = ["BatchValues"]


class BatchValues:
    """Arrays ``values[name]`` with the designs (or rotors) on axis 0, read as attributes.

    For a batch (``is_batch``) an attribute is the whole array; for one design its only row: a float for a
    per-design value, a 1-D array for a distribution.
    """

    def __getattr__(self, name):
        values = self.__dict__.get("values", {})
        if name not in values:
            raise AttributeError(name)
        value = values[name]
        return value if self.is_batch else (value[0] if value.ndim == 2 else float(value[0]))

    def __len__(self):
        return len(next(iter(self.values.values())))

    def _row_values(self, index):
        """The values of design ``index`` (a negative index counts from the end; IndexError outside)."""
        index = range(len(self))[index]
        return {name: value[index:index + 1] for name, value in self.values.items()}
