"""Run the bild-mdo command in-process, as the tests of its subcommands do."""
from bild_mdo.cli.main import main


def run(capsys, *argv):
    """Exit code, stdout and stderr of ``bild-mdo *argv``."""
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err
