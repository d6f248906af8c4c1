"""A direct linear solver for feed-forward chains: the assembled Jacobian factored in dependency order.

The Jacobian ``dR/do`` of a chain of explicit components and of implicit
components whose states each depend on themselves only (BILD's reference
station and eta2, the inflow angle of a BEM analysis) is triangular once its
unknowns are sorted so that every one comes after those it depends on.
OpenMDAO's :class:`~openmdao.api.DirectSolver` factors it with SuperLU's
default column ordering (COLAMD) and partial pivoting, which does not find that
order: on :class:`~bild_mdo.bild.BILDGroup` (one design, 30 stations, 575
unknowns) the factors hold 7,337 entries against the matrix's 3,421, the
factorisation takes 1.16 ms and each back-substitution 26 us.  In dependency
order with diagonal pivots the factors add no entry to the matrix (``L`` is the
matrix's lower triangle, ``U`` its diagonal): 0.11 ms and 12 us on the same
machine (benchmarks/bild_speed.py prints the totals this changes).

Diagonal pivots are exact here: a triangular solve needs no pivoting (it is
backward stable whatever the sizes of its entries).  The order is computed once
per sparsity structure (levels of the dependency graph, vectorised) and reused
while the structure stays the same.  A Jacobian with a cycle (a Newton loop
such as ``section_point='local'``), a dense or distributed one, or one whose
diagonal has a zero falls back to :class:`~openmdao.api.DirectSolver` unchanged,
which reports a singular matrix as it always does.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om
import scipy.sparse
import scipy.sparse.linalg
from openmdao.jacobians.jacobian import CSCJacobian
from openmdao.matrices.csc_matrix import CSCMatrix


def dependency_order(matrix):
    """An order of the unknowns of a square sparse matrix in which it is lower triangular, or None.

    Unknown ``j`` must come before unknown ``i`` when ``matrix[i, j] != 0``
    structurally (``i != j``).  Kahn's algorithm by levels: every level is the
    set of unknowns whose predecessors are all placed, found with whole-array
    operations (the number of levels is the depth of the chain).

    Returns
    -------
    ndarray of int or None
        ``order[k]`` is the unknown at position ``k``; None if the dependency
        graph has a cycle (no such order exists).
    """
    n = matrix.shape[0]
    coo = matrix.tocoo()
    off = coo.row != coo.col
    # successors[j] = the unknowns i that need j (CSR rows indexed by j).
    successors = scipy.sparse.csr_matrix((np.ones(np.count_nonzero(off)), (coo.col[off], coo.row[off])),
                                         shape=(n, n))
    successors.sum_duplicates()
    waiting = np.diff(successors.tocsc().indptr)  # predecessors not yet placed, per unknown
    levels = []
    level = np.flatnonzero(waiting == 0)
    placed = 0
    while level.size:
        levels.append(level)
        placed += level.size
        waiting[level] = -1
        starts, ends = successors.indptr[level], successors.indptr[level + 1]
        counts = ends - starts
        # The successors of the whole level, concatenated: indices[starts[k] : ends[k]] for every k.
        offsets = np.repeat(starts - np.concatenate([[0], np.cumsum(counts)[:-1]]), counts)
        needed = successors.indices[offsets + np.arange(counts.sum())]
        waiting -= np.bincount(needed, minlength=n)
        level = np.flatnonzero(waiting == 0)
    return np.concatenate(levels) if placed == n else None


class _PermutedLU:
    """The SuperLU factors of ``A[order][:, order]``, solving ``A x = b`` (or its transpose) for ``x``."""

    def __init__(self, lu, order):
        self._lu = lu
        self._order = order
        self._position = np.empty_like(order)
        self._position[order] = np.arange(order.size)

    def solve(self, rhs, trans="N"):
        # Gathers only (np.take): x = P^T y with y = LU^{-1} P b, P b = b[order], (P^T y) = y[position].
        return np.take(self._lu.solve(np.take(rhs, self._order, axis=0), trans), self._position, axis=0)


class BatchedCSCJacobian(CSCJacobian):
    """OpenMDAO's CSC assembled Jacobian, updated with one scatter of all sub-Jacobians instead of one each.

    ``CSCJacobian`` adds every sub-Jacobian into the matrix's data with its
    own gather and scatter: 231 of them for one BILD design, 1.3 ms of a
    linearisation that costs 3-4 ms in all.  This gathers their values with
    one ``np.concatenate`` and writes them with one scatter (a ``bincount``
    where two sub-Jacobians share an entry), using OpenMDAO's own map from
    sub-Jacobian entries to CSC entries.  The sparsity computation (random
    values) and any matrix this does not recognise take OpenMDAO's path.

    :class:`TriangularDirectSolver` installs it on the system it solves
    (:meth:`adopt`); it relies on OpenMDAO internals (``_submats``,
    ``_coo_slices``, ``_coo_to_csc_map``) and falls back to the parent's update
    where they are missing.
    """

    @staticmethod
    def adopt(jacobian):
        """Turn OpenMDAO's ``CSCJacobian`` ``jacobian`` into this class (same state); other types are left."""
        if type(jacobian) is CSCJacobian:
            jacobian.__class__ = BatchedCSCJacobian

    def _update_matrix(self, matrixobj, randgen, dtype):
        plan = self._plan(matrixobj) if randgen is None else None
        if plan is None:
            return super()._update_matrix(matrixobj, randgen, dtype)
        subjacs, index, factor, shared = plan
        matrixobj._pre_update(dtype)
        data = np.concatenate([subjac.get_as_coo_data(None) for subjac in subjacs])
        if factor is not None:
            data = data * factor
        target = matrixobj._matrix.data
        if not shared:
            target[index] = data
        elif np.iscomplexobj(data):
            target[:] = (np.bincount(index, weights=data.real, minlength=target.size)
                         + 1j * np.bincount(index, weights=data.imag, minlength=target.size))
        else:
            target[:] = np.bincount(index, weights=data, minlength=target.size)
        matrixobj._post_update()

    def _plan(self, matrixobj):
        """Sub-Jacobians, the CSC entry of each of their values, the factors and whether entries are shared."""
        plans = self.__dict__.setdefault("_batched_plans", {})
        subjacs = list(getattr(matrixobj, "_submats", {}).values())
        plan = plans.get(id(matrixobj))
        factors = [subjac.factor for subjac in subjacs]
        if plan is not None and plan[0] == subjacs and plan[1] == factors:
            return plan[2]
        plan = None
        mapping, slices = getattr(matrixobj, "_coo_to_csc_map", None), getattr(matrixobj, "_coo_slices", None)
        if isinstance(matrixobj, CSCMatrix) and mapping is not None and slices is not None and subjacs:
            try:
                parts = [mapping[slices[subjac.key]] for subjac in subjacs]
                sizes = [np.size(subjac.get_as_coo_data(None)) for subjac in subjacs]
            except (KeyError, AttributeError, TypeError):
                parts = None
            if parts is not None and sizes == [part.size for part in parts]:
                index = np.concatenate(parts)
                factor = None
                if any(f is not None for f in factors):
                    factor = np.repeat([1.0 if f is None else f for f in factors], sizes)
                shared = np.unique(index).size != index.size
                plan = (subjacs, index, factor, shared)
        plans[id(matrixobj)] = (subjacs, factors, plan)
        return plan


