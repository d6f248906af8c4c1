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

A reverse ``compute_totals`` asks for one solve with the transpose per output
entry (62 for one BILD design: thrust, torque, 30 chords, 30 twists), each seed
a unit vector.  The first seed of a variable solves the rest of that
variable's seeds with it, by levels of the dependency graph (one sparse product
per level for all of them), and the others are served from that block until
the next linearisation: 7 us per seed against 16 us for one SuperLU
back-substitution each.  The two costly parts of OpenMDAO's linearisation of
such a chain are replaced too: the assembly of the CSC matrix from its
sub-Jacobians (:class:`BatchedCSCJacobian`: one scatter, 0.22 ms against
1.3 ms) and the per-call checks of ``DirectSolver.solve``.

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

try:  # Y += A X for CSR A and row-major dense X, Y: SciPy's kernel behind csr_matrix @ ndarray.
    from scipy.sparse._sparsetools import csr_matvecs as _csr_matvecs
except ImportError:  # pragma: no cover - a SciPy without it: one SuperLU solve per seed
    _csr_matvecs = None


def dependency_order(matrix, levels=False):
    """An order of the unknowns of a square sparse matrix in which it is lower triangular, or None.

    Unknown ``j`` must come before unknown ``i`` when ``matrix[i, j] != 0``
    structurally (``i != j``).  Kahn's algorithm by levels: every level is the
    set of unknowns whose predecessors are all placed, found with whole-array
    operations (the number of levels is the depth of the chain).

    Returns
    -------
    ndarray of int or None
        ``order[k]`` is the unknown at position ``k``; None if the dependency
        graph has a cycle (no such order exists).  With ``levels=True``, the
        tuple ``(order, sizes)``, ``sizes`` the number of unknowns of each
        level in turn (an unknown depends only on unknowns of earlier levels).
    """
    n = matrix.shape[0]
    coo = matrix.tocoo()
    off = coo.row != coo.col
    # successors[j] = the unknowns i that need j (CSR rows indexed by j).
    successors = scipy.sparse.csr_matrix((np.ones(np.count_nonzero(off)), (coo.col[off], coo.row[off])),
                                         shape=(n, n))
    successors.sum_duplicates()
    waiting = np.diff(successors.tocsc().indptr)  # predecessors not yet placed, per unknown
    found = []
    level = np.flatnonzero(waiting == 0)
    placed = 0
    while level.size:
        found.append(level)
        placed += level.size
        waiting[level] = -1
        starts, ends = successors.indptr[level], successors.indptr[level + 1]
        counts = ends - starts
        # The successors of the whole level, concatenated: indices[starts[k] : ends[k]] for every k.
        offsets = np.repeat(starts - np.concatenate([[0], np.cumsum(counts)[:-1]]), counts)
        needed = successors.indices[offsets + np.arange(counts.sum())]
        waiting -= np.bincount(needed, minlength=n)
        level = np.flatnonzero(waiting == 0)
    order = np.concatenate(found) if placed == n else None
    if not levels:
        return order
    return order, (np.array([level.size for level in found]) if order is not None else None)


