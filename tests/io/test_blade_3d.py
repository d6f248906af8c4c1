"""3D blade export: closed STL surfaces, the frame and stacking conventions, NACA and file sections, STEP."""
import numpy as np
import pytest

from bild_mdo.io import blade_3d
from bild_mdo.io.blade_3d import blade_sections, blade_surface, section_coordinates, write_step, write_stl
from bild_mdo.io.geometry import RotorGeometry
from bild_mdo.results.design import design_rotor

trimesh = pytest.importorskip("trimesh")

# Hand integral of the NACA 4-digit thickness (Abbott & von Doenhoff ch. 6): the section area per chord^2 is
# int_0^1 2 y_t dx = 10 t (2/3 0.2969 - 0.1260/2 - 0.3516/3 + 0.2843/4 - a4/5), a4 = 0.1015 (open trailing
# edge), 0.1036 (closed, sharp trailing edge).
OPEN_TE_AREA = 10 * (2 / 3 * 0.2969 - 0.1260 / 2 - 0.3516 / 3 + 0.2843 / 4 - 0.1015 / 5)   # 0.68508 t
SHARP_TE_AREA = 10 * (2 / 3 * 0.2969 - 0.1260 / 2 - 0.3516 / 3 + 0.2843 / 4 - 0.1036 / 5)  # 0.68088 t


@pytest.fixture(scope="module")
def demo():
    # A small propeller; with 4 equal annuli from 0.2 R the second station is the reference r = 0.5 R.
    return design_rotor(radius=0.3, rpm=4000.0, ref_chord=0.03, num_radial=4)


def _mesh(surface):
    return trimesh.Trimesh(surface.vertices, surface.faces, process=False)


def _shoelace(loop):
    x, y = loop.T
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def _straight_blade(airfoil="naca0012", twist=0.0, chord=0.02):
    radii = np.linspace(0.06, 0.24, 5)
    return RotorGeometry(radii=radii, chord=np.full(5, chord), twist=np.full(5, twist), radius=0.25,
                         hub_radius=0.05, num_blades=2, airfoil=airfoil)


def _paired(loop, sharp=False):
    """Upper and lower surface (LE -> TE) of a loop of section_coordinates."""
    n = loop.shape[0] // 2
    upper = loop[n::-1]
    lower = np.vstack([loop[n:], loop[:1]]) if sharp else loop[n:]
    return upper, lower


def test_stl_of_a_demo_blade_is_closed_with_positive_volume(demo, tmp_path):
    path = write_stl(tmp_path / "blade.stl", demo)
    mesh = trimesh.load(path)
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.volume > 0.0
    # Written in mm: the file's volume is the mesh's (m^3) times 1e9, and the blade reaches the tip R = 300 mm.
    assert mesh.volume == pytest.approx(_mesh(blade_surface(demo)).volume * 1e9, rel=1e-6)
    assert mesh.bounds[1, 2] == pytest.approx(300.0, rel=1e-6)
    assert mesh.bounds[0, 2] == pytest.approx(60.0, rel=1e-6)


def test_all_blades_are_closed_copies_turned_about_the_axis(demo):
    one, every = _mesh(blade_surface(demo)), _mesh(blade_surface(demo, all_blades=True))
    assert every.is_watertight
    assert every.volume == pytest.approx(3 * one.volume, rel=1e-12)
    assert len(every.split(only_watertight=True)) == 3
    tips = every.vertices[np.isclose(np.linalg.norm(every.vertices[:, 1:], axis=1), 0.3, rtol=1e-3)]
    angles = np.unique(np.round(np.degrees(np.arctan2(tips[:, 2], tips[:, 1])) % 360.0, -1))
    assert set(angles) >= {90.0, 210.0, 330.0}