class TriangularDirectSolver(om.DirectSolver):
    """:class:`~openmdao.api.DirectSolver` that factors a triangular assembled Jacobian in dependency order.

    Same options and results as ``DirectSolver`` (module docstring): with
    ``assemble_jac=True`` and a sparse Jacobian without cycles, SuperLU runs
    on the Jacobian permuted into dependency order with diagonal pivots, so
    the factors add no entry; otherwise it is ``DirectSolver``.
    """

    SOLVER = "LN: DirectTriangular"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self._structure = None  # (indptr, indices, order or None, permuted matrix, data index)

    def _permuted(self, matrix):
        """``matrix`` in dependency order (a CSC matrix) and that order, or (None, None) if it has a cycle."""
        cached = self._structure
        if cached is None or not (cached[0].shape == matrix.indptr.shape and cached[1].shape == matrix.indices.shape
                                  and np.array_equal(cached[0], matrix.indptr)
                                  and np.array_equal(cached[1], matrix.indices)):
            order = dependency_order(matrix)
            permuted = index = None
            if order is not None:
                position = np.empty_like(order)
                position[order] = np.arange(order.size)
                coo = scipy.sparse.csc_matrix((np.arange(1.0, matrix.nnz + 1.0), matrix.indices, matrix.indptr),
                                              shape=matrix.shape).tocoo()
                permuted = scipy.sparse.csc_matrix((coo.data, (position[coo.row], position[coo.col])),
                                                   shape=matrix.shape)
                permuted.sort_indices()
                # Entry k of the permuted matrix is entry index[k] of the matrix (structure fixed from here on).
                index = permuted.data.astype(np.intp) - 1
            cached = self._structure = (matrix.indptr.copy(), matrix.indices.copy(), order, permuted, index)
        order, permuted, index = cached[2:]
        if order is None:
            return None, None
        permuted.data = matrix.data[index]
        return permuted, order

    def _linearize(self):
        system = self._system()
        if system._get_assembled_jac() is not None:
            BatchedCSCJacobian.adopt(system._assembled_jac)
        matrix = system._assembled_jac.get_dr_do_matrix() if system._get_assembled_jac() is not None else None
        if system.comm.size == 1 and isinstance(matrix, scipy.sparse.csc_matrix):
            permuted, order = self._permuted(matrix)
            diagonal_ok = permuted is not None and np.all(permuted.diagonal() != 0.0)
            if diagonal_ok:
                try:
                    lu = scipy.sparse.linalg.splu(permuted, permc_spec="NATURAL", diag_pivot_thresh=0.0)
                except RuntimeError:
                    lu = None
                if lu is not None:
                    self._lu = _PermutedLU(lu, order)
                    if self._lin_rhs_checker is not None:
                        self._lin_rhs_checker.clear()
                    return
        super()._linearize()

    def solve(self, mode, rel_systems=None):
        """``DirectSolver.solve``; with the triangular factors and no scaling, without its per-call overhead.

        A reverse ``compute_totals`` calls this once per seed (62 times for one BILD design), so the
        checks and the unit/scaling context of the parent, which do nothing here, are skipped.
        """
        system = self._system()
        if (not isinstance(self._lu, _PermutedLU) or system._has_output_scaling or system._has_resid_scaling
                or (mode != "fwd" and self._lin_rhs_checker is not None)):
            return super().solve(mode, rel_systems)
        if mode == "fwd":
            system._doutputs.asarray()[:] = self._lu.solve(system._dresiduals.asarray(), "N")
        else:
            system._dresiduals.asarray()[:] = self._lu.solve(system._doutputs.asarray(), "T")