class _PermutedLU:
    """Solves ``A x = b`` and ``A^T x = b`` with ``A[order][:, order]`` lower triangular.

    One right-hand side: SuperLU's factors of the permuted matrix (``solve``).
    A block of unit right-hand sides of the transpose (the seeds of one
    variable in a reverse ``compute_totals``): one back-substitution by levels
    for all of them at once, whole-array operations per level
    (``transposed_unit_block``): about 7 us per seed for a block of 30 against
    16 us for one SuperLU call each (BILD, one design, 575 unknowns).
    """

    def __init__(self, lu, order, permuted, level_sizes):
        self._lu = lu
        self._order = order
        self._position = np.empty_like(order)
        self._position[order] = np.arange(order.size)
        self._permuted = permuted
        self._bounds = np.concatenate([[0], np.cumsum(level_sizes)])
        self._inverse_diagonal = None
        self._levels = None  # per level: start, stop, its column pointers from 0, its entries' slice

    def solve(self, rhs, trans="N"):
        # Gathers only (np.take): x = P^T y with y = LU^{-1} P b, P b = b[order], (P^T y) = y[position].
        return np.take(self._lu.solve(np.take(rhs, self._order, axis=0), trans), self._position, axis=0)

    def transposed_unit_block(self, unknowns):
        """Columns ``x_k`` with ``A^T x_k = e_{unknowns[k]}``, shape ``(n, len(unknowns))``, column-major.

        Back-substitution on ``A_p^T`` (upper triangular) from the last level to the first:
        ``y_j = (c_j - sum_{k != j} A_p[k, j] y_k) / A_p[j, j]``, where every ``k`` with
        ``A_p[k, j] != 0`` needs ``j`` and so lies in a later level, already solved.  The
        columns of a level in the CSC matrix are the rows of ``A_p^T``: one sparse-times-dense
        product per level (SciPy's compiled ``csr_matvecs`` on slices of the matrix, no copy;
        the diagonal multiplies the still-zero ``y_j``).  Levels after the last seed's are zero
        and skipped; a seed ``c_j = 1`` is added where its level is solved.
        """
        matrix = self._permuted
        n, m = matrix.shape[0], len(unknowns)
        if self._levels is None:
            indptr = matrix.indptr
            self._inverse_diagonal = -1.0 / matrix.diagonal()
            self._levels = [(start, stop, indptr[start:stop + 1] - indptr[start], slice(indptr[start], indptr[stop]))
                            for start, stop in zip(self._bounds[:-1].tolist(), self._bounds[1:].tolist())]
        minus_inverse_diagonal = self._inverse_diagonal
        seeds = self._position[unknowns]
        seed_level = np.searchsorted(self._bounds, seeds, side="right") - 1
        y = np.zeros((n, m))
        flat = y.reshape(-1)
        data, indices = matrix.data, matrix.indices
        for level in range(int(seed_level.max()), -1, -1):
            start, stop, pointers, entries = self._levels[level]
            sums = np.zeros((stop - start, m))
            _csr_matvecs(stop - start, n, m, pointers, indices[entries], data[entries], flat, sums.reshape(-1))
            np.multiply(sums, minus_inverse_diagonal[start:stop, None], out=y[start:stop])
            if level in seed_level:
                here = np.flatnonzero(seed_level == level)
                y[seeds[here], here] -= minus_inverse_diagonal[seeds[here]]
        return np.asfortranarray(y[self._position])


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
                # An entry written by two sub-Jacobians (bincount: O(n), where np.unique sorts).
                shared = bool(index.size) and int(np.bincount(index).max()) > 1
                plan = (subjacs, index, factor, shared)
        plans[id(matrixobj)] = (subjacs, factors, plan)
        return plan


#: Largest block of reverse seeds solved together, and largest block in numbers (unknowns x seeds).
SEED_BLOCK = 64
SEED_BLOCK_ENTRIES = 2_000_000