def test_reference_section_has_the_design_chord_and_twist(demo):
    geometry = demo.geometry()
    # The design invariant: the chord at the reference station is c_ref.
    assert geometry.radii[1] == pytest.approx(0.15) and geometry.chord[1] == pytest.approx(0.03, rel=1e-9)
    # A symmetric section, so that the leading edge (0, 0) is the section point farthest from the trailing edge.
    mesh = _mesh(blade_surface(geometry, airfoil="naca0012"))
    points = trimesh.intersections.mesh_plane(mesh, [0, 0, 1], [0, 0, 0.15]).reshape(-1, 3)
    np.testing.assert_allclose(points[:, 2], 0.15)
    points = np.unique(points[:, :2].round(14), axis=0)  # each point is cut by several triangles
    dist = np.linalg.norm(points[:, None] - points[None], axis=-1)
    i, j = np.unravel_index(np.argmax(dist), dist.shape)
    le = min(points[i], points[j], key=lambda p: p[1])  # the leading edge points to -y
    # The two trailing-edge corners lie at the largest distance from it (the next points are 0.07 % nearer).
    far = np.linalg.norm(points - le, axis=1)
    te = points[far > (1 - 1e-4) * far.max()].mean(axis=0)
    assert np.linalg.norm(te - le) == pytest.approx(0.03, rel=1e-9)
    twist = np.arctan2(le[0] - te[0], te[1] - le[1])  # pitch from the rotor plane, leading edge forward
    assert twist == pytest.approx(geometry.twist[1], abs=1e-9)
    # Stacked at the quarter chord on the pitch-change axis.
    np.testing.assert_allclose(le + 0.25 * (te - le), 0.0, atol=1e-12)


def test_constant_chord_blade_volume_is_span_chord_squared_area():
    t, chord = 0.12, 0.02
    area = section_coordinates("naca0012")
    assert _shoelace(area) == pytest.approx(OPEN_TE_AREA * t, rel=1e-3)
    for twist in (0.0, 0.4):  # a constant twist turns every section rigidly: the same volume
        geometry = _straight_blade(twist=twist, chord=chord)
        mesh = _mesh(blade_surface(geometry))
        assert mesh.is_watertight
        assert mesh.volume == pytest.approx((0.25 - 0.05) * chord**2 * OPEN_TE_AREA * t, rel=1e-3)
        stations = _mesh(blade_surface(geometry, extend=False))
        assert stations.volume == pytest.approx((0.24 - 0.06) * chord**2 * OPEN_TE_AREA * t, rel=1e-3)


def test_frame_stacking_and_hand():
    geometry = _straight_blade(airfoil="naca4412", twist=np.radians(20.0))
    loops, sharp = blade_sections(geometry, stacking=0.5)
    assert not sharp and loops.shape == (7, 121, 3)
    section = loops[3]
    te_mid, le = 0.5 * (section[0] + section[-1]), section[60]
    # Leading edge towards -y (the blade moves to -y turning positively about +x) and forward (+x) for twist > 0.
    assert le[1] < 0.0 < te_mid[1] and le[0] > 0.0 > te_mid[0]
    np.testing.assert_allclose((0.5 * (le + te_mid))[:2], 0.0, atol=1e-12)
    assert np.linalg.norm(te_mid - le) == pytest.approx(0.02, rel=1e-4)
    np.testing.assert_allclose(section[:, 2], 0.15)
    # The upper (suction) surface faces the thrust direction +x.
    upper, lower = section[1:60], section[61:120]
    normal = np.array([np.cos(np.radians(20.0)), np.sin(np.radians(20.0))])
    assert (upper[:, :2] @ normal).mean() > (lower[:, :2] @ normal).mean()
    left, _ = blade_sections(geometry, stacking=0.5, hand="left")
    np.testing.assert_allclose(left * [1, -1, 1], loops)
    assert _mesh(blade_surface(geometry, hand="left")).volume > 0.0


