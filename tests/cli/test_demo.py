"""bild-mdo demo: the paper's rotor, its tables, geometry files and figures."""
from tests.cli.runner import run


def test_demo_writes_tables_and_files(tmp_path, capsys):
    code, out, err = run(capsys, "demo", "--output-dir", str(tmp_path / "demo"))
    assert code == 0, err
    assert "stations:" in out and "maximum efficiency" in out
    for name in ("hover_blade.csv", "hover_blade.json", "hover_blade.prop", "hover_blade.png", "blades_J0-2.png",
                 "efficiency_Jdes1.png"):
        assert (tmp_path / "demo" / name).stat().st_size > 0


def test_demo_airfoil_is_checked_before_any_file(tmp_path, capsys):
    code, out, err = run(capsys, "demo", "--output-dir", str(tmp_path / "demo"), "--airfoil", "no_such_airfoil")
    assert code == 2 and out == ""
    assert "--airfoil: unknown airfoil 'no_such_airfoil'" in err
    assert not (tmp_path / "demo").exists()


def test_an_empty_output_folder_is_refused(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = run(capsys, "demo", "--output-dir", "")
    assert code == 2 and "--output-dir is empty" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []
