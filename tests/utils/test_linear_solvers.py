"""TriangularDirectSolver and BatchedCSCJacobian: the same linear solutions as a dense solve, on small chains
whose total derivatives are derived by hand."""
import numpy as np
import openmdao.api as om
import pytest
import scipy.sparse
from openmdao.utils.assert_utils import assert_check_totals

from bild_mdo.utils.linear_solvers import (BatchedCSCJacobian, TriangularDirectSolver, _PermutedLU,
                                           dependency_order)


def test_dependency_order_makes_a_chain_lower_triangular_and_refuses_a_cycle():
    # x2 needs x0, x3 needs x2, x1 needs x3 and x0: the only order is 0, 2, 3, 1.
    rows, cols = [0, 1, 2, 3, 2, 3, 1, 1], [0, 1, 2, 3, 0, 2, 3, 0]
    matrix = scipy.sparse.csc_matrix((np.arange(1.0, 9.0), (rows, cols)), shape=(4, 4))
    order = dependency_order(matrix)
    assert order.tolist() == [0, 2, 3, 1]
    assert scipy.sparse.triu(matrix[order][:, order], k=1).nnz == 0
    cyclic = scipy.sparse.csc_matrix((np.ones(4), ([0, 1, 0, 1], [0, 1, 1, 0])), shape=(2, 2))
    assert dependency_order(cyclic) is None


class _Cubic(om.ImplicitComponent):
    """z**3 + z - y = 0, one state per entry (a diagonal block, as BILD's eta2)."""

    def setup(self):
        self.add_input("y", shape=3)
        self.add_output("z", shape=3, val=1.0)
        ar = np.arange(3)
        self.declare_partials("z", ["y", "z"], rows=ar, cols=ar)

    def solve_nonlinear(self, inputs, outputs):
        # Newton's method on the increasing cubic (one real root; complex-step safe).
        z = np.zeros_like(inputs["y"])
        for _ in range(40):
            z = z - (z ** 3 + z - inputs["y"]) / (3.0 * z ** 2 + 1.0)
        outputs["z"] = z

    def apply_nonlinear(self, inputs, outputs, residuals):
        residuals["z"] = outputs["z"] ** 3 + outputs["z"] - inputs["y"]

    def linearize(self, inputs, outputs, partials):
        partials["z", "z"] = 3.0 * outputs["z"] ** 2 + 1.0
        partials["z", "y"] = -np.ones(3)


def _chain(solver):
    """x (m) -> y = 2 a + 3 b with a (m) and b (cm) both connected to x -> z with z**3 + z = y -> w = sum z**2."""
    model = om.Group()
    model.add_subsystem("ivc", om.IndepVarComp("x", val=np.array([0.5, 1.0, 2.0]), units="m"))
    model.add_subsystem("lin", om.ExecComp("y = 2.0 * a + 0.03 * b", y=np.ones(3), a={"val": np.ones(3), "units": "m"},
                                           b={"val": np.ones(3), "units": "cm"}, has_diag_partials=True))
    model.add_subsystem("cubic", _Cubic())
    model.add_subsystem("sum", om.ExecComp("w = sum(z ** 2)", z=np.ones(3)))
    model.connect("ivc.x", ["lin.a", "lin.b"])
    model.connect("lin.y", "cubic.y")
    model.connect("cubic.z", "sum.z")
    model.linear_solver = solver
    return model


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_totals_of_a_chain_with_shared_entries_and_unit_factors_match_the_hand_derivation(mode):
    prob = om.Problem(_chain(TriangularDirectSolver(assemble_jac=True)), reports=False)
    prob.setup(mode=mode, force_alloc_complex=True)
    prob.run_model()
    for _ in range(2):  # the second linearisation runs on the batched assembly
        totals = prob.compute_totals(of=["cubic.z", "sum.w"], wrt=["ivc.x"])
    assert isinstance(prob.model._assembled_jac, BatchedCSCJacobian)
    assert isinstance(prob.model.linear_solver._lu, _PermutedLU)
    # y = 2 x + 0.03 (100 x) = 5 x;  dz/dx = 5 / (3 z**2 + 1);  dw/dx = 2 z dz/dx.
    x = np.array([0.5, 1.0, 2.0])
    z = prob.get_val("cubic.z")
    np.testing.assert_allclose(z ** 3 + z, 5.0 * x, rtol=1e-14)
    dz_dx = 5.0 / (3.0 * z ** 2 + 1.0)
    np.testing.assert_allclose(totals["cubic.z", "ivc.x"], np.diag(dz_dx), rtol=1e-14, atol=1e-300)
    np.testing.assert_allclose(totals["sum.w", "ivc.x"], [2.0 * z * dz_dx], rtol=1e-14)
    assert_check_totals(prob.check_totals(of=["sum.w"], wrt=["ivc.x"], method="cs", out_stream=None),
                        atol=1e-12, rtol=1e-12)