class TriangularDirectSolver(om.DirectSolver):
    """:class:`~openmdao.api.DirectSolver` that factors a triangular assembled Jacobian in dependency order.

    Same options and results as ``DirectSolver`` (module docstring): with
    ``assemble_jac=True`` and a sparse Jacobian without cycles, SuperLU runs
    on the Jacobian permuted into dependency order with diagonal pivots, so
    the factors add no entry, and a reverse seed (a unit right-hand side) is
    solved with the seeds after it in its variable, by levels, the rest served
    from that block until the next linearisation; otherwise it is
    ``DirectSolver``.
    """

    SOLVER = "LN: DirectTriangular"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self._structure = None  # (indptr, indices, order or None, level sizes, permuted matrix, data index)
        self._variable_stops = None  # (vector size, end of the variable of every unknown)
        self._seeds = {}  # unknown -> (block of solutions, column): transposed unit solves since the last linearize

    def _permuted(self, matrix):
        """``matrix`` in dependency order (a CSC matrix) and that order, or (None, None) if it has a cycle."""
        cached = self._structure
        if cached is None or not (cached[0].shape == matrix.indptr.shape and cached[1].shape == matrix.indices.shape
                                  and np.array_equal(cached[0], matrix.indptr)
                                  and np.array_equal(cached[1], matrix.indices)):
            order, level_sizes = dependency_order(matrix, levels=True)
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
            cached = self._structure = (matrix.indptr.copy(), matrix.indices.copy(), order, level_sizes, permuted,
                                        index)
        order, level_sizes, permuted, index = cached[2:]
        if order is None:
            return None, None, None
        # A fresh data array (not written in place): the factors and blocks of the previous linearisation are
        # discarded with it (the solver replaces its _PermutedLU), and SciPy's validation is not repeated.
        permuted.data = matrix.data[index]
        return permuted, order, level_sizes

    def _linearize(self):
        system = self._system()
        jacobian = system._get_assembled_jac()
        serial = system.comm.size == 1
        if serial and jacobian is not None:
            BatchedCSCJacobian.adopt(jacobian)
        matrix = jacobian.get_dr_do_matrix() if jacobian is not None else None
        if serial and isinstance(matrix, scipy.sparse.csc_matrix):
            permuted, order, level_sizes = self._permuted(matrix)
            diagonal_ok = permuted is not None and np.all(permuted.diagonal() != 0.0)
            if diagonal_ok:
                try:
                    lu = scipy.sparse.linalg.splu(permuted, permc_spec="NATURAL", diag_pivot_thresh=0.0)
                except RuntimeError:
                    lu = None
                if lu is not None:
                    self._lu = _PermutedLU(lu, order, permuted, level_sizes)
                    self._seeds = {}
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
            return
        rhs, solution = system._doutputs.asarray(), system._dresiduals.asarray()
        seed = rhs.nonzero()[0]
        if seed.size == 1:
            unknown = int(seed[0])
            hit = self._seeds.get(unknown)
            if hit is not None:  # a later seed of a variable whose block is solved
                np.multiply(hit[0][:, hit[1]], rhs[unknown], out=solution)
                return
            if rhs.dtype == np.float64:
                column = self._seed_solution(system, unknown)
                if column is not None:
                    np.multiply(column, rhs[unknown], out=solution)
                    return
        solution[:] = self._lu.solve(rhs, "T")

    def _seed_solution(self, system, unknown):
        """``x`` with ``A^T x = e_unknown``, solving with it the seeds after it in its variable (at most
        :data:`SEED_BLOCK` seeds, ``n`` x block at most :data:`SEED_BLOCK_ENTRIES` numbers), kept for the
        next seeds until the next linearisation; None for a seed alone in its variable (SuperLU solves it)."""
        size = system._doutputs.asarray().size
        if self._variable_stops is None or self._variable_stops[0] != size:
            ranges = getattr(system._doutputs, "ranges", None)  # (name, start, stop) of each variable
            if ranges is None:
                return None
            stops = np.zeros(size, dtype=np.intp)
            for _, start, stop in ranges():
                stops[start:stop] = stop
            self._variable_stops = (size, stops)
        stop = min(int(self._variable_stops[1][unknown]), size, unknown + SEED_BLOCK,
                   unknown + max(SEED_BLOCK_ENTRIES // size, 1))
        if stop - unknown < 2 or _csr_matvecs is None or self._lu._permuted.dtype != np.float64:
            return None
        unknowns = np.arange(unknown, stop)
        block = self._lu.transposed_unit_block(unknowns)
        for column, seed in enumerate(unknowns):
            self._seeds[int(seed)] = (block, column)
        return block[:, 0]