def test_naca_sections_have_their_camber_and_thickness():
    upper, lower = _paired(section_coordinates("naca4412", num_points=200))
    camber, thickness = 0.5 * (upper[:, 1] + lower[:, 1]), np.linalg.norm(upper - lower, axis=1)
    x = 0.5 * (upper[:, 0] + lower[:, 0])
    # NACA 4412: 4 % camber at 40 % chord, 12 % thickness (at 30 % chord).
    assert camber.max() == pytest.approx(0.04, abs=2e-5) and x[np.argmax(camber)] == pytest.approx(0.4, abs=0.01)
    assert thickness.max() == pytest.approx(0.12, abs=2e-4) and x[np.argmax(thickness)] == pytest.approx(0.3, abs=0.01)
    # Open trailing edge: 2 y_t(1) = 10 t (0.2969 - 0.1260 - 0.3516 + 0.2843 - 0.1015) = 0.00252 for t = 0.12.
    assert thickness[-1] == pytest.approx(0.00252, rel=1e-3)
    # NACA 23012: design c_l 0.3, maximum camber 1.84 % at 15 % chord (dy_c/dx = 0 at x = P/20).
    upper, lower = _paired(section_coordinates("NACA 23012", num_points=400))
    camber = 0.5 * (upper[:, 1] + lower[:, 1])
    assert camber.max() == pytest.approx(0.0184, abs=2e-4)
    assert 0.5 * (upper[np.argmax(camber), 0] + lower[np.argmax(camber), 0]) == pytest.approx(0.15, abs=0.005)
    # Reflexed NACA 23112: the mean line still closes at the trailing edge, and the aft part turns up.
    upper, lower = _paired(section_coordinates("naca23112"))
    camber = 0.5 * (upper[:, 1] + lower[:, 1])
    assert abs(camber[-1]) < 1e-9 and camber[0] == 0.0
    assert _shoelace(section_coordinates("23012")) == pytest.approx(OPEN_TE_AREA * 0.12, rel=2e-3)


def _write_selig(path, t=0.12, n=80, header="NACA 0012 sharp"):
    x = 0.5 * (1 - np.cos(np.linspace(0, np.pi, n)))
    y_t = 5 * t * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1036 * x**4)
    xy = np.vstack([np.column_stack([x, y_t])[::-1], np.column_stack([x, -y_t])[1:]])
    path.write_text(header + "\n" + "\n".join(f"{a:.8f} {b:.8f}" for a, b in xy) + "\n")
    return path


def test_sharp_trailing_edge_from_a_coordinates_file(tmp_path):
    path = _write_selig(tmp_path / "sharp.dat")
    loop = section_coordinates(path, num_points=60)
    assert loop.shape == (120, 2)  # the sharp trailing edge is one point
    assert _shoelace(loop) == pytest.approx(SHARP_TE_AREA * 0.12, rel=2e-3)
    geometry = _straight_blade(airfoil=str(path))
    mesh = _mesh(blade_surface(geometry))
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.volume == pytest.approx(0.2 * 0.02**2 * SHARP_TE_AREA * 0.12, rel=2e-3)
    # The file's scale and offset do not matter: the section is normalised to unit chord from its leading edge.
    scaled = np.loadtxt(path, skiprows=1) * 3.0 + [1.0, 0.5]
    np.testing.assert_allclose(section_coordinates(scaled, num_points=60), loop, atol=1e-12)


def test_zero_chord_stations_are_refused_or_trimmed():
    radii = np.linspace(0.06, 0.24, 6)
    chord = np.array([0.03, 0.03, 0.02, 0.01, 0.0, 0.0])
    geometry = RotorGeometry(radii=radii, chord=chord, twist=np.full(6, 0.2), radius=0.25, hub_radius=0.05,
                             num_blades=2, airfoil="naca4412")
    with pytest.raises(ValueError, match=r"^chord is 0 at 2 of 6 stations \(r = 0.204 \.\.\. 0.24 m\)") as err:
        blade_surface(geometry)
    assert "\n" not in str(err.value) and "zero_chord='trim'" in str(err.value)
    mesh = _mesh(blade_surface(geometry, zero_chord="trim"))
    assert mesh.is_watertight and mesh.volume > 0.0
    assert mesh.bounds[0, 2] == pytest.approx(0.05) and mesh.bounds[1, 2] == pytest.approx(radii[3])
    gap = RotorGeometry(radii=radii, chord=np.array([0.03, 0.0, 0.02, 0.01, 0.01, 0.01]), twist=np.zeros(6),
                        radius=0.25, hub_radius=0.05, num_blades=2, airfoil="naca4412")
    with pytest.raises(ValueError, match="a gap between them"):
        blade_surface(gap, zero_chord="trim")


@pytest.mark.parametrize("airfoil, message", [
    ("analytic", "names no section shape"),
    ("0.2:naca4415;1:naca4412", "names no section shape"),
    ("naca4012", "camber"),
    ("naca441", "only NACA 4- and 5-digit"),
    ("naca21112", "reflexed 5-digit mean line needs P = 2"),
    (np.array([[0.0, 0.0], [0.5, 0.1], [1.0, 0.0], [0.5, -0.1], [0.2, -0.05]]), "smallest x is at an end"),
])
def test_sections_that_cannot_be_built(airfoil, message):
    with pytest.raises(ValueError, match=message):
        section_coordinates(airfoil)


def test_polar_names_give_their_section():
    np.testing.assert_array_equal(section_coordinates("naca4412@re=1e6"), section_coordinates("naca4412"))
    np.testing.assert_array_equal(section_coordinates("neuralfoil:naca2412"), section_coordinates("2412"))


def test_options_are_checked(demo):
    with pytest.raises(ValueError, match="stacking"):
        blade_surface(demo, stacking=1.5)
    with pytest.raises(ValueError, match="hand must be one of right, left"):
        blade_surface(demo, hand="clockwise")
    with pytest.raises(ValueError, match="units must be one of"):
        write_stl("unused.stl", demo, units="furlong")


def test_missing_library_is_one_line(demo, monkeypatch, tmp_path):
    monkeypatch.setitem(blade_3d.LIBRARIES, "step", ("no_such_cad_module", "pip install 'bild-mdo[cad]'"))
    with pytest.raises(ImportError, match=r"^writing STEP needs no_such_cad_module: pip install 'bild-mdo\[cad\]'$"):
        write_step(tmp_path / "blade.step", demo)
    assert list(tmp_path.iterdir()) == []


def _read_step(path):
    from OCP.BRepGProp import BRepGProp
    from OCP.GProp import GProp_GProps
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.STEPControl import STEPControl_Reader

    reader = STEPControl_Reader()
    assert reader.ReadFile(str(path)) == IFSelect_RetDone
    reader.TransferRoots()
    shape = reader.OneShape()
    props = GProp_GProps()
    BRepGProp.VolumeProperties_s(shape, props, 1e-7)  # adaptive integration: the default rule is too coarse
    return shape, props.Mass()


def _count(shape, kind):
    from OCP.TopExp import TopExp_Explorer

    explorer, count = TopExp_Explorer(shape, kind), 0
    while explorer.More():
        count, _ = count + 1, explorer.Next()
    return count


@pytest.mark.parametrize("airfoil, faces", [("naca4412", 4), ("sharp", 3)])
def test_step_reads_back_with_the_same_faces(demo, tmp_path, airfoil, faces):
    pytest.importorskip("OCP")
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_FACE, TopAbs_SOLID

    section = str(_write_selig(tmp_path / "sharp.dat")) if airfoil == "sharp" else airfoil
    solid = blade_3d.step_solid(demo, airfoil=section)
    assert BRepCheck_Analyzer(solid).IsValid()
    # A smooth loft: one face over the airfoil surface, the trailing-edge base if finite, root and tip caps.
    assert _count(solid, TopAbs_FACE) == faces
    path = write_step(tmp_path / "blade.step", demo, units="m", airfoil=section)
    shape, volume = _read_step(path)
    assert _count(shape, TopAbs_FACE) == faces and _count(shape, TopAbs_SOLID) == 1
    # Read back in mm: the smooth loft holds the ruled STL's volume to about 1 % on these 6 sections.
    assert volume == pytest.approx(_mesh(blade_surface(demo, airfoil=section)).volume * 1e9, rel=0.02)
    every, _ = _read_step(write_step(tmp_path / "rotor.step", demo, all_blades=True, airfoil=section))
    assert _count(every, TopAbs_SOLID) == 3 and _count(every, TopAbs_FACE) == 3 * faces
