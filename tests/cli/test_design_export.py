"""bild-mdo design --stl / --step: 3D blade files, their options, and the checks made before the design runs."""
import numpy as np
import pytest

from bild_mdo.io import blade_3d
from bild_mdo.io.blade_3d import blade_surface
from bild_mdo.results.design import design_rotor
from tests.cli.runner import run

trimesh = pytest.importorskip("trimesh")

# A small propeller, quick to design: R = 0.3 m, 4000 rpm, c_ref = 30 mm at r/R = 0.5, 4 stations.
SMALL = ("--radius", "0.3", "--rpm", "4000", "--ref-chord", "0.03", "--num-radial", "4")


def test_design_writes_a_closed_stl_blade(tmp_path, capsys):
    path = tmp_path / "blade.stl"
    code, out, err = run(capsys, "design", *SMALL, "--stl", str(path))
    assert code == 0, err
    assert f"wrote {path}" in out
    mesh = trimesh.load(path)
    assert mesh.is_watertight and mesh.volume > 0.0
    # The default airfoil naca4412 gives the section; mm, one blade along +z from hub (60 mm) to tip (300 mm).
    reference = blade_surface(design_rotor(radius=0.3, rpm=4000.0, ref_chord=0.03, num_radial=4),
                              airfoil="naca4412")
    triangles = trimesh.load(path, process=False).triangles  # per face, as the file holds them (float32)
    np.testing.assert_allclose(triangles, reference.vertices[reference.faces] * 1e3, rtol=0, atol=1e-4)
    assert mesh.bounds[0, 2] == pytest.approx(60.0) and mesh.bounds[1, 2] == pytest.approx(300.0)


def test_all_blades_units_section_and_stacking(tmp_path, capsys):
    path = tmp_path / "rotor.stl"
    code, _, err = run(capsys, "design", *SMALL, "--num-blades", "2", "--stl", str(path), "--all-blades",
                       "--cad-units", "m", "--section", "naca0012", "--stacking", "0.5")
    assert code == 0, err
    mesh = trimesh.load(path)
    assert mesh.is_watertight and len(mesh.split(only_watertight=True)) == 2
    # Two blades, along +z and -z, in metres.
    assert mesh.bounds[1, 2] == pytest.approx(0.3, rel=1e-6) and mesh.bounds[0, 2] == pytest.approx(-0.3, rel=1e-6)


def test_batch_writes_one_stl_per_design(tmp_path, capsys):
    code, out, err = run(capsys, "design", *SMALL[:4], "--num-radial", "4", "--ref-chord", "0.02", "0.03",
                         "--stl", str(tmp_path / "b.stl"))
    assert code == 0, err
    for i in (0, 1):
        assert trimesh.load(tmp_path / f"b_{i}.stl").is_watertight
        assert f"wrote {tmp_path / f'b_{i}.stl'}" in out


def test_an_airfoil_without_a_section_shape_asks_for_section(tmp_path, capsys):
    path = tmp_path / "blade.stl"
    code, out, err = run(capsys, "design", *SMALL, "--airfoil", "analytic", "--stl", str(path))
    assert code == 2 and out == ""
    assert err.strip() == ("bild-mdo design: error: --stl/--step need the section shape, and --airfoil 'analytic' "
                           "gives none; add --section with a NACA designation (naca4412) or a Selig coordinates file")
    code, _, err = run(capsys, "design", *SMALL, "--airfoil", "analytic", "--stl", str(path), "--section", "no.dat")
    assert code == 2 and err.startswith("bild-mdo design: error: --section: airfoil 'no.dat' names no section shape")
    code, _, err = run(capsys, "design", *SMALL, "--airfoil", "analytic", "--stl", str(path), "--section", "441")
    assert code == 2 and "--section: airfoil '441': only NACA 4- and 5-digit designations" in err
    assert list(tmp_path.iterdir()) == []
    code, _, err = run(capsys, "design", *SMALL, "--airfoil", "analytic", "--stl", str(path), "--section", "23012")
    assert code == 0, err
    assert trimesh.load(path).is_watertight


def test_zero_chord_design_writes_no_blade(tmp_path, capsys):
    # As for the geometry files: c_ref = 0.1 mm on R = 1.5 m leaves the outer annuli unloaded (chord 0).
    code, out, err = run(capsys, "design", "--ref-chord", "0.0001", "--num-radial", "8", "--stl",
                         str(tmp_path / "z.stl"))
    assert code == 2 and out == ""
    assert "zero chord at" in err and "of 8 stations" in err and "(no geometry file written)" in err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("options, message", [
    (("--stacking", "1.5"), "--stacking must be a finite number within [0, 1], got 1.5"),
    (("--cad-units", "ft"), "argument --cad-units: invalid choice: 'ft'"),
])
def test_bad_blade_options(tmp_path, capsys, options, message):
    code, _, err = run(capsys, "design", *SMALL, "--stl", str(tmp_path / "b.stl"), *options)
    assert code == 2 and message in err
    assert list(tmp_path.iterdir()) == []


def test_step_without_opencascade_is_one_line_before_the_design(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(blade_3d.LIBRARIES, "step", ("no_such_cad_module", "pip install 'bild-mdo[cad]'"))
    code, out, err = run(capsys, "design", *SMALL, "--step", str(tmp_path / "b.step"), "--stl",
                         str(tmp_path / "b.stl"))
    assert code == 2 and out == ""
    assert err.strip() == ("bild-mdo design: error: writing STEP needs no_such_cad_module: "
                           "pip install 'bild-mdo[cad]'")
    assert list(tmp_path.iterdir()) == []


def test_design_writes_a_step_solid(tmp_path, capsys):
    pytest.importorskip("OCP")
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    path = tmp_path / "blade.step"
    code, out, err = run(capsys, "design", *SMALL, "--step", str(path), "--all-blades")
    assert code == 0, err
    assert f"wrote {path}" in out and "Open CASCADE" not in out
    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    reader.TransferRoots()
    explorer, solids = TopExp_Explorer(reader.OneShape(), TopAbs_SOLID), 0
    while explorer.More():
        solids, _ = solids + 1, explorer.Next()
    assert solids == 3


def test_help_documents_the_frame(capsys):
    code, out, _ = run(capsys, "design", "--help")
    assert code == 0
    for text in ("--stl FILE", "--step FILE", "--section AIRFOIL", "--stacking X", "--all-blades", "--cad-units",
                 "pitch-change axis", "thrust direction"):
        assert text in out