def test_a_coupled_loop_falls_back_to_the_plain_direct_solver():
    # x = a + y / 2, y = x / 2 (Newton-coupled): x = 4 a / 3, dx/da = 4/3 (hand derivation).
    model = om.Group()
    model.add_subsystem("ivc", om.IndepVarComp("a", val=3.0))
    loop = model.add_subsystem("loop", om.Group())
    loop.add_subsystem("cx", om.ExecComp("x = a + 0.5 * y"))
    loop.add_subsystem("cy", om.ExecComp("y = 0.5 * x"))
    loop.connect("cx.x", "cy.x")
    loop.connect("cy.y", "cx.y")
    loop.nonlinear_solver = om.NewtonSolver(solve_subsystems=False, iprint=-1)
    loop.linear_solver = TriangularDirectSolver(assemble_jac=True)
    model.connect("ivc.a", "loop.cx.a")
    prob = om.Problem(model, reports=False)
    prob.setup()
    prob.run_model()
    totals = prob.compute_totals(of=["loop.cx.x"], wrt=["ivc.a"])
    assert prob.get_val("loop.cx.x")[0] == pytest.approx(4.0, rel=1e-12)
    assert totals["loop.cx.x", "ivc.a"][0, 0] == pytest.approx(4.0 / 3.0, rel=1e-12)
    assert not isinstance(loop.linear_solver._lu, _PermutedLU)


@pytest.mark.parametrize("mode", ["fwd", "rev"])
def test_reverse_seeds_solved_by_variable_inside_a_subgroup_match_the_hand_derivation(mode):
    # The chain of _chain inside a subgroup (its own TriangularDirectSolver), a component after it at the top:
    # the subgroup's vectors are views into the model's, so a variable's range must be found in the view.
    model = om.Group()
    model.add_subsystem("ivc", om.IndepVarComp("x", val=np.array([0.5, 1.0, 2.0]), units="m"))
    sub = model.add_subsystem("sub", om.Group())
    sub.add_subsystem("lin", om.ExecComp("y = 2.0 * a + 0.03 * b", y=np.ones(3), a={"val": np.ones(3), "units": "m"},
                                         b={"val": np.ones(3), "units": "cm"}, has_diag_partials=True))
    sub.add_subsystem("cubic", _Cubic())
    sub.connect("lin.y", "cubic.y")
    sub.linear_solver = TriangularDirectSolver(assemble_jac=True)
    model.add_subsystem("sum", om.ExecComp("w = sum(z ** 2)", z=np.ones(3)))
    model.connect("ivc.x", ["sub.lin.a", "sub.lin.b"])
    model.connect("sub.cubic.z", "sum.z")
    prob = om.Problem(model, reports=False)
    prob.setup(mode=mode)
    prob.run_model()
    for _ in range(2):
        totals = prob.compute_totals(of=["sub.cubic.z", "sub.lin.y", "sum.w"], wrt=["ivc.x"])
    x, z = np.array([0.5, 1.0, 2.0]), prob.get_val("sub.cubic.z")
    dz_dx = 5.0 / (3.0 * z ** 2 + 1.0)
    np.testing.assert_allclose(totals["sub.cubic.z", "ivc.x"], np.diag(dz_dx), rtol=1e-14, atol=1e-300)
    np.testing.assert_allclose(totals["sub.lin.y", "ivc.x"], 5.0 * np.eye(3), rtol=1e-14, atol=1e-300)
    np.testing.assert_allclose(totals["sum.w", "ivc.x"], [2.0 * z * dz_dx], rtol=1e-14)
    np.testing.assert_allclose(z ** 3 + z, 5.0 * x, rtol=1e-14)
    # Reverse: the seeds of each 3-entry variable were solved as one block (none in forward mode).
    assert (len(sub.linear_solver._seeds) > 0) == (mode == "rev")
